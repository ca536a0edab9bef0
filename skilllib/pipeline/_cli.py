"""``python -m skilllib run`` (or the ``skilllib`` command): the book's pipeline on the synthetic cohort or
on your recordings.

Exit status: 0 on success; 2 for a file that cannot be read, a bad option or an output folder that cannot
be used (one line on stderr, no traceback); 3 when the run finished but too few trials were selected to
find prototypes (results.json is written, with every trial, and one or two selected trials transferred as
they are); 1 for an unexpected error (one line;
``--debug`` shows the traceback); 130 when interrupted (Ctrl-C), at any point; 141 when standard output
was closed early (as ``| head``) or is full (``> /dev/full``), quietly; 143 when terminated (SIGTERM),
cleaned up as after Ctrl-C.

Start-up is kept light: ``--help`` and ``--version`` import neither pandas nor scikit-learn,
roboticstoolbox or matplotlib; those are imported when a run starts.
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
from collections.abc import Sequence
from pathlib import Path

from .. import __version__


def _setting(text: str) -> dict[str, float]:
    """``fc=10`` or ``fc=10,amp_th=0.1,padlevel=4`` (a bare number is fc) -> a dict of SPARC parameters."""
    from ..task import parse_setting

    try:
        return parse_setting(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _columns(text: str) -> dict[str, str]:
    """``time=t,px=x`` -> {"time": "t", "px": "x"}: the file's column names and the book's."""
    out: dict[str, str] = {}
    for part in text.split(","):
        old, sep, new = part.partition("=")
        if not sep or not old.strip() or not new.strip():
            raise argparse.ArgumentTypeError(f"{text!r}: write each mapping as old=new, separated by commas")
        out[old.strip()] = new.strip()
    return out


def _seed(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if not 0 <= value <= 2**32 - 1:
        raise argparse.ArgumentTypeError(f"{value} is outside 0 .. {2**32 - 1} (K-means' random_state)")
    return value


def _parser() -> argparse.ArgumentParser:
    from ..prototypes import DEFAULT_K
    from ..robot import ROBOT_NAMES
    from ..smoothness import DEFAULT_AMP_TH, DEFAULT_FC, DEFAULT_PADLEVEL

    p = argparse.ArgumentParser(
        prog="python -m skilllib", description="Smoothness-based prototypes and their transfer to a robot arm."
    )
    p.add_argument("--version", action="version", version=f"skilllib {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser(
        "run",
        help="run the whole pipeline and write results.json and figures",
        description="Read recordings (CSV: participant, trial, t, x, y, z, contact; s and m; or C3D, "
        "TRC, a folder of them), compute features, find prototypes, transfer them to a "
        "robot arm.",
    )
    r.add_argument(
        "--data",
        metavar="PATH",
        help="recordings: a CSV or tab/semicolon-separated table (also .gz, .zip, ...), a .c3d, .trc or Vicon "
        "Nexus CSV file (one trial), or a folder of them (default: the book's synthetic cohort)",
    )
    r.add_argument(
        "--out",
        metavar="DIR",
        required=True,
        help="folder for results.json and the figures (replaced as a whole when the run ends)",
    )
    g = r.add_argument_group("reading other formats (chapter 11)")
    g.add_argument(
        "--columns",
        type=_columns,
        metavar="OLD=NEW,...",
        help="rename the file's columns to participant, trial, t, x, y, z, contact",
    )
    g.add_argument(
        "--units",
        choices=("m", "cm", "mm"),
        help="unit of the positions (default: m, or the C3D/TRC/Nexus header's); a stated unit is believed",
    )
    g.add_argument(
        "--time-unit",
        choices=("s", "ms", "us"),
        help="unit of a table's time column (default: s); t is divided into seconds",
    )
    g.add_argument(
        "--sep",
        choices=(",", ";", "tab", "\\t", "\t"),
        metavar="SEP",
        help="the separator of a table: ',', ';' or 'tab' (default: detected from the first lines)",
    )
    g.add_argument(
        "--max-gap",
        type=float,
        metavar="S",
        help="fill gaps of missing, frozen or jumping positions up to S seconds by interpolation (default 0.1); "
        "a longer gap before contact makes a trial invalid, after contact cuts it",
    )
    g.add_argument("--fill", choices=("cubic", "linear"), help="how the short gaps are filled (default: cubic)")
    g.add_argument(
        "--up-axis", choices=("x", "y", "z", "-x", "-y", "-z"), help="the file's vertical axis, pointing up (default y)"
    )
    g.add_argument(
        "--marker",
        metavar="NAME[,NAME...]",
        help="the C3D/TRC/Nexus marker to use, with or without the subject prefix (default: the only one); "
        "several: the one of them that moves most in each file",
    )
    g.add_argument(
        "--contact-channel",
        metavar="NAME",
        help="C3D analog channel or event that marks contact (default: 'contact' when present)",
    )
    g.add_argument(
        "--contact-threshold",
        type=float,
        metavar="V",
        help="the C3D analog level above which a frame is in contact (default: halfway between the "
        "channel's minimum and maximum)",
    )
    g.add_argument(
        "--contact-height",
        type=float,
        metavar="M",
        help="without a contact signal: contact from the first sample at or below this height (m)",
    )
    g.add_argument(
        "--name-pattern",
        metavar="REGEX",
        help="for a folder: a regular expression with groups (?P<participant>...) and (?P<trial>...) "
        "matched against each file's name",
    )
    g.add_argument(
        "--contact-below",
        action="store_true",
        default=None,
        help="the contact channel is in contact below its threshold (a load cell that goes negative under load)",
    )
    t = r.add_argument_group("the task: segmentation, selection, features (chapter 15; docs/cli.md: Tasks)")
    t.add_argument(
        "--task",
        metavar="FILE|PRESET",
        help="a task file (.toml), a results.json to run again, or a preset (paper); the options below override it",
    )
    t.add_argument(
        "--start",
        metavar="RULE",
        help="where a movement starts: speed:0.05 (m/s, the default), speed:5%% (of the peak speed) or event:LABEL",
    )
    t.add_argument(
        "--end",
        metavar="RULE",
        help="where it ends: contact (the default), offset (speed back below the start threshold), offset:0.05, "
        "offset:5%%, event:LABEL, height-above:M or height-below:M (m, on the up axis)",
    )
    t.add_argument(
        "--hold",
        type=float,
        metavar="S",
        help="how long the speed stays below the offset threshold, and the shortest rest between movements "
        "(s; default 0.1)",
    )
    t.add_argument(
        "--split",
        action="store_true",
        default=None,
        help="a recording holds several movements: split it at rests (or at start/end events)",
    )
    t.add_argument(
        "--select",
        action="append",
        metavar="none|FEATURE=LO:HI",
        help="which trials are clustered: windows on per-trial features, repeatable (default "
        "contact_speed=0.3:0.7 when the end is contact, else none)",
    )
    t.add_argument(
        "--features",
        metavar="NAME,NAME[,...]",
        help="the clustering features (default pv,sparc; also ldlj, duration, contact_speed, peak_acc, path_length)",
    )
    r.add_argument(
        "--lowpass",
        metavar="auto|none|HZ",
        help="low-pass filter of the positions before differentiating: auto (default: Winter's residual "
        "analysis, only when the noise needs it), none, or a cut-off in Hz",
    )
    r.add_argument("--k", type=int, help=f"number of clusters (default {DEFAULT_K})")
    r.add_argument("--robot", choices=ROBOT_NAMES, help="robot arm (default simple6)")
    r.add_argument(
        "--qd-max",
        type=float,
        nargs="+",
        metavar="RAD_S",
        help="joint velocity limits in rad/s: one for all joints or one per joint (default: the robot's)",
    )
    r.add_argument(
        "--qdd-max",
        type=float,
        nargs="+",
        metavar="RAD_S2",
        help="joint acceleration limits in rad/s^2: one for all joints or one per joint (default: the robot's; README)",
    )
    r.add_argument(
        "--tau-max",
        type=float,
        nargs="+",
        metavar="NM",
        help="joint torque limits in N m, one for all joints or one per joint (arms with dynamics: "
        "ur5, puma560, panda; default: the robot's)",
    )
    r.add_argument(
        "--scaling",
        choices=("raw", "standard"),
        help="features as they are (the paper, the default) or standardised before K-means",
    )
    r.add_argument("--seed", type=_seed, help="random_state of K-means, 0 .. 2**32-1 (default 0)")
    r.add_argument(
        "--fc",
        type=float,
        metavar="HZ",
        help=f"SPARC's maximum cut-off frequency in Hz (default {DEFAULT_FC:g}, the paper's 0-20 Hz; "
        "below the Nyquist frequency of the recordings)",
    )
    r.add_argument(
        "--amp-th",
        type=float,
        metavar="FRACTION",
        help=f"SPARC's amplitude threshold (default {DEFAULT_AMP_TH:g})",
    )
    r.add_argument(
        "--padlevel",
        type=int,
        metavar="N",
        help=f"SPARC's zero padding, nfft = 2**(ceil(log2 N) + padlevel) (default {DEFAULT_PADLEVEL})",
    )
    r.add_argument(
        "--sensitivity",
        type=_setting,
        nargs="+",
        metavar="SETTING",
        help="compare the run with other SPARC settings, each like fc=10 or fc=10,amp_th=0.1 "
        "(results.json sparc_sensitivity; chapter 6)",
    )
    g = r.add_argument_group("large corpora on a Dask cluster (docs/cli.md: Large corpora)")
    g.add_argument(
        "--workers",
        type=int,
        metavar="N",
        help="compute the features of --data, a folder of Parquet files, on a local Dask cluster of N worker processes",
    )
    g.add_argument(
        "--scheduler", metavar="ADDRESS", help="the same on a running Dask cluster (e.g. tcp://10.0.0.5:8786)"
    )
    r.add_argument("--no-figures", action="store_true", help="write results.json only")
    r.add_argument("--quiet", action="store_true", help="no progress bars (they are shown only on a terminal)")
    r.add_argument("--debug", action="store_true", help="show the traceback of an unexpected error")
    return p


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return False
    return os.access(folder, os.W_OK)


def _matplotlib_dir() -> str | None:
    """A private, writable configuration and cache folder for matplotlib (``MPLCONFIGDIR``, removed at the
    end of the run) when its own (``~/.config/matplotlib``, ``~/.cache/matplotlib`` or the XDG ones) cannot
    be written, as with a read-only HOME; else None. Otherwise matplotlib, which roboticstoolbox imports even
    when no figure is drawn, prints warnings on stderr before anything the run says."""
    if "matplotlib" in sys.modules or os.environ.get("MPLCONFIGDIR"):
        return None
    try:
        home = Path.home()
    except (KeyError, RuntimeError):
        home = None
    config = os.environ.get("XDG_CONFIG_HOME") or (home and home / ".config")
    cache = os.environ.get("XDG_CACHE_HOME") or (home and home / ".cache")
    if config and cache and all(_writable(Path(d) / "matplotlib") for d in (config, cache)):
        return None
    return tempfile.mkdtemp(prefix="skilllib-matplotlib-")


def _run(args: argparse.Namespace) -> int:
    private = _matplotlib_dir()
    if private is None:
        return _run_analysis(args)
    os.environ["MPLCONFIGDIR"] = private  # before roboticstoolbox (and with it matplotlib) is imported
    try:
        return _run_analysis(args)
    finally:
        os.environ.pop("MPLCONFIGDIR", None)
        shutil.rmtree(private, ignore_errors=True)


def _run_analysis(args: argparse.Namespace) -> int:
    from tqdm.auto import tqdm

    from ..recordings import DataFormatError
    from ._output import OutputError
    from ._run import OptionError, run
    from ._summary import summary_lines

    units = {"features": " trial", "silhouette": " k", "transfer": " prototype"}
    show = not args.quiet and sys.stderr.isatty()

    def progress(items, desc):
        return tqdm(items, desc=desc, unit=units.get(desc, " item"), disable=not show, leave=False, file=sys.stderr)

    def one_or_all(values):
        return None if values is None else (values[0] if len(values) == 1 else values)

    qd_max = one_or_all(args.qd_max)
    read_options = {
        "columns": args.columns,
        "units": args.units,
        "up_axis": args.up_axis,
        "sep": args.sep,
        "time_unit": args.time_unit,
        "marker": args.marker,
        "contact_channel": args.contact_channel,
        "contact_threshold": args.contact_threshold,
        "contact_height": args.contact_height,
        "name_pattern": args.name_pattern,
        "contact_below": args.contact_below,
    }
    read_options.update(
        {k: v for k, v in (("max_gap_s", args.max_gap), ("fill", args.fill)) if v is not None}
    )  # real-data defects (skilllib.recordings.repair_trial): only when given
    try:
        result = run(
            args.data,
            args.out,
            task=args.task,
            start=args.start,
            end=args.end,
            hold=args.hold,
            split=args.split,
            select=args.select,
            features=args.features,
            k=args.k,
            robot=args.robot,
            qd_max=qd_max,
            qdd_max=one_or_all(args.qdd_max),
            tau_max=one_or_all(args.tau_max),
            scaling=args.scaling,
            random_state=args.seed,
            fc=args.fc,
            amp_th=args.amp_th,
            padlevel=args.padlevel,
            sensitivity=args.sensitivity,
            lowpass=args.lowpass,
            read_options=read_options,
            progress=progress,
            write_figures=not args.no_figures,
            workers=args.workers,
            scheduler=args.scheduler,
        )
    except (DataFormatError, OptionError, OutputError, OSError) as e:  # the user's file, options or folder
        if args.debug:
            raise
        print(f"error: {e}", file=sys.stderr)
        return 2
    except Exception as e:  # an unexpected failure: one line, the traceback only on request
        if args.debug:
            raise
        print(f"error: unexpected {type(e).__name__}: {e} (run again with --debug for the traceback)", file=sys.stderr)
        return 1
    print("\n".join(summary_lines(result)))
    n_fig = len(result.results.get("figures", []))
    print(f"wrote {args.out}/results.json" + ("" if args.no_figures else f" and {n_fig} figure files (PNG, SVG)"))
    return 0 if result.prototypes is not None else 3


def run_command(*args: str) -> subprocess.CompletedProcess:
    """Run ``python -m skilllib run --quiet ARGS`` in a new process, as a user would in a terminal.

    Parameters
    ----------
    \\*args : str
        The options after ``run`` (text), e.g. ``"--data", "rec.csv", "--out", "results"``.

    Returns
    -------
    subprocess.CompletedProcess
        What the command printed (``stdout``, ``stderr``; text) and its exit status (``returncode``,
        dimensionless; the statuses of :func:`main`).
    """
    command = [sys.executable, "-m", "skilllib", "run", "--quiet", *args]
    return subprocess.run(command, capture_output=True, text=True, check=False)


class _Terminated(BaseException):
    """SIGTERM, raised where the run is, so that it cleans up as after Ctrl-C (a BaseException: no
    ``except Exception`` on the way swallows it)."""


def _on_sigterm(signum: int, frame: object) -> None:
    raise _Terminated


def main(argv: Sequence[str] | None = None) -> int:
    """The command line ``python -m skilllib run ...`` (the ``skilllib`` command): parse, run, print a summary.

    The exit statuses are those of the module docstring; a user's error (a file that cannot be read, a bad
    option, an output folder that cannot be used) is one line on stderr, never a traceback.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments after the program's name (text); None for ``sys.argv[1:]``.

    Returns
    -------
    int
        The exit status: 0 success, 1 unexpected error, 2 the user's error, 3 too few selected trials for
        prototypes, 130 interrupted (Ctrl-C), 141 standard output closed early or full, 143 terminated (SIGTERM)
        (dimensionless).

    Raises
    ------
    SystemExit
        From argparse, for ``--help``, ``--version`` (status 0) or arguments it cannot parse (status 2).
    """
    in_main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _on_sigterm) if in_main_thread else None
    try:
        args = _parser().parse_args(argv)
        code = _run(args)
        sys.stdout.flush()
        return code
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except _Terminated:  # the output folder is left as it was, as after Ctrl-C
        print("error: terminated", file=sys.stderr)
        return 143
    except OSError as e:  # stdout closed early (| head) or full (> /dev/full): end quietly, as Unix tools do
        if not isinstance(e, BrokenPipeError) and e.errno not in (errno.ENOSPC, errno.EIO, errno.EBADF):
            raise
        with contextlib.suppress(OSError, ValueError):  # what is still buffered goes nowhere at exit
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        return 141
    finally:
        if in_main_thread:
            signal.signal(signal.SIGTERM, previous)
