# ---
# jupyter:
#   jupytext:
#     cell_metadata_filter: -all
#     formats: ipynb,py:percent
#     notebook_metadata_filter: kernelspec,jupytext
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#       jupytext_version: 1.19.6
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Your own data
#
# The previous chapters ran on the book's synthetic cohort. This one is for the lab engineer who wants
# to run the same pipeline on their own recordings tomorrow: how to export them to the book's format,
# the one command that runs everything, what it writes, how to choose another robot and other joint
# velocity limits, and what happens when a file or a trial is broken.
#
# ```{note}
# The example recordings in this chapter are synthetic too: a small cohort written by the book's
# generator (`skilllib.cohort`) at **120 Hz**, not the cohort's 60 Hz, to show that nothing
# in the pipeline assumes the paper's sampling rate. With your own file, replace its path.
# ```

# %%
import json
import subprocess
import sys
from pathlib import Path

import pandas as pd
from IPython.display import Image, display

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.data import COLUMNS, write_recordings

work = Path("_your_data")  # everything this chapter writes goes here
work.mkdir(exist_ok=True)

# %% [markdown]
# ## The format
#
# One CSV file, a long table with **one row per sample** and these columns:
#
# | column | unit | meaning |
# |---|---|---|
# | `participant` | – | participant id (an integer or a label such as `P01`) |
# | `trial` | – | trial number within the participant (integer) |
# | `t` | s | time stamp of the sample (any origin; increasing within a trial) |
# | `x`, `y`, `z` | m | tool-tip position: x mediolateral, **y vertical (up)**, z anteroposterior |
# | `contact` | 0/1 | 1 while the tip touches the target surface |
#
# The rows of one trial are contiguous and in time order; extra columns are ignored. The sampling rate
# is read from the time stamps, so any rate works, as long as one file has one rate.
#
# A typical device export is something else: one file per trial, millimetres, milliseconds, a
# different vertical axis. Converting it is a few lines of pandas. Here is a made-up export of one
# trial, and its conversion:

# %%
export = pd.DataFrame({  # one trial as a device might export it: ms, mm, z up, a force channel
    "time_ms": [0.0, 8.3, 16.7, 25.0],
    "X_mm": [1.20, 1.21, 1.19, 1.22],
    "Y_mm": [40.1, 40.3, 40.2, 40.4],
    "Z_mm": [80.0, 79.8, 76.5, 70.1],
    "force_N": [0.0, 0.0, 0.0, 0.6],
})
converted = pd.DataFrame({
    "participant": "P01",
    "trial": 1,
    "t": export["time_ms"] / 1000,  # ms -> s
    "x": export["X_mm"] / 1000,  # mm -> m, mediolateral
    "y": export["Z_mm"] / 1000,  # this device's z is up: it becomes the book's y
    "z": export["Y_mm"] / 1000,  # anteroposterior
    "contact": (export["force_N"] > 0.1).astype(int),  # contact from a force threshold
})[list(COLUMNS)]
converted

# %% [markdown]
# Concatenate the trials of all participants (`pd.concat`) and write the table with
# `skilllib.data.write_recordings(table, "my_recordings.csv")`, or with `DataFrame.to_csv(index=False)`.
#
# ## An example file at 120 Hz
#
# The chapter writes a small synthetic file instead of your recordings: 5 participants × 40 trials,
# sampled at 120 Hz.

# %%
example = generate_cohort(seed=11, model=CohortModel(n_participants=5, n_trials=40, fs=120.0)).frame
data_file = write_recordings(example, work / "lab_recordings.csv")
print(f"{data_file}: {len(example)} rows, {example.groupby(['participant', 'trial']).ngroups} trials")
example.head()

# %% [markdown]
# ## The command
#
# From the repository, with the project's environment (`make book` or `make test` creates `.venv`):
#
# ```bash
# .venv/bin/python -m skilllib run --data lab_recordings.csv --out results/
# ```
#
# Options: `--k K` (clusters, default 6), `--robot NAME` (`simple6`, `ur5`, `puma560`, `panda`),
# `--qd-max RAD_S ...` (one joint velocity limit for all joints, or one per joint), `--scaling raw|standard`
# (features as the paper uses them, or standardised before K-means), `--seed`, `--no-figures`, `--quiet`.
# Progress bars show the long steps; a summary closes the run. The chapter runs the command as a
# subprocess, exactly as you would in a terminal:

# %%
def skilllib_run(*args: str) -> int:
    """Run `python -m skilllib run ARGS` and show what it prints; return its exit status."""
    proc = subprocess.run([sys.executable, "-m", "skilllib", "run", "--quiet", *args],
                          capture_output=True, text=True)
    print(proc.stdout + proc.stderr)
    return proc.returncode


status = skilllib_run("--data", str(data_file), "--out", str(work / "results"))
print("exit status:", status)

# %% [markdown]
# ## What it writes
#
# `results.json` holds everything the summary names, in a documented schema (README, *results.json*):
# the data set and its sampling rate, the SPARC parameters, **one entry for every input trial** with
# its status (`selected`, `excluded` or `invalid`), the reason when it was not selected, and its
# features; the silhouette of every k; the clusters and their prototypes; and the transfer to the robot.

# %%
results = json.loads((work / "results" / "results.json").read_text())
print("top-level keys:", list(results))
print("dataset:", results["dataset"])
trials = pd.DataFrame(results["trials"])
trials["status"].value_counts()

# %% [markdown]
# The sampling rate came from the time stamps. The trials that were not selected say why:

# %%
trials[trials["status"] != "selected"].head(8)

# %% [markdown]
# The clusters and their prototypes, ordered by the peak speed of their centre, and the transfer of
# each prototype to the robot:

# %%
clusters = pd.json_normalize(results["clusters"])
transfer = pd.DataFrame(results["transfer"]["prototypes"])
clusters.join(transfer[["feasible", "time_scale"]]).round(3)

# %% [markdown]
# Every figure of the pipeline is written beside `results.json`, as PNG and SVG:

# %%
print(sorted(results["figures"]))

# %%
#| label: fig-your-clusters
#| caption: The PV-SPARC plane of the 120 Hz example file as the pipeline draws it, with the centres and the prototype trials.
display(Image(filename=str(work / "results" / "clusters_pv_sparc.png"), width=520))

# %% [markdown]
# ## Another robot, other limits
#
# `--robot` chooses the arm and its start pose; `--qd-max` replaces its joint velocity limits (rad/s).
# A prototype whose joints would exceed the limits is marked infeasible, and `time_scale` says how
# much slower it must be executed: every joint velocity divides by that factor. Here is the UR5 with a
# cautious limit of 1 rad/s on every joint:

# %%
status = skilllib_run("--data", str(data_file), "--out", str(work / "ur5"), "--robot", "ur5",
                      "--qd-max", "1.0", "--no-figures")
ur5 = json.loads((work / "ur5" / "results.json").read_text())["transfer"]
print(ur5["robot"], "start pose (deg):", [round(q, 1) for q in ur5["q0_deg"]])
pd.DataFrame(ur5["prototypes"])[["cluster", "feasible", "time_scale", "max_cond_j"]].round(3)

# %% [markdown]
# ## When the input is broken
#
# A problem with the **file** stops the run before anything is computed, with one line that names
# the file and, where it applies, the line and the column, and a non-zero exit status (2). Positions
# in millimetres, for instance:

# %%
(example.assign(x=example.x * 1000, y=example.y * 1000, z=example.z * 1000)
 .to_csv(work / "in_mm.csv", index=False))
print("exit status:", skilllib_run("--data", str(work / "in_mm.csv"), "--out", str(work / "mm")))

# %% [markdown]
# A cell that is not a number:

# %%
lines = (work / "lab_recordings.csv").read_text().splitlines()
lines[5] = lines[5].replace(lines[5].split(",")[4], "0.1O2", 1)  # a letter O typed for a zero
(work / "typo.csv").write_text("\n".join(lines) + "\n")
print("exit status:", skilllib_run("--data", str(work / "typo.csv"), "--out", str(work / "typo")))

# %% [markdown]
# A problem with one **trial** (time going backwards or repeated, a missing position, no contact, no
# movement onset, too few samples, rows of one trial scattered in the file) never stops the run: the
# trial is kept in `results.json` as `invalid`, with its reason, and the rest is analysed. Here two
# trials lose their contact samples and one gets an empty cell:

# %%
broken = example.copy()
first_two = broken[["participant", "trial"]].drop_duplicates().head(2)
for p, tr in first_two.itertuples(index=False):
    broken.loc[(broken.participant == p) & (broken.trial == tr), "contact"] = 0
broken.loc[broken.index[(broken.participant == 3) & (broken.trial == 7)][10], "y"] = float("nan")
write_recordings(broken, work / "broken.csv")
status = skilllib_run("--data", str(work / "broken.csv"), "--out", str(work / "broken"), "--no-figures")
bad = pd.DataFrame(json.loads((work / "broken" / "results.json").read_text())["trials"])
bad[bad["status"] == "invalid"][["participant", "trial", "status", "reason"]]

# %% [markdown]
# ## Summary
#
# - Recordings enter the book as one CSV file: `participant, trial, t, x, y, z, contact`, in seconds
#   and metres with y up; a few lines of pandas convert a device's export.
# - `python -m skilllib run --data FILE --out DIR` runs the whole pipeline at any sampling rate and
#   writes `results.json` and every figure; `--robot` and `--qd-max` choose the arm and its limits.
# - A broken file stops with one line naming the problem; a broken trial is kept, marked `invalid`
#   with its reason, and everything else is analysed. No trial is dropped silently.
