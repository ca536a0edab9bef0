"""The human summary of a pipeline run: counts, the commonest reasons, k, prototypes, feasibility.

``python -m skilllib run`` prints :func:`summary_lines` at the end of a run; :func:`reason_kind` groups
trials' reasons that differ only in their numbers.
"""

from __future__ import annotations

import re
from collections import Counter
from typing import TYPE_CHECKING

import numpy as np

from ..recordings import MAX_RANGE_M
from ..robot import limits_text

if TYPE_CHECKING:
    from ._run import PipelineRun


def _verdict(tr, a) -> str:
    """A transfer's verdict for a summary line: feasible, the time scaling it needs, or its flags."""
    dyn = a.dynamics
    if dyn.feasible:
        return "feasible"
    return (
        f"needs time scaling x{dyn.time_scale:.2f} ({dyn.binding_limit} binds)"
        if not tr.flags
        else (f"{len(tr.flags)} flag(s)")
    )


def _described(row: dict, features: tuple[str, ...]) -> str:
    """A prototype by its clustering features: ``PV 0.52 m/s, SPARC -1.55`` (the paper's), ``LDLJ -9.4``."""
    from ..features import FEATURE_UNITS

    out = []
    for f in features:
        if f == "pv":
            out.append(f"PV {row[f]:.2f} m/s")
        elif f == "sparc":
            out.append(f"SPARC {row[f]:.2f}")
        else:
            label, unit = FEATURE_UNITS.get(f, (f, ""))
            out.append(f"{label} {row[f]:.3g}" + (f" {unit}" if unit else ""))
    return ", ".join(out)


def _task_lines(task: dict | None) -> list[str]:
    """One line on the task when it is not the paper's: its rules, selection and features."""
    if not task:
        return []
    seg, sel, clu = task["segment"], task["select"]["windows"], task["cluster"]
    paper = (
        seg["start"] == "speed:0.05"
        and seg["end"] == "contact"
        and not seg["split"]
        and sel == ["contact_speed=0.3:0.7"]
        and clu["features"] == ["pv", "sparc"]
    )
    if paper:
        return []
    windows = "every valid trial" if sel == "none" else " and ".join(sel)
    split = ", several movements per recording (split)" if seg["split"] else ""
    return [
        f"task {task['name']}: start {seg['start']}, end {seg['end']}{split}; selected: {windows}; "
        f"clustered on {', '.join(clu['features'])}"
    ]


def summary_lines(run_: PipelineRun) -> list[str]:
    """A short human summary of a run: counts, commonest reasons, k, prototypes, feasibility.

    Parameters
    ----------
    run\\_ : PipelineRun
        The finished run, as :func:`skilllib.pipeline.run` returns it.

    Returns
    -------
    list of str
        The lines, without newlines (text): PV in m/s, peak joint velocities in rad/s, the limits with
        their units, the sampling rate in Hz.
    """
    f = run_.features
    counts = f["status"].value_counts()
    fs = run_.recordings.fs
    rate = f"at {fs:.4g} Hz (from the time stamps)" if np.isfinite(fs) else "at an unknown sampling rate"
    lines = (
        _files_lines(run_.results["dataset"])
        + _task_lines(run_.results.get("task"))
        + [
            f"trials read: {len(f)} from {run_.results['dataset']['n_participants']} participant(s) {rate}",
            (
                f"selected: {counts.get('selected', 0)}, excluded: {counts.get('excluded', 0)}, "
                f"invalid: {counts.get('invalid', 0)}"
            ),
        ]
    )
    if "repairs" in f.columns and (f["repairs"] != "").any():
        rep = f["repairs"] != ""
        lines.append(
            f"repaired: {int(rep.sum())} trial(s), {int(f['n_repaired'].sum())} sample(s) replaced by interpolation "
            f"(stale leading frames, frozen positions, jumps, gaps; trials[].repairs)"
        )
    for status in ("invalid", "excluded"):
        reasons = Counter(reason_kind(r) for r in f.loc[f["status"] == status, "reason"])
        if reasons:
            top = "; ".join(f"{n} x {r}" for r, n in reasons.most_common(3))
            lines.append(f"  commonest {status} reasons: {top}")
    if run_.prototypes is not None:
        fit = run_.prototypes
        how = (
            ""
            if fit.silhouette_estimate is None
            else f" (estimate, SD {fit.silhouette_estimate.sd:.3f} over subsamples)"
        )
        lines.append(f"k = {fit.k} clusters ({fit.scaling} features), average silhouette {fit.silhouette:.3f}{how}")
        for c, (tr, a) in enumerate(zip(run_.transfers, run_.assessments)):
            p = {col: fit.prototypes.at[c, col] for col in fit.prototypes.columns}
            verdict = _verdict(tr, a)
            peak = f"{np.nanmax(tr.peak_abs_qd):.2f}" if np.isfinite(tr.peak_abs_qd).any() else "n/a"
            lines.append(
                f"  cluster {c}: size {fit.sizes[c]}, prototype participant {p['participant']} trial "
                f"{p['trial']} ({_described(p, fit.features)}); "
                f"peak |qd| {peak} rad/s, {verdict}"
            )
        n_ok = sum(a.dynamics.feasible for a in run_.assessments)
        lines.append(
            f"feasibility on {run_.transfers[0].robot} ({limits_text(run_.assessments[0].dynamics)}): "
            f"{n_ok} of {fit.k} prototypes feasible as recorded"
        )
    elif run_.transfers:  # too few selected trials to cluster: each was transferred as it is
        for c, (tr, a) in enumerate(zip(run_.transfers, run_.assessments)):
            p, trial = run_.transferred[c]
            peak = f"{np.nanmax(tr.peak_abs_qd):.2f}" if np.isfinite(tr.peak_abs_qd).any() else "n/a"
            lines.append(
                f"  selected trial {c}: participant {p} trial {trial}; peak |qd| {peak} rad/s, {_verdict(tr, a)}"
            )
        n_ok = sum(a.dynamics.feasible for a in run_.assessments)
        lines.append(
            f"feasibility on {run_.transfers[0].robot} ({limits_text(run_.assessments[0].dynamics)}): "
            f"{n_ok} of {len(run_.transfers)} selected trials feasible as recorded (no clusters)"
        )
    if run_.sensitivity is not None:
        sens = run_.sensitivity
        lines.append(f"SPARC sensitivity, against this run's {sens.reference.label}:")
        for label, c in sens.comparison().iterrows():
            lines.append(
                f"  {label}: SPARC changed in {int(c['changed'])} of {int(c['of'])} selected trials (mean |change| "
                f"{c['mean |change|']:.3f}, SD across trials {c['reference SD']:.3f}); ARI {c['ARI']:.2f} "
                f"with this run's k = {sens.k} partition; {int(c['prototypes kept'])} of {sens.k} prototypes kept"
            )
    lines += [f"note: {m}" for m in run_.messages]
    return lines


#: The most skipped files of a folder the summary lists (all of them are in results.json).
MAX_SKIPPED_LINES = 10


def _files_lines(dataset: dict) -> list[str]:
    """For a folder input: how many files it holds, read and skipped, and the skipped ones with their reason
    (at most :data:`MAX_SKIPPED_LINES`); nothing for other inputs."""
    if "n_files" not in dataset:
        return []
    skipped = dataset["skipped_files"]
    n_read = dataset["n_files"] - len(skipped)
    lines = [f"files found: {dataset['n_files']}, trials read: {n_read}, files skipped: {len(skipped)}"]
    lines += [f"  skipped {q['path']}: {q['reason']}" for q in skipped[:MAX_SKIPPED_LINES]]
    if len(skipped) > MAX_SKIPPED_LINES:
        lines.append(f"  and {len(skipped) - MAX_SKIPPED_LINES} more (results.json dataset.skipped_files)")
    return lines


#: Reasons whose numbers differ from trial to trial, and the kind they are counted as in the summary.
_REASON_KINDS = (
    (r"contact speed \S+ m/s (below|above) (\S+ m/s)", r"contact speed \1 \2"),
    (r"sampled at ", "sampled at another rate than the file"),
    (r"positions span ", f"positions span more than {MAX_RANGE_M:g} m"),
    (r"in contact from sample ", "in contact from the start: no approach recorded"),
)


def reason_kind(reason: str) -> str:
    """A trial's reason without its trial-specific parts (line numbers, values), so that like reasons are
    counted together: ``"time goes backwards at line 12 (t = ...)"`` -> ``"time goes backwards"``.

    Parameters
    ----------
    reason : str
        The reason (text), as in the feature table or results.json.

    Returns
    -------
    str
        Its kind (text).
    """
    s = str(reason)
    for pattern, kind in _REASON_KINDS:
        m = re.match(pattern, s)
        if m:
            return m.expand(kind)
    s = s.split(":")[0]
    s = re.sub(r"\s*\([^)]*\d[^)]*\)", "", s)  # parentheses with numbers: "(3; need at least 5)"
    s = re.sub(r"\s+at (line|row) \d+.*$", "", s)
    return re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "N", s).strip()
