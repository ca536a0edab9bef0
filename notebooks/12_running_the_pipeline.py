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
#   enumerator: "12.%s"
# ---
# # Running the pipeline on your recordings
#
# Chapter 11 showed how to bring recordings into the book's format, or read them as a lab writes them,
# and how to check an export. This chapter runs the whole pipeline on such a file with one command,
# `python -m skilllib run`: what it prints and its exit statuses, the folder it writes, how to read
# `results.json` and the figures, how to choose another robot and other joint velocity limits, the
# same steps from Python, and what happens when a file or a trial is broken. The reference pages hold
# the details: [the command](../docs/cli.md), [the input formats](../docs/inputs.md) and
# [results.json](../docs/results.md).
#
# ```{note}
# The example file of this chapter is synthetic: chapter 11's small cohort (five participants with 40
# trials each, at 120 Hz, a higher rate than the paper's 60 Hz), written again by the book's generator
# (`skilllib.cohort`), and broken copies of it. With your own file, replace its path.
# ```

# %% tags=["hide-input"] jupyter={"source_hidden": true}
import json
import shutil
import subprocess
import textwrap
from pathlib import Path

import numpy as np
import pandas as pd
from IPython.display import Image, display

import skilllib as sk

work = Path("_running_the_pipeline")  # everything this chapter writes goes here
shutil.rmtree(work, ignore_errors=True)  # start empty: no results of an earlier run
work.mkdir()
pd.set_option("display.max_colwidth", 120)


def wrapped(text: str) -> str:
    """``text`` with every line wrapped to the page's 88 columns."""
    return "\n".join(
        textwrap.fill(line, 88, subsequent_indent="    ") if line else ""
        for line in text.splitlines()
    )


def skilllib_run(*args: str) -> subprocess.CompletedProcess:
    """`sk.run_command(*args)` (`python -m skilllib run --quiet ARGS` as in a terminal);
    show what it printed (long lines wrapped to the page) and its exit status."""
    proc = sk.run_command(*args)
    print(wrapped(proc.stdout + proc.stderr))
    print("exit status:", proc.returncode)
    return proc


# the example file of chapter 11, written again
model = sk.CohortModel(n_participants=5, n_trials=40, fs=120.0)
example = sk.generate_cohort(seed=11, model=model).frame
data_file = sk.write_recordings(example, work / "lab_recordings.csv")
check = sk.load_recordings(data_file)
print(f"{data_file}: {len(check)} trials, sampled at {check.fs:.4g} Hz")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden on the site; nbmake fails if one breaks)
assert example["participant"].nunique() == 5 and len(check) == 5 * 40, (
    "text: 'five participants with 40 trials each'"
)
assert round(check.fs) == 120, "text: 'at 120 Hz' (read back from the time stamps)"
assert check.fs > sk.CohortModel().fs == 60, (
    "text: 'a higher rate than the paper's 60 Hz'"
)

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
# (of K-means), `--lowpass auto|none|HZ` (the low-pass filter of
# [the next chapter](13_noise_and_filters.ipynb)), the reading options of chapter 11 (*Other formats*),
# `--no-figures`, `--quiet` (no progress bars; they appear only on a terminal, never in a redirected
# log), `--debug` (a traceback for an unexpected error), `--version`. A summary closes the run.
#
# SPARC's parameters have options too: `--fc HZ` (the maximum cut-off frequency, default 20 Hz, the
# paper's 0–20 Hz band), `--amp-th` (the amplitude threshold, default 0.05) and `--padlevel` (the zero
# padding, default 4); `--sensitivity fc=10 ...` compares the run with other settings
# (`sparc_sensitivity` in results.json). Chapter 6 explains them; `--help` lists every option, and
# [the command's reference page](../docs/cli.md) explains each.
#
# `--out` names a folder that the run **replaces as a whole** when it has finished: it writes into a
# fresh folder beside it and then swaps it in, so figures of an earlier run never sit beside new
# results, and a run that fails or is interrupted leaves the folder as it was. A folder holding files
# that no run wrote is refused, and so is a second run on a folder while the first is still writing it.
#
# The chapter runs the command as a subprocess, exactly as you would in a terminal, and reads the
# `results.json` it writes:

# %%
run = skilllib_run("--data", str(data_file), "--out", str(work / "results"))
results = json.loads((work / "results" / "results.json").read_text())

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above and below (hidden on the site; nbmake fails if one breaks)
assert results["k"] == 6, "text: '--k K (clusters, default 6 as in the paper)'"
assert list(sk.ROBOT_NAMES) == ["simple6", "ur5", "puma560", "panda"], (
    "text: the robots of --robot"
)
assert results["transfer"]["robot"] == "Simple6", "text: '`simple6`, the default'"
assert results["sparc_params"] == {"fc": 20, "amp_th": 0.05, "padlevel": 4}, (
    "text: '--fc default 20 Hz, --amp-th default 0.05, --padlevel default 4'"
)
assert run.returncode == 0, "text: exit status 0: done"
status = pd.Series([t["status"] for t in results["trials"]]).value_counts()
assert len(results["trials"]) == len(check) == 200, (
    "text: 'All 200 trials of the file are valid'"
)
assert status.get("invalid", 0) == 0, "text: 'All 200 trials of the file are valid'"
assert status["selected"] == 78 and status["excluded"] == 122, (
    "text: '78 are selected and 122 excluded'"
)
reasons = [t["reason"] or "" for t in results["trials"]]
n_slow = sum(r.startswith("contact speed") and "below" in r for r in reasons)
n_fast = sum(r.startswith("contact speed") and "above" in r for r in reasons)
assert n_slow + n_fast == status["excluded"], "text: 'all for their contact speed'"
assert abs(n_slow - n_fast) <= 0.1 * status["excluded"], (
    "text: 'about as many too slow as too fast'"
)
assert 6 in results["silhouette_valid_k"], (
    "text: 'k = 6 is silhouette-valid for these data'"
)
transfer_s6 = results["transfer"]["prototypes"]
assert all(p["feasible_velocity"] for p in transfer_s6), (
    "text: 'within the velocity limits, all six'"
)
limit_s6 = min(results["transfer"]["qd_limits"])
peak_s6 = max(max(p["peak_abs_qd"]) for p in transfer_s6)
assert round(limit_s6, 2) == 3.14 and peak_s6 < 0.5 * limit_s6, (
    "text: 'under half its limit of 3.14 rad/s'"
)
assert not any(p["feasible"] for p in transfer_s6), (
    "text: 'none is feasible as recorded' (summary: 0 of 6)"
)
assert {p["binding_limit"] for p in transfer_s6} == {"acceleration"}, (
    "text: 'the acceleration limit binds'"
)
scales_s6 = [p["time_scale"] for p in transfer_s6]
assert 1.2 < min(scales_s6) and max(scales_s6) < 1.9, "text: 'slowed by x1.2 to x1.9'"
assert "0 of 6 prototypes feasible as recorded" in run.stdout, (
    "text: the summary's feasibility line"
)
n_capped = sum(
    bool(t["sparc_capped"]) for t in results["trials"] if t["status"] == "selected"
)
assert len(results["messages"]) == 1 and "sparc_capped" in results["messages"][0], (
    "text: 'one note: line'"
)
assert n_capped == 4, "text: '4 of the 78 selected trials' (capped by fc)"
assert n_capped / status["selected"] < 0.1, (
    "text: 'fc decides the SPARC of only a few trials'"
)

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
# adapting: k = 6 is silhouette-valid for these data. On Simple6 all six prototypes stay within the
# joint *velocity* limits (the paper's question), the fastest joint under half its limit of 3.14 rad/s;
# but none is feasible as recorded: the acceleration limit (5 rad/s², the book's assumption for
# Simple6, chapter 9) binds for every one, and each would have to be slowed by x1.2 to x1.9, as the
# summary's `feasibility` line says (0 of 6). The one `note:` line counts the
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
# | 130 | interrupted (Ctrl-C), at any point: one line, the output folder as it was |
# | 141 | standard output closed early (e.g. piped into `head`): the run ends quietly |
#
# The run above ended with 0; the examples at the end of the chapter end with 2 and 3.
#
# ## Reading results.json
#
# `results.json` holds everything the summary names, in the schema of
# [its reference page](../docs/results.md): the data set and its sampling rate, the SPARC parameters, **one entry for every
# input trial** with its status (`selected`, `excluded` or `invalid`), the reason when it was not
# selected, and its features, among them where its SPARC band ended (`sparc_band_end_hz`) and whether
# fc ended it (`sparc_capped`); the silhouette of every k and which k are valid; the clusters and their
# prototypes; the transfer to the robot; the notes of the run; the figure files.

# %%
print(wrapped(f"top-level keys: {', '.join(results)}"))
for key, value in results["dataset"].items():
    print(f"dataset.{key}: {value}")
print(wrapped(f"messages: {results['messages']}"))
trials = pd.DataFrame(results["trials"])
trials["status"].value_counts()

# %% [markdown]
# The `trials` list is a table: load it with pandas and filter it. The trials that were not selected
# say why:

# %%
trials[trials["status"] != "selected"].head(5)

# %% [markdown]
# The clusters, ordered by the peak speed of their centre, with their prototype trials (`prototype.*`)
# and the transfer of each prototype to the robot: `feasible` is whether every limit checked
# (velocity, acceleration and, for arms with dynamics, torque) holds as the human moved, `time_scale`
# how much slower the robot must execute it otherwise (1 when feasible), `binding_limit` the limit that
# asks for that stretch; `feasible_velocity` answers the paper's question, the velocity limits alone:

# %%
clusters = pd.json_normalize(results["clusters"])
transfer = pd.DataFrame(results["transfer"]["prototypes"])
columns = ["feasible_velocity", "feasible", "time_scale", "binding_limit", "max_cond_j"]
clusters.join(transfer[columns]).round(3)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above and below (hidden on the site; nbmake fails if one breaks)
assert (np.diff(clusters["centre.pv"]) > 0).all(), (
    "text: 'The clusters, ordered by the peak speed of their centre'"
)
assert (transfer["feasible"] == (transfer["time_scale"] == 1)).all(), (
    "text: 'time_scale ... (1 when feasible)'"
)
assert transfer["feasible_velocity"].all() and (transfer["time_scale"] > 1).all(), (
    "text: 'every prototype is within its velocity limits; every time_scale above 1'"
)
small = clusters["size"].idxmin()
assert clusters.loc[small, "size"] == 2 and (clusters["size"].drop(small) > 2).all(), (
    "text: 'one cluster holds just two trials'"
)
sparc_sorted = clusters["centre.sparc"].sort_values()
assert sparc_sorted.index[0] == small, "text: 'its centre lies lowest in SPARC'"
assert sparc_sorted.iloc[1] - sparc_sorted.iloc[0] > 0.15, (
    "text: 'more than 0.15 below the next centre'"
)
capped = trials.set_index(["participant", "trial"])["sparc_capped"]
proto_capped = [
    bool(capped[(p, tr)])
    for p, tr in zip(clusters["prototype.participant"], clusters["prototype.trial"])
]
assert proto_capped[small] and sum(proto_capped) == 1, (
    "text: 'its prototype is one of the 4 ... whose SPARC band fc ended' (the only one)"
)

# %% [markdown]
# On Simple6 every prototype is within its velocity limits, and every `time_scale` is above 1: the
# acceleration limit binds. The cluster sizes differ a lot:
# one cluster holds just two trials, and its centre lies lowest in SPARC, more than 0.15 below the next
# centre. Its prototype stands for two unusually jerky approaches, not for a habit of the
# participants, and it is one of the 4 selected trials whose SPARC band fc ended (`sparc_capped`): its
# SPARC depends on fc. Look at the sizes and at `sparc_capped` before you read a
# prototype as typical.
#
# ## Reading the figures
#
# Every figure of the pipeline is written beside `results.json`, as PNG (to look at) and SVG (to put
# in a paper), and the segmentation pages as PNG only (pages for checking an export, not for a paper):

# %%
print(wrapped(", ".join(sorted(results["figures"]))))

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above and below (hidden on the site; nbmake fails if one breaks)
FIGURES = set(
    "trials_by_participant participant_features features sparc_vs_length "
    "silhouette_sweep silhouettes_k clusters_pv_sparc prototype_speed_profiles "
    "joint_velocities frame_mapping joint_accelerations executed_speed "
    "time_scales".split()
)
pages = sorted(f for f in results["figures"] if f.startswith("segmentation-"))
stems = {Path(f).stem for f in results["figures"] if f not in pages}
assert sorted(set(results["figures"]) - set(pages)) == sorted(
    f"{s}.{e}" for s in stems for e in ("png", "svg")
), "text: 'Every figure ... is written ..., as PNG ... and SVG'"
assert pages and all(f.endswith(".png") for f in pages), (
    "text: 'segmentation pages as PNG only'"
)
assert stems == FIGURES, (
    "text: the table of figure files (sparc_sensitivity 'only with --sensitivity')"
)

# %% [markdown]
# | file | shows | explained in |
# |---|---|---|
# | `trials_by_participant` | height y and speed of every valid trial against time from contact, per participant (the paper's Fig. 1b) | chapter 3 |
# | `participant_features` | PV, contact speed, duration and SPARC per participant | chapter 3 |
# | `features` | the contact-speed histogram with the selection window; PV against SPARC, bands ended by fc ringed | chapter 3 |
# | `sparc_vs_length` | SPARC of every valid trial against its segment length, bands ended by fc ringed; the share of such bands at each length | chapter 2 |
# | `silhouette_sweep` | average silhouette for every k, valid k filled | chapter 4 |
# | `silhouettes_k` | the silhouette of every trial at the k used | chapter 4 |
# | `clusters_pv_sparc` | clusters, centres and prototypes in the PV-SPARC plane (the paper's Fig. 2a) | chapter 4 |
# | `prototype_speed_profiles` | the speed profile of every prototype (the paper's Fig. 2b) | chapter 4 |
# | `joint_velocities` | the robot's joint velocities for every prototype, with the limits (the paper's Fig. 4) | chapter 5 |
# | `frame_mapping` | where the fastest prototype's path lies in the robot's workspace | chapter 5 |
# | `joint_accelerations` | the robot's joint accelerations for every prototype, with the limits | chapter 9 |
# | `joint_torques` | only on an arm with dynamic parameters (`ur5`, `puma560`, `panda`): every joint's torque over its limit | chapter 9 |
# | `executed_speed` | the prototype's tool speed against the simulated execution, as recorded and slowed by its time scale | chapter 10 |
# | `time_scales` | the time scale each limit asks for and the one of every limit, with the binding limit | chapter 9 |
# | `sparc_sensitivity` | only with `--sensitivity`: each selected trial's SPARC under the other settings against this run's; the silhouette sweep under every setting | chapter 6 |
# | `segmentation-01.png`, ... | pages of small multiples, one panel per trial: speed against time over the whole recording, onset and contact marked, the analysed segment shaded, repaired samples crossed, the status and reason (every invalid trial first, then valid ones spread over the participants, at most three pages) | chapter 11 |
#
# Look at `trials_by_participant` first: chapter 11 drew it for the example file and showed how it
# tells at once whether an export is right. Then the clusters and their prototypes, and what the robot must do to reproduce them:

# %%
#| label: fig-your-clusters
#| caption: Synthetic example file. The PV-SPARC plane of its selected trials as the command draws it, coloured by cluster, with the K-means centres (crosses) and the prototype trials (circles) (clusters_pv_sparc.png).
display(Image(filename=str(work / "results" / "clusters_pv_sparc.png"), width=560))

# %%
#| label: fig-your-joints
#| caption: Synthetic example file. Joint velocities (rad/s) of Simple6 reproducing each of its prototypes against time from start (s), one panel per cluster, with the joint velocity limits dashed (joint_velocities.png).
display(Image(filename=str(work / "results" / "joint_velocities.png"), width=680))

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims below (hidden on the site; nbmake fails if one breaks)
# rad/s, the curves of the figure
peaks_s6 = np.array([p["peak_abs_qd"] for p in transfer_s6])
fastest = clusters["prototype.pv"].idxmax()
assert peaks_s6[fastest].max() == peaks_s6.max(), (
    "text: 'the fastest prototype ... needs the highest joint speed'"
)
assert round(peaks_s6.max(), 2) == 1.31, "text: '1.31 rad/s'"
others = np.delete(peaks_s6, [1, 5], axis=1).max(axis=1)
assert (others < 0.5 * peaks_s6[:, [1, 5]].min(axis=1)).all(), (
    "text: 'q2 and q6 ... every other joint stays below half of either'"
)

# %% [markdown]
# In the PV-SPARC plane ([](#fig-your-clusters)) the two-trial cluster lies alone at the bottom, below
# the others in SPARC. On Simple6 ([](#fig-your-joints)) the fastest prototype also needs the highest
# joint speed, 1.31 rad/s, less than half the limit; in every prototype the shoulder q2 and the last
# wrist joint q6 do the work, and every other joint stays below half of either.
#
# ## Another robot, other limits
#
# `--robot` chooses the arm and its start pose; each comes with default joint velocity limits
# (justified in [`skilllib.robot`](#skilllib.robot)):

# %%
rows = []
for name in sk.ROBOT_NAMES:
    arm = sk.get_robot(name)
    rows.append({
        "--robot": name, "arm": arm.robot.name, "joints": arm.n,
        "start pose q0 (deg)": np.round(np.rad2deg(arm.q0), 1).tolist(),
        "default limits (rad/s)": np.round(arm.qd_limits, 3).tolist(),
    })  # fmt: skip
pd.DataFrame(rows).set_index("--robot")

# %% [markdown]
# `--qd-max` replaces the limits: one value for every joint, or one per joint, in rad/s. A prototype
# whose joints would exceed them is not `feasible_velocity`, and `time_scales.velocity` says how much
# slower it must be executed for them (`time_scale`, the stretch for every limit, is at least that):
# every joint velocity divides by that factor, and so does the prototype's peak speed. Its
# SPARC stays the same as long as the amplitude threshold, not fc, ends its band (`sparc_capped` false;
# chapter 8). Here is the UR5 with slower base, shoulder and elbow joints (q1–q3) than wrist joints
# (q4–q6):

# %%
limits = ["1.0", "1.0", "1.0", "2.0", "2.0", "2.0"]  # rad/s, q1..q6
run = skilllib_run("--data", str(data_file), "--out", str(work / "ur5"),
                   "--robot", "ur5", "--qd-max", *limits, "--no-figures")  # fmt: skip
ur5 = json.loads((work / "ur5" / "results.json").read_text())
protos_ur5 = pd.json_normalize(ur5["transfer"]["prototypes"])
columns = ["cluster", "feasible_velocity", "time_scales.velocity", "max_cond_j"]
table = protos_ur5[columns].copy()
# the velocity limits' stretch
table = table.rename(columns={"time_scales.velocity": "time_scale"})
peaks_ur5 = np.array(protos_ur5["peak_abs_qd"].tolist())  # rad/s, prototype x joint
table["peak |qd| q1..q6 (rad/s)"] = np.round(peaks_ur5, 2).tolist()
table["PV as recorded (m/s)"] = [c["prototype"]["pv"] for c in ur5["clusters"]]
table["PV executable (m/s)"] = table["PV as recorded (m/s)"] / table["time_scale"]
table.round(3)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims below (hidden on the site; nbmake fails if one breaks)
assert run.returncode == 0, "text: the UR5 run is done (exit status 0)"
assert not table["feasible_velocity"].any(), (
    "text: 'none of the six prototypes can run as recorded'"
)
assert (protos_ur5["time_scale"] >= table["time_scale"]).all(), (
    "text: 'time_scale ... is at least that'"
)
assert (
    round(table["time_scale"].min(), 1) == 1.2
    and round(table["time_scale"].max(), 1) == 2.8
), "text: 'from 1.2 to 2.8 times slower'"
lim_ur5 = np.array(ur5["transfer"]["qd_limits"])
assert ((peaks_ur5 / lim_ur5).argmax(axis=1) == 2).all(), (
    "text: 'in every prototype the elbow q3 sets the time scale'"
)
assert np.allclose(table["time_scale"], peaks_ur5[:, 2] / lim_ur5[2]), (
    "text: 'the elbow q3 ... sets the time scale'"
)
assert (peaks_ur5[:, 3] > peaks_ur5[:, 2]).all(), "text: 'the wrist q4 moves faster'"
pv_rec, pv_exe = table["PV as recorded (m/s)"], table["PV executable (m/s)"]
assert np.ptp(pv_exe) < 0.5 * np.ptp(pv_rec), (
    "text: 'span less than half the range of the recorded ones'"
)
assert (pv_exe < pv_exe[pv_rec.idxmax()]).sum() == 1, (
    "text: 'the fastest human prototype is the second slowest'"
)
proto_ur5 = [
    (c["prototype"]["participant"], c["prototype"]["trial"]) for c in ur5["clusters"]
]
assert proto_ur5 == list(
    zip(clusters["prototype.participant"], clusters["prototype.trial"])
), "text: the UR5 run has the Simple6 run's prototypes ('the two-trial cluster')"
assert [bool(capped[k]) for k in proto_ur5] == proto_capped and sum(
    proto_capped
) == 1, "text: 'five of the six prototypes ... the two-trial cluster's' (uncapped band)"

# %% [markdown]
# With these limits none of the six prototypes can run as recorded: they must run from 1.2 to 2.8
# times slower. In every prototype the elbow q3, limited to 1 rad/s, sets the time scale; the wrist q4
# moves faster, but its limit is 2 rad/s. Slowed down, the prototypes' peak speeds (`PV executable`)
# span less than half the range of the recorded ones, and the fastest human prototype is the second
# slowest on the robot. The SPARC of five of the six prototypes does not change; the exception is the
# two-trial cluster's, whose band fc ended: its SPARC may change when it is slowed down.
#
# The same from Python: [`sk.analyse`](#skilllib.pipeline.analyse) reads, segments, selects and
# clusters as the command does, [`sk.get_robot`](#skilllib.robot.get_robot) gives the arm with the
# limits of `--qd-max`, and [`sk.transfer`](#skilllib.robot.transfer) takes the arm and a prototype's
# segment. For the fastest prototype:

# %%
analysis = sk.analyse(data_file)
arm = sk.get_robot("ur5", qd_max=[float(v) for v in limits])
proto = analysis.segments[-1]  # the prototype of the last cluster (highest centre PV)
moved = sk.transfer(arm, proto)
peak = np.round(moved.peak_abs_qd, 2).tolist()  # rad/s, per joint
print(
    f"{arm.robot.name}, prototype of participant {proto.participant} "
    f"trial {proto.trial}:\npeak |qd| q1..q6 {peak} rad/s"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above and below (hidden on the site; nbmake fails if one breaks)
last = ur5["clusters"][-1]["prototype"]
assert clusters["prototype.pv"].idxmax() == len(clusters) - 1, (
    "text: 'the fastest prototype'"
)
assert (proto.participant, proto.trial) == (last["participant"], last["trial"]), (
    "text: 'as the command does' (the same prototype)"
)
assert np.allclose(moved.peak_abs_qd, peaks_ur5[-1], rtol=1e-6, atol=1e-9), (
    "text: 'the same joint speeds as the command's last row'"
)

# %% [markdown]
# The same joint speeds as the command's last row. An arm the command does not know can be used the
# same way: `sk.transfer(robot, t, positions, velocities, q0=..., qd_limits=...)` takes any
# roboticstoolbox arm with at least six joints, a start pose inside its joint limits and its velocity
# limits (chapter 5 shows how the start poses above were chosen).
#
# ## When the input is broken
#
# A problem with the **file** stops the run before anything is computed, with one line that names
# the file and, where it applies, the line and the column and how to fix it, and exit status 2.
# Positions in millimetres, for instance:

# %%
in_mm = example.assign(x=example.x * 1000, y=example.y * 1000, z=example.z * 1000)
in_mm.to_csv(work / "in_mm.csv", index=False)
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

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden on the site; nbmake fails if one breaks)
for r, name in ((run_mm, "in_mm.csv"), (run_typo, "typo.csv")):
    assert r.returncode == 2, "text: 'and exit status 2'"
    assert r.stdout == "" and len(r.stderr.strip().splitlines()) == 1, (
        "text: 'with one line'"
    )
    assert name in r.stderr, "text: 'one line that names the file'"
    out = work / name.removesuffix(".csv").replace("in_", "")
    assert not out.exists(), "text: 'before anything is computed'"
assert "divide millimetres by 1000" in run_mm.stderr, "text: 'and how to fix it'"
assert "line 6" in run_typo.stderr and "column 'y'" in run_typo.stderr, (
    "text: 'the line and the column'"
)

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
r = rows(2)  # empty cells for 0.17 s of the approach: a gap too long to fill
c = int(np.flatnonzero(broken.loc[r, "contact"].to_numpy())[0])
broken.loc[r[c - 22 : c - 2], "y"] = np.nan
broken.loc[rows(3)[10], "z"] = np.inf  # an infinite position
broken.loc[rows(4), "contact"] = 0  # never touches the surface
r = rows(
    5
)  # never moves before contact: no onset (a still hand, 0.03 mm tracker noise)
c = int(np.flatnonzero(broken.loc[r, "contact"].to_numpy())[0])
xyz = ["x", "y", "z"]
still = np.random.default_rng(5).normal(0, 3e-5, (c, 3))
broken.loc[r[:c], xyz] = broken.loc[r[0], xyz].to_numpy(dtype=float) + still
broken = broken.drop(rows(6)[3:])  # only 3 samples left
# the first row of a trial moved to the end of the file: rows not contiguous
first = rows(7)[0]
broken = pd.concat([broken.drop(first), broken.loc[[first]]])
sk.write_recordings(broken, work / "broken.csv")
run = skilllib_run(
    "--data", str(work / "broken.csv"), "--out", str(work / "broken"), "--no-figures"
)
broken_results = json.loads((work / "broken" / "results.json").read_text())
bad = pd.DataFrame(broken_results["trials"])
bad[bad["status"] == "invalid"][["participant", "trial", "status", "reason"]]

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims below (hidden on the site; nbmake fails if one breaks)
assert run.returncode == 0, "text: 'the run ends with exit status 0'"
invalid = bad[bad["status"] == "invalid"]
broken_keys = {(p, tr) for p, tr in keys}  # text ids, as in the file
assert set(zip(invalid["participant"], invalid["trial"])) == broken_keys, (
    "text: 'The eight broken trials, and only they, are invalid'"
)
assert invalid["reason"].nunique() == 8, "text: 'each with its own reason'"
assert len(bad) == len(trials) == 200, (
    "text: 'every trial of the file is in results.json' ('No trial is dropped')"
)
both = trials.merge(bad, on=["participant", "trial"], suffixes=("", "_broken"))
intact = ~both.set_index(["participant", "trial"]).index.isin(list(broken_keys))
assert (both.loc[intact, "status"] == both.loc[intact, "status_broken"]).all(), (
    "text: 'the other 192 trials keep the status they have in the intact file'"
)
assert intact.sum() == 192, "text: 'the other 192 trials'"
n_sel_broken = both.loc[~intact, "status"].eq("selected").sum()
assert n_sel_broken == 2, (
    "text: 'two of the broken trials were selected in the intact file'"
)


def prototype_ids(res: dict) -> set[tuple[str, str]]:
    """(participant, trial) of every prototype of a results.json."""
    return {
        (c["prototype"]["participant"], c["prototype"]["trial"])
        for c in res["clusters"]
    }


protos, protos_broken = prototype_ids(results), prototype_ids(broken_results)
assert protos_broken != protos, "text: 'some prototypes change'"

# %% [markdown]
# The eight broken trials, and only they, are invalid, each with its own reason, which gives the line
# of the file where it applies; the run ends with exit status 0, and every trial of the file is in
# `results.json`. (A single empty cell, or a short run of them, does not break a trial: it is filled by
# interpolation between the recorded samples around it and reported in the trial's `repairs`,
# [chapter 11](11_your_data.ipynb).) The other 192 trials keep the status they have in the intact
# file. Two of the broken
# trials were selected in the intact file, so the clusters are computed on two trials fewer and some
# prototypes change.
#
# Two more trial-level checks need no example: a trial with fewer samples from onset to contact than
# the segmentation needs is invalid (*too short*), and so is a trial sampled at another rate than the
# rest of the file or with a gap in its time stamps ([chapter 13](13_noise_and_filters.ipynb)). With
# few selected trials the silhouette range
# shrinks to what they allow, and a `--k` larger than that is reduced, each said in a `note:` line and
# in `messages`. With fewer than 3 selected trials the run still writes `results.json` with every
# trial, skips the clustering and ends with exit status 3; each selected trial is then transferred as
# it is, so that even one demonstration gets the robot's verdict (`transfer.selected_trials`). A file
# with the example's excluded trials and only two of its selected ones:

# %%
excluded = trials[trials["status"] == "excluded"]
few_keys = pd.concat([excluded, trials[trials["status"] == "selected"].head(2)])
# those trials' rows, in file order
few = example.merge(few_keys[["participant", "trial"]])
sk.write_recordings(few, work / "few.csv")
run = skilllib_run(
    "--data", str(work / "few.csv"), "--out", str(work / "few"), "--no-figures"
)
few_results = json.loads((work / "few" / "results.json").read_text())
print(
    f"results.json: {len(few_results['trials'])} trials, "
    f"{few_results['n_selected']} selected; clusters: {'clusters' in few_results}, "
    f"transfer: {'transfer' in few_results}"
)
print("transferred as they are:")
for key in few_results["transfer"]["selected_trials"]:
    print(f"  participant {key['participant']}, trial {key['trial']}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden on the site; nbmake fails if one breaks)
assert few_results["n_selected"] == 2, "text: 'only two of its selected ones'"
assert run.returncode == 3, "text: 'ends with exit status 3'"
assert len(few_results["trials"]) == len(few_keys), (
    "text: 'results.json with every trial'"
)
assert "clusters" not in few_results, "text: 'skips the clustering'"
sel = few_keys[few_keys["status"] == "selected"]
assert few_results["transfer"]["selected_trials"] == [
    {"participant": p, "trial": t} for p, t in zip(sel["participant"], sel["trial"])
], "text: 'each selected trial is then transferred as it is'"

# %% [markdown]
# ## Summary
#
# - `python -m skilllib run --data PATH --out DIR` runs the whole pipeline and writes `results.json`
#   (every trial with its status and reason, the clusters, the prototypes, the transfer) and every
#   figure as PNG and SVG into a folder it replaces as a whole; its exit status says whether it is
#   done (0), stopped on the input or an option (2) or selected fewer than 3 trials (3).
# - `--robot` and `--qd-max` choose the arm and its joint velocity limits; `feasible_velocity` and
#   `time_scales.velocity` answer for the velocity limits, `feasible` and `time_scale` for every limit
#   checked ([the command](../docs/cli.md), [results.json](../docs/results.md)). From Python,
#   `sk.analyse`, `sk.get_robot` and `sk.transfer` do the same steps.
# - A broken file stops with one line naming the problem and how to fix it; a broken trial (or an
#   unreadable file in a folder) is kept, marked `invalid` with its reason, and everything else is
#   analysed. No trial is dropped silently.
