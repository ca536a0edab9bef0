# ---
# jupyter:
#   jupytext:
#     cell_metadata_filter: tags,-all
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
# the one command that runs everything, how to read what it writes (`results.json` and the figures),
# how to choose another robot and other joint velocity limits, and what happens when a file or a trial
# is broken.
#
# ```{note}
# The example recordings in this chapter are synthetic too: a small cohort written by the book's
# generator (`skilllib.cohort`) at a higher sampling rate than the cohort's (the paper's Phantom
# recorded at 60 Hz), to show that nothing in the pipeline assumes the paper's rate. With your own
# file, replace its path.
# ```

# %%
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from IPython.display import Image, display

import skilllib.data
from skilllib.cohort import CohortModel, generate_cohort
from skilllib.data import COLUMNS, read_recordings, write_recordings
from skilllib.features import diff_window, trial_features
from skilllib.robots import ROBOT_NAMES, get_robot

work = Path("_your_data")  # everything this chapter writes goes here
work.mkdir(exist_ok=True)
pd.set_option("display.max_colwidth", 120)

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
# The rows of one trial are contiguous and in time order; extra columns are ignored. The movement
# analysed is the approach from rest down to the first sample with `contact = 1`, so the recording of a
# trial should start while the hand is still at rest and must include the moment of contact.
#
# A typical device export is something else: one file per trial, millimetres, milliseconds, a
# different vertical axis, contact as a force. Converting it is a few lines of pandas. Here is a
# made-up export of one trial, and its conversion:

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
# **The sampling rate** is not an option: it is read from the time stamps (the median over trials of
# each trial's mean interval), so any rate works, as long as one file has one rate. Small jitter of the
# time stamps is tolerated (the analysis then assumes uniform sampling at that rate). The checks and
# their tolerances, from `skilllib.data`:

# %%
print(f"a trial whose median interval differs by more than {skilllib.data.RATE_TOLERANCE:.0%} from the file's "
      f"is invalid (sampled at another rate);\nif more than {skilllib.data.MIXED_FRACTION:.0%} of the trials "
      f"are, the file mixes rates and the run stops;\na single interval more than "
      f"{skilllib.data.INTERVAL_TOLERANCE:.0%} off the file's makes its trial invalid (irregular sampling, "
      f"e.g. a dropped sample).")

# %% [markdown]
# If your participants were recorded at different rates, split the file by rate and run each part, or
# resample every trial to one rate first (e.g. `numpy.interp` of x, y, z on a regular time grid).
#
# **High sampling rates.** A finite difference over one sample interval turns position noise into speed
# noise in proportion to the rate: at 1 kHz the device's 0.03 mm resolution alone would give about
# $0.03\,\text{mm} \times 1000\,\text{Hz} / \sqrt{2} \approx 21$ mm/s of noise, with peaks near the
# 0.05 m/s onset threshold, and a trial whose speed at its first sample exceeds the
# threshold cannot be segmented (*no rest before onset*). skilllib therefore differentiates over a window
# of fixed *duration* (chapter 2), which is three samples at 60 Hz and more at higher rates. The window
# at each rate, the share of invalid trials and the median features of the same generator recorded at
# several rates show that the rate does not change the result:

# %%
rates = []
for fs in (60, 120, 240, 500, 1000):
    rec = generate_cohort(seed=3, model=CohortModel(n_participants=3, n_trials=20, fs=float(fs))).frame
    f = trial_features(rec)
    rates.append({"rate (Hz)": fs, "window (samples)": diff_window(fs),
                  "invalid trials": f"{(f['status'] == 'invalid').mean():.0%}",
                  "median PV (m/s)": f"{f['pv'].median():.3f}", "median SPARC": f"{f['sparc'].median():.3f}",
                  "median contact speed (m/s)": f"{f['contact_speed'].median():.3f}"})
pd.DataFrame(rates).set_index("rate (Hz)")

# %% [markdown]
# The contact speed falls slightly with the rate: it is the speed at the last sample before contact,
# and at 60 Hz that sample lies up to 1/60 s before the touch, while the approach is still
# decelerating. If your device is much noisier than the Phantom, low-pass filter the positions before
# export (e.g. `scipy.signal.savgol_filter` or a zero-phase Butterworth filter); the command's summary
# suggests it when many trials fail with *no rest before onset*.
#
# ## An example file
#
# The chapter writes a small synthetic file instead of your recordings: a few participants with a few
# dozen trials each, at 120 Hz. The sampling rate printed here is the one read back from the time
# stamps of the file.

# %%
example = generate_cohort(seed=11, model=CohortModel(n_participants=5, n_trials=40, fs=120.0)).frame
data_file = write_recordings(example, work / "lab_recordings.csv")
check = read_recordings(data_file)
print(f"{data_file}: {len(example)} rows, {example['participant'].nunique()} participants, "
      f"{len(check)} trials, sampled at {check.fs:.4g} Hz")
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
# Options: `--k K` (clusters, default 6 as in the paper), `--robot NAME` (`simple6`, `ur5`, `puma560`,
# `panda`), `--qd-max RAD_S ...` (one joint velocity limit for all joints, or one per joint),
# `--scaling raw|standard` (features as the paper uses them, or standardised before K-means), `--seed`
# (of K-means), `--no-figures`, `--quiet` (no progress bars), `--debug` (a traceback for an unexpected
# error). In a terminal, progress bars follow the long steps (the features of every trial, the
# silhouette sweep over k, the transfer of every prototype); a summary closes the run. The chapter runs
# the command as a subprocess, exactly as you would in a terminal:

# %%
def skilllib_run(*args: str) -> int:
    """Run `python -m skilllib run --quiet ARGS`, show what it prints; return its exit status."""
    proc = subprocess.run([sys.executable, "-m", "skilllib", "run", "--quiet", *args],
                          capture_output=True, text=True, check=False)
    print(proc.stdout + proc.stderr)
    return proc.returncode


status = skilllib_run("--data", str(data_file), "--out", str(work / "results"))
print("exit status:", status)

# %% [markdown]
# The summary says how many trials were read, selected (contact speed in the paper's window),
# excluded (with the commonest reasons) and invalid; the k used and the average silhouette; each
# cluster's prototype trial and its peak joint speed on the robot; how many prototypes the robot can
# execute as recorded. `note:` lines report what the run adapted: a silhouette range shrunk because
# there are few selected trials, a k reduced to what the data allow, a k that is not silhouette-valid
# for these data.
#
# The exit status tells a script what happened:
#
# | status | meaning |
# |---|---|
# | 0 | done: results.json, figures and prototypes |
# | 2 | the file cannot be read or an option is wrong: one line on stderr, nothing computed |
# | 3 | done, but fewer than 3 (distinct) trials were selected: results.json lists every trial, no prototypes |
# | 1 | an unexpected error (please report it, with the output of `--debug`) |
#
# ## Reading results.json
#
# `results.json` holds everything the summary names, in the schema documented in the README
# (*results.json*): the data set and its sampling rate, the SPARC parameters, **one entry for every
# input trial** with its status (`selected`, `excluded` or `invalid`), the reason when it was not
# selected, and its features; the silhouette of every k and which k are valid; the clusters and their
# prototypes; the transfer to the robot; the notes of the run; the figure files.

# %%
results = json.loads((work / "results" / "results.json").read_text())
print("top-level keys:", list(results))
print("dataset:", results["dataset"])
print("messages:", results["messages"])
trials = pd.DataFrame(results["trials"])
trials["status"].value_counts()

# %% [markdown]
# The `trials` list is a table: load it with pandas and filter it. The trials that were not selected
# say why:

# %%
trials[trials["status"] != "selected"].head(5)

# %% [markdown]
# The clusters, ordered by the peak speed of their centre, with their prototype trials (`prototype.*`)
# and the transfer of each prototype to the robot: `feasible` is whether every joint stays within its
# velocity limit as the human moved, `time_scale` how much slower the robot must execute it otherwise
# (1 when feasible):

# %%
clusters = pd.json_normalize(results["clusters"])
transfer = pd.DataFrame(results["transfer"]["prototypes"])
clusters.join(transfer[["feasible", "time_scale", "max_cond_j"]]).round(3)

# %% [markdown]
# ## Reading the figures
#
# Every figure of the pipeline is written beside `results.json`, as PNG (to look at) and SVG (to put
# in a paper):

# %%
print(sorted(results["figures"]))

# %% [markdown]
# | file | shows | explained in |
# |---|---|---|
# | `trials_by_participant` | height y and speed of every valid trial against time from contact, per participant (the paper's Fig. 1b) | chapter 2 |
# | `participant_features` | PV, contact speed, duration and SPARC per participant | chapter 2 |
# | `features` | the contact-speed histogram with the selection window; PV against SPARC | chapter 2 |
# | `silhouette_sweep` | average silhouette for every k, valid k filled | chapter 3 |
# | `silhouettes_k` | the silhouette of every trial at the k used | chapter 3 |
# | `clusters_pv_sparc` | clusters, centres and prototypes in the PV-SPARC plane (the paper's Fig. 2a) | chapter 3 |
# | `prototype_speed_profiles` | the speed profile of every prototype (the paper's Fig. 2b) | chapter 3 |
# | `joint_velocities` | the robot's joint velocities for every prototype, with the limits (the paper's Fig. 4) | chapter 4 |
# | `frame_mapping` | where the fastest prototype's path lies in the robot's workspace | chapter 4 |
#
# Look at `trials_by_participant` first: it shows at once whether the export is right (y should fall
# to the contact surface and stay there; speed should rise from rest and end at contact). For the
# example file:

# %%
#| label: fig-your-trials
#| caption: Height y (m) and approach speed (m/s) of every valid trial of the example file against time from contact (s), one column per participant; selected trials in colour, excluded ones in grey. Written by the command as trials_by_participant.png.
display(Image(filename=str(work / "results" / "trials_by_participant.png"), width=680))

# %% [markdown]
# Then the clusters and their prototypes, and what the robot must do to reproduce them:

# %%
#| label: fig-your-clusters
#| caption: The PV-SPARC plane of the example file as the command draws it, with the K-means centres and the prototype trials (clusters_pv_sparc.png).
display(Image(filename=str(work / "results" / "clusters_pv_sparc.png"), width=560))

# %%
#| label: fig-your-joints
#| caption: Joint velocities (rad/s) of Simple6 reproducing each prototype of the example file, one panel per cluster, with the joint velocity limits dashed (joint_velocities.png).
display(Image(filename=str(work / "results" / "joint_velocities.png"), width=680))

# %% [markdown]
# ## Another robot, other limits
#
# `--robot` chooses the arm and its start pose; each comes with default joint velocity limits
# (justified in `skilllib.robots`):

# %%
rows = []
for name in ROBOT_NAMES:
    arm = get_robot(name)
    rows.append({"--robot": name, "arm": arm.robot.name, "joints": arm.robot.n,
                 "start pose q0 (deg)": np.round(np.rad2deg(arm.q0), 1).tolist(),
                 "default limits (rad/s)": np.round(arm.qd_limits, 3).tolist()})
pd.DataFrame(rows).set_index("--robot")

# %% [markdown]
# `--qd-max` replaces the limits: one value for every joint, or one per joint, in rad/s. A prototype
# whose joints would exceed them is marked infeasible, and `time_scale` says how much slower it must be
# executed: every joint velocity divides by that factor, and so does the prototype's peak speed, while
# its SPARC stays the same (chapter 4). Here is the UR5 with slower base joints than wrist joints:

# %%
limits = ["1.0", "1.0", "1.0", "2.0", "2.0", "2.0"]  # rad/s, q1..q6
status = skilllib_run("--data", str(data_file), "--out", str(work / "ur5"), "--robot", "ur5",
                      "--qd-max", *limits, "--no-figures")
ur5 = json.loads((work / "ur5" / "results.json").read_text())
table = pd.DataFrame(ur5["transfer"]["prototypes"])[["cluster", "feasible", "time_scale", "max_cond_j"]]
table["PV as recorded (m/s)"] = [c["prototype"]["pv"] for c in ur5["clusters"]]
table["PV executable (m/s)"] = table["PV as recorded (m/s)"] / table["time_scale"]
table.round(3)

# %% [markdown]
# An arm the command does not know can be used from Python: `skilllib.transfer.transfer(robot, t,
# positions, velocities, q0=..., qd_limits=...)` takes any roboticstoolbox arm with at least six
# joints, a start pose inside its joint limits and its velocity limits (chapter 4 shows how the start
# poses above were chosen).
#
# ## When the input is broken
#
# A problem with the **file** stops the run before anything is computed, with one line that names
# the file and, where it applies, the line and the column and how to fix it, and exit status 2.
# Positions in millimetres, for instance:

# %%
(example.assign(x=example.x * 1000, y=example.y * 1000, z=example.z * 1000)
 .to_csv(work / "in_mm.csv", index=False))
print("exit status:", skilllib_run("--data", str(work / "in_mm.csv"), "--out", str(work / "mm")))

# %% [markdown]
# A cell that is not a number:

# %%
lines = (work / "lab_recordings.csv").read_text().splitlines()
cells = lines[5].split(",")
cells[4] = cells[4].replace("0", "O", 1)  # a letter O typed for a zero in column y
lines[5] = ",".join(cells)
(work / "typo.csv").write_text("\n".join(lines) + "\n")
print("exit status:", skilllib_run("--data", str(work / "typo.csv"), "--out", str(work / "typo")))

# %% [markdown]
# The other file-level problems are a missing or empty file, a missing column (named), time stamps in
# milliseconds, a file that mixes sampling rates, and a participant or trial id left empty.
#
# A problem with one **trial** never stops the run: the trial is kept in `results.json` as `invalid`,
# with its reason, and the rest is analysed. The next file breaks one trial in each of the ways the
# pipeline recognises:

# %%
broken = example.copy()
keys = broken[["participant", "trial"]].drop_duplicates().to_numpy()[:8]


def rows(i: int) -> pd.Index:
    """Index of the rows of the i-th trial of the file."""
    p, tr = keys[i]
    return broken.index[(broken.participant == p) & (broken.trial == tr)]


r = rows(0)
broken.loc[r[20], "t"] = broken.loc[r[18], "t"]  # time goes backwards
r = rows(1)
broken.loc[r[20], "t"] = broken.loc[r[19], "t"]  # a repeated time stamp
broken.loc[rows(2)[10], "y"] = np.nan  # an empty cell
broken.loc[rows(3)[10], "z"] = np.inf  # an infinite position
broken.loc[rows(4), "contact"] = 0  # never touches the surface
r = rows(5)  # never moves before contact: no onset
c = int(np.flatnonzero(broken.loc[r, "contact"].to_numpy())[0])
broken.loc[r[:c], ["x", "y", "z"]] = broken.loc[r[0], ["x", "y", "z"]].to_numpy(dtype=float)
broken = broken.drop(rows(6)[3:])  # only 3 samples left
first = rows(7)[0]  # the first row of a trial moved to the end of the file: rows not contiguous
broken = pd.concat([broken.drop(first), broken.loc[[first]]])
write_recordings(broken, work / "broken.csv")
status = skilllib_run("--data", str(work / "broken.csv"), "--out", str(work / "broken"), "--no-figures")
bad = pd.DataFrame(json.loads((work / "broken" / "results.json").read_text())["trials"])
bad[bad["status"] == "invalid"][["participant", "trial", "status", "reason"]]

# %% [markdown]
# Two more trial-level checks need no example: a trial with fewer samples from onset to contact than
# the segmentation needs is invalid (*too short*), and so is a trial sampled at another rate than the
# rest of the file or with a missing sample (above). With fewer than 3 selected trials the run still
# writes `results.json` with every trial, skips the clustering and the transfer, and ends with exit
# status 3; with few selected trials the silhouette range shrinks to what they allow, and a `--k` larger
# than that is reduced, each said in a `note:` line and in `messages`.
#
# ## Summary
#
# - Recordings enter the book as one CSV file: `participant, trial, t, x, y, z, contact`, in seconds
#   and metres with y up; a few lines of pandas convert a device's export. The sampling rate comes from
#   the time stamps: any rate, one per file.
# - `python -m skilllib run --data FILE --out DIR` runs the whole pipeline and writes `results.json`
#   (every trial with its status and reason, the clusters, the prototypes, the transfer) and every
#   figure as PNG and SVG; `--robot` and `--qd-max` choose the arm and its joint velocity limits, and
#   `time_scale` says how much slower an infeasible prototype must run.
# - A broken file stops with one line naming the problem and how to fix it; a broken trial is kept,
#   marked `invalid` with its reason, and everything else is analysed. No trial is dropped silently.
