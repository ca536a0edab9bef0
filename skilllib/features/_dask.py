"""The features of a partitioned Parquet dataset on a Dask cluster (``--workers N``, ``--scheduler ADDRESS``).

A corpus too large for one machine's memory is a folder of Parquet files (:mod:`skilllib.recordings`), each
holding whole trials: a partition. Every partition is processed on a worker of a ``distributed`` cluster
by the functions of the in-memory path (:func:`skilllib.recordings.recordings_from_frame`,
:func:`skilllib.features.trial_features`); only per-trial numbers travel to the client. What the in-memory
path decides over the whole file is decided here over the whole corpus, from the partitions' summaries,
so the feature table is the same (tested on a ``LocalCluster``):

1. **rates**: each partition's usable trials' median and regular mean intervals, spans and 95th
   percentile steps; the client takes the corpus's sampling interval and checks rates and units
   (:func:`skilllib.recordings.corpus_rate`, :func:`skilllib.recordings.check_corpus_units`) and that no trial
   lies in two partitions;
2. **noise at rest**: each partition's per-trial, per-axis estimates
   (:func:`skilllib.features.rest_noise_rows`, combined over the corpus by
   :func:`skilllib.features.combine_rest_noise`, as in memory) decide the low-pass filter of
   ``--lowpass auto``; when it filters, or the decision is borderline, the residual analysis reads the
   same trials as in memory (every k-th approach of the corpus);
3. **features**: each partition's feature table with the corpus's rate and filter, concatenated in
   partition order.

Clustering and transfer then run on the client on the gathered table, as in memory; the prototypes'
samples are read from their partitions. ``--workers N`` starts a ``distributed.LocalCluster`` of N
single-threaded worker processes; ``--scheduler ADDRESS`` connects to a running scheduler (docs/cli.md:
``dask scheduler`` and ``dask worker`` on the nodes, dask-jobqueue on a batch system, dask-kubernetes).
The workers need skilllib installed and the dataset's path readable at the same place.
"""

from __future__ import annotations

import contextlib
import gc
import logging
import signal
import threading
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..recordings import (
    COLUMNS,
    RATE_TOLERANCE,
    DataFormatError,
    Recordings,
    check_corpus_units,
    corpus_rate,
    first_true,
    is_parquet,
    natural_key,
    parquet_files,
    read_parquet,
    recordings_from_frame,
)
from ._filtering import (
    BORDERLINE_FRACTION,
    SPEED_NOISE_LIMIT,
    Lowpass,
    choose_lowpass,
    combine_rest_noise,
    residual_trials,
    rest_noise_rows,
    rest_samples,
)
from ._segmentation import MIN_DIFF_WINDOW, diff_window
from ._table import trial_features


def _recordings(path: str, rate: tuple[float, float]) -> Recordings:
    frame, place = read_parquet(path, COLUMNS, natural_key)
    return recordings_from_frame(frame, path, place=place, rate=rate)


def partition_rates(path: str) -> dict[str, Any]:
    """Step 1 on a worker: the trials' ids and the statistics the corpus's rate and units come from
    (NaN for trials with a problem of their own)."""
    rec = _recordings(path, (np.nan, np.nan))
    stats = rec._cache.get("stats")
    none = np.full(len(rec), np.nan)
    return {
        "keys": rec.keys(),
        **{k: none if stats is None else getattr(stats, k) for k in ("med_dt", "mean_dt", "span", "step95")},
    }


def partition_noise(path: str, rate: tuple[float, float]) -> dict[str, Any]:
    """Step 2 on a worker: the per-trial rest-noise estimates (m) and the approach lengths of the trials
    that the filter choice reads (status ok, at least 4 samples before contact)."""
    rec = _recordings(path, rate)
    ok = (rec.trials["status"] == "ok").to_numpy()
    t, pos, contact = rec.arrays()
    runs = rec.runs()
    length = first_true(contact, runs)
    separate = {}
    for i in np.flatnonzero(ok):
        if rec.is_resampled(*rec.keys()[i]):
            d = rec.trial(*rec.keys()[i])
            hits = np.flatnonzero(d.contact)
            separate[int(i)] = d.pos[: int(hits[0])] if hits.size else d.pos
            length[i] = len(separate[int(i)])
    picked = ok & (length >= 4)
    fs = rate_fs(rate)
    n = rest_samples(fs)
    start = runs.start
    approaches = [  # only the rest windows are read; views, no copies
        separate[int(i)] if int(i) in separate else pos[start[i] : start[i] + length[i]]
        for i in np.flatnonzero(picked)
        if length[i] >= n
    ]
    return {"picked": int(picked.sum()), "rows": rest_noise_rows(approaches, fs)}


def partition_approaches(path: str, rate: tuple[float, float], which: Sequence[int]) -> list[np.ndarray]:
    """Step 2b on a worker: the approaches (m) number ``which`` among the partition's picked trials (as
    :func:`partition_noise` counts them), for the residual analysis."""
    rec = _recordings(path, rate)
    picked = []
    for i in np.flatnonzero((rec.trials["status"] == "ok").to_numpy()):
        d = rec.trial(*rec.keys()[i])  # resampled trials as resampled, as in memory
        hits = np.flatnonzero(d.contact)
        a = d.pos[: int(hits[0])] if hits.size else d.pos
        if len(a) >= 4:
            picked.append(a)
    return [picked[j] for j in which]


def partition_features(
    path: str, rate: tuple[float, float], lowpass: Lowpass, options: Mapping[str, Any]
) -> pd.DataFrame:
    """Step 3 on a worker: the partition's feature table (:func:`skilllib.features.trial_features`)."""
    return trial_features(_recordings(path, rate), lowpass=lowpass, **options)


def rate_fs(rate: tuple[float, float]) -> float:
    return 1.0 / rate[1]


@dataclass
class DistributedFeatures:
    """What :func:`corpus_features` computed: the feature table (all partitions, in order), the corpus's
    sampling rate ``fs`` (Hz) and ``rate`` (ref, dt in s), the filter, the partition files and the
    partition of each trial (aligned with the table), and the notes on the dataset's entries not read."""

    features: pd.DataFrame
    fs: float
    rate: tuple[float, float]
    lowpass: Lowpass
    files: list[str]
    partition: np.ndarray
    notes: tuple = ()

    def recordings_of(self, k: int) -> Recordings:
        """The recordings of partition ``k``, read with the corpus's rate (on the client)."""
        return _recordings(self.files[k], self.rate)


def client_for(workers: int | None = None, scheduler: str | None = None):
    """A ``distributed.Client``: to the scheduler at ``scheduler``, or to a new LocalCluster of
    ``workers`` single-threaded worker processes (closed with the client)."""
    from distributed import Client, LocalCluster

    if scheduler:
        return Client(scheduler)
    cluster = LocalCluster(
        n_workers=int(workers or 1),
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",
        silence_logs=QUIET_LEVEL,  # the workers' own logs ("Compute Failed" for a bad file): the error says it
    )
    client = Client(cluster)
    client._skilllib_cluster = cluster  # closed by close_client
    return client


def close_client(client) -> None:
    """Close ``client`` and the LocalCluster :func:`client_for` started with it (quietly, also after Ctrl-C:
    a second Ctrl-C while closing is ignored, so that no worker process is left behind)."""
    cluster = getattr(client, "_skilllib_cluster", None)
    in_main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if in_main else None
    try:
        with contextlib.suppress(Exception):
            client.close(timeout=CLOSE_TIMEOUT_S)
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close(timeout=CLOSE_TIMEOUT_S)
    finally:
        if in_main:
            signal.signal(signal.SIGINT, previous)


def _block_sigint() -> tuple | None:
    """While a LocalCluster starts: SIGINT ignored, so that the worker processes started meanwhile inherit
    that (a Python process leaves an ignored SIGINT ignored) and a Ctrl-C, which the terminal sends to every
    process of the command, reaches only the client, which closes the cluster (the workers print no
    traceback); and blocked in this (the main) thread, so that a Ctrl-C meanwhile is held, not lost.
    Returns what :func:`_unblock_sigint` restores (None: nothing changed, not the main thread)."""
    if threading.current_thread() is not threading.main_thread():
        return None
    blocked = hasattr(signal, "pthread_sigmask") and signal.SIGINT not in signal.pthread_sigmask(
        signal.SIG_BLOCK, {signal.SIGINT}
    )
    return signal.signal(signal.SIGINT, signal.SIG_IGN), blocked


def _unblock_sigint(saved: tuple | None) -> None:
    """Undo :func:`_block_sigint`; a SIGINT held meanwhile is delivered now (KeyboardInterrupt)."""
    if saved is not None:
        handler, blocked = saved
        signal.signal(signal.SIGINT, handler)
        if blocked:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


#: The level distributed's and asyncio's loggers are held at during a cluster run (above CRITICAL: none of
#: their lines is printed). What goes wrong reaches the run as an exception: one line of the command (an
#: interrupted gather's tasks, a worker killed while closing, a worker's failed task are not news then).
QUIET_LEVEL = logging.CRITICAL + 1

#: Seconds the client and the LocalCluster are given to close.
CLOSE_TIMEOUT_S = 10


@contextlib.contextmanager
def quiet_logs(names: Sequence[str] = ("distributed", "asyncio", "tornado")) -> Iterator[None]:
    """Hold the loggers ``names`` at :data:`QUIET_LEVEL` within the block; their levels are restored after.

    Parameters
    ----------
    names : sequence of str
        The loggers' names (text).

    Returns
    -------
    contextlib.AbstractContextManager
        The block's context (nothing to bind).
    """
    loggers = [logging.getLogger(n) for n in names]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(QUIET_LEVEL)
    try:
        yield
    finally:
        gc.collect()  # tasks of an interrupted gather report "exception never retrieved" when collected: now
        for lg, level in zip(loggers, levels):
            lg.setLevel(level)


def corpus_features(
    path: str | Path,
    client,
    *,
    lowpass: str | float | Lowpass | None = "auto",
    options: Mapping[str, Any] | None = None,
) -> DistributedFeatures:
    """The feature table of the Parquet folder ``path`` computed on ``client``'s cluster (module
    docstring). ``options``: keywords of :func:`skilllib.features.trial_features` (sparc_params, window,
    onset_speed, min_samples). Raises DataFormatError as the in-memory path does, and when a trial lies
    in two partitions."""
    path = Path(path)
    skipped: list = []  # hidden, AppleDouble, _metadata, stray files: not read, said in the notes
    files = [str(f) for f in parquet_files(path, natural_key, skipped)]
    if not files:
        raise DataFormatError(f"{path}: no Parquet files in this folder")
    parts = client.gather(client.map(partition_rates, files, pure=False))
    owner: dict[tuple[str, str], int] = {}
    for k, p in enumerate(parts):
        for key in p["keys"]:
            if key in owner:
                raise DataFormatError(
                    f"{path}: trial {key[1]!r} of participant {key[0]!r} lies in two partitions, "
                    f"{Path(files[owner[key]]).name} and {Path(files[k]).name}: a partition must "
                    f"hold whole trials"
                )
            owner[key] = k
    med = np.concatenate([p["med_dt"] for p in parts])
    mean = np.concatenate([p["mean_dt"] for p in parts])
    if np.isnan(med).all():
        rate = (np.nan, np.nan)
    else:
        rate = corpus_rate(str(path), med, mean)
        ok = ~np.isnan(med) & (np.abs(med / rate[0] - 1) <= RATE_TOLERANCE)  # usable and on the rate
        span = np.concatenate([p["span"] for p in parts])
        step = np.concatenate([p["step95"] for p in parts])
        check_corpus_units(str(path), span[ok], step[ok] / rate[1])
    filt = _corpus_lowpass(files, client, rate, lowpass)
    tables = client.gather(
        client.map(partition_features, files, rate=rate, lowpass=filt, options=dict(options or {}), pure=False)
    )
    features = pd.concat(tables, ignore_index=True)
    features.attrs["lowpass"] = filt
    partition = np.repeat(np.arange(len(files)), [len(t) for t in tables])
    notes = tuple(f"{Path(q).name}: skipped: {reason}" for q, reason in skipped)  # as in memory
    return DistributedFeatures(
        features, rate_fs(rate) if np.isfinite(rate[1]) else np.nan, rate, filt, files, partition, notes
    )


def _corpus_lowpass(files: list[str], client, rate: tuple[float, float], lowpass: Any) -> Lowpass:
    """The filter of the run, chosen over the whole corpus as :func:`skilllib.features.run_lowpass` does."""
    fs = rate_fs(rate) if np.isfinite(rate[1]) else np.nan
    if isinstance(lowpass, Lowpass):
        return lowpass
    window = diff_window(fs) if np.isfinite(fs) else MIN_DIFF_WINDOW
    if lowpass != "auto" or not np.isfinite(fs):
        return choose_lowpass(lowpass, [], fs, window)
    noise_parts = client.gather(client.map(partition_noise, files, rate=rate, pure=False))
    counts = [p["picked"] for p in noise_parts]
    if not sum(counts):
        return choose_lowpass("auto", [], fs, window)
    noise = combine_rest_noise(np.concatenate([p["rows"] for p in noise_parts]), fs, window)
    offsets = np.cumsum([0, *counts])
    approaches: dict[int, np.ndarray] = {}
    if noise.speed >= (1 - BORDERLINE_FRACTION) * SPEED_NOISE_LIMIT:  # the residual analysis reads these trials
        wanted = list(residual_trials(int(offsets[-1])))
        part = np.searchsorted(offsets, wanted, side="right") - 1
        for k in np.unique(part):
            local = [int(j - offsets[k]) for j, q in zip(wanted, part) if q == k]
            got = client.submit(partition_approaches, files[k], rate, local, pure=False).result()
            approaches.update({int(offsets[k]) + j: a for j, a in zip(local, got)})

    class Approaches(Sequence):  # the corpus's picked approaches; only those the analysis reads are here
        def __len__(self) -> int:
            return int(offsets[-1])

        def __getitem__(self, j):
            return approaches[int(j)]

    return choose_lowpass("auto", Approaches(), fs, window, noise=noise)


class PartitionedRecordings:
    """Stands for the recordings of a corpus computed on the cluster: its sampling rate ``fs`` (Hz),
    ``source``, and the segment of any trial, read on the client from the partition that holds it."""

    def __init__(self, result: DistributedFeatures, source: str) -> None:
        self.result, self.fs, self.source = result, result.fs, source
        self.notes = result.notes  # the dataset's entries not read, as the in-memory path says them
        f = result.features
        self._where = dict(zip(zip(f["participant"], f["trial"]), result.partition))

    def segment(self, participant: Any, trial: Any, lowpass: Lowpass | None = None):
        """The segment of one trial (:func:`skilllib.features.segment` on its partition's recordings)."""
        from ._table import segment

        k = int(self._where[(str(participant), str(trial))])
        return segment(self.result.recordings_of(k), participant, trial, lowpass=lowpass)


class ClusterOptionError(ValueError):
    """An option the cluster path does not take (the pipeline reports it as an option error)."""


def cluster_features(
    data: Any,
    workers: int | None,
    scheduler: str | None,
    *,
    lowpass: Any,
    sparc_params: Mapping[str, float],
    read_options: Mapping[str, Any] | None = None,
    variants: Sequence[Any] = (),
) -> tuple[PartitionedRecordings, pd.DataFrame]:
    """The run's features on a cluster (``--workers``/``--scheduler``).

    Returns the recordings' stand-in and the feature table. The client (and a LocalCluster it started) is
    closed before returning.

    Parameters
    ----------
    data : Any
        The recordings: a folder of Parquet files, each holding whole trials (text path).
    workers : int or None
        Number of local worker processes (dimensionless), >= 1; None: the scheduler's.
    scheduler : str or None
        Address of a running Dask scheduler (text); None: a LocalCluster.
    lowpass : Any
        The positions' low-pass filter, as :func:`run_lowpass` takes it (cut-off in Hz).
    sparc_params : mapping of str to float
        SPARC's parameters ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless).
    read_options : mapping of str to Any or None
        The read options of :func:`skilllib.recordings.load_recordings` (text); all must be None here.
    variants : sequence
        SPARC settings of a sensitivity run; must be empty here.

    Returns
    -------
    recordings : PartitionedRecordings
        The recordings' stand-in.
    features : pandas.DataFrame
        The feature table of :func:`trial_features` (m/s, s, SPARC dimensionless).

    Raises
    ------
    ValueError
        :class:`ClusterOptionError` for what the cluster path does not take; DataFormatError (also a
        ValueError) for the data.
    """
    if data is None or not isinstance(data, (str, Path)) or not Path(data).is_dir() or not is_parquet(data):
        raise ClusterOptionError(
            "--workers and --scheduler need --data a folder of Parquet files (each holding "
            "whole trials; benchmarks/corpus.py --parquet writes one)"
        )
    if any(v is not None for v in dict(read_options or {}).values()) or variants:
        raise ClusterOptionError(
            "--workers and --scheduler read the recordings format as it is: no --columns, "
            "--units, ... and no --sensitivity"
        )
    if workers is not None and (isinstance(workers, bool) or int(workers) < 1):
        raise ClusterOptionError(f"workers must be a number of worker processes >= 1, got {workers!r}")
    with quiet_logs():  # one line for what goes wrong, as in memory (a bad file, Ctrl-C): no cluster logs
        blocked = _block_sigint()  # a Ctrl-C while the cluster starts is held until it can be closed
        try:
            client = client_for(workers, scheduler)
        except BaseException:
            _unblock_sigint(blocked)
            raise
        try:
            _unblock_sigint(blocked)  # a Ctrl-C held during start-up is raised here, and the cluster closed
            result = corpus_features(data, client, lowpass=lowpass, options={"sparc_params": dict(sparc_params)})
        finally:
            close_client(client)
    return PartitionedRecordings(result, str(data)), result.features
