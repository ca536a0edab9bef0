"""``python -m skilllib run``: the book's pipeline on the synthetic cohort or on your recordings.

Exit status: 0 on success; 2 for a file that cannot be read or a bad option (one line on stderr,
no traceback); 3 when the run finished but too few trials were selected to find prototypes (results.json
is written, with every trial); 1 for an unexpected error (one line; ``--debug`` shows the traceback);
130 when interrupted.
"""
from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .data import DataFormatError
from .prototypes import DEFAULT_K
from .robots import ROBOT_NAMES
from .smoothness import DEFAULT_AMP_TH, DEFAULT_FC, DEFAULT_PADLEVEL


def _setting(text: str) -> dict[str, float]:
    """``fc=10`` or ``fc=10,amp_th=0.1,padlevel=4`` (a bare number is fc) -> a dict of SPARC parameters."""
    out: dict[str, float] = {}
    for part in text.split(","):
        key, sep, value = part.partition("=")
        key, value = (key.strip(), value.strip()) if sep else ("fc", key.strip())
        key = key.replace("-", "_")
        if key not in ("fc", "amp_th", "padlevel"):
            raise argparse.ArgumentTypeError(f"{text!r}: unknown SPARC parameter {key!r} (use fc, amp_th, padlevel)")
        try:
            out[key] = int(value) if key == "padlevel" else float(value)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: {key} = {value!r} is not a number") from None
    return out


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m skilllib",
                                description="Smoothness-based prototypes and their transfer to a robot arm.")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run the whole pipeline and write results.json and figures",
                       description="Read recordings (CSV: participant, trial, t, x, y, z, contact; s and m), "
                                   "compute features, find prototypes, transfer them to a robot arm.")
    r.add_argument("--data", metavar="FILE", help="recordings CSV (default: the book's synthetic cohort)")
    r.add_argument("--out", metavar="DIR", required=True, help="folder for results.json and the figures")
    r.add_argument("--k", type=int, default=DEFAULT_K, help=f"number of clusters (default {DEFAULT_K})")
    r.add_argument("--robot", default="simple6", choices=ROBOT_NAMES, help="robot arm (default simple6)")
    r.add_argument("--qd-max", type=float, nargs="+", metavar="RAD_S",
                   help="joint velocity limits in rad/s: one for all joints or one per joint "
                        "(default: the robot's)")
    r.add_argument("--qdd-max", type=float, nargs="+", metavar="RAD_S2",
                   help="joint acceleration limits in rad/s^2: one for all joints or one per joint "
                        "(default: the robot's; README)")
    r.add_argument("--tau-max", type=float, nargs="+", metavar="NM",
                   help="joint torque limits in N m, one for all joints or one per joint (arms with dynamics: "
                        "ur5, puma560, panda; default: the robot's)")
    r.add_argument("--scaling", choices=("raw", "standard"), default="raw",
                   help="features as they are (the paper) or standardised before K-means")
    r.add_argument("--seed", type=int, default=0, help="random_state of K-means (default 0)")
    r.add_argument("--fc", type=float, default=DEFAULT_FC, metavar="HZ",
                   help=f"SPARC's maximum cut-off frequency in Hz (default {DEFAULT_FC:g}, the paper's 0-20 Hz; "
                        "at most the Nyquist frequency of the recordings)")
    r.add_argument("--amp-th", type=float, default=DEFAULT_AMP_TH, metavar="FRACTION",
                   help=f"SPARC's amplitude threshold (default {DEFAULT_AMP_TH:g})")
    r.add_argument("--padlevel", type=int, default=DEFAULT_PADLEVEL, metavar="N",
                   help=f"SPARC's zero padding, nfft = 2**(ceil(log2 N) + padlevel) (default {DEFAULT_PADLEVEL})")
    r.add_argument("--sensitivity", type=_setting, nargs="+", metavar="SETTING",
                   help="compare the run with other SPARC settings, each like fc=10 or fc=10,amp_th=0.1 "
                        "(results.json sparc_sensitivity; chapter 3)")
    r.add_argument("--no-figures", action="store_true", help="write results.json only")
    r.add_argument("--quiet", action="store_true", help="no progress bars")
    r.add_argument("--debug", action="store_true", help="show the traceback of an unexpected error")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    from tqdm.auto import tqdm

    from .pipeline import OptionError, run, summary_lines

    units = {"features": " trial", "silhouette": " k", "transfer": " prototype"}

    def progress(items, desc):
        return tqdm(items, desc=desc, unit=units.get(desc, " item"), disable=args.quiet, leave=False,
                    file=sys.stderr)

    def one_or_all(values):
        return None if values is None else (values[0] if len(values) == 1 else values)

    qd_max = one_or_all(args.qd_max)
    try:
        result = run(args.data, args.out, k=args.k, robot=args.robot, qd_max=qd_max,
                     qdd_max=one_or_all(args.qdd_max), tau_max=one_or_all(args.tau_max), scaling=args.scaling,
                     random_state=args.seed, fc=args.fc, amp_th=args.amp_th, padlevel=args.padlevel,
                     sensitivity=args.sensitivity, progress=progress, write_figures=not args.no_figures)
    except (DataFormatError, OptionError, OSError) as e:  # the user's file, options or output folder
        if args.debug:
            raise
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except Exception as e:  # an unexpected failure: one line, the traceback only on request
        if args.debug:
            raise
        print(f"error: unexpected {type(e).__name__}: {e} (run again with --debug for the traceback)",
              file=sys.stderr)
        return 1
    print("\n".join(summary_lines(result)))
    n_fig = len(result.results.get("figures", []))
    print(f"wrote {args.out}/results.json" + ("" if args.no_figures else f" and {n_fig} figure files (PNG, SVG)"))
    return 0 if result.prototypes is not None else 3


if __name__ == "__main__":
    sys.exit(main())
