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
#   enumerator: "11.%s"
# ---
# # Your recordings
#
# The previous chapters ran on the book's synthetic cohort. This one is for the lab engineer who wants
# to run the same pipeline on their own recordings tomorrow: how to export them to the book's format
# or read them as the lab writes them (C3D, TRC, folders, other columns, units and axes), and how to
# check an export before anything is computed. The next chapter,
# [Running the pipeline on your recordings](12_running_the_pipeline.ipynb), runs the one command that
# does everything on such a file and reads what it writes; what the pipeline does with the time
# stamps, the sampling rate and tracker noise before it computes a feature is the subject of
# chapter 13, [Noise, sampling rates and the low-pass filter](13_noise_and_filters.ipynb). The
# reference pages hold the details: [the command](../docs/cli.md), [the input formats](../docs/inputs.md)
# and [results.json](../docs/results.md).
#
# ```{note}
# Most example recordings in this chapter are synthetic too: small cohorts written by the book's
# generator (`skilllib.cohort`), at higher sampling rates than the cohort's (the paper's Phantom
# recorded at 60 Hz), one of them as a motion-capture folder of TRC files, to show what the pipeline
# does with each. The last section reads real recordings from other labs (`data/real/`). With your own
# file, replace its path.
# ```

# %% tags=["hide-input"] jupyter={"source_hidden": true}
import json
import shutil
import textwrap
from pathlib import Path

import numpy as np
import pandas as pd

import skilllib as sk
import skilllib.figures as skf

work = Path("_your_data")  # everything this chapter writes goes here
shutil.rmtree(work, ignore_errors=True)  # start empty: no results of an earlier run
work.mkdir()


# %% [markdown]
# ## The format
#
# The book's own format is one CSV file, a long table with **one row per sample** and these columns:
#
# | column | unit | meaning |
# |---|---|---|
# | `participant` | – | participant id: text, read exactly as written (`01`, `1` and `NA` are three ids) |
# | `trial` | – | trial id within the participant: text as well |
# | `t` | s | time stamp of the sample (any origin; increasing within a trial) |
# | `x`, `y`, `z` | m | tool-tip position: x mediolateral, **y vertical (up)**, z anteroposterior |
# | `contact` | 0/1 | 1 while the tip touches the target surface |
#
# The rows of one trial are contiguous and in time order; extra columns are ignored; the file may be
# compressed (`.csv.gz`, `.zip`, ...). The movement analysed is the approach from rest down to the first
# sample with `contact = 1`, so the recording of a trial should start while the hand is still at rest
# and must include the moment of contact. Identifiers are never turned into numbers: a lab's `01` and
# `1` stay two participants, and `results.json` writes them as the file does.
#
# ## Other formats
#
# Recordings rarely come in that form. `--data` also takes a **C3D** file (Vicon, Qualisys, OptiTrack
# exports), an **OpenSim TRC** file, or a **folder** of them, one trial per file, and the options below
# map a lab's own table onto the book's:
#
# | option | what it does |
# |---|---|
# | `--columns OLD=NEW,...` | renames the file's columns, e.g. `time=t,subject=participant,touch=contact` |
# | `--units m\|cm\|mm` | the unit of the positions (C3D and TRC: read from the file's header) |
# | `--up-axis=AXIS` | the file's vertical axis pointing up (`y`, `z`, `-z`, `x`, ...): positions are rotated, without mirroring, so that it becomes y |
# | `--marker NAME` | which marker of a C3D or TRC file (the only one by default; with several the error lists them) |
# | `--contact-channel NAME` | a C3D analog channel or event that marks contact (default `contact` when present) |
# | `--contact-height M` | where the file has no contact signal: contact from the first sample whose height y (m, after the mapping) is at or below M |
# | `--name-pattern REGEX` | for a folder: groups `(?P<participant>...)` and `(?P<trial>...)` taken from each file's name |
#
# In a folder, `DIR/<participant>/<trial>.c3d` takes the participant from the sub-folder and the trial
# from the file's name; files directly in `DIR` are named `<participant>_<trial>.trc` (split at the last
# `_`) unless `--name-pattern` says otherwise. A file that cannot be read becomes an `invalid` trial with
# the file's name and the problem; the others are analysed. The rules are those of
# [the input formats](../docs/inputs.md) and of [`skilllib.recordings`](#skilllib.recordings) (its
# documentation has the rotation of every `--up-axis`).
#
# Here is a small motion-capture export written the way such systems write it: a folder per participant,
# one TRC file per trial, millimetres, **z up** (as Vicon and Qualisys use), and no contact signal, so
# that contact comes from the height of the touched surface. The movements are the book's generator's:

# %%
SURFACE = -0.10  # m, height of the touched surface in the book's frame (y up)
mocap_model = sk.CohortModel(
    n_participants=2, n_trials=6, fs=100.0, surface_y=(SURFACE,) * 2
)
mocap = sk.generate_cohort(seed=12, model=mocap_model)
for (p, tr), g in mocap.frame.groupby(["participant", "trial"], sort=False):
    # the book's y up -> the lab's z up
    lab = g[["x", "y", "z"]].to_numpy() @ sk.UP_AXIS_ROTATIONS["z"]
    trc = work / "mocap" / f"S{p}" / f"touch{tr}.trc"
    sk.write_trc(trc, {"spoon_tip": lab}, g["t"].to_numpy(), units="mm")
print(
    sorted(str(f.relative_to(work)) for f in (work / "mocap").rglob("*.trc"))[:3], "..."
)
trc = (work / "mocap" / "S1" / "touch1.trc").read_text().expandtabs(4).splitlines()
for line in trc[:7]:  # a line longer than the page wrapped, its continuation marked ↪
    print(textwrap.fill(line, 88, subsequent_indent="  ↪ ") if len(line) > 88 else line)

# %% [markdown]
# The command (chapter 12) reads the folder with the axis and the surface height given (the height in the book's
# frame, metres, y up; 0.2 mm above the surface, so that the tip's first sample on it counts). Beside it,
# the same movements from the generator's own CSV, whose contact flag comes from the simulated touch:

# %%
mocap_run = sk.run_command("--data", str(work / "mocap"), "--up-axis", "z",
                         "--contact-height", str(SURFACE + 0.0002), "--no-figures",
                         "--out", str(work / "mocap_results"))  # fmt: skip
print(mocap_run.stdout.splitlines()[0], "| exit status", mocap_run.returncode)
mocap_results = json.loads((work / "mocap_results" / "results.json").read_text())
from_trc = pd.DataFrame(mocap_results["trials"])
from_csv = sk.trial_features(mocap.recordings)
compare = pd.DataFrame({
    "participant": from_trc.participant, "trial": from_trc.trial,
    "status (TRC)": from_trc.status, "status (CSV)": from_csv.status,
    "segment samples (TRC)": np.round(from_trc.duration * mocap_model.fs).astype(int),
    "segment samples (CSV)": from_csv.n.astype(int),
    "PV (TRC)": from_trc.pv, "PV (CSV)": from_csv.pv,
    "SPARC (TRC)": from_trc.sparc, "SPARC (CSV)": from_csv.sparc,
})  # fmt: skip
compare.round(4)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims below (hidden on the site; nbmake fails if one breaks)
assert mocap_run.returncode in (0, 3), mocap_run.stderr
assert mocap_model.fs == 100.0, "the TRC files' rate (duration x 100 Hz: samples)"
assert from_trc.participant.tolist() == ["S" + p for p in from_csv.participant], (
    "text: participant from the sub-folder"
)
assert from_trc.trial.tolist() == ["touch" + t for t in from_csv.trial], (
    "text: trial from the file name"
)
assert (compare["status (TRC)"] == compare["status (CSV)"]).all(), (
    "text: 'every trial has the same status'"
)
assert (compare["PV (TRC)"] - compare["PV (CSV)"]).abs().max() < 1e-4, (
    "text: 'PV within 0.1 mm/s'"
)
dn = compare["segment samples (TRC)"] - compare["segment samples (CSV)"]
d_sparc = (compare["SPARC (TRC)"] - compare["SPARC (CSV)"]).abs()
assert (d_sparc[dn == 0] < 1e-3).all() and (dn.abs() <= 1).all(), (
    "text: 'same segment: same SPARC; else one sample'"
)
assert 0 < (dn != 0).sum() <= 4 and d_sparc[dn != 0].max() > 0.05, (
    "text: 'in a few trials ... by up to'"
)

# %% [markdown]
# Participants come from the sub-folders (`S1`, `S2`) and trials from the file names. Every trial has the
# same status as from the CSV and the same PV within 0.1 mm/s (the TRC holds positions to 1 µm). Where the
# height rule finds the touch at the sample the simulation flagged, SPARC agrees within 0.001; in a few
# trials the rule ends the segment one sample earlier or later, and SPARC moves by several hundredths
# (table above): on segments this short, one sample more or less is visible in SPARC (chapter 2). Choose
# the contact height with that in mind, and prefer a measured contact signal where there is one: a C3D
# file's analog channel or event named by `--contact-channel` gives contact directly.
#
# Time stamps come as labs write them too: at any rate, with jitter and dropped frames, and with
# tracker noise in the positions. What the pipeline does with them (it reads the rate, resamples
# irregular trials and low-pass filters noisy positions) is the subject of
# [chapter 13](13_noise_and_filters.ipynb).

# %% [markdown]
# ## An example file
#
# The chapter writes a small synthetic file instead of your recordings: five participants with 40
# trials each, at 120 Hz. The sampling rate printed here is the one read back from the time stamps of
# the file. Chapter 12 runs the pipeline on the same file.

# %%
model = sk.CohortModel(n_participants=5, n_trials=40, fs=120.0)
example = sk.generate_cohort(seed=11, model=model).frame
data_file = sk.write_recordings(example, work / "lab_recordings.csv")
check = sk.load_recordings(data_file)
print(
    f"{data_file}: {len(example)} rows, "
    f"{example['participant'].nunique()} participants, "
    f"{len(check)} trials, sampled at {check.fs:.4g} Hz"
)
example.head()

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden on the site; nbmake fails if one breaks)
assert example["participant"].nunique() == 5 and len(check) == 5 * 40, (
    "text: 'five participants with 40 trials each'"
)
assert round(check.fs) == 120, "text: 'at 120 Hz' (read back from the time stamps)"
assert check.fs > sk.CohortModel().fs == 60, (
    "text: 'at a higher sampling rate than the cohort's (... 60 Hz)'"
)

# %% [markdown]
# ## Checking the export
#
# Before you run anything, look at the trials as the pipeline sees them.
# [`sk.trial_features`](#skilllib.features.trial_features) segments every trial and gives its status;
# [`skf.plot_trials_by_participant`](#skilllib.figures.experiment.plot_trials_by_participant) draws the height y
# and the speed of every valid trial against time from contact, the figure the command also writes
# (`trials_by_participant`, chapter 12). It shows at once whether the export is right: y should fall
# to the contact surface and stay there; speed should rise from rest and end at contact. For the
# example file, whose trials' contact speeds decide the colours (the paper's window):

# %%
features = sk.trial_features(check)
print(features["status"].value_counts().to_dict(), "| window (m/s):", sk.CONTACT_WINDOW)

# %%
#| label: fig-your-trials
#| caption: Synthetic example file. Height y (m) and approach speed (m/s) of every valid trial against time from contact (s), y above speed for each participant; selected trials in colour, excluded ones in grey. The command writes the same figure as trials_by_participant.png.
fig = skf.plot_trials_by_participant(check, features)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims below (hidden on the site; nbmake fails if one breaks)
valid = features[features["status"] != "invalid"]
assert len(valid) == len(features), "text: every trial of the example is drawn (valid)"
v_contact = valid["contact_speed"]
in_window = v_contact.between(*sk.CONTACT_WINDOW)
assert tuple(sk.CONTACT_WINDOW) == (0.3, 0.7), (
    "text: 'slower than 0.3 m/s or faster than 0.7'"
)
assert ((valid["status"] == "selected") == in_window).all(), (
    "text: 'The grey curves are the excluded trials, those that reach the surface "
    "slower than 0.3 m/s or faster than 0.7 m/s'"
)

# %% [markdown]
# The export of the example file passes this check: in each participant's panels y falls from rest to
# that participant's contact surface and stays there, and the speed rises from rest and ends at the
# dotted line of contact. The grey curves are the excluded trials, those that reach the surface slower
# than 0.3 m/s or faster than 0.7 m/s. What the command says about a file or a trial that is broken
# is in chapter 12.
#
# ## Recordings from other labs
#
# Everything above was synthetic. The repository also holds real recordings written by other labs'
# software (`data/real/`, each with its source and licence in its README), and the readers are tested on
# them. 160 are **Vicon Nexus "Trajectories" CSV exports** of an open database of daily upper-limb
# activities: 16 healthy adults reach forward and touch a target sticker with the index fingertip, with
# the left or the right hand (`L`, `R` in the name), recorded at 100 Hz in millimetres with z up; four of
# them are read here (chapter 15 takes all 160 through the paper's method). Nexus
# writes a section name, the rate, the marker names with the subject's prefix (`ADL005:RFTP`), the
# coordinate names and a units row before the frames; the files are read as they are, the rate and the
# unit from their header. `--marker RFTP,LFTP` takes, in each file, the listed marker that moves most
# (the moving hand's fingertip), and the name pattern splits names like `ADL005FR3`, which have no `_`:

# %%
adl_dir = work / "ue-adl"
adl_dir.mkdir()
adl_all = sorted(Path("../data/real/ue-adl-forward-reach").glob("*.csv.gz"))
print(f"{len(adl_all)} Nexus exports in data/real/ue-adl-forward-reach")
for name in ["ADL001FL1", "ADL001FR1", "ADL002FR2", "ADL005FR3"]:
    shutil.copy(f"../data/real/ue-adl-forward-reach/{name}.csv.gz", adl_dir)
adl = sk.load_recordings(
    adl_dir,
    marker="RFTP,LFTP",
    up_axis="z",
    name_pattern=r"(?P<participant>ADL\d+)(?P<trial>F[LR]\d)",
    contact_height=-1.0,  # m: no contact signal; a height never reached
)
adl_features = sk.trial_features(adl)
adl_rows = []
for p, tr in adl.keys():
    trial = adl.trial(p, tr)
    speed = np.linalg.norm(sk.velocity(trial.pos, adl.fs), axis=1)
    adl_rows.append({"participant": p, "trial": tr, "samples": len(trial.t),
                     "duration (s)": trial.t[-1] - trial.t[0],
                     "peak fingertip speed (m/s)": speed.max()})  # fmt: skip
print(f"{len(adl)} recordings at {adl.fs:.4g} Hz (from the time stamps); status:",
      adl_features["status"].value_counts().to_dict())  # fmt: skip
pd.DataFrame(adl_rows).round(3)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above and below (hidden on the site; nbmake fails if one breaks)
adl_table = pd.DataFrame(adl_rows)
assert len(adl) == 4 and round(adl.fs) == 100, "text: 'four ... at 100 Hz'"
assert len(adl_all) == 160, "text: '160 are Vicon Nexus exports'"
assert adl_table["peak fingertip speed (m/s)"].between(0.3, 1.1).all(), (
    "text: 'peak speeds of a comfortable reach'"
)
assert (adl_features["reason"].str.startswith("no contact")).all(), (
    "text: 'every recording is invalid for the paper's task: no contact'"
)
assert adl.trials["repairs"].eq("").all(), "text: 'nothing needed repairing'"

# %% [markdown]
# The recordings are read without a conversion by hand, with peak fingertip speeds of a comfortable
# reach, and nothing in them needed repairing. They are all `invalid` for the paper's task, with the
# reason *no contact*: the touch of a sticker leaves no contact signal, and the finger starts and ends
# at rest at about the same height, so no height rule marks it. The pipeline still shows what it read.
# `run` writes **segmentation pages** (`segmentation-01.png`, ...; chapter 12), one panel per trial:
# speed against time over the whole recording, the onset and the contact marked when found, the
# analysed segment shaded, repaired samples crossed, and the status with its reason. They are the
# first thing to look at with a new export:

# %%
#| label: fig-real-segmentation
#| caption: "Real recordings (Vicon Nexus CSV exports of the UE-ADL database, forward reaches to a target, 100 Hz): the segmentation page run writes, one panel per recording. Each reach rises from rest and returns to it; no contact is found (the task has no contact signal), so every panel is invalid and no segment is shaded."
fig = skf.plot_segmentation_pages(adl, adl_features)[0]

# %% [markdown]
# Real exports also have defects that a generator does not make. The last file is a tab-separated
# table of 45 reach-to-grasp trials of one participant, recorded with an NDI Optotrak at about 85 Hz,
# time in milliseconds, positions in millimetres. Its separator is found from the header, and
# `--time-unit ms` (here `time_unit="ms"`) says what the time stamps are. Every sample of a trial is
# checked for the defects real trackers produce, and each repair is counted and named in the trial's
# `repairs` (results.json's too; the rules and their limits are in
# [`skilllib.recordings`](#skilllib.recordings)): a stale first frame left from an earlier trial is
# dropped; positions frozen (repeated exactly) while the hand moves, a single-frame jump no hand can
# make and short runs of missing samples are replaced by interpolation between the recorded samples
# around them; a gap too long to fill invalidates the trial only where the analysis reads:

# %%
kinesis = sk.load_recordings(
    "../data/real/kinesis_rtgData.txt",
    columns="subjName=participant,trialN=trial,globalTime=t,"
    "indexXraw=x,indexYraw=y,indexZraw=z",
    time_unit="ms",
    units="mm",
    contact_height=-1.0,  # m: no contact signal; a height never reached
)
kt = kinesis.trials
repaired_by, invalid_by = kt["repairs"].str.contains, kt["reason"].str.contains
repair_counts = pd.Series(
    {
        "trials": len(kt),
        "with a stale first frame dropped": int(repaired_by("stale").sum()),
        "with frozen samples replaced": int(repaired_by("frozen").sum()),
        "with a jump replaced": int(repaired_by("jump").sum()),
        "samples replaced by interpolation": int(kt["n_repaired"].sum()),
        "invalid: frozen too long to fill": int(invalid_by("frozen").sum()),
    }
)
print(f"sampled at {kinesis.fs:.3g} Hz (from the time stamps)")
repair_counts

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above and below (hidden on the site; nbmake fails if one breaks)
rc = repair_counts
assert rc["trials"] == 45 and 84 < kinesis.fs < 86, (
    "text: '45 ... trials ... about 85 Hz'"
)
assert rc["with a stale first frame dropped"] >= 40, "text: 'nearly every trial'"
assert rc["with frozen samples replaced"] >= 10, "text: 'many trials have frozen runs'"
assert rc["invalid: frozen too long to fill"] >= 5, "text: 'some ... too long to fill'"

# %% [markdown]
# Nearly every trial starts with a stale frame (far from the next, left over from the tracker's
# previous state), which would otherwise read as a movement already under way; many trials
# have frozen runs where the marker was occluded, and in some the freeze is too long to fill. This
# task, too, is not the paper's: a reach to grasp ends at rest at the object, with no contact. The
# pipeline reads it faithfully, says what it changed, and refuses only what it cannot repair honestly.
#
# ## Summary
#
# - Recordings enter the book as one long CSV (`participant, trial, t, x, y, z, contact`, seconds and
#   metres, y up, ids as text), compressed or not, or as C3D and TRC files and folders of them;
#   `--columns`, `--units`, `--up-axis`, `--marker`, `--contact-channel` and `--contact-height` map a
#   lab's own layout onto it ([the input formats](../docs/inputs.md)). Contact from a height rule can
#   end a segment one sample off, which SPARC shows on short segments: prefer a measured contact signal.
# - `sk.load_recordings` reads a file as the command does and gives its sampling rate; the trials'
#   height and speed against time from contact (`trials_by_participant`) show at once whether an
#   export is right.
# - Real exports are read as the labs write them (Vicon Nexus CSV and C3D, Optotrak tables, TRC);
#   defects of real trackers (stale first frames, frozen or jumping positions, short gaps) are repaired
#   and counted in each trial's `repairs`, and the segmentation pages show what the analysis read.
# - Chapter 12 runs the pipeline on such a file and reads what it writes; time stamps, sampling rates
#   and tracker noise are chapter 13's subject.
