"""The whole pipeline of the paper on one recordings file: ``python -m skilllib run``.

Steps (each a skilllib function the chapters also call): read and validate the recordings
(:mod:`skilllib.recordings`); segment every trial and compute its features, status and reason
(:mod:`skilllib.features`); silhouette sweep and K-means prototypes on the selected trials' (PV, SPARC)
tuples (:mod:`skilllib.prototypes`); joint velocities of every prototype on a robot arm
(:mod:`skilllib.robot`), its accelerations, torques, limits, time scaling and executed motion
(:mod:`skilllib.robot`). :func:`run` returns the results dictionary that is
written to ``results.json`` (schema in docs/results.md) and writes the figures beside it.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .. import __version__
from .. import prototypes as pt
from ..datasets import cohort_path
from ..features import (
    PAPER_START,
    EndRule,
    Lowpass,
    StartRule,
    Window,
    apply_selection,
    parse_lowpass,
    run_lowpass,
    segment,
    select,
    trial_features,
)
from ..prototypes import SparcSensitivity, json_value, sparc_sensitivity
from ..recordings import Recordings, load_recordings
from ..robot import (
    Arm,
    Assessment,
    TransferResult,
    assess,
    get_robot,
    transfer,
    transfer_block,
)
from ..task import PAPER_TASK, Task, TaskError, load_task
from ._output import check_output, output_folder, write_json_atomic
from ._trials_file import in_json, trials_block, write_trials

#: The book's synthetic cohort (default input), shipped with skilllib (:mod:`skilllib.datasets`).
DEFAULT_DATA = cohort_path()

#: Fewest selected trials the clustering step accepts (K-means with k = 2 and a silhouette need 3).
MIN_SELECTED = 3

#: The version of results.json's layout (docs/results.md): 2 since ``feasible`` and ``time_scale``
#: cover every limit checked (in 1 they were the velocity limits', beside ``feasible_all_limits`` and
#: ``time_scale_all_limits``).
SCHEMA_VERSION = 2

#: More trials than this fraction invalid with "no rest before onset": the summary suggests why.
NO_REST_FRACTION = 0.2

Progress = Callable[[Sequence[Any], str], Any]


class OptionError(ValueError):
    """An option of :func:`run` is wrong; checked before the data are read (``fc`` against the Nyquist
    frequency of the recordings once their sampling rate is known)."""


def _no_progress(items: Sequence[Any], desc: str) -> Sequence[Any]:
    return items


@dataclass
class PipelineRun:
    """Everything one run computed: the results dictionary and the objects behind it."""

    results: dict[str, Any]
    recordings: Recordings
    features: pd.DataFrame
    sweep: pt.SilhouetteSweep | None = None
    prototypes: pt.PrototypeResult | None = None
    transfers: list[TransferResult] = field(default_factory=list)
    profiles: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    messages: list[str] = field(default_factory=list)
    sensitivity: SparcSensitivity | None = None
    assessments: list[Assessment] = field(default_factory=list)
    task: Task = PAPER_TASK
    transferred: list[tuple[str, str]] = field(default_factory=list)  # (participant, trial) of each transfer


def _is_shipped_cohort(given: Any) -> bool:
    """Whether the run's data are the book's synthetic cohort (its figures say so)."""
    if given is None:
        return True
    return isinstance(given, (str, Path)) and Path(given).resolve() == DEFAULT_DATA.resolve()


#: The line every figure of a run on the shipped cohort carries.
SYNTHETIC_NOTE = "Synthetic data: the book's generated cohort, not the paper's recordings (which are not public)."


def _display_path(given: Any) -> str:
    """The data for results.json: the path as given, ``<DataFrame>``, or the shipped cohort's name."""
    if given is None:
        return "skilllib/datasets/cohort.csv"
    if isinstance(given, (str, Path)):
        return str(given)
    return getattr(given, "source", "<DataFrame>")


def choose_k(requested: int, sweep: pt.SilhouetteSweep) -> tuple[int, str | None]:
    """The k to use: ``requested`` if the sweep reached it, else the largest k the data allow."""
    largest, requested = int(sweep.ks[-1]), int(requested)
    if requested <= largest:
        return requested, None
    return largest, (
        f"k = {requested} needs more distinct selected trials than there are; "
        f"using k = {largest}, the largest the data allow"
    )


def check_sparc_params(fc: float, amp_th: float, padlevel: int) -> dict[str, float]:
    """The SPARC parameters as a dict (fc in Hz, amp_th, padlevel); :class:`OptionError` for a bad one."""
    try:
        fc, amp_th = float(fc), float(amp_th)
    except (TypeError, ValueError):
        raise OptionError(f"fc and amp_th must be numbers, got fc = {fc!r}, amp_th = {amp_th!r}") from None
    if not (math.isfinite(fc) and fc > 0):
        raise OptionError(f"fc must be a maximum cut-off frequency > 0 Hz, got {fc:g}")
    if not 0 < amp_th < 1:
        raise OptionError(f"amp_th must lie between 0 and 1 (a fraction of the spectrum's peak), got {amp_th:g}")
    if isinstance(padlevel, bool) or not isinstance(padlevel, (int, np.integer)) or not 0 <= padlevel <= 10:
        raise OptionError(
            f"padlevel must be an integer from 0 to 10 (nfft = 2**(ceil(log2 N) + padlevel)), got {padlevel!r}"
        )
    return {"fc": fc, "amp_th": amp_th, "padlevel": int(padlevel)}


#: K-means' random_state must lie in 0 .. 2**32 - 1 (numpy's legacy seeding, which scikit-learn uses).
MAX_SEED = 2**32 - 1


#: The smallest joint limit accepted (rad/s, rad/s^2, N m): below it the time scale a limit asks for
#: (a peak over the limit) overflows. Limits above it that still stop the arm are reported, not simulated
#: (:data:`skilllib.robot.MAX_TIME_SCALE`).
MIN_LIMIT = 1e-12


def _max_workers() -> int:
    """The most local Dask workers a run starts: one single-threaded process per core of this machine."""
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


def check_options(
    k: int,
    robot: str,
    qd_max: Sequence[float] | float | None,
    scaling: str,
    random_state: int = 0,
    qdd_max: Sequence[float] | float | None = None,
    tau_max: Sequence[float] | float | None = None,
) -> Arm:
    """Check the options before the data are read, so that a wrong one fails at once.

    Parameters
    ----------
    k : int
        Number of clusters, at least 2.
    robot : str
        A name of :func:`skilllib.robot.get_robot`.
    qd_max, qdd_max, tau_max : float or sequence of float or None
        The user's joint velocity (rad/s), acceleration (rad/s^2) and torque (N m) limits, or None for the
        arm's.
    scaling : str
        ``"raw"`` or ``"standard"``.
    random_state : int
        K-means' seed, 0 to :data:`MAX_SEED`.

    Returns
    -------
    Arm
        The arm with every limit the run checks.

    Raises
    ------
    OptionError
        For a bad option, with the option named.
    """
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 2:
        raise OptionError(f"k must be an integer of at least 2, got {k!r}")
    if (
        isinstance(random_state, bool)
        or not isinstance(random_state, (int, np.integer))
        or not 0 <= random_state <= MAX_SEED
    ):
        raise OptionError(f"seed must be an integer from 0 to {MAX_SEED} (K-means' random_state), got {random_state!r}")
    if scaling not in ("raw", "standard"):
        raise OptionError(f"scaling must be 'raw' or 'standard', got {scaling!r}")
    try:
        arm = get_robot(robot)
    except ValueError as e:
        raise OptionError(str(e)) from None
    try:
        out = arm.with_limits(qd_max, qdd_max, tau_max)
    except ValueError as e:
        raise OptionError(f"{e} ({arm.robot.name}, {arm.n} joints)") from None
    for name, given, unit in (
        ("qd_max", qd_max, "rad/s"),
        ("qdd_max", qdd_max, "rad/s^2"),
        ("tau_max", tau_max, "N m"),
    ):
        least = None if given is None else float(np.min(np.asarray(given, dtype=float)))
        if least is not None and least < MIN_LIMIT:
            raise OptionError(
                f"{name} must be at least {MIN_LIMIT:g} {unit}, got {least:g}: an arm that slow does not move "
                f"(the time scale it asks for overflows)"
            )
    return out


#: A sampling rate within this relative distance of a whole number of Hz is taken to be that nominal rate
#: (60 Hz for the 59.98 Hz that jittered or imprecisely written stamps of a 60 Hz system give).
NOMINAL_RATE_RTOL = 1e-3


def nominal_rate(fs: float) -> float:
    """The nominal sampling rate behind a rate estimated from time stamps: the nearest whole number of Hz
    when within :data:`NOMINAL_RATE_RTOL`, else ``fs`` itself.

    Parameters
    ----------
    fs : float
        The sampling rate estimated from the time stamps (Hz).

    Returns
    -------
    float
        The nominal rate (Hz); NaN for NaN.
    """
    whole = float(np.round(fs))
    return whole if np.isfinite(fs) and whole > 0 and abs(fs / whole - 1) <= NOMINAL_RATE_RTOL else float(fs)


def _check_nyquist(params: dict[str, float], fs: float) -> None:
    """fc at or above the Nyquist frequency would take the band into the spectrum's mirror image: SPARC's
    band must end below the Nyquist frequency of the nominal rate (and of the estimated one, when lower), so
    that stamps that put the rate a little off (59.98 Hz for 60 Hz) never make a computation fail later."""
    if not np.isfinite(fs):
        return
    nominal = nominal_rate(fs)
    nyquist = min(fs, nominal) / 2
    if params["fc"] >= nyquist:
        rate = f"{nominal:g} Hz" if nominal == fs else f"{nominal:g} Hz nominal, {fs:.6g} Hz from the time stamps"
        raise OptionError(
            f"fc = {params['fc']:g} Hz is at or above the Nyquist frequency {nyquist:.6g} Hz of these "
            f"recordings (sampled at {rate}); choose fc below {nyquist:.6g} Hz"
        )


#: What a task's name gains when options given with it change it (results.json ``task.name``).
OVERRIDDEN = " + options"

#: The reading options of a task (:attr:`skilllib.task.Task.read`) and the keywords of
#: :func:`skilllib.recordings.load_recordings` they are passed as.
READ_KEYWORDS = {"max_gap": "max_gap_s"}


def _load_options(read: Mapping[str, Any]) -> dict[str, Any]:
    """The task's reading options as keywords of :func:`skilllib.recordings.load_recordings`."""
    return {READ_KEYWORDS.get(k, k): v for k, v in read.items() if v is not None}


def _onset_text(start: StartRule) -> str:
    th = start.threshold
    if start.kind == "event":
        return "onset speed"
    return f"{th.speed:g} m/s onset speed" if th.fraction is None else f"onset speed ({th.text()} of the peak)"


def resolve_task(
    task: Task | str | Path | None = None,
    *,
    read_options: Mapping[str, Any] | None = None,
    random_state: int | None = None,
    select: Sequence[Window | str] | str | None = None,
    start: StartRule | str | None = None,
    end: EndRule | str | None = None,
    hold: float | None = None,
    **options: Any,
) -> Task:
    """The task a run carries out: ``task`` (a :class:`~skilllib.task.Task`, a task file, a preset name or a
    results.json; None: the paper's) with the options given here over it (None: the task's).

    Values are taken as given; :func:`run` checks them (:class:`OptionError`). Texts are read as on the
    command line: ``start="speed:5%"``, ``end="offset"``, ``select=["none"]``, ``features="pv,ldlj"``.

    Parameters
    ----------
    task : Task, str, pathlib.Path or None
        The base task.
    read_options : mapping, optional
        Reading options (:func:`skilllib.recordings.load_recordings`; ``max_gap_s`` in s).
    random_state : int, optional
        K-means' seed.
    select : sequence of Window or str, or str, optional
        Selection windows (``FEATURE=LO:HI``) or ``none``.
    start, end : StartRule, EndRule or str, optional
        The segmentation rules or their texts.
    hold : float, optional
        The offset's hold and the shortest rest between movements (s).
    \\*\\*options : Any
        ``k``, ``robot``, ``qd_max`` (rad/s), ``qdd_max`` (rad/s^2), ``tau_max`` (N m), ``scaling``, ``fc`` (Hz),
        ``amp_th``, ``padlevel``, ``sensitivity``, ``lowpass``, ``split``, ``features``.

    Returns
    -------
    Task
        The resolved task.
    """
    from ..features import RuleError, SelectionError, parse_end, parse_features, parse_selection, parse_start

    try:
        base = task if isinstance(task, Task) else PAPER_TASK if task is None else load_task(task)
        changes: dict[str, Any] = {}
        read = dict(base.read)
        for key, v in (read_options or {}).items():
            if v is not None:
                read[{v2: k2 for k2, v2 in READ_KEYWORDS.items()}.get(key, key)] = v
        changes["read"] = read
        if random_state is not None:
            changes["seed"] = random_state
        for key in ("k", "robot", "qd_max", "qdd_max", "tau_max", "scaling", "fc", "amp_th", "padlevel"):
            if options.get(key) is not None:
                changes[key] = options[key]
        if options.get("sensitivity") is not None:
            changes["sensitivity"] = tuple(options["sensitivity"])
        if options.get("lowpass") is not None:
            changes["lowpass"] = options["lowpass"]
        if options.get("split") is not None:
            changes["split"] = bool(options["split"])
        if options.get("features") is not None:
            changes["features"] = parse_features(options["features"])
        if select is not None:
            items = [select] if isinstance(select, (str, Window)) else list(select)
            changes["selection"] = (
                tuple(items) if all(isinstance(w, Window) for w in items) else parse_selection(map(str, items))
            )
        if start is not None:
            changes["start"] = start if isinstance(start, StartRule) else parse_start(start)
        if hold is not None and not (isinstance(hold, (int, float)) and np.isfinite(hold) and hold >= 0):
            raise OptionError(f"hold must be a time of at least 0 s, got {hold!r}")
        hold_s = base.end.hold_s if hold is None else float(hold)  # the task's hold unless one is given
        new_end = base.end if end is None else end if isinstance(end, EndRule) else parse_end(end, hold_s)
        changes["end"] = new_end if hold is None else replace(new_end, hold_s=hold_s)
        job = replace(base, **changes)
        if job != base and not base.name.endswith(OVERRIDDEN):  # the task as given, then changed by options
            job = replace(job, name=base.name + OVERRIDDEN)
    except (TaskError, RuleError, SelectionError) as e:
        raise OptionError(str(e)) from None
    if job.start.kind == "event" and job.end.kind == "offset" and job.end.threshold is None:
        raise OptionError(
            "--end offset takes the start's speed threshold, but the start is an event: give the offset's "
            "threshold (--end offset:0.05 or offset:5%)"
        )
    return job


def run(
    data: str | Path | pd.DataFrame | Recordings | None = None,
    out: str | Path | None = None,
    *,
    task: Task | str | Path | None = None,
    k: int | None = None,
    robot: str | None = None,
    qd_max: Sequence[float] | float | None = None,
    qdd_max: Sequence[float] | float | None = None,
    tau_max: Sequence[float] | float | None = None,
    scaling: str | None = None,
    random_state: int | None = None,
    fc: float | None = None,
    amp_th: float | None = None,
    padlevel: int | None = None,
    sensitivity: Sequence[Mapping[str, float]] | None = None,
    lowpass: str | float | Lowpass | None = None,
    read_options: Mapping[str, Any] | None = None,
    start: StartRule | str | None = None,
    end: EndRule | str | None = None,
    hold: float | None = None,
    split: bool | None = None,
    select: Sequence[Window | str] | str | None = None,
    features: Sequence[str] | str | None = None,
    progress: Progress = _no_progress,
    write_figures: bool = True,
    workers: int | None = None,
    scheduler: str | None = None,
) -> PipelineRun:
    """Run the pipeline on ``data`` (default: the book's synthetic cohort) and write ``out``.

    ``data``: a path (CSV, compressed CSV, C3D, TRC, or a folder of them), a pandas DataFrame in the
    recordings format, or :class:`~skilllib.recordings.Recordings`; None: the book's synthetic cohort;
    ``read_options``: how to read it (the options of :func:`skilllib.recordings.load_recordings`); ``k``:
    clusters (the paper: 6), reduced with a message when the selected trials allow fewer; ``robot``: a name
    of :func:`skilllib.robot.get_robot`; ``qd_max``: joint velocity limits
    in rad/s (one for all joints or one per joint; default: the robot's); ``qdd_max`` (rad/s^2) and
    ``tau_max`` (N m): joint acceleration and torque limits, likewise (default: the robot's,
    :func:`skilllib.robot.dynamic_limits`); ``scaling``: "raw" (the paper) or "standard"; ``random_state``:
    K-means' seed (0 .. 2**32 - 1); ``fc`` (Hz, below the Nyquist frequency
    of the recordings), ``amp_th`` and ``padlevel``: the SPARC parameters (:func:`skilllib.smoothness.sparc`;
    default the book's, fc = 20 Hz); ``sensitivity``: other SPARC settings (dicts of some of fc, amp_th,
    padlevel; the rest as this run's) to compare with this run's
    (:func:`skilllib.prototypes.sparc_sensitivity`, results.json ``sparc_sensitivity``); ``lowpass``: the
    positions' low-pass filter, ``"auto"`` (default: only when the noise needs it), ``"none"`` or a cut-off
    in Hz (:mod:`skilllib.features`; results.json ``filter``); ``progress(items, description)`` wraps the
    long loops (e.g. tqdm); ``workers`` / ``scheduler``: compute the features of a folder of Parquet files
    on a Dask cluster, a LocalCluster of that many worker processes or the running scheduler at that
    address (:mod:`skilllib.features`; the same feature table as in memory).

    Raises :class:`OptionError` for a bad option (before reading the data),
    :class:`skilllib.recordings.DataFormatError` for a file that cannot be read and
    :class:`skilllib.pipeline.OutputError` for an output folder that cannot be used. Bad trials never raise:
    they are in ``results["trials"]`` as ``invalid`` with their reason. With fewer than :data:`MIN_SELECTED`
    selected trials (or fewer than 2 distinct ones) the clustering and transfer are skipped, said in
    ``messages``. ``out`` is written as a whole (:mod:`skilllib.pipeline`): a fresh folder replaces it only
    when everything is written, so old figures never sit beside new results and a failed run leaves it as
    it was.

    Parameters
    ----------
    data : str, pathlib.Path, pandas.DataFrame, Recordings or None
        The recordings (positions in m, times in s): a path, a long table or
        :class:`~skilllib.recordings.Recordings`; None for the book's synthetic cohort.
    out : str, pathlib.Path or None
        The output folder for results.json and the figures (text); None to write nothing.
    task : Task, str, pathlib.Path or None
        The task (:mod:`skilllib.task`): a Task, a TOML task file, a preset name (``paper``) or a results.json
        to run again; None: the paper's. Every option below that is None takes the task's value; one that is
        given overrides it. results.json ``task`` records the resolved task.
    k : int
        Number of clusters (dimensionless; the paper's 6).
    robot : str
        The arm, a name of :func:`skilllib.robot.get_robot` (text).
    qd_max : float or sequence of float, optional
        Joint velocity limits (rad/s), one for all joints or one per joint; the robot's by default.
    qdd_max : float or sequence of float, optional
        Joint acceleration limits (rad/s^2), likewise.
    tau_max : float or sequence of float, optional
        Joint torque limits (N m), likewise; only for arms with dynamic parameters.
    scaling : str
        ``"raw"`` (the paper: PV in m/s and SPARC as they are) or ``"standard"`` (text).
    random_state : int
        K-means' seed, 0 .. 2**32 - 1 (dimensionless).
    fc : float
        SPARC's maximum cut-off frequency, below the recordings' Nyquist frequency (Hz).
    amp_th : float
        SPARC's amplitude threshold, a fraction of the peak magnitude (dimensionless).
    padlevel : int
        SPARC's zero-padding level (dimensionless).
    sensitivity : sequence of mapping of str to float, optional
        Other SPARC settings to compare with: some of ``fc`` (Hz), ``amp_th`` and ``padlevel``
        (dimensionless), the rest as this run's.
    lowpass : str, float, Lowpass or None
        The positions' low-pass filter: ``"auto"``, ``"none"`` or a cut-off in Hz.
    read_options : mapping of str to Any, optional
        How to read ``data`` (:func:`skilllib.recordings.load_recordings`: columns, units, up axis,
        marker, contact channel, threshold and height in m, name pattern, separator, time unit).
    start : StartRule or str, optional
        Where a movement starts (``speed:0.05`` m/s, the paper; ``speed:5%``; ``event:LABEL``).
    end : EndRule or str, optional
        Where it ends (``contact``, the paper; ``offset``, ``offset:0.05`` m/s, ``offset:5%``,
        ``event:LABEL``, ``height-above:M``, ``height-below:M`` in m).
    hold : float, optional
        How long the speed stays below the offset threshold, and the shortest rest between movements (s).
    split : bool, optional
        Whether each recording holds several movements, split at rests or events
        (:func:`skilllib.features.split_movements`).
    select : sequence of Window or str, or str, optional
        Selection windows ``FEATURE=LO:HI`` or ``none`` (default: the paper's contact-speed window when the
        end is contact, no window otherwise).
    features : sequence of str or str, optional
        The clustering features (``pv,sparc``, the paper; any columns of
        :data:`skilllib.features.FEATURE_UNITS`).
    progress : callable
        ``progress(items, description)`` wrapping the long loops, e.g. tqdm; by default none.
    write_figures : bool
        Whether to write the figures (PNG, SVG) beside results.json (dimensionless).
    workers : int, optional
        Compute the features of a folder of Parquet files on a local Dask cluster of that many worker
        processes (dimensionless).
    scheduler : str, optional
        The same on the running Dask scheduler at that address (text).

    Returns
    -------
    PipelineRun
        ``results`` (the results.json dictionary) and the objects behind it: recordings, feature table,
        silhouette sweep, prototypes, transfers, executions' assessments and messages.

    Raises
    ------
    OptionError
        For a bad option, before the data are read (``fc`` against the Nyquist frequency once the sampling
        rate is known).
    skilllib.recordings.DataFormatError
        For a file that cannot be read.
    OutputError
        For an output folder that cannot be used.
    """
    given = isinstance(lowpass, Lowpass)
    job = resolve_task(
        task,
        k=k,
        robot=robot,
        qd_max=qd_max,
        qdd_max=qdd_max,
        tau_max=tau_max,
        scaling=scaling,
        random_state=random_state,
        fc=fc,
        amp_th=amp_th,
        padlevel=padlevel,
        sensitivity=sensitivity,
        lowpass=None if given else lowpass,
        read_options=read_options,
        start=start,
        end=end,
        hold=hold,
        split=split,
        select=select,
        features=features,
    )
    arm = check_options(job.k, job.robot, job.qd_max, job.scaling, job.seed, job.qdd_max, job.tau_max)
    params = check_sparc_params(job.fc, job.amp_th, job.padlevel)
    variants = [check_sparc_params(**{**params, **dict(v)}) for v in _settings(job.sensitivity)]

    def limit(v: Any) -> Any:  # one number for every joint, or one per joint, as plain floats
        return None if v is None else float(v) if np.ndim(v) == 0 else tuple(float(x) for x in np.ravel(v))

    job = replace(  # checked: recorded as plain numbers (results.json task)
        job,
        k=int(job.k),
        seed=int(job.seed),
        **params,
        sensitivity=tuple(dict(v) for v in _settings(job.sensitivity)),
        qd_max=limit(job.qd_max),
        qdd_max=limit(job.qdd_max),
        tau_max=limit(job.tau_max),
    )
    lowpass = lowpass if given else job.lowpass
    if not isinstance(lowpass, Lowpass):
        try:
            lowpass = parse_lowpass(lowpass)
        except ValueError as e:
            raise OptionError(str(e)) from None
    paper_rules = job.start == PAPER_START and job.end.kind == "contact" and not job.split
    if (workers or scheduler) and not paper_rules:
        raise OptionError(
            "a Dask cluster (--workers, --scheduler) computes the paper's segmentation only (start speed:0.05, "
            f"end contact, no --split); this task has start {job.start.text()}, end {job.end.text()}"
            + (", --split" if job.split else "")
        )
    read_options = _load_options(job.read)
    if job.end.kind != "contact" and read_options.get("contact_height") is None:
        read_options["contact_height"] = -math.inf  # no contact signal is needed: the end rule does not read it
    if workers is not None and not (
        isinstance(workers, (int, np.integer)) and not isinstance(workers, bool) and 1 <= workers <= _max_workers()
    ):
        raise OptionError(
            f"workers must be an integer from 1 to {_max_workers()} (this machine's cores), got {workers!r}"
        )
    if out is not None:  # everything about the output folder is checked before anything is computed
        out = check_output(out, inputs=(data,) if isinstance(data, (str, Path)) else ())
    table = None
    if workers or scheduler:
        from ..features import cluster_features

        try:
            recordings, table = cluster_features(
                data,
                workers,
                scheduler,
                lowpass=lowpass,
                sparc_params=params,
                read_options=read_options,
                variants=variants,
            )
        except ValueError as e:  # an option the cluster path does not take
            raise OptionError(str(e)) from None
        filt = table.attrs["lowpass"]
    else:
        recordings = load_recordings(DEFAULT_DATA if data is None else data, **read_options)
        if job.split:
            from ..features import split_movements

            recordings = split_movements(recordings, job.start, job.end, hold_s=job.hold)
    for p in (params, *variants):
        _check_nyquist(p, recordings.fs)
    try:
        filt = filt if table is not None else run_lowpass(recordings, lowpass, end=job.end)
    except ValueError as e:  # a cut-off too high for the sampling rate
        raise OptionError(str(e)) from None
    result = compute(
        recordings,
        data,
        arm=arm,
        task=job,
        params=params,
        variants=variants,
        lowpass=filt,
        progress=progress,
        features=table,
    )
    if out is not None:
        with output_folder(out) as folder:
            if not in_json(result.features):
                write_trials(result.features, folder)
            write_json_atomic(result.results, folder / "results.json")
            if write_figures:
                result.results["figures"] = _write_figures(result, folder, arm.robot)
                write_json_atomic(result.results, folder / "results.json")
    return result


def compute(
    recordings: Recordings,
    data: Any,
    *,
    arm: Arm,
    task: Task,
    params: dict[str, float],
    variants: list[dict[str, float]],
    lowpass: Lowpass,
    progress: Progress = _no_progress,
    features: pd.DataFrame | None = None,
) -> PipelineRun:
    """The pipeline's computation on validated ``recordings`` with checked options (see :func:`run`;
    ``task``: the resolved task); ``features``: their feature table when computed already (on a cluster)."""
    k, scaling, random_state = task.k, task.scaling, task.seed
    windows = task.resolved_selection()
    if features is None:
        features = trial_features(
            recordings, sparc_params=params, lowpass=lowpass, progress=progress, start=task.start, end=task.end
        )
    features = apply_selection(features, windows)
    selected = select(features)
    results: dict[str, Any] = {
        "schema_version": SCHEMA_VERSION,
        "skilllib_version": __version__,
        "dataset": {
            "path": _display_path(data),
            "synthetic": _is_shipped_cohort(data),
            "n_trials": len(features),
            "n_participants": int(features["participant"].nunique()),
            "fs": json_value(float(recordings.fs)),
            "n_resampled": int(features["resampled"].sum()),
            "n_repaired": int((features["repairs"] != "").sum()),
            "n_repaired_samples": int(features["n_repaired"].sum()),
        },
        "sparc_params": {"fc": params["fc"], "amp_th": params["amp_th"], "padlevel": int(params["padlevel"])},
        "filter": lowpass.to_dict(),
        "contact_speed_window": next(
            ([w.lo, w.hi] for w in windows if w.feature == "contact_speed" and None not in (w.lo, w.hi)), None
        ),
        "selection": [w.text() for w in windows],
        "task": task.to_dict(),
        **trials_block(features),
        "n_selected": len(selected),
    }
    skipped = getattr(recordings, "skipped", None)
    if skipped is not None:  # a folder of trial files: each file is one trial (read or invalid) or skipped
        results["dataset"]["n_files"] = len(features) + len(skipped)
        results["dataset"]["skipped_files"] = [{"path": q.path, "reason": q.reason} for q in skipped]
    result = PipelineRun(results=results, recordings=recordings, features=features, task=task)
    if not np.isfinite(recordings.fs):
        result.messages.append("the sampling rate is unknown: no trial is usable to derive it from the time stamps")
    n_res = results["dataset"]["n_resampled"]
    if n_res:
        result.messages.append(
            f"{n_res} trial(s) had irregular time stamps (jitter or dropped frames) and were "
            f"resampled onto a uniform {recordings.fs:.4g} Hz grid (trials[].resampled)"
        )
    result.messages += list(getattr(recordings, "notes", ()))  # what the readers noticed (none on a cluster)
    n_rep = results["dataset"]["n_repaired"]
    if n_rep:
        result.messages.append(
            f"{n_rep} trial(s) had real-data defects repaired (stale leading frames, frozen positions, jumps, "
            f"gaps): {results['dataset']['n_repaired_samples']} sample(s) replaced by interpolation "
            f"(trials[].repairs; --max-gap)"
        )
    no_rest = int(features["reason"].astype(str).str.startswith("no rest before onset").sum())
    if no_rest > NO_REST_FRACTION * len(features):
        hint = (
            "a stronger low-pass filter (--lowpass HZ)"
            if lowpass.cutoff_hz is not None
            else "a low-pass filter (--lowpass auto or HZ)"
            if lowpass.chosen_by == "none"
            else "a low-pass filter (--lowpass HZ)"
        )
        result.messages.append(
            f"{no_rest} of {len(features)} trials are invalid with 'no rest before onset': either the recordings "
            f"start after the movement began, or the position noise is so large that its derivative exceeds the "
            f"{_onset_text(task.start)}; then try {hint} (chapter 13)"
        )
    if lowpass.cutoff_hz is not None:
        result.messages.append(filter_message(selected, lowpass))
    if getattr(features.attrs.get("lowpass"), "note", ""):  # a borderline auto decision and what the other would change
        result.messages.append(features.attrs["lowpass"].note)
    if len(selected):
        result.messages.append(capped_message(selected, params))

    sweep = None

    def transfer_each(keys: list[tuple[Any, Any]], what: str) -> None:
        """Transfer the trials ``keys`` (their segments) in order, numbered 0, 1, ...: results' transfer."""
        for c in progress(list(range(len(keys))), "transfer"):
            p, tr = keys[c]
            seg = (
                segment(recordings, p, tr, lowpass=lowpass, start=task.start, end=task.end)
                if isinstance(recordings, Recordings)
                else recordings.segment(p, tr, lowpass=lowpass)
            )
            result.profiles.append((seg.time, seg.speed))
            result.transfers.append(transfer(arm, seg, cluster=c))
            result.transferred.append((str(p), str(tr)))
        result.assessments = assess(arm.robot, result.transfers, arm.dynamic_limits, sparc_params=params)
        results["transfer"] = transfer_block(result.assessments)
        result.messages += [  # an execution not simulated (a time scale beyond MAX_TIME_SCALE, ...) and why
            f"{what} {a.transfer.cluster}: {a.note}" for a in result.assessments if a.note
        ]

    if len(selected) < MIN_SELECTED:
        result.messages.append(
            f"only {len(selected)} selected trial(s): clustering needs at least {MIN_SELECTED}; no prototypes"
            + (
                "; each selected trial is transferred as it is (transfer.prototypes, numbered in trial order)"
                if len(selected)
                else " and no transfer"
            )
        )
        if len(selected):  # one or two demonstrations: no clusters, but the robot's verdict on each
            transfer_each(list(zip(selected["participant"], selected["trial"])), "selected trial")
            results["transfer"]["selected_trials"] = [{"participant": p, "trial": t} for p, t in result.transferred]
    else:
        try:
            with warnings.catch_warnings(record=True) as caught:  # a shrunk k range: a note of the run
                warnings.simplefilter("always", UserWarning)
                sweep = pt.silhouette_sweep(
                    selected, scaling=scaling, random_state=random_state, progress=progress, features=task.features
                )
        except ValueError as e:
            result.messages.append(f"{e}; no prototypes and no transfer")
        else:
            result.messages += [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
    if sweep is not None:
        k_used, note = choose_k(k, sweep)
        result.messages += [note] if note else []
        fit = sweep.results[k_used]
        if not fit.valid:
            valid = sweep.valid_ks()
            result.messages.append(
                f"k = {k_used} is not silhouette-valid for these data (a cluster lies wholly below the average "
                f"silhouette); valid k: {', '.join(map(str, valid)) or 'none'} (see silhouette_sweep.png, --k)"
            )
        result.sweep, result.prototypes = sweep, fit
        results["silhouette"] = sweep.to_dict()
        results["silhouette_estimate"] = est = sweep.estimate_dict()
        if est["method"] == "subsample":
            sd = max(v["sd"] for v in est["per_k"].values())
            result.messages.append(
                f"silhouettes estimated: {est['n_points']} selected trials > {est['exact_max']} (exact up to that); "
                f"mean of {est['repeats']} stratified random subsamples of {est['sample_size']} per k, seeded by "
                f"--seed (largest SD over the subsamples {sd:.3f}; silhouette_estimate)"
            )
        results["silhouette_valid_k"] = sweep.valid_ks()
        results["k"] = k_used
        results["scaling"] = scaling
        results["clusters"] = fit.to_dict()["clusters"]
        transfer_each(list(zip(fit.prototypes["participant"], fit.prototypes["trial"])), "prototype of cluster")
    if variants and sweep is not None and "sparc" not in task.features:
        result.messages.append(
            f"no SPARC sensitivity analysis: the clustering features ({', '.join(task.features)}) do not include "
            "sparc, so the clusters cannot depend on the SPARC setting"
        )
    elif variants and sweep is not None:

        def table(p: Mapping[str, float]) -> pd.DataFrame:
            feats = trial_features(recordings, sparc_params=p, lowpass=lowpass, start=task.start, end=task.end)
            return apply_selection(feats, windows)

        result.sensitivity = sparc_sensitivity(
            recordings,
            [params, *variants],
            k=results["k"],
            scaling=scaling,
            random_state=random_state,
            reference=(features, sweep),
            lowpass=lowpass,
            features=task.features,
            table=table if isinstance(recordings, Recordings) else None,  # a cluster run: the paper's task only
        )
        results["sparc_sensitivity"] = result.sensitivity.to_dict()
    elif variants:
        result.messages.append("no SPARC sensitivity analysis: too few selected trials to cluster")
    results["messages"] = result.messages
    return result


def _settings(sensitivity: Sequence[Mapping[str, float]] | None) -> list[Mapping[str, float]]:
    """The ``sensitivity`` option as a list of settings; :class:`OptionError` for a bad one."""
    if sensitivity is None:
        return []
    out = []
    for v in sensitivity:
        if not isinstance(v, Mapping) or not v or set(v) - {"fc", "amp_th", "padlevel"}:
            raise OptionError(f"each sensitivity setting must give some of fc, amp_th, padlevel, got {v!r}")
        out.append(v)
    return out


def capped_message(selected: pd.DataFrame, params: Mapping[str, float]) -> str:
    """How many selected trials had their SPARC band ended by fc rather than the amplitude threshold."""
    n = int(selected["sparc_capped"].sum())
    return (
        f"{n} of {len(selected)} selected trials have their SPARC band ended by fc = {params['fc']:g} Hz rather "
        f"than by the amplitude threshold {params['amp_th']:g} (sparc_capped): their SPARC depends on fc "
        f"(compare settings with --sensitivity, chapter 6)"
    )


def filter_message(selected: pd.DataFrame, lowpass: Lowpass) -> str:
    """What the low-pass filter did, and how many selected trials SPARC read beyond its cut-off."""
    beyond = int((selected["sparc_band_end_hz"] > lowpass.cutoff_hz).sum())
    return (
        f"positions were low-pass filtered at {lowpass.cutoff_hz:.3g} Hz ({lowpass.chosen_by}; zero-lag "
        f"Butterworth, filter in results.json); SPARC's band reaches above that cut-off in {beyond} of "
        f"{len(selected)} selected trials, whose SPARC is partly the filter's (chapter 13)"
    )


def _write_figures(run_: PipelineRun, out: Path, robot) -> list[str]:
    """Write every figure of the pipeline (PNG and SVG; the segmentation pages PNG only) to ``out``; return
    their file names."""
    from .. import figures as fg

    written = []

    def keep(fig, name: str, note: str = "", save: Callable | None = None) -> None:
        if run_.results["dataset"]["synthetic"]:
            fig.text(0.995, 0.003, SYNTHETIC_NOTE, ha="right", va="bottom", fontsize=8, color="0.35")
        if note:
            fig.text(0.005, 0.003, f"Shown: {note}.", ha="left", va="bottom", fontsize=8, color="0.35")
        written.extend(p.name for p in (save or fg.save)(fig, out, name))
        fg.plt.close(fig)

    samples = isinstance(run_.recordings, Recordings)  # not on the cluster path: the samples stay there
    window = run_.results["contact_speed_window"]
    window = tuple(window) if window else None
    end = {"contact": "contact", "offset": "offset", "event": "end event"}.get(run_.task.end.kind, "height crossing")
    if (run_.features["status"] != "invalid").any():  # the data figures need at least one valid trial
        amp_th = run_.results["sparc_params"]["amp_th"]
        keep(fg.plot_feature_overview(run_.features, amp_th, window=window, end=end), "features")
        few, note = fg.few_participants(run_.features)  # one panel per participant: at most 12
        if samples:
            keep(fg.plot_trials_by_participant(run_.recordings, few, end=end), "trials_by_participant", note)
        keep(fg.plot_participant_features(few, window=window, end=end), "participant_features", note)
        if samples:
            keep(
                fg.plot_sparc_vs_length(run_.features, run_.recordings.fs, run_.results["sparc_params"]["amp_th"]),
                "sparc_vs_length",
            )
    if samples and len(run_.features):  # each trial's segmentation (every invalid one included): PNG pages of 24
        shown, note = fg.segmentation_keys(run_.features, fg.MAX_SEGMENTATION_TRIALS)
        pages = fg.plot_segmentation_pages(
            run_.recordings, run_.features, keys=shown, start=run_.task.start, end=run_.task.end
        )
        for i, fig in enumerate(pages, 1):
            keep(fig, f"segmentation-{i:02d}", note, save=fg.save_page)
    if run_.prototypes is not None:
        keep(fg.plot_silhouette_sweep(run_.sweep, chosen_k=run_.prototypes.k), "silhouette_sweep")
        keep(fg.plot_silhouettes(run_.prototypes), "silhouettes_k")
        keep(fg.plot_clusters(run_.prototypes), "clusters_pv_sparc")
        keep(fg.plot_prototype_profiles(run_.profiles, run_.prototypes.prototypes), "prototype_speed_profiles")
    if run_.transfers:  # the prototypes', or each selected trial's when too few to cluster
        keep(fg.plot_joint_velocities(run_.transfers), "joint_velocities")
        keep(fg.plot_frame_mapping(robot, run_.transfers[-1]), "frame_mapping")  # the fastest prototype
        for fig, name in fg.dynamics_figures(run_.assessments):
            keep(fig, name)
    if run_.sensitivity is not None:
        keep(fg.plot_sparc_sensitivity(run_.sensitivity), "sparc_sensitivity")
    return written
