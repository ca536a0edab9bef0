# ---
# jupyter:
#   jupytext:
#     cell_metadata_filter: tags,jupyter,-all
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
#   enumerator: "3.%s"
# ---
# # The experiment and its data
#
# @maldonado2020 asked ten people to touch a box with a virtual spoon at a prescribed
# speed. This chapter describes the task and the device, and the open format in which the book keeps
# recordings. It presents the generative model that stands in for the unpublished recordings and checks
# that model against every number the paper publishes. It then turns each trial into a segment from
# movement onset to contact and into the features the clustering chapter uses: peak speed (PV), contact
# speed, duration, SPARC and LDLJ.
#
# ```{note}
# **The data in this chapter are synthetic.** The paper's recordings are not public. Every trial shown
# here was made by the seeded generative model in [`skilllib.cohort`](#skilllib.cohort) (function [`generate_cohort`](#skilllib.cohort.generate_cohort), seed 9:
# the first seed that meets every calibration target, see below and `data/README.md`), calibrated to the
# paper's aggregate numbers, and committed as `data/cohort.csv`.
# Nothing here is a measurement of a person. The same loader and feature code run on real recordings in
# the same format (see the chapter on your own data). Every number the text states about the cohort is
# checked by a hidden cell of the notebook, so the book does not build when a statement stops being true.
# ```

# %% tags=["hide-input"] jupyter={"source_hidden": true}
import time

import numpy as np
import pandas as pd
from scipy.stats import maxwell
from sklearn.cluster import KMeans
from sklearn.metrics import roc_auc_score, silhouette_score

import skilllib as sk
import skilllib.figures as skf

pd.set_option("display.precision", 3)
COHORT_CSV = sk.cohort_path()  # data/cohort.csv in the repository

# %% [markdown]
# ## The task and the device
#
# In a virtual environment the participant holds the stylus of a Phantom Premium 1.5 (3D Systems), to
# which a virtual spoon is attached. The device renders the contact force when the spoon touches a solid
# red *contact box*. A trial starts with the spoon tip resting in a semi-transparent *start box* above
# the contact box. The participant moves down in a roughly vertical plane and touches the top of the box,
# aiming at a contact speed of 0.5 m/s. After the touch the tip stays briefly on the surface. The paper
# records 10 participants x 150 trials, with the tip position sampled at 60 Hz
# [@maldonado2020, Sect. 5; @maldonado2019].
#
# Axes follow the paper's Fig. 1: $x$ mediolateral (side to side), $y$ vertical (up), $z$
# anteroposterior (forward and back). Units are metres and seconds. The Phantom Premium 1.5 reaches about
# 381 x 267 x 191 mm ($x$, $y$, $z$) with a nominal position resolution of about 0.03 mm. Its own velocity
# signal is noisy, so speeds here come from differentiated positions.
#
# ## The recordings format
#
# One CSV file holds a long table with one row per sample:
#
# | column | unit | meaning |
# |---|---|---|
# | `participant` | – | participant id (integer or label) |
# | `trial` | – | trial number within the participant |
# | `t` | s | time stamp (increasing within a trial) |
# | `x`, `y`, `z` | m | spoon-tip position in the device frame |
# | `contact` | 0/1 | 1 while the tip touches the contact surface |
#
# A trial's rows are contiguous and in time order. [`skilllib.recordings.read_recordings`](#skilllib.recordings.read_recordings) reads and checks a
# file. Problems with the file itself raise `DataFormatError` with the file, line and column: a missing
# column, a cell that is not a number, positions in millimetres, time in milliseconds, or mixed sampling
# rates. Problems with a single trial mark that trial `invalid` with a reason and the rest goes on; those
# are time going backwards, missing positions, too few samples, or rows that are not contiguous. The
# sampling rate comes from the time stamps.

# %%
t0 = time.perf_counter()
rec = sk.read_recordings(COHORT_CSV)
t_read = time.perf_counter() - t0
print(
    f"{COHORT_CSV.name}: {COHORT_CSV.stat().st_size / 1e6:.1f} MB, "
    f"{len(rec.frame)} rows,\n"
    f"{len(rec)} trials of {rec.trials.participant.nunique()} participants, "
    f"sampling rate {rec.fs:.2f} Hz from the time stamps;\n"
    f"read and validated in {t_read:.2f} s"
)
print("trial status after reading:", rec.trials.status.value_counts().to_dict())
rec.frame.head()

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert (len(rec), rec.trials.participant.nunique()) == (1500, 10), (
    "text: 10 x 150 trials"
)

# %% [markdown]
# The committed file is exactly what the seeded generator writes: regenerating the cohort and passing it
# through the same writer (`skilllib.recordings.format_recordings`, which rounds t to 0.1 ms and positions to
# 0.01 mm) reproduces the file byte for byte. A test checks the same.

# %%
synthetic = sk.generate_cohort(sk.SEED)
same = sk.format_recordings(synthetic.frame).encode() == COHORT_CSV.read_bytes()
print(
    f"generate_cohort(seed={synthetic.seed}) written again equals {COHORT_CSV.name}:",
    same,
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert same and synthetic.seed == 9, "text: 'seed 9', 'byte for byte'"

# %% [markdown]
# ## The generative model
#
# The model builds each trial from published regularities of arm movements; it is not fitted to
# anyone's trajectories.
#
# **Submovements.** The vertical drop of the tip is a sum of minimum-jerk submovements [@flash1985].
# Decomposing reaching movements into overlapping submovements with onset, duration and amplitude is the
# standard account of intermittency [@rohrer2003]. One submovement of amplitude $D$ and duration
# $T$ has speed
#
# $$ v(\tau) = \frac{D}{T}\,30\,\tau^2 (1-\tau)^2, \qquad \max v = 1.875\,\frac{D}{T} \text{ at } \tau = 0.5 . $$ (eq-mj)
#
# Normalised speed profiles of vertical arm movements keep their shape across speed and load
# [@atkeson1985]. In *downward* movements the acceleration phase is relatively longer than in upward
# ones [@papaxanthis1998], and the relative time to peak speed $k$ moves above 0.5 for fast
# movements and below 0.5 for slow ones [@nagasaki1989]. The model therefore joins the rising half of a
# minimum-jerk bell of duration $2kT$ to the falling half of one of duration $2(1-k)T$. The two halves
# share the peak [](#eq-mj) and the acceleration is continuous. $k$ is a participant trait (0.5–0.6),
# decreases by 0.2 per second of duration and varies from trial to trial.
#
# **Hitting the surface at a speed.** A participant cannot stop *at* the surface and still hit it at
# 0.5 m/s. Without a correction, the primary submovement aims *through* the surface: it is planned so that
# the tip reaches the box on the falling flank of its bell, at the intended contact speed. The approach
# ends there with non-zero speed, a truncated bell. In many trials the primary instead stops short of the
# surface, as primary submovements tend to do [@meyer1988; @elliott2004]. A corrective
# submovement then starts during its deceleration, and its amplitude is solved so that the tip reaches
# the surface at the intended contact speed. Faster primaries are less accurate, so the probability of a
# correction grows with the primary's peak speed [@meyer1988]. Corrective submovements are brief
# (0.15–0.35 s) and start, on average, during the primary's deceleration. Whether they blend into the
# primary or show as a second peak decides how much they lower SPARC [@balasubramanian2015].
#
# **Participants and trials.** Each participant has a start-to-surface distance (0.08–0.2 m, inside the
# device's 267 mm vertical range), a preferred primary duration (never below 0.2 s, an assumption
# that rules out implausibly fast aiming), a typical contact speed that is biased
# away from 0.5 m/s, and an asymmetry and a correction rate. Their trial-to-trial variability has its
# own size. The traits are drawn by Latin-hypercube sampling, so that ten participants cover each range
# evenly. Each trial varies the start position inside a 2 cm start box, the duration, the intended
# contact speed (log-normal; its tails below 0.2 m/s and above 1 m/s are compressed smoothly into
# 0.1–1.8 m/s, as a hard clip would pile those trials up at one speed), the corrections, and the rest before onset (0.3–0.6 s) and after contact
# (0.2–0.4 s).
#
# **Contact, off-axis motion and the device.** At the touch the tip meets a stiff virtual wall,
# critically damped with a 10 ms time constant. It then rests 0.2–1 mm into it, and `contact` is 1 from
# the first sample at or after the touch. Off the vertical there is a participant-specific tilt of a few
# degrees, a lateral bow of a few millimetres per trial, and slow postural sway of at most 0.3 mm. White
# noise at the device's 0.03 mm resolution is added on every axis, and samples are taken at 60 Hz.
# Randomness comes from `numpy.random.default_rng` streams spawned from one seed: one stream for the
# traits and one per trial.
#
# The population parameters, as used for the committed cohort, with their units. A pair of numbers is the
# range of a uniform draw, except where the meaning says "mean and SD"; a "log-SD" is the standard
# deviation of the logarithm of a log-normal draw.

# %%
sk.model_table()

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
cm = sk.CohortModel()
assert cm.rtpv == (0.5, 0.6) and cm.rtpv_slope == -0.2, (
    "text: k 0.5-0.6, 0.2 per second"
)
assert cm.correction_duration == (0.15, 0.35), "text: corrections 0.15-0.35 s"
assert cm.travel == (0.08, 0.2) and cm.min_duration == 0.2, "text: 0.08-0.2 m, 0.2 s"
assert cm.start_box == 0.02, "text: a 2 cm start box"
assert (cm.aim_soft_min, cm.aim_soft_max) == ((0.2, 0.1), (1.0, 1.8)), (
    "text: tails below 0.2 m/s and above 1 m/s compressed into 0.1-1.8 m/s"
)
assert (cm.rest_before, cm.rest_after) == ((0.3, 0.6), (0.2, 0.4)), "text: rests"
assert cm.wall_tau == 0.01 and cm.press_depth == (0.0002, 0.001), (
    "text: 10 ms time constant, 0.2-1 mm into the wall"
)
assert 2 <= cm.tilt_sd <= 5 and 0.001 <= cm.bow_sd <= 0.005, (
    "text: a tilt of a few degrees, a bow of a few millimetres"
)
assert cm.sway == 0.0003 and cm.noise_sd == 3e-5 and cm.fs == 60.0, (
    "text: sway at most 0.3 mm, noise 0.03 mm, 60 Hz"
)

# %% [markdown]
# ## Calibration: target against obtained
#
# The paper publishes only aggregate numbers, and the table compares each with the synthetic cohort. In
# the paper's recordings, 650 of 1500 trials had a contact speed in [0.3, 0.7] m/s; participants varied
# widely in peak speed, contact speed and duration (its Fig. 1b); silhouette analysis found valid
# clusterings for every $k$ from 2 to 16; and six clusters gave an average silhouette of 0.337, with
# centres whose PVs were well separated. Those are the paper's numbers; the cohort's are in the column
# "obtained". The paper names K-means from scikit-learn [@pedregosa2011], and nothing more: it does not say whether it
# scaled the features, nor how many restarts or which seed it used. The book clusters the **raw** (PV in
# m/s, SPARC) tuples of the selected trials, since the paper mentions no scaling, with `n_init=10`
# (scikit-learn's default when the paper was written) and `random_state=0` (the book's choice), via
# [`skilllib.prototypes.silhouette_sweep`](#skilllib.prototypes.silhouette_sweep); chapter 6 shows what these choices change. A clustering is
# "valid" when its average silhouette is positive and every cluster has at least one trial above the
# average (scikit-learn's silhouette example, which the paper cites [@sklearnsilhouette]). The table's last column says whether each target is met;
# the per-$k$ averages follow it.

# %%
t0 = time.perf_counter()
feats = sk.trial_features(rec)
t_feat = time.perf_counter() - t0
print(f"features of {len(feats)} trials in {t_feat:.2f} s")
sweep = sk.silhouette_sweep(sk.select(feats), 2, 16, scaling="raw")
calib = sk.calibration_table(feats, sweep)
calib

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert calib["met"].all(), "text: the committed cohort meets every target (seed rule)"

# %%
sweep.table().T

# %% [markdown]
# **How the seed was chosen, and what it hides.** With ten participants a cohort is a small sample, and
# the calibration numbers vary from seed to seed as they would between two real cohorts. The model's
# parameters were therefore tuned by their average over seeds, and the committed cohort uses the first
# seed 0, 1, 2, ... that meets every target at once. `data/seed_survey.csv` holds the survey of seeds
# 0 to the committed seed, the rows the rule looks at (`sk.seed_survey(range(sk.SEED + 1))`, which
# generates and clusters a whole cohort per seed, so it is not rerun here; the test suite recomputes
# every row). The counts below show how many
# seeds meet each target: the silhouette window and the gap between centre PVs are the targets the model
# misses most often, and only the last seed, the committed one, meets all of them.

# %%
survey = pd.read_csv(sk.SURVEY_CSV, index_col="seed")
s6 = survey.silhouette_k6
print(
    f"silhouette at k = 6 over {len(survey)} seeds: mean {s6.mean():.3f}, "
    f"SD {s6.std():.3f}, range {s6.min():.3f}-{s6.max():.3f};\n"
    f"paper 0.337; committed cohort (seed {sk.SEED}) {sweep.results[6].silhouette:.3f}"
)
met = sk.survey_summary(survey)
met.to_frame("seeds meeting the target").T

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
per_target = met.drop(["seeds", "all targets"])
assert set(per_target.nsmallest(2).index) == {"silhouette k = 6", "centre gap"}, (
    "text: missed most often"
)
assert met["all targets"] == 1, "text: only the last seed, the committed one, meets all"
assert survey["all"].idxmax() == sk.SEED == survey.index.max(), (
    "text: only the last seed, the committed one, meets all"
)
assert s6.mean() > 0.337, "text: the model sits above the paper's 0.337 on average"

# %% [markdown]
# So the model sits above the paper's 0.337 on average over seeds. The committed cohort meets the
# 0.30–0.38 target because the seed rule demands it, not because the model centres on 0.337. The reason
# is the shape of the cloud. Clustered raw, as the paper does, (PV, SPARC) is dominated by whichever
# feature spreads more in its own units. In the synthetic cohort PV spreads about three times more than
# SPARC (printed below), so K-means cuts the cloud into slices along PV. Slices of a one-dimensional
# cloud give high silhouettes, and a round two-dimensional cloud gives values near the paper's. The cell
# compares the selected tuples with both extremes, using the same K-means and silhouette: the cohort lies
# between them, nearer the round cloud. The paper's 0.337 is consistent with a (PV, SPARC) cloud a little
# rounder than ours, in which SPARC spreads more relative to PV; the paper gives no spreads to check
# this against. The changes tried while calibrating (more corrections, later corrections, longer or less
# varied durations) moved the average silhouette little (data/README.md), and the paper publishes
# nothing that would justify a larger change. The book keeps the model and states the difference; the
# clustering chapter's conclusions do not depend on the third decimal of this number.


# %%
def silhouette_k6(x):
    """Average silhouette of K-means, k = 6 (n_init = 10, random_state = 0)."""
    return silhouette_score(x, KMeans(6, n_init=10, random_state=0).fit_predict(x))


x = sk.select(feats)[["pv", "sparc"]].to_numpy()
sd = x.std(axis=0)
round_cloud = np.random.default_rng(0).normal(size=x.shape)
print(
    f"selected trials: SD of PV {sd[0]:.3f} m/s, SD of SPARC {sd[1]:.3f} "
    f"(ratio {sd[0] / sd[1]:.1f})"
)
shapes = pd.Series(
    {
        "(PV, SPARC), raw: the calibration": silhouette_k6(x),
        "PV alone (a one-dimensional cloud)": silhouette_k6(x[:, :1]),
        "round Gaussian cloud of the same size": silhouette_k6(round_cloud),
    },
    name="average silhouette, k = 6",
)
shapes.to_frame()

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert 2.5 < sd[0] / sd[1] < 3.5, "text: PV spreads about three times more than SPARC"
cal, line, ball = shapes.to_numpy()
assert ball < cal < line and cal - ball < line - cal, (
    "text: between the extremes, nearer the round cloud"
)

# %% [markdown]
# ## The paper's Figure 1b, redrawn
#
# [](#fig-trials) shows, as the paper's Fig. 1b does, the vertical trajectory $y(t)$ and the speed
# profile of every trial, aligned at contact and with one column per participant. Selected trials are in
# colour and excluded ones in grey. Speed is drawn only up to contact, as the features use it. Start
# heights, peak speeds, contact speeds and durations differ clearly between participants. Within a
# participant some trials reach the surface at the end of a single bell, and others after a
# slow-down and a second push.

# %%
#| label: fig-trials
#| caption: Synthetic cohort. Vertical tip position y (device frame) and approach speed of every trial against time from contact, one column per participant; selected trials (contact speed 0.3-0.7 m/s) in colour, excluded ones in grey.
fig = skf.plot_trials_by_participant(rec, feats)

# %% [markdown]
# ## Per-participant summaries
#
# The table gives, per participant, the median and interquartile range over all valid trials. [](#fig-participants)
# shows every trial.

# %%
sk.participant_summary(feats)

# %%
#| label: fig-participants
#| caption: Synthetic cohort. Peak speed, contact speed (selection window shaded), duration from onset to contact, and SPARC of every valid trial per participant; boxes show quartiles, selected trials are coloured.
fig = skf.plot_participant_features(feats)

# %% [markdown]
# ## From samples to a segment
#
# **Speed.** Velocity is the derivative of the positions, taken by a Savitzky-Golay derivative (a
# quadratic fitted over a window of fixed duration, 2/60 s). At the experiment's 60 Hz that window is
# three samples and the derivative is the second-order finite difference (central inside, three-point
# one-sided at the ends); at higher rates the window keeps its duration, so the speed noise does not grow
# with the rate (chapter 13 shows why that matters). Its norm is the speed. Only the samples *before* contact are
# used: the impact is a velocity discontinuity, and a difference across it would mix the approach with
# the rest on the surface. No low-pass filter is applied. White position noise of standard deviation
# $\sigma$ = 0.03 mm (the device's resolution) becomes, through the central difference
# $(x_{i+1} - x_{i-1}) f_s / 2$, a velocity noise of $\sigma f_s / \sqrt{2} \approx 1.3$ mm/s **on each
# axis**. The speed is the norm of three such axes, which is larger: the norm of three independent normal
# components of standard deviation $s$ follows a Maxwell distribution with median about $1.54\,s$, here
# about 2 mm/s, still far below the 0.05 m/s onset threshold. SPARC reads the spectrum only above 5 % of
# its peak and up to the adaptive cut-off, so that noise does not reach it (chapter 1). A filter, by
# contrast, would itself smooth the profile that SPARC measures. The speed at rest, more than 0.2 s
# before onset, shows the noise floor; besides the device noise it contains the slow postural sway of
# the model, which adds a little:

# %%
rs = sk.rest_speed(rec, feats, margin=0.2)  # s before onset
axis_sd = sk.CohortModel().noise_sd * rec.fs / np.sqrt(2)  # m/s, per axis
noise_only = maxwell(scale=axis_sd)  # the norm of three such axes
print(
    f"device noise alone: {1e3 * axis_sd:.2f} mm/s per axis;\n"
    f"  speed (3-D norm) median {1e3 * noise_only.median():.2f} mm/s, "
    f"99th percentile {1e3 * noise_only.ppf(0.99):.2f} mm/s"
)
print(
    f"speed at rest over {rs.size} samples: median {1e3 * np.median(rs):.2f} mm/s,\n"
    f"  99th percentile {1e3 * np.percentile(rs, 99):.2f} mm/s, "
    f"maximum {1e3 * rs.max():.2f} mm/s "
    f"(onset threshold {1e3 * sk.ONSET_SPEED:.0f} mm/s)"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert round(1e3 * axis_sd, 1) == 1.3, "text: 1.3 mm/s"
assert round(noise_only.median() / axis_sd, 2) == 1.54, "text: median about 1.54 s"
assert round(1e3 * noise_only.median()) == 2, "text: about 2 mm/s"
assert 1 < np.median(rs) / noise_only.median() < 1.25, "text: the sway adds a little"
assert rs.max() < sk.ONSET_SPEED / 5, "text: far below the onset threshold"
assert sk.DIFF_SPAN_S == 2 / 60 and sk.diff_window(60.0) == 3, (
    "text: a window of 2/60 s, three samples at 60 Hz"
)

# %% [markdown]
# **Onset, contact, segment.** Contact is the first sample flagged `contact = 1`. Onset is the first
# earlier sample whose speed exceeds 0.05 m/s (the paper). The segment runs from onset to the last sample
# before contact. Its peak is PV, its last speed is the *contact speed*, and its length $N$ gives the
# duration $N/f_s$ from onset to the first contact sample. SPARC is computed on the segment with
# $f_c$ = 20 Hz, amplitude threshold 0.05 and zero-padding level 4, the SPARC chapter's choice, together
# with where its band ended and whether $f_c$ ended it (`sparc_band_end_hz`, `sparc_capped`), and LDLJ
# on the same segment. A trial that cannot be segmented stays in the table as `invalid` with the reason:
# no contact, no rest before onset, no onset, fewer than 5 samples from onset to contact, or bad samples.
# [](#fig-segmentation) shows four trials: a selected trial with the median SPARC, the least smooth
# selected trial, and one excluded on each side of the window.

# %%
valid = feats[feats.status != "invalid"]
examples = skf.segmentation_examples(feats, speeds=(1.0, 0.2))
shown = ["status", "reason", "pv", "contact_speed", "duration", "sparc", "sparc_capped"]
feats.set_index(["participant", "trial"]).loc[examples, [*shown, "ldlj"]]

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert sk.MIN_SEGMENT_SAMPLES == 5 and sk.ONSET_SPEED == 0.05, (
    "text: 5 samples, 0.05 m/s"
)
assert sk.SPARC_PARAMS == {"fc": 20.0, "amp_th": 0.05, "padlevel": 4}, (
    "text: fc = 20 Hz, 0.05, 4"
)
assert len(examples) == 4, "text: four trials"

# %%
#| label: fig-segmentation
#| caption: Synthetic cohort. Segmentation of four trials. Top, vertical position; bottom, approach speed with the 0.05 m/s onset threshold (dashed); shaded, the segment from onset (circle) to the last sample before contact (square, the contact speed); dotted, the first contact sample.
fig = skf.plot_segmentation(rec, feats, examples)

# %% [markdown]
# (contact-speed-60hz)=
# ### What 60 Hz can tell
#
# Because the data are synthetic, the generator's noise-free ground truth is known, and each estimate
# can be checked against it ([](#fig-truth), top row). PV agrees closely. Duration starts at the
# 0.05 m/s onset rather than at the true start of motion, so it reads short. The contact speed is the
# speed at the last sample before the touch, which lies up to one sampling interval (16.7 ms) before
# contact. At the end of these approaches the speed changes a lot within one interval, so the error is
# not a small offset: its SD is about 0.08 m/s, a fifth of the width of the 0.3-0.7 m/s selection
# window, and the largest is 0.45 m/s. On average it reads high (bias +0.02 m/s): approaches without a
# correction decelerate into the surface, so the speed a little earlier is higher. Approaches that end
# with a corrective submovement err both ways, by more: high where the correction brakes in the last
# interval, low where it still accelerates.

# %%
ids = ["participant", "trial"]
m = valid.merge(synthetic.truth, on=ids, suffixes=("", "_true"))
pv_err = np.median(m.pv / m.pv_true - 1)
dur_err = m.duration - (m.t_contact_true - m.t_onset_true)
last = sk.estimate_errors(m.contact_speed, m.contact_speed_true)
err = m.contact_speed - m.contact_speed_true
by_corr = err.groupby(m.n_corrections > 0).agg(["mean", "std"])
print(
    f"PV: median relative error {100 * pv_err:+.1f} %\n"
    f"duration: median error {1e3 * dur_err.median():+.0f} ms\n"
    f"contact speed (last sample before contact) minus the true one, {len(m)} trials:\n"
    f"  bias {last['bias']:+.3f} m/s, SD {last['SD']:.3f} m/s, "
    f"95th percentile of |error| {last['95th pct |error|']:.3f} m/s, "
    f"max {last['max |error|']:.2f} m/s\n"
    f"  without a correction: mean {by_corr.loc[False, 'mean']:+.3f} m/s, "
    f"SD {by_corr.loc[False, 'std']:.3f} m/s\n"
    f"  with a correction:    mean {by_corr.loc[True, 'mean']:+.3f} m/s, "
    f"SD {by_corr.loc[True, 'std']:.3f} m/s"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
window_width = sk.CONTACT_WINDOW[1] - sk.CONTACT_WINDOW[0]
assert abs(pv_err) < 0.02, "text: PV agrees closely"
assert dur_err.median() < 0, "text: duration reads short"
assert round(last["SD"], 2) == 0.08, "text: SD about 0.08 m/s"
assert 0.17 < last["SD"] / window_width < 0.23, "text: a fifth of the window's width"
assert round(last["max |error|"], 2) == 0.45, "text: the largest is 0.45 m/s"
assert round(last["bias"], 2) == 0.02, "text: reads high, bias +0.02 m/s"
assert by_corr.loc[False, "mean"] > 0.03, "text: uncorrected approaches read high"
assert abs(by_corr.loc[True, "mean"]) < 0.01, "text: corrected ones err both ways"
assert by_corr.loc[True, "std"] > 1.3 * by_corr.loc[False, "std"], "text: by more"

# %% [markdown]
# **The selection rests on this estimate.** With the true contact speed in place of the estimate, 178
# of the 1500 trials (12 %) would change side of the window: 120 selected trials lie outside it in
# truth, and 58 excluded ones inside. Which of a participant's trials are clustered therefore depends
# in part on where the 60 Hz samples happen to fall relative to the touch. And in 72 of the 680
# selected trials (11 %) the highest speed of the segment is its last sample: these trials touch at or
# just after their peak speed (their true contact ratio has a median of 0.995), so their PV *is* the
# contact speed that selected them, inside the window by construction.

# %%
sel = sk.select(feats)
selected = (m.status == "selected").to_numpy()
in_truth = m.contact_speed_true.between(*sk.CONTACT_WINDOW).to_numpy()
peak_last = sel.merge(synthetic.truth, on=ids, suffixes=("", "_true"))
peak_last = peak_last[peak_last.pv == peak_last.contact_speed]
true_ratio = (peak_last.contact_speed_true / peak_last.pv_true).median()
n_flips = int(last["flips"])
print(
    f"{n_flips} of {len(m)} trials ({100 * n_flips / len(m):.0f} %) change "
    f"selection with the true contact speed:\n"
    f"  {(selected & ~in_truth).sum()} selected but outside the window in truth, "
    f"{(~selected & in_truth).sum()} excluded but inside it\n"
    f"selected trials whose peak speed is the segment's last sample: "
    f"{len(peak_last)} of {len(sel)} ({100 * len(peak_last) / len(sel):.0f} %),\n"
    f"  their true contact ratio median {true_ratio:.3f}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert (last["flips"], len(m)) == (178, 1500), "text: 178 of the 1500 trials"
assert round(100 * last["flips"] / len(m)) == 12, "text: 12 %"
assert ((selected & ~in_truth).sum(), (~selected & in_truth).sum()) == (120, 58), (
    "text: 120 selected outside, 58 excluded inside"
)
assert (len(peak_last), len(sel)) == (72, 680), "text: 72 of the 680 selected trials"
assert round(100 * len(peak_last) / len(sel)) == 11, "text: 11 %"
assert round(true_ratio, 3) == 0.995, "text: true contact ratio median 0.995"

# %% [markdown]
# **An estimate at the contact instant.**
# [`sk.contact_speed_estimates`](#skilllib.features.contact_speed_estimates) fits a cubic to the last
# four positions before contact (least squares, each axis) and evaluates its derivative at an estimate
# of the contact instant. `"crossing"` puts that instant where the fitted path reaches the surface,
# which the samples *after* contact show (the tip rests on it), kept inside the last sampling interval
# as the contact flag requires; so it uses the samples on both sides of the touch. `"midpoint"` takes
# the middle of that interval. The table measures both, and the feature table's last sample, against
# the truth: over all 1500 trials, and over the 680 that the last-sample estimate selects (flips count
# the trials the estimate puts on the other side of the window from the truth).

# %%
estimates = {"last sample (the feature table)": m.contact_speed}
for method in ["midpoint", "crossing"]:
    e = m[ids].merge(sk.contact_speed_estimates(rec, feats, method=method), on=ids)
    estimates[method] = e.contact_speed
crossing = e.assign(t_true=m.t_contact_true)
t_err_ms = 1e3 * (crossing.t_contact - crossing.t_true).abs().median()
errors = pd.concat(
    {
        "all trials": pd.DataFrame(
            {
                k: sk.estimate_errors(v, m.contact_speed_true)
                for k, v in estimates.items()
            }
        ).T,
        "selected by the last sample": pd.DataFrame(
            {
                k: sk.estimate_errors(v[selected], m.contact_speed_true[selected])
                for k, v in estimates.items()
            }
        ).T,
    }
)
new_err = estimates["crossing"] - m.contact_speed_true
new_sd = new_err.groupby(m.n_corrections > 0).std()
print(
    f"crossing: contact instant within {t_err_ms:.1f} ms of the truth (median);\n"
    f"  error SD {new_sd[True]:.3f} m/s with a correction, "
    f"{new_sd[False]:.3f} m/s without"
)
errors.round(3)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
old, mid, new = (errors.loc["all trials"].loc[k] for k in estimates)
measures = ["SD", "RMSE", "95th pct |error|", "max |error|", "flips"]
assert abs(new["bias"]) < abs(old["bias"]) and (new[measures] < old[measures]).all(), (
    "text: crossing better than the last sample on all six measures"
)
assert round(new["bias"], 3) == -0.009 and round(old["bias"], 3) == 0.022, (
    "text: bias -0.009 instead of +0.022 m/s"
)
assert (round(new["SD"], 3), round(old["SD"], 3)) == (0.069, 0.082), "text: SD"
assert (round(new["95th pct |error|"], 2), round(old["95th pct |error|"], 2)) == (
    0.16,
    0.19,
), "text: 95th percentile 0.16 instead of 0.19"
assert (round(new["max |error|"], 2), round(old["max |error|"], 2)) == (0.41, 0.45), (
    "text: largest 0.41 instead of 0.45"
)
assert (new["flips"], old["flips"]) == (107, 178), "text: 107 flips instead of 178"
assert round(t_err_ms) == 1, "text: the instant to about 1 ms"
assert abs(mid["SD"] - new["SD"]) < 0.005 and abs(mid["bias"]) < abs(new["bias"]), (
    "text: midpoint as good on the spread, better on the bias"
)
assert abs(mid["max |error|"] - old["max |error|"]) < 0.005, (
    "text: its largest error is the last sample's"
)
assert mid["flips"] > new["flips"], "text: midpoint flips more trials"
assert 0.06 < new["SD"] < 0.075, "text: SD stays near 0.07 m/s"
assert new_sd[True] > 1.5 * new_sd[False], "text: the corrected trials carry the error"

# %% [markdown]
# In the book's draw the crossing estimate is better than the last sample on all six measures over
# all trials: bias −0.009 instead of +0.022 m/s, SD 0.069 instead of 0.082 m/s, 95th percentile of
# the absolute error 0.16 instead of 0.19 m/s, largest error 0.41 instead of 0.45 m/s, and 107 flips
# instead of 178. It places the contact instant to about 1 ms. The midpoint estimate is as good on the
# spread and better on the bias, but its largest error is the last sample's, and it flips more trials.
# Neither comes near the truth: the SD stays near 0.07 m/s,
# because a cubic through samples 16.7 ms apart cannot see a corrective submovement that changes its
# speed within the last interval, and the corrected trials carry most of the error (above). The second
# row of [](#fig-truth) shows both estimates against the truth.
#
# Is a new estimate better in general, or in this draw? The same comparison over 24 draws of the model
# (chapter 16 computes them; `sk.read_replication()` reads the committed table) counts, for each
# estimate, the draws in which it beats the last sample on every measure at once (the size of the
# bias, SD, RMSE, 95th percentile, largest error and flips):

# %%
draws = sk.read_replication()
beats = {}
for method in ["midpoint", "crossing"]:
    better = [
        (draws[f"contact_{method}_{k}"].abs() < draws[f"contact_sample_{k}"].abs())
        for k in ["bias", "sd", "rmse", "p95", "max", "flips"]
    ]
    beats[method] = pd.concat(better, axis=1).all(axis=1)
    worse_max = draws[f"contact_{method}_max"] > draws["contact_sample_max"]
    print(
        f"{method}: better on every measure in {int(beats[method].sum())} of "
        f"{len(draws)} draws; a larger largest error in {int(worse_max.sum())}"
    )
window = draws[[f"in_window_{m}" for m in ["sample", "midpoint", "crossing", "true"]]]
excess = window["in_window_sample"] - window["in_window_true"]
print("trials in the window, median over the draws:")
print(window.median().astype(int).to_string())
print(f"last sample minus truth: {excess.min()} to {excess.max()} trials")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert len(draws) == 24, "text: 24 draws"
assert not beats["midpoint"].all() and not beats["crossing"].all(), (
    "text: neither is better on every measure in every draw: the default stays"
)
# the draws' table reproduces this chapter's numbers for the book's draw
row = draws.loc[sk.SEED]
assert row["contact_sample_flips"] == last["flips"] == 178
assert (excess.min(), excess.max()) == (16, 79), "text: between 16 and 79 more"
assert (window["in_window_midpoint"] < window["in_window_true"]).all(), "text: fewer"
assert (window["in_window_crossing"] < window["in_window_true"]).all(), "text: fewer"
assert abs(row["contact_crossing_rmse"] - new["RMSE"]) < 1e-12

# %% [markdown]
# Neither estimate beats the last sample on every measure in every draw: in some draws its largest
# error is larger. The feature table therefore keeps the last sample by default, the reading of
# "contact speed" the book has used so far; `sk.trial_features(rec, contact_estimator="crossing")` (or
# `"midpoint"`) gives the table with a new estimate and the selection it makes. The other chapters use
# the default. The count in the window moves with the estimate in every draw: the last sample puts
# between 16 and 79 more trials in it than the true contact speed does, the two new estimates fewer.

# %%
#| label: fig-truth
#| caption: Synthetic cohort. Top, peak speed, contact speed (last sample before contact) and duration estimated from the 60 Hz samples against the generator's noise-free values; dashed, identity. Bottom, the contact speed by the last sample before contact (grey) and by the crossing estimate (blue; a cubic fitted to the last four positions, at the estimated contact instant) against the true one, their errors against the true contact speed (dotted, the selection window 0.3-0.7 m/s) and the histogram of the errors (clipped at 0.5 m/s).
est_crossing = sk.contact_speed_estimates(rec, feats, method="crossing")
fig = skf.plot_estimates_vs_truth(
    feats, synthetic.truth, est_crossing, label="crossing, cubic fit"
)

# %% [markdown]
# **What the paper's 650 depends on.** The paper's count, 650 of 1500 trials in the window, is a count
# of its estimate of the contact speed at 60 Hz. The table counts the trials in the window for the same
# synthetic movements by each estimate, by the truth, and with the same movements sampled at 120 Hz
# (`sk.CohortModel(fs=120.0)` with the same seed: the same movements, new noise, half the sampling
# interval).

# %%
fast = sk.generate_cohort(sk.SEED, sk.CohortModel(fs=120.0))
feats120 = sk.trial_features(fast.recordings)
est120 = sk.contact_speed_estimates(fast.recordings, feats120, method="crossing")
win = sk.CONTACT_WINDOW
counts_by = pd.Series(
    {
        "60 Hz, last sample (the book)": int((feats.status == "selected").sum()),
        "60 Hz, midpoint": int(estimates["midpoint"].between(*win).sum()),
        "60 Hz, crossing": int(estimates["crossing"].between(*win).sum()),
        "120 Hz, last sample": int((feats120.status == "selected").sum()),
        "120 Hz, crossing": int(est120.contact_speed.between(*win).sum()),
        "true contact speed": int(m.contact_speed_true.between(*win).sum()),
    },
    name="trials in the window",
)
same = fast.truth.contact_speed.equals(synthetic.truth.contact_speed)
v_true = m.contact_speed_true
slow_in = int((selected & (v_true < win[0])).sum())
lost_low = int((v_true.between(*win) & (estimates["crossing"] < win[0])).sum())
print(
    f"the 120 Hz cohort has the same true contact speeds: {same}\n"
    f"selected by the last sample, below {win[0]} m/s in truth: {slow_in}\n"
    f"in the window in truth, below {win[0]} m/s by the crossing: {lost_low}"
)
counts_by.to_frame()

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
lo, hi = counts_by.min(), counts_by.max()
assert same, "text: the same movements"
assert (lo, hi) == (577, 680), "text: from 577 to 680"
assert counts_by["true contact speed"] == 618, "text: the truth 618"
assert counts_by["120 Hz, last sample"] == 645, "text: 645 at 120 Hz"
assert abs(counts_by["120 Hz, last sample"] - 618) < abs(680 - 618), (
    "text: 120 Hz brings the last-sample count nearer the truth"
)
assert (
    counts_by["60 Hz, crossing"] < 618 < counts_by["60 Hz, last sample (the book)"]
), "text: the crossing counts below the truth, the last sample above"
assert hi - lo > 100, "text: a range of about a hundred trials"
assert (slow_in, lost_low) == (81, 50), "text: 81 slow trials read high; 50 read low"
assert slow_in > (selected & ~in_truth).sum() / 2, "text: mostly at the lower bound"
assert round(1e3 / fast.recordings.fs, 1) == 8.3, "text: never more than 8.3 ms early"

# %% [markdown]
# For the same movements, the count runs from 577 (crossing) to 680 (the last sample at 60 Hz, the
# book's); the truth is 618. The last sample counts too many, mostly at the lower bound: 81 of the
# selected trials touch below 0.3 m/s in truth, and read high because they decelerate into the surface.
# The crossing counts too few, the other way round: 50 trials that touch inside the window read below
# 0.3 m/s. At 120 Hz the last sample is never more than 8.3 ms early and counts 645. So a count like
# the paper's 650 belongs to the estimator and the sampling rate as much as to the participants: it
# moves over a range of about a hundred trials with how the contact speed is estimated. The book's 680
# and the paper's 650 lie well inside that range of each other, and whether the paper's 650 lies above
# or below its own true count cannot be told: its recordings are not public.

# %% [markdown]
# ## SPARC and the length of the segment
#
# SPARC has a limit of its own at this rate. The segments are short, and chapter 2 showed what that does:
# a segment of $N$ samples spans $T = N/f_s$ seconds and resolves its spectrum only every $1/T$ Hz, so the
# band up to $f_c$ = 20 Hz holds only about $f_c T$ independent spectral values, and the cut at contact
# spreads the spectrum over them. Intermittency has little room to show: a second submovement starting
# $\Delta$ seconds after the first puts the first zero of its ripple at $1/(2\Delta)$ Hz, and inside a
# segment $\Delta < T$. The shorter the segment, the more often the band still reaches the threshold at
# $f_c$, where the cap ends it and SPARC rises with shortness alone. [](#fig-sparc-length) shows SPARC
# against the segment length, and the share of bands ended by the cap at each length.

# %%
#| label: fig-sparc-length
#| caption: "Synthetic cohort. Left, SPARC of every valid trial against its segment length N (samples at 60 Hz; top axis, duration); selected trials blue, excluded grey; ringed, trials whose band the maximum cut-off fc = 20 Hz ended; dashed, the highest SPARC a band ended by the amplitude threshold can have (chapter 2). Right, the share of bands ended by fc at each length, with the number of trials above each bar."
fig = skf.plot_sparc_vs_length(feats, rec.fs)
n_values = sk.SPARC_PARAMS["fc"] * sel.duration.median()
bound = skf.threshold_bound()
above = valid[valid.sparc > bound]
print(
    f"segments: {valid.n.min()}-{valid.n.max()} samples for the valid trials, "
    f"{sel.n.min()}-{sel.n.max()} for the selected ones\n"
    f"  (median {sel.n.median():g}, {sel.duration.median():.2f} s: "
    f"about {n_values:.0f} independent spectral values below fc)"
)
print(
    f"bands ended by fc: {int(valid.sparc_capped.sum())} of {len(valid)} valid trials, "
    f"{int(sel.sparc_capped.sum())} of {len(sel)} selected\n"
    f"valid trials above the bound {bound:.3f}: {len(above)}, "
    f"all of them capped: {bool(above.sparc_capped.all())}"
)
by_len = sk.sparc_by_length(feats)
by_len.round(3)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert (valid.n.min(), valid.n.max(), sel.n.min(), sel.n.max()) == (5, 34, 10, 28), (
    "text: 5-34 and 10-28 samples"
)
assert by_len["capped share"].iloc[0] > 0.5 > by_len["capped share"].iloc[2], (
    "text: short segments reach the cap"
)
assert above.sparc_capped.all(), "text: only capped bands above"
assert round(n_values) == 5, "text: about 5 independent values"
assert sel.n.median() == 15 and 0.2 < sel.duration.median() < 0.3, (
    "text: median 15, a quarter of a second"
)
assert by_len.index[0] == "(0, 12]" and by_len.index[2].startswith("(16,"), (
    "text: up to about 12 samples; from about 16 samples on"
)

# %% [markdown]
# Most of the shortest segments, up to about 12 samples, have their band ended by the cap; from about 16
# samples on, few do. The few trials above the dashed line all have capped bands. The selected trials
# run from 10 to 28 samples, median 15: a quarter of a second, about five independent spectral values
# below 20 Hz.

# %% [markdown]
# (sparc-on-segments)=
# ### What SPARC measures on these segments
#
# Because the data are synthetic, the generator's ground truth says which trials have a corrective
# submovement, the intermittency SPARC is meant to detect. Three
# other properties of a segment may drive SPARC as well: its duration (length), how much of the bell the
# contact cuts off (the *contact ratio*, contact speed divided by PV: 1 means contact at peak speed) and
# PV. The table gives the share of SPARC's variance across the selected trials that each explains alone
# and all together (linear least squares, [`skilllib.prototypes.variance_explained`](#skilllib.prototypes.variance_explained)), with the book's 20 Hz
# and, for comparison, with 10 Hz:

# %%
feats10 = sk.trial_features(rec, sparc_params={"fc": 10.0})
truth = synthetic.truth[["participant", "trial", "n_corrections"]]
held = ["log_duration", "contact_ratio"]
PARTIAL = "partial r(SPARC, corrected | duration, contact ratio)"


def with_truth(f):
    """The selected trials with covariates and the generator's corrections (0/1)."""
    out = sk.with_covariates(sk.select(f)).merge(truth, on=["participant", "trial"])
    return out.assign(corrected=(out.n_corrections > 0).astype(float))


what = {}
for label, f in {"fc = 20 Hz": feats, "fc = 10 Hz": feats10}.items():
    d = with_truth(f)
    r2 = sk.variance_explained(d, "sparc", [*held, "pv", "corrected"])
    what[label] = {
        **{f"R² {c}": v for c, v in r2.items()},
        PARTIAL: sk.partial_correlation(d, "sparc", "corrected", held),
        "AUC of -SPARC for corrected trials": roc_auc_score(d.corrected, -d.sparc),
    }
what = pd.DataFrame(what)
d20 = with_truth(feats)
ratio = d20.groupby("corrected").contact_ratio.median()
print(
    f"{int(d20.corrected.sum())} of {len(d20)} selected trials have a corrective "
    f"submovement;\ncontact ratio: corrected {ratio[1.0]:.2f}, "
    f"uncorrected {ratio[0.0]:.2f} (medians)"
)
what.round(3)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
w20, w10 = what["fc = 20 Hz"], what["fc = 10 Hz"]
alone = [c for c in what.index if c.startswith("R²") and c != "R² all"]
assert w20["R² contact_ratio"] == w20[alone].max(), "text: at 20 Hz the contact ratio"
assert w10["R² log_duration"] == w10[alone].max(), "text: at 10 Hz the duration"
assert w20["R² corrected"] < 0.01 and w10["R² corrected"] < 0.01, (
    "text: corrections alone explain almost nothing"
)
assert w20["AUC of -SPARC for corrected trials"] < 0.5, (
    "text: corrected trials even score a little higher SPARC"
)
assert w20[PARTIAL] < -0.35, "text: held fixed, corrections lower SPARC"
assert w20[PARTIAL] < 1.5 * w10[PARTIAL], "text: more clearly at 20 Hz than at 10 Hz"
assert ratio[1.0] < ratio[0.0], (
    "text: corrected trials touch at a lower share of their peak speed"
)

# %% [markdown]
# On its own, SPARC does not tell corrected from uncorrected trials here: the corrections explain almost
# none of its variance, and a corrected trial is, if anything, a little *more* likely to score a higher
# SPARC (an area under the ROC curve below 0.5). With 20 Hz, the contact ratio explains most of SPARC; with
# 10 Hz the duration does, as chapter 2 predicted. The corrections are hidden behind the contact ratio:
# a corrected approach ends on the slow flank of a short corrective submovement and touches at a smaller
# share of its peak speed, which alone raises its SPARC. Hold the duration and the contact
# ratio fixed (the partial correlation) and corrections do lower SPARC, more clearly with 20 Hz than with
# 10 Hz. So on these segments a low SPARC means first an abrupt end at contact, then a long segment, and
# only then an intermittent movement. Whether the paper's recordings behave the same cannot be checked:
# they are not public. Any 60 Hz recording with segments this short faces the same limits.
#
# This is how the rest of the book reads SPARC. Where a cluster, a prototype or an execution has a
# higher or lower SPARC, the chapters say what changed (a dip and a second rise, the contact ratio, where
# the band ends) instead of calling it smoother or less smooth. Chapter 7 asks what SPARC's reading does
# to the clusters, offers a SPARC adjusted for duration and contact ratio, and measures other candidates
# against the generator's corrections ([](#corrections-measure)); chapter 16 shows that the contact
# ratio outweighs the corrections in every draw of the model, and chapter 17 how much SPARC moves with
# the sampling instants alone.

# %% [markdown]
# ## The selection
#
# The paper keeps the trials with $0.3 \le$ contact speed $\le 0.7$ m/s: 650 of its 1500. The synthetic
# cohort has 680 such trials by the book's estimate of the contact speed, the last sample before contact
# (618 by the true contact speed; [](#contact-speed-60hz) says what the count depends on); none of its
# trials is invalid. Every trial stays in the feature table with
# its status: `selected`, `excluded` with the reason (the first excluded trial's is "contact speed
# 1.200 m/s above 0.7 m/s"), or `invalid`.

# %%
counts = sk.status_counts(feats)
first_excluded = feats.loc[feats.status == "excluded", "reason"].iloc[0]
print(f"first excluded trial: {first_excluded}")
counts.T

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert counts.loc["all", "selected"] == 680, "text: 680 selected"
assert counts.loc["all", "invalid"] == 0, "text: none invalid"
assert counts_by["true contact speed"] == 618, "text: 618 by the true contact speed"
assert sk.CONTACT_WINDOW == (0.3, 0.7), "text: 0.3 to 0.7 m/s"
assert first_excluded == "contact speed 1.200 m/s above 0.7 m/s", "text: the example"

# %%
#| label: fig-contact-speeds
#| caption: Synthetic cohort. Contact speeds of all valid trials; the selection window 0.3-0.7 m/s shaded.
fig = skf.plot_contact_speeds(feats)

# %% [markdown]
# ## The feature table
#
# The clustering chapter starts from this table: one row per trial, with the status and reason, PV (m/s),
# contact speed (m/s), duration (s), SPARC with the last frequency of its band (Hz) and whether the cap
# ended it, LDLJ, the segment length and the onset and contact time stamps (s). Its selected rows are
# the (PV, SPARC) tuples of [](#fig-feature-space). The clustering chapter gets the table, its
# selection, the clustering and the prototypes' segments in one call, `sk.analyse(path)`, which chains
# `sk.read_recordings`, `sk.trial_features` and `sk.select` as this chapter did step by step;
# `sk.segment(recordings, participant, trial)` returns one trial's segmented positions, velocities and
# speeds for the transfer chapter.

# %%
feats.head(8)

# %%
sel[["pv", "contact_speed", "duration", "sparc", "ldlj"]].describe()

# %%
#| label: fig-feature-space
#| caption: Synthetic cohort. Peak speed PV against SPARC; selected trials coloured by participant, excluded trials grey; ringed, trials whose SPARC band the cut-off fc = 20 Hz ended; dashed, the highest SPARC a band ended by the threshold can have. The selected tuples are the input of the clustering chapter.
fig = skf.plot_feature_space(feats)

# %% [markdown]
# ## Summary
#
# - The book's data are synthetic. A seeded model of minimum-jerk submovements (a primary one, often
#   with a corrective one) produces 10 x 150 approaches that end at a surface with non-zero speed,
#   sampled at 60 Hz like the Phantom. It reproduces the paper's published aggregates: the selected
#   count, large differences between participants, valid clusterings for k = 2..16 and centres spread
#   in PV at k = 6. Its average silhouette at k = 6 is higher than the paper's 0.337 on average over
#   seeds; the committed seed meets the 0.30–0.38 target by the seed rule. Clustered raw, the cloud is
#   cut mainly along PV, which spreads about three times more than SPARC.
# - Recordings live in one open CSV format. `read_recordings` rejects broken files with the file, line
#   and column, and marks broken trials `invalid` with a reason instead of dropping them.
# - Features come from positions differentiated up to contact. Onset is at 0.05 m/s and contact at the
#   first contact sample, and the segment runs from onset to the last sample before contact. Every trial
#   keeps a status and a reason; the selected trials go on to the clustering chapter.
# - The contact speed, the speed at the last sample before contact, is up to 16.7 ms early: its error
#   against the generator's truth has an SD of about 0.08 m/s and reaches 0.45 m/s, and 12 % of the
#   trials would change side of the selection window with the true contact speed. In 11 % of the
#   selected trials the peak speed is the contact speed. A cubic fitted to the last four positions and
#   evaluated where it reaches the surface (`contact_estimator="crossing"`) is better on every measure
#   in this draw, but not close to the truth either; the default stays the last sample. The count in
#   the window ranges from 577 to 680 trials with the estimator and the sampling rate (truth 618), so
#   the paper's 650 is not a number the book can match more closely than that.
# - The segments are short: 10 to 28 samples for the selected trials. The shortest reach SPARC's cap
#   even at 20 Hz (flagged `sparc_capped`). On these segments SPARC ranks trials mainly by how abruptly
#   the contact ends them and by their length; the generator's corrective submovements lower SPARC only
#   once those two are held fixed. Chapter 7 takes this into account.
