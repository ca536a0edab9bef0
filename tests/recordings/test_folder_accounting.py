"""Every entry of a folder of trial files is accounted for (issue 23): a trial, an ``invalid`` trial with
its reason (a file that cannot be read), or a skipped entry with its reason (hidden, an unlistable
sub-folder, a broken link, too deep, another format, a name that gives no ids). Nothing is dropped without
a word; one unreadable file never stops the run.

The tests run as root in the project's container, where ``chmod 000`` does not stop reading or listing:
unreadable files and folders are simulated by making ``Path.open``, ``Path.read_bytes`` or ``os.scandir``
raise PermissionError for one path (the logic under test is what the reader does with that error); one
test uses a real ``chmod 000`` and runs only when not root.
"""

from __future__ import annotations

import json
import os
import pathlib
from pathlib import Path

import numpy as np
import pytest

from skilllib.pipeline import main
from skilllib.recordings import DataFormatError, SkippedFile, load_recordings, read_folder, write_trc

T = np.arange(120) / 100  # s, 100 Hz
POS = np.column_stack([0 * T, 0.3 - 0.2 * np.clip(T - 0.3, 0, 0.5), 0 * T])  # m: rest, a descent, rest
OPTS = dict(contact_height=0.2)


def _trc(path: Path) -> Path:
    return write_trc(path, {"tip": POS}, T)


def _csv(path: Path) -> Path:
    """A one-trial CSV (columns t, x, y, z)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = "".join(f"{t:.2f},{x:.4f},{y:.4f},{z:.4f}\n" for t, (x, y, z) in zip(T, POS))
    path.write_text("t,x,y,z\n" + rows)
    return path


def _lab(root: Path, participants: str = "AB", trials: int = 5) -> list[Path]:
    """``root/<participant>/<trial>.trc``: ``len(participants) * trials`` readable files."""
    return [_trc(root / p / f"{k}.trc") for p in participants for k in range(1, trials + 1)]


def _accounted(root: Path, rec) -> dict[str, str]:
    """Every file under ``root`` (links too) -> ``"trial"``, ``"invalid: reason"`` or ``"skipped: reason"``;
    asserts that each is exactly one of them."""
    files = sorted(
        p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file() or p.is_symlink() or p.is_dir()
    )
    skipped = {q.path.rstrip("/"): q.reason for q in rec.skipped}
    invalid = {
        r.split(": ", 1)[0].removeprefix("file "): r.split(": ", 1)[1]
        for r in rec.trials["reason"]
        if r.startswith("file ")
    }
    got = {}
    for f in files:
        if any(f.startswith(s + "/") for s in skipped):  # inside a folder skipped whole
            continue
        kind = [k for k, where in (("skipped", skipped), ("invalid", invalid)) if f in where]
        if kind:
            assert len(kind) == 1, f
            got[f] = f"{kind[0]}: {(skipped if kind[0] == 'skipped' else invalid)[f]}"
        elif (root / f).is_file():
            got[f] = "trial"
    assert sum(v == "trial" for v in got.values()) == len(rec.trials) - len(invalid), got  # one trial per file
    return got


def test_a_plain_folder_has_nothing_skipped(tmp_path):
    _lab(tmp_path)
    rec = load_recordings(tmp_path, **OPTS)
    assert len(rec) == 10 and rec.skipped == ()
    assert set(_accounted(tmp_path, rec).values()) == {"trial"}


def test_other_inputs_have_no_skipped_list(tmp_path):
    rec = load_recordings(_trc(tmp_path / "P1_1.trc"), **OPTS)
    assert rec.skipped is None


def test_hidden_files_and_folders_are_skipped_and_said(tmp_path):
    """macOS writes ``._name.c3d`` (AppleDouble) beside each file copied to a foreign disk: not a trial."""
    _lab(tmp_path, "A", 3)
    (tmp_path / "A" / "._1.trc").write_bytes(b"\x00\x05\x16\x07 AppleDouble")
    (tmp_path / ".DS_Store").write_bytes(b"\x00")
    _trc(tmp_path / ".backup" / "1.trc")
    rec = load_recordings(tmp_path, **OPTS)
    assert len(rec) == 3
    assert list(rec.skipped) == [
        SkippedFile(".backup/", "hidden folder"),
        SkippedFile(".DS_Store", "hidden file"),
        SkippedFile("A/._1.trc", "hidden file"),
    ]


def test_a_dangling_link_among_eleven_files_is_named(tmp_path):
    """Issue 23: 11 files, one a link to a file that is gone: 10 trials and a word on the eleventh."""
    _lab(tmp_path)
    os.symlink("../gone/6.trc", tmp_path / "B" / "6.trc")
    rec = load_recordings(tmp_path, **OPTS)
    assert len(rec) == 10
    assert list(rec.skipped) == [SkippedFile("B/6.trc", "broken link to ../gone/6.trc")]
    assert sum(v == "trial" for v in _accounted(tmp_path, rec).values()) == 10


def test_a_link_to_a_file_is_read(tmp_path):
    _lab(tmp_path, "A", 2)
    os.symlink(tmp_path / "A" / "1.trc", tmp_path / "A" / "3.trc")
    rec = load_recordings(tmp_path, **OPTS)
    assert rec.keys() == [("A", "1"), ("A", "2"), ("A", "3")] and rec.skipped == ()


def test_a_sub_folder_that_cannot_be_listed_is_said(tmp_path, monkeypatch):
    """Issue 23: a participant's folder without read permission lost its trials silently (Path.rglob
    ignores the error). Listing it raises PermissionError here (simulated: root lists any folder)."""
    _lab(tmp_path, "ABC", 2)
    locked = str(tmp_path / "B")
    scandir = os.scandir

    def refuse(path="."):
        if os.fspath(path) == locked:
            raise PermissionError(13, "Permission denied", locked)
        return scandir(path)

    monkeypatch.setattr(os, "scandir", refuse)
    rec = load_recordings(tmp_path, **OPTS)
    assert rec.keys() == [("A", "1"), ("A", "2"), ("C", "1"), ("C", "2")]
    assert list(rec.skipped) == [SkippedFile("B/", "cannot list the folder: Permission denied")]


def test_the_folder_itself_cannot_be_listed_is_one_error(tmp_path, monkeypatch):
    _lab(tmp_path, "A", 2)
    scandir = os.scandir

    def refuse(path="."):
        if os.fspath(path) == str(tmp_path):
            raise PermissionError(13, "Permission denied", str(tmp_path))
        return scandir(path)

    monkeypatch.setattr(os, "scandir", refuse)
    with pytest.raises(DataFormatError, match="cannot list the folder: Permission denied"):
        read_folder(tmp_path)


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root reads any file and folder")
def test_real_permissions(tmp_path):
    """The same as the simulated tests, with chmod 000 (only where it stops reading)."""
    _lab(tmp_path, "AB", 5)
    (tmp_path / "A" / "3.trc").chmod(0)
    (tmp_path / "B").chmod(0)
    try:
        rec = load_recordings(tmp_path, **OPTS)
    finally:
        (tmp_path / "B").chmod(0o755)
        (tmp_path / "A" / "3.trc").chmod(0o644)
    st = rec.trials.set_index(["participant", "trial"])
    assert st.loc[("A", "3"), "status"] == "invalid" and "Permission denied" in st.loc[("A", "3"), "reason"]
    assert list(rec.skipped) == [SkippedFile("B/", "cannot list the folder: Permission denied")]


@pytest.mark.parametrize("refused", ["open", "read_bytes"])
def test_one_unreadable_file_of_ten_is_an_invalid_trial_not_an_error(tmp_path, monkeypatch, refused):
    """Issue 23: one file of 10 without read permission stopped the whole run (exit 2, Permission denied);
    it is an ``invalid`` trial with that reason, as the README promises for folders. Simulated: opening
    the file (``open``: the check before reading) or reading it (``read_bytes``: the TRC reader) raises
    PermissionError, as it does for a user without the permission."""
    _lab(tmp_path)
    bad = tmp_path / "B" / "4.trc"
    original = getattr(pathlib.Path, refused)

    def refuse(self, *args, **kwargs):
        if self == bad:
            raise PermissionError(13, "Permission denied", str(self))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(pathlib.Path, refused, refuse)
    rec = load_recordings(tmp_path, **OPTS)
    assert len(rec) == 10 and rec.skipped == ()
    st = rec.trials.set_index(["participant", "trial"])
    assert st.loc[("B", "4"), "status"] == "invalid"
    assert st.loc[("B", "4"), "reason"] == "file B/4.trc: cannot be read: Permission denied"
    assert (rec.trials["status"] != "invalid").sum() == 9


def test_an_unreadable_csv_names_the_permission(tmp_path, monkeypatch):
    """A one-trial CSV that cannot be opened: 'Permission denied', not a decompression error."""
    for k in (1, 2):
        _csv(tmp_path / "A" / f"{k}.csv")
    bad = tmp_path / "A" / "2.csv"
    original = pathlib.Path.open

    def refuse(self, *args, **kwargs):
        if self == bad:
            raise PermissionError(13, "Permission denied", str(self))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(pathlib.Path, "open", refuse)
    rec = load_recordings(tmp_path, **OPTS)
    assert rec.trials["reason"].tolist() == ["", "file A/2.csv: cannot be read: Permission denied"]


def test_too_deep_other_formats_names_and_duplicates_are_each_accounted_for(tmp_path):
    _lab(tmp_path, "A", 3)
    _trc(tmp_path / "A" / "raw" / "4.trc")  # too deep
    _trc(tmp_path / "A" / "raw" / "old" / "5.trc")  # deeper still
    (tmp_path / "A" / "notes.txt").write_text("participant A was left-handed\n")
    (tmp_path / "trials.xlsx").write_bytes(b"PK\x03\x04")
    _csv(tmp_path / "A" / "1.csv")  # a second file for A, 1: an invalid trial, as before
    _trc(tmp_path / "nounderscore.trc")  # directly in the folder, no ids in its name
    _csv(tmp_path / "B_1.csv")
    rec = load_recordings(tmp_path, **OPTS)
    got = _accounted(tmp_path, rec)
    assert got == {
        "A/1.csv": "trial",  # the first of the two in order of names
        "A/1.trc": "invalid: participant 'A' trial '1' is also " + str(tmp_path / "A" / "1.csv"),
        "A/2.trc": "trial",
        "A/3.trc": "trial",
        "A/notes.txt": "skipped: not a C3D, TRC, Nexus or CSV file",
        "A/raw/4.trc": f"skipped: in a sub-sub-folder: only {tmp_path}/<participant>/<file> is read",
        "A/raw/old/5.trc": f"skipped: in a sub-sub-folder: only {tmp_path}/<participant>/<file> is read",
        "B_1.csv": "trial",
        "nounderscore.trc": (
            "skipped: cannot tell participant and trial from the name 'nounderscore': name it PARTICIPANT_TRIAL, "
            "put it in a sub-folder named after the participant, or give a name pattern"
        ),
        "trials.xlsx": "skipped: not a C3D, TRC, Nexus or CSV file",
    }
    assert set(rec.trials["participant"]) == {"A", "B"}  # no "(no id)" participant for the files without ids


def test_names_that_do_not_match_the_pattern_are_skipped(tmp_path):
    _trc(tmp_path / "sub-07_run-2.trc")
    _trc(tmp_path / "calibration.trc")
    rec = load_recordings(tmp_path, name_pattern=r"sub-(?P<participant>\w+)_run-(?P<trial>\d+)", **OPTS)
    assert rec.keys() == [("07", "2")]
    assert [q.path for q in rec.skipped] == ["calibration.trc"]
    assert rec.skipped[0].reason.startswith("name 'calibration' does not match the name pattern")


def test_a_folder_with_nothing_readable_says_what_it_skipped(tmp_path):
    (tmp_path / "notes.txt").write_text("x")
    with pytest.raises(DataFormatError, match=r"no \.c3d.*\(1 skipped; first: notes\.txt: not a C3D"):
        read_folder(tmp_path)
    _trc(tmp_path / "calibration.trc")
    with pytest.raises(DataFormatError, match=r"none of the 1 files could be read \(first: .*calibration\.trc: name"):
        read_folder(tmp_path, name_pattern=r"sub-(?P<trial>\d+)")


def test_run_reports_the_files_found_read_and_skipped(tmp_path, capsys):
    """The summary counts the folder's files and lists the skipped ones (at most 10, then how many more);
    results.json's dataset has n_files and skipped_files."""
    root = tmp_path / "lab"
    _lab(root, "AB", 3)
    for k in range(12):
        (root / "A" / f"._{k}.trc").write_bytes(b"\x00")
    os.symlink("gone.trc", root / "B" / "9.trc")
    out = tmp_path / "out"
    code = main(["run", "--quiet", "--data", str(root), "--out", str(out), "--no-figures", "--contact-height", "0.2"])
    printed = capsys.readouterr().out
    assert code in (0, 3)
    assert "files found: 19, trials read: 6, files skipped: 13" in printed
    assert "  skipped A/._0.trc: hidden file" in printed and "  skipped A/._9.trc: hidden file" in printed
    assert "  and 3 more (results.json dataset.skipped_files)" in printed
    dataset = json.loads((out / "results.json").read_text())["dataset"]
    assert dataset["n_files"] == 19 and dataset["n_trials"] == 6
    assert len(dataset["skipped_files"]) == 13
    assert {"path": "B/9.trc", "reason": "broken link to gone.trc"} in dataset["skipped_files"]
    assert all(set(q) == {"path", "reason"} for q in dataset["skipped_files"])


def test_run_on_a_file_has_no_file_counts(tmp_path, capsys):
    out = tmp_path / "out"
    data = _trc(tmp_path / "P1_1.trc")
    main(["run", "--quiet", "--data", str(data), "--out", str(out), "--no-figures", "--contact-height", "0.2"])
    assert "files found" not in capsys.readouterr().out
    dataset = json.loads((out / "results.json").read_text())["dataset"]
    assert "n_files" not in dataset and "skipped_files" not in dataset


def test_run_with_one_unreadable_file_of_ten_exits_as_usual(tmp_path, capsys, monkeypatch):
    """Issue 23: the run stopped with exit 2 (Permission denied); it runs, that trial invalid with the reason
    (simulated as above: reading the file raises PermissionError)."""
    root = tmp_path / "lab"
    _lab(root)
    bad = root / "A" / "2.trc"
    original = pathlib.Path.read_bytes

    def refuse(self):
        if self == bad:
            raise PermissionError(13, "Permission denied", str(self))
        return original(self)

    monkeypatch.setattr(pathlib.Path, "read_bytes", refuse)
    out = tmp_path / "out"
    code = main(["run", "--quiet", "--data", str(root), "--out", str(out), "--no-figures", "--contact-height", "0.2"])
    printed = capsys.readouterr().out
    assert code in (0, 3) and "files found: 10, trials read: 10, files skipped: 0" in printed
    trials = {(t["participant"], t["trial"]): t for t in json.loads((out / "results.json").read_text())["trials"]}
    assert trials["A", "2"]["status"] == "invalid"
    assert trials["A", "2"]["reason"] == "file A/2.trc: cannot be read: Permission denied"
