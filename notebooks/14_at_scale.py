# ---
# jupyter:
#   jupytext:
#     cell_metadata_filter: tags,jupyter,-all
#     formats: ipynb,py:percent
#     notebook_metadata_filter: kernelspec,jupytext
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#       jupytext_version: 1.19.6
#   kernelspec:
#     display_name: Smoothness-based prototypes (skilllib)
#     language: python
#     name: skilllib
# ---

# %% [markdown]
# ---
# numbering:
#   enumerator: "14.%s"
# ---
# # At scale
#
# One lab records 1,500 touches. A lab that runs the protocol for years, a multi-site study or a VR
# application that logs every reach of its players records $10^5$ to $10^8$. The paper's procedure does
# not change with the number of trials; what changes is how it is computed: the features without a
# Python loop per trial, the silhouettes without comparing every pair of trials, the data in a columnar
# format, and beyond one machine's memory a Dask cluster. This chapter shows each change and checks that
# the numbers stay what they were.
#
# ```{note}
# The corpora here are synthetic: the book's cohort, and for the benchmark the cohort tiled with jittered
# copies (`benchmarks/corpus.py`: each copy's trials scaled a little in amplitude and shifted, the
# participants renamed). The timings were measured on one shared 2-core virtual machine, at the commit
# printed with them below: they are a record of that commit, not of the code that built this page
# (`benchmarks/bench_scale.py` measures them again).
# ```

# %% tags=["hide-input"] jupyter={"source_hidden": true}
import json
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd
from sklearn.metrics import silhouette_score

import skilllib as sk
import skilllib.figures as skf

# the repository (the benchmark's measurements are committed there), wherever it runs
SCALE_JSON = Path("benchmarks", "results", "scale.json")
ROOT = next(
    p
    for p in [Path.cwd(), *Path.cwd().parents, Path(sk.__file__).parents[1]]
    if (p / SCALE_JSON).exists()
)
rec = sk.read_recordings(sk.cohort_path())
table = sk.trial_features(rec)

# %% [markdown]
# ## The same table without a loop per trial
#
# Chapters 3 and 4 segment one trial at a time with
# [`sk.segment_arrays`](#skilllib.features.segment_arrays): the derivative of the approach, the onset,
# the segment. That remains the definition. For many trials
# [`sk.trial_features`](#skilllib.features.trial_features) gathers the trials whose approaches have the same
# length into one block and runs every step on the block along its rows. A numpy reduction along the rows
# of a block (the sums of LDLJ, the medians of the checks, the derivative's convolution) computes each
# row exactly as it computes that row alone, so the block path gives the same bits (at high sampling
# rates, where the derivative's window is longer and scipy fits the first and last velocities of an
# approach by least squares, those agree to rounding error instead). Below, the cohort's
# feature table is recomputed one trial at a time and compared with the table of the vectorised path.

# %%
rows = []
for (p, tr), status in zip(rec.keys(), rec.trials["status"]):
    d = rec.trial(p, tr)
    seg = sk.segment_arrays(d.t, d.pos, d.contact, rec.fs)
    if status == "ok" and not isinstance(seg, str):
        v = seg.speed
        rows.append(
            {
                "pv": v.max(),
                "contact_speed": v[-1],
                "duration": seg.duration,
                "ldlj": sk.ldlj(v, rec.fs),
                "speed": v,
            }
        )
one_by_one = pd.DataFrame(rows)
one_by_one["sparc"] = sk.sparc_bands(list(one_by_one["speed"]), rec.fs).sparc
vectorised = table[table["status"] != "invalid"].reset_index(drop=True)
same = {
    c: bool(np.array_equal(one_by_one[c].to_numpy(), vectorised[c].to_numpy()))
    for c in ("pv", "contact_speed", "duration", "ldlj", "sparc")
}
print(f"{len(one_by_one)} segmented trials, one by one and vectorised:")
for column, equal in same.items():
    print(f"  {column:14s} every bit the same: {equal}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
assert len(one_by_one) == len(vectorised) and all(same.values()), (
    "text: 'the same bits'"
)

# %% [markdown]
# SPARC needs one more condition. [`sparc_bands`](#skilllib.smoothness.sparc_bands) evaluates the
# spectra of many profiles together, and a profile's value must not depend on which other profiles share
# its batch. Two things made it depend, by a few units in the last place:
#
# - batches were padded to their longest profile;
# - BLAS rounds a row of a matrix product differently depending on how many rows it computes at once.
#
# So profiles are batched by length, and the products use numpy's own loops. The Dask path below
# computes each partition's trials in other batches than the in-memory path and still gets the same
# bits.
#
# ## Silhouettes: exact up to 5,000 points, then an estimate
#
# The silhouette of a trial compares its distance to its own cluster with its distance to the nearest
# other cluster [@rousseeuw1987]. Every pair of trials enters, so the cost of the exact average grows with
# $N^2$, and the sweep fits 15 clusterings. Up to 5,000 points (`sk.SILHOUETTE_EXACT_MAX`)
# the book computes it exactly. Beyond that
# it reports the mean over 10 random subsamples of 1,000 trials each, stratified by cluster so that a
# small cluster is always represented, together with the spread of that mean. The subsamples are seeded
# by `--seed`. Below, the cohort's selected trials are tiled 12 times with a small jitter, about 8,000
# points, and the estimate for $k = 6$ is compared with the exact value.

# %%
sel = sk.select(table)
rng = np.random.default_rng(1)
copies, n = 12, len(sel)
tiled = pd.DataFrame(
    {
        "participant": np.repeat(np.arange(copies), n).astype(str),
        "trial": np.tile(np.arange(n), copies).astype(str),
        "pv": np.tile(sel["pv"], copies) * rng.uniform(0.97, 1.03, copies * n),
        "sparc": np.tile(sel["sparc"], copies) + rng.normal(0, 0.01, copies * n),
    }
)
fit = sk.fit_prototypes(tiled, 6)
est = fit.silhouette_estimate
se = est.sd / np.sqrt(est.repeats)  # the standard error of the estimate
exact = silhouette_score(tiled[["pv", "sparc"]].to_numpy(), fit.labels)
print(f"{len(tiled)} points, k = 6")
print(
    f"  estimate: {fit.silhouette:.4f} (mean of {est.repeats} subsamples "
    f"of {est.sample_size}; SD of the mean {se:.4f})"
)
print(f"  exact:    {exact:.4f} (difference {fit.silhouette - exact:+.4f})")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
assert (sk.SILHOUETTE_EXACT_MAX, est.repeats, est.sample_size) == (5000, 10, 1000), (
    "text: 'up to 5,000 points', '10 random subsamples of 1,000 trials'"
)
assert sk.TRIALS_IN_JSON_MAX == 10_000, "text: 'above 10,000 trials'"
assert fit.silhouette_method == "subsample" and len(tiled) > sk.SILHOUETTE_EXACT_MAX
assert 7_500 < len(tiled) < 8_500, "text: 'about 8,000 points'"
assert abs(fit.silhouette - exact) < 3 * se, "text: estimate within its spread"

# %% [markdown]
# The estimate lies within three of its standard errors of the exact value. `results.json` says which
# one a run used (`silhouette_estimate`, with the spread per $k$), and the run prints a note when it
# estimated. The K-means fits themselves use all points.
#
# ## Columnar data and the cluster
#
# A corpus of $10^5$ trials is a CSV file of hundreds of megabytes. skilllib reads plain CSV files (one
# record per line) with pyarrow's CSV reader; any other goes to pandas' reader, with the same result. It reads Parquet files, and folders of them, directly. Above 10,000 trials
# it writes the per-trial table as `trials.parquet` beside `results.json`.
#
# Beyond one machine the corpus is a folder of Parquet files, each holding whole trials: the partitions.
# [`sk.cluster_features`](#skilllib.features.cluster_features) runs on every partition, on a worker of a
# Dask cluster, the same functions as the in-memory path. What the in-memory path decides over the whole
# file is decided here over the whole corpus, from small per-partition summaries:
#
# - the sampling rate;
# - whether positions are in metres;
# - whether the noise at rest needs a low-pass filter.
#
# Only the feature table comes back. Here the cohort is written as three Parquet files and processed on a
# local cluster of two worker processes.

# %%
folder = Path(tempfile.mkdtemp()) / "cohort"
folder.mkdir()
frame = rec.frame.astype({"participant": str, "trial": str})
first = frame["participant"].to_numpy()
cuts = [0, int((first == "4").argmax()), int((first == "8").argmax()), len(frame)]
for k in range(3):
    part = frame.iloc[cuts[k] : cuts[k + 1]]
    part.to_parquet(folder / f"part-{k}.parquet", index=False)
n_parts = len(list(folder.glob("*.parquet")))
_, on_cluster = sk.cluster_features(
    folder, 2, None, lowpass="auto", sparc_params=sk.SPARC_PARAMS
)  # a local cluster of 2 workers, closed on return
identical = on_cluster.equals(table)
print(f"{n_parts} partitions on 2 workers: {len(on_cluster)} trials")
print(f"the feature table equals the in-memory one: {identical}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
assert identical, "text: the cluster's feature table is the in-memory one"

# %% [markdown]
# The command line does the same with `--workers N` (a local cluster) or `--scheduler ADDRESS` (a running
# one). README's "At scale" section shows how to start one:
#
# - on several machines with `dask scheduler` and `dask worker`;
# - on a batch system with dask-jobqueue;
# - on Kubernetes.
#
# Clustering and the transfer then run on the client, on the gathered table.
#
# ## How time and memory grow
#
# `benchmarks/bench_scale.py` runs the whole pipeline without figures, as the command line does, on
# corpora from 1,500 to about $10^6$ trials. It records the wall time and the peak resident memory of the
# run and of its largest Dask worker. The measurements are committed in `benchmarks/results/scale.json`.
# [](#fig-scaling) draws them.

# %%
bench = json.loads((ROOT / SCALE_JSON).read_text())
runs = pd.DataFrame(bench["rows"])
columns = [
    "trials",
    "input",
    "mode",
    "wall_s",
    "peak_main_mb",
    "peak_worker_mb",
    "failed",
]
shown = runs[columns].copy()
shown.loc[shown["mode"] != "dask", "peak_worker_mb"] = (
    np.nan
)  # only Dask runs have workers
machine = bench["machine"]
print(
    f"measured {bench['when']} at commit {machine['commit']} on {machine['cpus']} CPUs"
)
print(shown.round(1).to_string(index=False))

# %%
#| label: fig-scaling
#| caption: Synthetic corpora (the cohort tiled with jittered copies). Wall time and peak memory of `python -m skilllib run --no-figures` against the number of trials, in memory from one CSV file or a folder of Parquet files, and on a local Dask cluster of two workers; measured on one shared 2-core virtual machine (benchmarks/results/scale.json).
fig = skf.plot_scaling(bench["rows"])
# %%
# bench_scale.py's fits: the slope from 150,000 trials up, the cost of 10^6 more
fits = bench["fits"]
memory_csv, cluster = fits["in-memory, csv"], fits["Dask, 2 workers, parquet"]
slope = memory_csv["time_s"]["slope"]
s_per_million = memory_csv["time_s"]["per_million"]
mb_per_million = memory_csv["peak_main_mb"]["per_million"]
client_gb_per_million = cluster["peak_main_mb"]["per_million"] / 1e3
by_mode = runs.set_index("trials")
csv_runs = by_mode[(by_mode["mode"] == "inmemory") & (by_mode["input"] == "csv")]
parquet_runs = by_mode[
    (by_mode["mode"] == "inmemory") & (by_mode["input"] == "parquet")
]
dask_runs = by_mode[by_mode["mode"] == "dask"]
at_150k = csv_runs.loc[150_000]
print(
    f"150,000 trials in memory: {at_150k['wall_s']:.0f} s, "
    f"{at_150k['peak_main_mb']:,.0f} MB"
)
print(f"in memory, from 150,000 trials up: time ~ N^{slope:.2f}")
print(
    f"  10^6 more trials cost {s_per_million:.0f} s and {mb_per_million / 1e3:.1f} GB"
)
print(
    f"  10^8 trials: about {s_per_million * 100 / 3600:.1f} h "
    f"and {mb_per_million * 100 / 1e3:,.0f} GB"
)
print("on the cluster, the client's memory:")
print(
    f"  +{client_gb_per_million:.2f} GB per 10^6 trials, "
    f"about {client_gb_per_million * 100:.0f} GB for 10^8"
)
print(
    "a Dask worker's peak, largest over all runs:",
    f"{dask_runs['peak_worker_mb'].max():.0f} MB",
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
assert at_150k["wall_s"] < 60 and at_150k["peak_main_mb"] < 1500, (
    "issue 15: 150,000 trials under 60 s and 1.5 GB"
)
assert memory_csv["time_s"]["sizes"][0] == 150_000, (
    "text: the slope is fitted from 150,000 trials up"
)
assert 0.85 < slope < 1.15, "text: time grows in proportion to N from 150,000 trials up"
assert runs["trials"].max() >= 1_000_000 and not runs["failed"].any(), (
    "text: every run up to 10^6 trials finished"
)
assert mb_per_million * 100 > machine["ram_mb"], (
    "text: 10^8 trials do not fit in this machine in memory"
)
assert client_gb_per_million * 100 > 20, "text: the client needs tens of GB at 10^8"
assert dask_runs["peak_worker_mb"].max() < 1000, (
    "text: a worker's peak stays within a few hundred MB"
)
assert (dask_runs["wall_s"] > parquet_runs["wall_s"]).all(), (
    "text: two local workers are slower than the in-memory path"
)

# %% [markdown]
# From 150,000 trials up, the time of a whole run grows in proportion to the number of trials (the slope
# printed above; below that, the few seconds of start-up weigh). The cost per trial is the reading, the
# segmentation and the K-means fits of the sweep, all linear in $N$. The silhouette costs a fixed amount
# per $k$ once it is an estimate. Memory grows linearly too. $10^8$ trials do not fit in this machine's
# memory on the in-memory path.
#
# On the cluster, a worker holds one partition at a time. Its peak stays within a few hundred MB,
# whatever the corpus. The client still gathers the feature table and runs K-means on all selected
# trials, and its memory grows with $N$ at the rate printed above. So $10^8$ trials need a client of
# that size, or a clustering that runs on the cluster too, which the book does not build. With two
# local workers on the same two cores, the cluster is slower than the in-memory path: it reads each
# partition three times, and moves data between processes. It is meant for workers on other machines,
# which this benchmark did not measure.
#
# ## Summary
#
# - The features of every trial are computed in blocks of trials of equal length, with the same bits as
#   the per-trial definitions of chapters 3 and 4 (a test compares them on the cohort and on trials that
#   fail in every way). SPARC of a profile does not depend on the other profiles computed with it.
# - Silhouettes are exact up to 5,000 selected trials. Beyond that they are the mean of 10 stratified
#   subsamples with its spread, seeded by `--seed`, and `results.json` says which.
# - Plain CSV files are read by pyarrow. Parquet files and folders can be read in. Above 10,000 trials
#   the per-trial table goes to `trials.parquet`.
# - A folder of Parquet files runs on a Dask cluster with `--workers` or `--scheduler`. Its feature table
#   is the in-memory path's, bit for bit.
# - Time and memory grow linearly with the number of trials. One machine handles $10^6$ in memory;
#   $10^8$ needs the cluster, and a client that holds the feature table.
