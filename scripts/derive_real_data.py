"""Write the compact copy of the UE-ADL forward reaches that the repository ships (`data/real/`).

    .venv/bin/python scripts/derive_real_data.py [SOURCE] [--out DIR] [--check]

SOURCE is a folder of the 160 original exports, ``ADL0PPF{L,R}{1-5}.csv.gz`` (MiaH-kin/UE_ADLdatabase,
``ADL0PP/ADL0PPF{L,R}{1-5}.csv`` at commit d196e59b49d60e57e6ae2199bc6a266a804aac10, gzip-compressed;
default: the development set, ``/work/shared/real-recordings/ue-adl-forward-reach``). Each is a Vicon
Nexus 2.10 "Trajectories" CSV export (100 Hz, mm, 49 markers). The copy, written to DIR (default
``data/real/ue-adl-forward-reach``) under the same name, is the same export with fewer columns:

* kept: the five header lines (``Trajectories``, the rate, the marker names with their subject prefix,
  ``Frame,Sub Frame,X,Y,Z,...``, the units), the columns ``Frame`` and ``Sub Frame`` and the three
  columns of each fingertip marker, ``RFTP`` and ``LFTP`` (in the file's order), every row, the blank
  line that ends the section, the byte-order mark and the line ends. Every kept cell is copied as text,
  exactly as Nexus wrote it (no number is parsed or rounded), so the copy reads as the original does;
* dropped: the other 47 markers' columns (shoulder, upper-arm, forearm and hand clusters of both sides),
  and the trailing empty field of the marker-name line is kept as Nexus writes it.

No file is renamed: the database's names ``ADL0PPF<hand><repetition>`` already give the participant
(``ADL0PP``, which the script checks against the subject prefix of the marker names inside the file),
the hand (``L``/``R``) and the repetition (1-5), e.g. the name pattern
``(?P<participant>ADL\\d{3})F(?P<trial>(?P<hand>[LR])\\d)``.

The output is gzip-compressed deterministically (level 9, no file name, modification time 0), so the
same originals give byte-identical copies. With ``--check`` the script then reads every original and its
copy with ``skilllib.load_recordings(path, marker="RFTP,LFTP", contact_height=-1.0)`` and checks that
t, x, y and z are bit-identical; it prints the total sizes either way. The licence (MIT, Mia Huang 2021)
goes with the copy as ``LICENSE`` in DIR (copied from SOURCE/../licences/UE_ADLdatabase-LICENSE when
present).
"""

from __future__ import annotations

import argparse
import gzip
import io
import re
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCE = Path("/work/shared/real-recordings/ue-adl-forward-reach")
OUT = ROOT / "data" / "real" / "ue-adl-forward-reach"
KEEP = ("RFTP", "LFTP")  #: the markers kept (name after the subject prefix)
NAME = re.compile(r"(?P<participant>ADL\d{3})F(?P<hand>[LR])(?P<repetition>[1-5])\.csv\.gz")
BOM = "\ufeff"
HEADER_LINES = 5  #: Trajectories, rate, marker names, column names, units


def compact(text: str, participant: str) -> str:
    """The export ``text`` with only Frame, Sub Frame and the KEEP markers' columns; cells as written."""
    bom = text.startswith(BOM)
    body = text[len(BOM) :] if bom else text
    lines = body.split("\n")
    if lines[0].strip().strip(",") != "Trajectories":
        raise ValueError(f"first line {lines[0]!r} is not 'Trajectories'")
    if any(line.strip() == "" for line in lines[:HEADER_LINES]):
        raise ValueError("the header is cut short")
    names = lines[2].rstrip("\r").split(",")
    n_fields = len(lines[3].rstrip("\r").split(","))
    columns = [0, 1]
    for name in KEEP:
        at = [j for j, n in enumerate(names) if n.rsplit(":", 1)[-1] == name]
        if len(at) != 1:
            raise ValueError(f"{len(at)} markers named {name} in {names[2:8]}...")
        prefix = names[at[0]].rsplit(":", 1)[0]
        if prefix != participant:
            raise ValueError(f"marker {names[at[0]]!r}: subject {prefix!r}, file name {participant!r}")
        columns += [at[0], at[0] + 1, at[0] + 2]
    columns.sort()  # the file's order
    out = []
    end = len(lines)
    for i, line in enumerate(lines):
        if i >= HEADER_LINES and line.strip() == "":
            end = i  # the blank line that ends the section: it and what follows are copied as they are
            break
        if i < 2:  # the section name and the rate, as they are
            out.append(line)
            continue
        cr = "\r" if line.endswith("\r") else ""
        fields = line[: len(line) - len(cr)].split(",")
        # the marker-name line has one field more than the others (Nexus's trailing comma): keep it
        extra = fields[n_fields:] if i == 2 else []
        if i != 2 and len(fields) != n_fields:
            raise ValueError(f"line {i + 1}: {len(fields)} fields, not {n_fields}")
        out.append(",".join([fields[j] for j in columns] + extra) + cr)
    rest = lines[end:]
    if any(line.strip() for line in rest):
        raise ValueError("a section after Trajectories: not expected in these exports")
    return (BOM if bom else "") + "\n".join(out + rest)


def gzip_bytes(data: bytes) -> bytes:
    """``data`` gzip-compressed deterministically: level 9, no file name, modification time 0."""
    buf = io.BytesIO()
    with gzip.GzipFile(filename="", mode="wb", fileobj=buf, compresslevel=9, mtime=0) as f:
        f.write(data)
    return buf.getvalue()


def derive(source: Path, out: Path) -> list[tuple[Path, Path]]:
    """Write the compact copy of every original in ``source`` to ``out``; (original, copy) pairs."""
    files = sorted(p for p in source.iterdir() if NAME.fullmatch(p.name))
    if not files:
        raise SystemExit(f"{source}: no ADL0PPF<hand><repetition>.csv.gz files")
    out.mkdir(parents=True, exist_ok=True)
    for stale in out.glob("*.csv.gz"):  # the copy is the whole set, nothing left from an earlier one
        if not (source / stale.name).is_file():
            stale.unlink()
    pairs = []
    for path in files:
        participant = NAME.fullmatch(path.name)["participant"]
        text = gzip.decompress(path.read_bytes()).decode("utf-8")
        target = out / path.name
        target.write_bytes(gzip_bytes(compact(text, participant).encode("utf-8")))
        pairs.append((path, target))
    licence = source.parent / "licences" / "UE_ADLdatabase-LICENSE"
    if licence.is_file():
        shutil.copyfile(licence, out / "LICENSE")
    return pairs


def check(pairs: list[tuple[Path, Path]]) -> None:
    """Every copy reads bit-identically to its original (t, x, y, z; the same marker chosen)."""
    sys.path.insert(0, str(ROOT))
    import numpy as np

    import skilllib as sk

    for original, copy in pairs:
        a = sk.load_recordings(original, marker="RFTP,LFTP", contact_height=-1.0)
        b = sk.load_recordings(copy, marker="RFTP,LFTP", contact_height=-1.0)
        assert a.keys() == b.keys(), (original.name, a.keys(), b.keys())
        for key in a.keys():
            ta, tb = a.trial(*key), b.trial(*key)
            for name in ("t", "pos"):
                va, vb = np.asarray(getattr(ta, name)), np.asarray(getattr(tb, name))
                assert va.shape == vb.shape and va.tobytes() == vb.tobytes(), (original.name, name)
    print(f"checked: {len(pairs)} copies read bit-identically to their originals (t, x, y, z)")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("source", nargs="?", type=Path, default=SOURCE, help="folder of the originals")
    parser.add_argument("--out", type=Path, default=OUT, help="folder of the copy (default: %(default)s)")
    parser.add_argument("--check", action="store_true", help="read both and compare t, x, y, z")
    args = parser.parse_args(argv)
    pairs = derive(args.source, args.out)
    size_in = sum(p.stat().st_size for p, _ in pairs)
    size_out = sum(c.stat().st_size for _, c in pairs)
    print(
        f"{len(pairs)} files: {size_in / 1e6:.1f} MB of originals (gzip) -> {size_out / 1e6:.2f} MB "
        f"({size_out / size_in:.1%}) in {args.out}"
    )
    if args.check:
        check(pairs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
