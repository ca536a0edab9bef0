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
#     display_name: Smoothness-based prototypes (skilllib)
#     language: python
#     name: skilllib
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

# %% tags=["hide-input"]
import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from IPython.display import Image, display

import skilllib.data
from skilllib.cohort import CohortModel, generate_cohort
from skilllib.data import COLUMNS, read_recordings, write_recordings
from skilllib.features import ONSET_SPEED, diff_window, trial_features
from skilllib.robots import ROBOT_NAMES, get_robot

work = Path("_your_data")  # everything this chapter writes goes here
shutil.rmtree(work, ignore_errors=True)  # start from an empty folder: no results of an earlier run
work.mkdir()
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
# their tolerances, from [`skilllib.data`](#skilllib.data):

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
# **High sampling rates.** Differentiating positions turns position noise into speed noise in
# proportion to the rate. The three-point difference $v_i = (x_{i+1} - x_{i-1})\,f_s / 2$ turns white
# position noise of standard deviation $\sigma$ into speed noise of $\sigma f_s / \sqrt{2}$ on each
# axis: at 1 kHz the device's resolution alone gives the speed noise printed below, and a hand at rest
# (three axes: $\sqrt{3}$ times more) would seem to move at about three quarters of the 0.05 m/s onset
# threshold, so that the noise crosses the threshold now and then. A trial whose speed at its first
# sample exceeds the threshold cannot be segmented (*no rest before onset*).

# %%
noise_sd = CohortModel().noise_sd  # m, the generator's position noise: the device's resolution
noise_axis = noise_sd * 1000 / np.sqrt(2)  # m/s, three-point difference at 1 kHz, one axis
noise_rest = np.sqrt(3) * noise_axis  # m/s, RMS speed of a hand at rest
print(f"position noise {noise_sd * 1e3:.2f} mm; at 1 kHz: speed noise {noise_axis * 1e3:.0f} mm/s per axis, "
      f"{noise_rest * 1e3:.0f} mm/s RMS at rest; onset threshold {ONSET_SPEED * 1e3:.0f} mm/s")

# %% tags=["remove-cell"]
# checks of the claims above (hidden on the site; nbmake fails when one stops holding)
assert round(noise_sd * 1e3, 2) == 0.03, "text: 'the device's resolution' (0.03 mm, the generator's noise)"
assert ONSET_SPEED == 0.05, "text: 'the 0.05 m/s onset threshold'"
assert 0.65 < noise_rest / ONSET_SPEED < 0.85, "text: 'about three quarters of the 0.05 m/s onset threshold'"

# %% [markdown]
# skilllib therefore differentiates over a window of fixed *duration* (chapter 2), which is three samples
# at 60 Hz and more at higher rates. The table gives the window at each rate, the share of invalid
# trials and the median features of the same generator recorded at several rates:

# %%
rates = []
for fs in (60, 120, 240, 500, 1000):
    rec = generate_cohort(seed=3, model=CohortModel(n_participants=3, n_trials=20, fs=float(fs))).frame
    f = trial_features(rec)
    rates.append({"rate (Hz)": fs, "window (samples)": diff_window(fs),
                  "invalid trials (%)": 100 * (f["status"] == "invalid").mean(),
                  "median PV (m/s)": f["pv"].median(), "median SPARC": f["sparc"].median(),
                  "median contact speed (m/s)": f["contact_speed"].median()})
by_rate = pd.DataFrame(rates).set_index("rate (Hz)")
by_rate.round(3)

# %% tags=["remove-cell"]
# checks of the claims above (hidden on the site; nbmake fails when one stops holding)
win = by_rate["window (samples)"]
assert win.loc[60] == 3 and (np.diff(win) > 0).all(), "text: 'three samples at 60 Hz and more at higher rates'"
assert (by_rate["invalid trials (%)"] == 0).all(), "text: 'no trial is invalid at any rate'"
assert np.ptp(by_rate["median PV (m/s)"]) < 0.01, "text: 'the median PV agrees within 0.01 m/s'"
assert np.ptp(by_rate["median SPARC"]) < 0.01, "text: 'the median SPARC within 0.01'"
cs = by_rate["median contact speed (m/s)"]
assert (np.diff(cs) < 0).all(), "text: 'The median contact speed falls with the rate'"
assert 0 < 1 - cs.loc[1000] / cs.loc[60] < 0.1, "text: 'by less than a tenth from 60 Hz to 1 kHz'"

# %% [markdown]
# No trial is invalid at any rate, and across the rates the median PV agrees within 0.01 m/s and the
# median SPARC within 0.01: the rate does not change these features. The median contact speed
# falls with the rate, by less than a tenth from 60 Hz to 1 kHz: it is the speed at the last sample
# before contact, and at 60 Hz that sample lies up to 1/60 s before the touch, while the approach is
# still decelerating. If your device is much noisier than the Phantom, low-pass filter the positions
# before export (e.g. `scipy.signal.savgol_filter` or a zero-phase Butterworth filter); the command's
# summary suggests it when more than a fifth of the trials fail with *no rest before onset*.

# %% tags=["remove-cell"]
# checks of the claims above (hidden on the site; nbmake fails when one stops holding)
import skilllib.pipeline  # only for this check

assert skilllib.pipeline.NO_REST_FRACTION == 0.2, "text: 'when more than a fifth of the trials fail'"

# %% [markdown]
# ## An example file
#
# The chapter writes a small synthetic file instead of your recordings: five participants with 40
# trials each, at 120 Hz. The sampling rate printed here is the one read back from the time stamps of
# the file.

# %%
example = generate_cohort(seed=11, model=CohortModel(n_participants=5, n_trials=40, fs=120.0)).frame
data_file = write_recordings(example, work / "lab_recordings.csv")
check = read_recordings(data_file)
print(f"{data_file}: {len(example)} rows, {example['participant'].nunique()} participants, "
      f"{len(check)} trials, sampled at {check.fs:.4g} Hz")
example.head()

# %% tags=["remove-cell"]
# checks of the claims above (hidden on the site; nbmake fails when one stops holding)
assert example["participant"].nunique() == 5 and len(check) == 5 * 40, "text: 'five participants with 40 trials each'"
assert round(check.fs) == 120, "text: 'at 120 Hz' (read back from the time stamps)"
assert check.fs > CohortModel().fs == 60, "text: 'at a higher sampling rate than the cohort's (... 60 Hz)'"

# %% [markdown]
# ## The command
#
# From the repository, with the project's environment (`make book` or `make test` creates `.venv`):
#
# ```bash
# .venv/bin/python -m skilllib run --data lab_recordings.csv --out results/
# ```
#
# Options: `--k K` (clusters, default 6 as in the paper), `--robot NAME` (`simple6`, the default, `ur5`,
# `puma560`, `panda`), `--qd-max RAD_S ...` (one joint velocity limit for all joints, or one per joint),
# `--scaling raw|standard` (features as the paper uses them, or standardised before K-means), `--seed`
# (of K-means), `--no-figures`, `--quiet` (no progress bars), `--debug` (a traceback for an unexpected
# error). In a terminal, progress bars follow the long steps (the features of every trial, the
# silhouette sweep over k, the transfer of every prototype); a summary closes the run.
#
# SPARC's parameters have options too: `--fc HZ` (the maximum cut-off frequency, default 20 Hz, the
# paper's 0–20 Hz band), `--amp-th` (the amplitude threshold, default 0.05) and `--padlevel` (the zero
# padding, default 4); `--sensitivity fc=10 ...` compares the run with other settings
# (`sparc_sensitivity` in results.json). Chapter 3 explains them; `--help` lists every option.
#
# The chapter runs the command as a subprocess, exactly as you would in a terminal, and reads the
# `results.json` it writes:

# %%
def skilllib_run(*args: str) -> subprocess.CompletedProcess:
    """Run `python -m skilllib run --quiet ARGS`; show what it prints and its exit status."""
    proc = subprocess.run([sys.executable, "-m", "skilllib", "run", "--quiet", *args],
                          capture_output=True, text=True, check=False)
    print(proc.stdout + proc.stderr)
    print("exit status:", proc.returncode)
    return proc


run = skilllib_run("--data", str(data_file), "--out", str(work / "results"))
results = json.loads((work / "results" / "results.json").read_text())

# %% tags=["remove-cell"]
# checks of the claims above and below (hidden on the site; nbmake fails when one stops holding)
assert results["k"] == 6, "text: '--k K (clusters, default 6 as in the paper)'"
assert list(ROBOT_NAMES) == ["simple6", "ur5", "puma560", "panda"], "text: the robots of --robot"
assert results["transfer"]["robot"] == "Simple6", "text: '`simple6`, the default'"
assert results["sparc_params"] == {"fc": 20, "amp_th": 0.05, "padlevel": 4}, (
    "text: '--fc default 20 Hz, --amp-th default 0.05, --padlevel default 4'")
assert run.returncode == 0, "text: exit status 0: done"
status = pd.Series([t["status"] for t in results["trials"]]).value_counts()
assert len(results["trials"]) == len(check) == 200, "text: 'All 200 trials of the file are valid'"
assert status.get("invalid", 0) == 0, "text: 'All 200 trials of the file are valid'"
assert status["selected"] == 78 and status["excluded"] == 122, "text: '78 are selected and 122 excluded'"
reasons = [t["reason"] or "" for t in results["trials"]]
n_slow = sum(r.startswith("contact speed") and "below" in r for r in reasons)
n_fast = sum(r.startswith("contact speed") and "above" in r for r in reasons)
assert n_slow + n_fast == status["excluded"], "text: 'all for their contact speed'"
assert abs(n_slow - n_fast) <= 0.1 * status["excluded"], "text: 'about as many too slow as too fast'"
assert 6 in results["silhouette_valid_k"], "text: 'k = 6 is silhouette-valid for these data'"
transfer_s6 = results["transfer"]["prototypes"]
assert all(p["feasible"] for p in transfer_s6), "text: 'all six prototypes are feasible on Simple6'"
limit_s6 = min(results["transfer"]["qd_limits"])
peak_s6 = max(max(p["peak_abs_qd"]) for p in transfer_s6)
assert round(limit_s6, 2) == 3.14 and peak_s6 < 0.5 * limit_s6, "text: 'under half its limit of 3.14 rad/s'"
n_capped = sum(bool(t["sparc_capped"]) for t in results["trials"] if t["status"] == "selected")
assert len(results["messages"]) == 1 and "sparc_capped" in results["messages"][0], "text: 'one note: line'"
assert n_capped == 4, "text: '4 of the 78 selected trials' (capped by fc)"
assert n_capped / status["selected"] < 0.1, "text: 'fc decides the SPARC of only a few trials'"

# %% [markdown]
# The summary says how many trials were read, selected (contact speed in the paper's window),
# excluded (with the commonest reasons) and invalid; the k used and the average silhouette; each
# cluster's prototype trial and its peak joint speed on the robot; how many prototypes the robot can
# execute as recorded. `note:` lines report what the run adapted or what to look at: a silhouette range
# shrunk because there are few selected trials, a k reduced to what the data allow, a k that is not
# silhouette-valid for these data, and how many selected trials have a SPARC that depends on fc.
#
# For the example file: all 200 trials of the file are valid; 78 are selected and 122 excluded, all
# for their contact speed, about as many too slow as too fast. With 78 selected trials nothing needs
# adapting: k = 6 is silhouette-valid for these data, and all six prototypes are feasible on Simple6,
# the fastest joint staying under half its limit of 3.14 rad/s. The one `note:` line counts the
# selected trials whose SPARC band was ended by fc = 20 Hz rather than by the amplitude threshold
# (`sparc_capped`): 4 of the 78 selected trials, so fc decides the SPARC of only a few trials here.
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
# The run above ended with 0; the examples at the end of the chapter end with 2 and 3.
#
# ## Reading results.json
#
# `results.json` holds everything the summary names, in the schema documented in the README
# (*results.json*): the data set and its sampling rate, the SPARC parameters, **one entry for every
# input trial** with its status (`selected`, `excluded` or `invalid`), the reason when it was not
# selected, and its features, among them where its SPARC band ended (`sparc_band_end_hz`) and whether
# fc ended it (`sparc_capped`); the silhouette of every k and which k are valid; the clusters and their
# prototypes; the transfer to the robot; the notes of the run; the figure files.

# %%
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

# %% tags=["remove-cell"]
# checks of the claims above and below (hidden on the site; nbmake fails when one stops holding)
assert (np.diff(clusters["centre.pv"]) > 0).all(), "text: 'The clusters, ordered by the peak speed of their centre'"
assert (transfer.loc[transfer["feasible"], "time_scale"] == 1).all(), "text: 'time_scale ... (1 when feasible)'"
assert transfer["feasible"].all() and (transfer["time_scale"] == 1).all(), "text: 'every time_scale is 1'"
small = clusters["size"].idxmin()
assert clusters.loc[small, "size"] == 2 and (clusters["size"].drop(small) > 2).all(), "text: 'one cluster holds just two trials'"
sparc_sorted = clusters["centre.sparc"].sort_values()
assert sparc_sorted.index[0] == small, "text: 'its centre lies lowest in SPARC'"
assert sparc_sorted.iloc[1] - sparc_sorted.iloc[0] > 0.15, "text: 'more than 0.15 below the next centre'"
capped = trials.set_index(["participant", "trial"])["sparc_capped"]
proto_capped = [bool(capped[(p, tr)]) for p, tr in zip(clusters["prototype.participant"], clusters["prototype.trial"])]
assert proto_capped[small] and sum(proto_capped) == 1, (
    "text: 'its prototype is one of the 4 selected trials whose SPARC band fc ended' (the only capped prototype)")

# %% [markdown]
# On Simple6 every prototype is feasible, so every `time_scale` is 1. The cluster sizes differ a lot:
# one cluster holds just two trials, and its centre lies lowest in SPARC, more than 0.15 below the next
# centre. Its prototype stands for two unusually jerky approaches, not for a habit of the
# participants, and it is one of the 4 selected trials whose SPARC band fc ended (`sparc_capped`): its
# SPARC depends on fc. Look at the sizes and at `sparc_capped` before you read a
# prototype as typical.
#
# ## Reading the figures
#
# Every figure of the pipeline is written beside `results.json`, as PNG (to look at) and SVG (to put
# in a paper):

# %%
print(sorted(results["figures"]))

# %% tags=["remove-cell"]
# checks of the claims above and below (hidden on the site; nbmake fails when one stops holding)
FIGURES = {"trials_by_participant", "participant_features", "features", "sparc_vs_length", "silhouette_sweep",
           "silhouettes_k", "clusters_pv_sparc", "prototype_speed_profiles", "joint_velocities", "frame_mapping"}
stems = {Path(f).stem for f in results["figures"]}
assert sorted(results["figures"]) == sorted(f"{s}.{e}" for s in stems for e in ("png", "svg")), (
    "text: 'Every figure ... is written ..., as PNG ... and SVG'")
assert stems == FIGURES, "text: the table of figure files (all but sparc_sensitivity, 'only with --sensitivity')"

# %% [markdown]
# | file | shows | explained in |
# |---|---|---|
# | `trials_by_participant` | height y and speed of every valid trial against time from contact, per participant (the paper's Fig. 1b) | chapter 2 |
# | `participant_features` | PV, contact speed, duration and SPARC per participant | chapter 2 |
# | `features` | the contact-speed histogram with the selection window; PV against SPARC, bands ended by fc ringed | chapter 2 |
# | `sparc_vs_length` | SPARC of every valid trial against its segment length, bands ended by fc ringed; the share of such bands at each length | chapter 1 |
# | `silhouette_sweep` | average silhouette for every k, valid k filled | chapter 3 |
# | `silhouettes_k` | the silhouette of every trial at the k used | chapter 3 |
# | `clusters_pv_sparc` | clusters, centres and prototypes in the PV-SPARC plane (the paper's Fig. 2a) | chapter 3 |
# | `prototype_speed_profiles` | the speed profile of every prototype (the paper's Fig. 2b) | chapter 3 |
# | `joint_velocities` | the robot's joint velocities for every prototype, with the limits (the paper's Fig. 4) | chapter 4 |
# | `frame_mapping` | where the fastest prototype's path lies in the robot's workspace | chapter 4 |
# | `sparc_sensitivity` | only with `--sensitivity`: each selected trial's SPARC under the other settings against this run's; the silhouette sweep under every setting | chapter 3 |
#
# Look at `trials_by_participant` first: it shows at once whether the export is right (y should fall
# to the contact surface and stay there; speed should rise from rest and end at contact). For the
# example file:

# %%
#| label: fig-your-trials
#| caption: Synthetic example file. Height y (m) and approach speed (m/s) of every valid trial against time from contact (s), y above speed for each participant; selected trials in colour, excluded ones in grey. Written by the command as trials_by_participant.png.
display(Image(filename=str(work / "results" / "trials_by_participant.png"), width=680))

# %% [markdown]
# The export of the example file passes this check: in each participant's panels y falls from rest to
# that participant's contact surface and stays there, and the speed rises from rest and ends at the
# dotted line of contact. The grey curves are the excluded trials, those that reach the surface slower
# than 0.3 m/s or faster than 0.7 m/s.
#
# Then the clusters and their prototypes, and what the robot must do to reproduce them:

# %%
#| label: fig-your-clusters
#| caption: Synthetic example file. The PV-SPARC plane of its selected trials as the command draws it, coloured by cluster, with the K-means centres (crosses) and the prototype trials (circles) (clusters_pv_sparc.png).
display(Image(filename=str(work / "results" / "clusters_pv_sparc.png"), width=560))

# %%
#| label: fig-your-joints
#| caption: Synthetic example file. Joint velocities (rad/s) of Simple6 reproducing each of its prototypes against time from start (s), one panel per cluster, with the joint velocity limits dashed (joint_velocities.png).
display(Image(filename=str(work / "results" / "joint_velocities.png"), width=680))

# %% tags=["remove-cell"]
# checks of the claims below (hidden on the site; nbmake fails when one stops holding)
peaks_s6 = np.array([p["peak_abs_qd"] for p in transfer_s6])  # rad/s, the curves of the figure
fastest = clusters["prototype.pv"].idxmax()
assert peaks_s6[fastest].max() == peaks_s6.max(), "text: 'the fastest prototype ... needs the highest joint speed'"
assert round(peaks_s6.max(), 2) == 1.31, "text: '1.31 rad/s'"
others = np.delete(peaks_s6, [1, 5], axis=1).max(axis=1)
assert (others < 0.5 * peaks_s6[:, [1, 5]].min(axis=1)).all(), (
    "text: 'q2 and q6 ... every other joint stays below half of either'")

# %% [markdown]
# In the PV-SPARC plane ([](#fig-your-clusters)) the two-trial cluster lies alone at the bottom, below
# the others in SPARC. On Simple6 ([](#fig-your-joints)) the fastest prototype also needs the highest
# joint speed, 1.31 rad/s, less than half the limit; in every prototype the shoulder q2 and the last
# wrist joint q6 do the work, and every other joint stays below half of either.
#
# ## Another robot, other limits
#
# `--robot` chooses the arm and its start pose; each comes with default joint velocity limits
# (justified in [`skilllib.robots`](#skilllib.robots)):

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
# executed: every joint velocity divides by that factor, and so does the prototype's peak speed. Its
# SPARC stays the same as long as the amplitude threshold, not fc, ends its band (`sparc_capped` false;
# chapter 4). Here is the UR5 with slower base, shoulder and elbow joints (q1–q3) than wrist joints
# (q4–q6):

# %%
limits = ["1.0", "1.0", "1.0", "2.0", "2.0", "2.0"]  # rad/s, q1..q6
run = skilllib_run("--data", str(data_file), "--out", str(work / "ur5"), "--robot", "ur5",
                   "--qd-max", *limits, "--no-figures")
ur5 = json.loads((work / "ur5" / "results.json").read_text())
table = pd.DataFrame(ur5["transfer"]["prototypes"])[["cluster", "feasible", "time_scale", "max_cond_j"]]
table["peak |qd| q1..q6 (rad/s)"] = [np.round(p["peak_abs_qd"], 2).tolist() for p in ur5["transfer"]["prototypes"]]
table["PV as recorded (m/s)"] = [c["prototype"]["pv"] for c in ur5["clusters"]]
table["PV executable (m/s)"] = table["PV as recorded (m/s)"] / table["time_scale"]
table.round(3)

# %% tags=["remove-cell"]
# checks of the claims below (hidden on the site; nbmake fails when one stops holding)
assert run.returncode == 0, "text: the UR5 run is done (exit status 0)"
assert not table["feasible"].any(), "text: 'none of the six prototypes can run as recorded'"
assert round(table["time_scale"].min(), 1) == 1.2 and round(table["time_scale"].max(), 1) == 2.8, (
    "text: 'from 1.2 to 2.8 times slower'")
peaks_ur5 = np.array([p["peak_abs_qd"] for p in ur5["transfer"]["prototypes"]])
lim_ur5 = np.array(ur5["transfer"]["qd_limits"])
assert ((peaks_ur5 / lim_ur5).argmax(axis=1) == 2).all(), "text: 'in every prototype the elbow q3 sets the time scale'"
assert np.allclose(table["time_scale"], peaks_ur5[:, 2] / lim_ur5[2]), "text: 'the elbow q3 ... sets the time scale'"
assert (peaks_ur5[:, 3] > peaks_ur5[:, 2]).all(), "text: 'the wrist q4 moves faster'"
pv_rec, pv_exe = table["PV as recorded (m/s)"], table["PV executable (m/s)"]
assert np.ptp(pv_exe) < 0.5 * np.ptp(pv_rec), "text: 'span less than half the range of the recorded ones'"
assert (pv_exe < pv_exe[pv_rec.idxmax()]).sum() == 1, "text: 'the fastest human prototype is the second slowest'"
proto_ur5 = [(c["prototype"]["participant"], c["prototype"]["trial"]) for c in ur5["clusters"]]
assert proto_ur5 == list(zip(clusters["prototype.participant"], clusters["prototype.trial"])), (
    "text: the UR5 run has the same prototypes as the Simple6 run ('the two-trial cluster')")
assert [bool(capped[k]) for k in proto_ur5] == proto_capped and sum(proto_capped) == 1, (
    "text: 'five of the six prototypes ... all but the two-trial cluster's' (uncapped band)")

# %% [markdown]
# With these limits none of the six prototypes can run as recorded: they must run from 1.2 to 2.8
# times slower. In every prototype the elbow q3, limited to 1 rad/s, sets the time scale; the wrist q4
# moves faster, but its limit is 2 rad/s. Slowed down, the prototypes' peak speeds (`PV executable`)
# span less than half the range of the recorded ones, and the fastest human prototype is the second
# slowest on the robot. The SPARC of five of the six prototypes does not change; the exception is the
# two-trial cluster's, whose band fc ended: its SPARC may change when it is slowed down.
#
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
run_mm = skilllib_run("--data", str(work / "in_mm.csv"), "--out", str(work / "mm"))

# %% [markdown]
# A cell that is not a number:

# %%
lines = (work / "lab_recordings.csv").read_text().splitlines()
cells = lines[5].split(",")
cells[4] = cells[4].replace("0", "O", 1)  # a letter O typed for a zero in column y
lines[5] = ",".join(cells)
(work / "typo.csv").write_text("\n".join(lines) + "\n")
run_typo = skilllib_run("--data", str(work / "typo.csv"), "--out", str(work / "typo"))

# %% tags=["remove-cell"]
# checks of the claims above (hidden on the site; nbmake fails when one stops holding)
for r, name in ((run_mm, "in_mm.csv"), (run_typo, "typo.csv")):
    assert r.returncode == 2, "text: 'and exit status 2'"
    assert r.stdout == "" and len(r.stderr.strip().splitlines()) == 1, "text: 'with one line'"
    assert name in r.stderr, "text: 'one line that names the file'"
    assert not (work / name.removesuffix(".csv").replace("in_", "")).exists(), "text: 'before anything is computed'"
assert "divide millimetres by 1000" in run_mm.stderr, "text: 'and how to fix it'"
assert "line 6" in run_typo.stderr and "column 'y'" in run_typo.stderr, "text: 'the line and the column'"

# %% [markdown]
# The other file-level problems are a missing or empty file, a missing column (named), time stamps in
# milliseconds, a file that mixes sampling rates, and a participant or trial id left empty.
#
# A problem with one **trial** never stops the run: the trial is kept in `results.json` as `invalid`,
# with its reason, and the rest is analysed. The next file breaks eight trials, each in a different way
# that the pipeline recognises:

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
run = skilllib_run("--data", str(work / "broken.csv"), "--out", str(work / "broken"), "--no-figures")
broken_results = json.loads((work / "broken" / "results.json").read_text())
bad = pd.DataFrame(broken_results["trials"])
bad[bad["status"] == "invalid"][["participant", "trial", "status", "reason"]]

# %% tags=["remove-cell"]
# checks of the claims below (hidden on the site; nbmake fails when one stops holding)
assert run.returncode == 0, "text: 'the run ends with exit status 0'"
invalid = bad[bad["status"] == "invalid"]
broken_keys = {(int(p), int(tr)) for p, tr in keys}
assert set(zip(invalid["participant"], invalid["trial"])) == broken_keys, "text: 'The eight broken trials, and only they, are invalid'"
assert invalid["reason"].nunique() == 8, "text: 'each with its own reason'"
assert len(bad) == len(trials) == 200, "text: 'every trial of the file is in results.json' / 'No trial is dropped silently'"
both = trials.merge(bad, on=["participant", "trial"], suffixes=("", "_broken"))
intact = ~both.set_index(["participant", "trial"]).index.isin(list(broken_keys))
assert (both.loc[intact, "status"] == both.loc[intact, "status_broken"]).all(), (
    "text: 'the other 192 trials keep the status they have in the intact file'")
assert intact.sum() == 192, "text: 'the other 192 trials'"
n_sel_broken = both.loc[~intact, "status"].eq("selected").sum()
assert n_sel_broken == 2, "text: 'two of the broken trials were selected in the intact file'"
protos = {(c["prototype"]["participant"], c["prototype"]["trial"]) for c in results["clusters"]}
protos_broken = {(c["prototype"]["participant"], c["prototype"]["trial"]) for c in broken_results["clusters"]}
assert protos_broken != protos, "text: 'some prototypes change'"

# %% [markdown]
# The eight broken trials, and only they, are invalid, each with its own reason, which gives the line
# of the file where it applies; the run ends with exit status 0, and every trial of the file is in
# `results.json`. The other 192 trials keep the status they have in the intact file. Two of the broken
# trials were selected in the intact file, so the clusters are computed on two trials fewer and some
# prototypes change.
#
# Two more trial-level checks need no example: a trial with fewer samples from onset to contact than
# the segmentation needs is invalid (*too short*), and so is a trial sampled at another rate than the
# rest of the file or with a missing sample (above). With few selected trials the silhouette range
# shrinks to what they allow, and a `--k` larger than that is reduced, each said in a `note:` line and
# in `messages`. With fewer than 3 selected trials the run still writes `results.json` with every
# trial, skips the clustering and the transfer, and ends with exit status 3. A file with the example's
# excluded trials and only two of its selected ones:

# %%
few_keys = pd.concat([trials[trials["status"] == "excluded"], trials[trials["status"] == "selected"].head(2)])
few = example.merge(few_keys[["participant", "trial"]])  # the rows of those trials, in the file's order
write_recordings(few, work / "few.csv")
run = skilllib_run("--data", str(work / "few.csv"), "--out", str(work / "few"), "--no-figures")
few_results = json.loads((work / "few" / "results.json").read_text())
print(f"results.json: {len(few_results['trials'])} trials, {few_results['n_selected']} selected; "
      f"clusters: {'clusters' in few_results}, transfer: {'transfer' in few_results}")

# %% tags=["remove-cell"]
# checks of the claims above (hidden on the site; nbmake fails when one stops holding)
assert few_results["n_selected"] == 2, "text: 'only two of its selected ones'"
assert run.returncode == 3, "text: 'ends with exit status 3'"
assert len(few_results["trials"]) == len(few_keys), "text: 'results.json with every trial'"
assert "clusters" not in few_results and "transfer" not in few_results, "text: 'skips the clustering and the transfer'"

# %% [markdown]
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
