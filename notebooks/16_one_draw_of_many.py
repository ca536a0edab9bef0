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
#   enumerator: "16.%s"
# ---
# # One draw of many
#
# Every number of the book so far comes from one draw of the generative model: the cohort of one
# seed. This chapter runs the book's headline analysis on 24 draws of the same model and places the
# book's draw among them: which results hold in every draw, which vary from draw to draw, and
# whether the paper's published numbers lie within the model's spread.
#
# ```{note}
# The data in this chapter are synthetic: 24 draws of the book's generative model (`skilllib.cohort`),
# seeds 0 to 23 with the default parameters, the book's draw among them. The paper's recordings are
# not public. The table is computed once by `scripts/replicate_draws.py` and committed with the
# library; this chapter reads it.
# ```

# %% tags=["hide-input"] jupyter={"source_hidden": true}
import pandas as pd

import skilllib as sk
import skilllib.figures as skf

pd.set_option("display.width", 88)

draws = sk.read_replication()  # one row per seed: sk.draw_results(seed)
book = draws.loc[sk.SEED]
n_draws = len(draws)
print(
    f"{n_draws} draws, seeds {draws.index.min()} to {draws.index.max()}; "
    f"the book's draw is seed {sk.SEED}"
)

# %% [markdown]
# ## How the book's draw was chosen
#
# Chapter 3 chose the seed by a rule: the first seed whose cohort meets every calibration target
# (the selection, all $k$ valid, the silhouette at $k = 6$, separated centres, large differences
# between participants). Of the ten seeds surveyed, only seed 9 met them all. Among the 24 draws
# here it is still the only one.

# %%
survey = pd.read_csv(sk.SURVEY_CSV, index_col="seed")
meets = draws.index[draws["all_targets"]].tolist()
print(
    f"seed survey: {int(survey['all'].sum())} of {len(survey)} seeds meet every "
    f"target (seed {survey['all'].idxmax()});\n"
    f"these draws: {len(meets)} of {n_draws} (seed {meets[0]})"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert len(survey) == 10 and survey["all"].sum() == 1, "text: 'of the ten seeds, only'"
assert survey["all"].idxmax() == sk.SEED == 9, "text: 'only seed 9 met them all'"
assert meets == [sk.SEED] and n_draws == 24, (
    "text: 'among the 24 draws, still the only one'"
)

# %% [markdown]
# So the book's draw is not a typical one: it was selected because it is the only one that meets
# every target at once.
#
# ## The headline results over the draws
#
# Each row of the committed table is
# [`sk.draw_results`](#skilllib.cohort.draw_results) of one seed: the book's analysis in one call,
# each quantity computed as its chapter computes it (the selection and silhouettes of chapters 3
# and 4, the cut-off comparison of chapter 6, the participants of chapter 7, what SPARC tracks from
# chapter 3, the verdicts per arm of chapters 5 and 9, with the limits those chapters assume). The
# table gives each quantity's median, its 10th and 90th percentiles and its range over the draws,
# the book's value and its rank among the draws (1 = lowest; tied draws share the mean rank). The
# table also holds, per draw, the contact speed's estimators against the truth; chapter 3 reads those
# ([](#contact-speed-60hz)).

# %%
summary = sk.replication_summary(draws)
contact = [q for q in summary.index if q.startswith(("contact_", "in_window_"))]
columns = ["median", "p10", "p90", "min", "max", "book", "rank"]
shown = summary.drop(index=contact)[columns]
shown.rename(index=sk.DRAW_QUANTITIES).round(3)

# %% [markdown]
# [](#fig-draws) shows the same draws, each quantity on its own scale: standard deviations from the
# draws' mean.

# %%
#| label: fig-draws
#| caption: "Synthetic cohort. The book's headline quantities over 24 draws of the generative model (grey dots, one per seed), each in standard deviations from the draws' mean; the book's draw (seed 9) red, the paper's silhouette at k = 6 a black cross. Right: the range over the draws and the book's value in the quantity's unit (PV in m/s). A quantity equal in every draw sits at 0."
FIGURE = [
    "n_selected",
    "n_valid_k",
    "silhouette_k6",
    "centre_pv_1",
    "centre_pv_6",
    "ari_fc10",
    "capped_fraction",
    "nmi_participants",
    "r2_contact_ratio",
    "r2_corrections",
    *[c for c in draws.columns if c.startswith("feasible")],
]
fig = skf.plot_draws(draws, columns=FIGURE, paper={"silhouette_k6": 0.337})

# %% [markdown]
# ## The paper against the book and the draws
#
# The paper publishes three numbers the model can be held to. The table sets each beside the book's
# draw and the draws' median and range, and says whether the paper's value lies within the range of
# the draws (`sds`: how many of the draws' standard deviations it lies from their mean;
# [`sk.within_draws`](#skilllib.cohort.within_draws)).

# %%
PAPER = {"n_selected": 650, "n_valid_k": 15, "silhouette_k6": 0.337}
paper = sk.within_draws(draws, PAPER)
paper.rename(index=sk.DRAW_QUANTITIES).round(3)

# %%
sil = summary.loc["silhouette_k6"]
sil_sds = abs(paper.at["silhouette_k6", "sds"])
all_k = int((draws["n_valid_k"] == 15).sum())
print(
    f"silhouette at k = 6: paper 0.337 is {sil_sds:.1f} SD "
    f"below the draws' mean {sil['mean']:.3f};\n"
    f"the draws range from {sil['min']:.3f} to {sil['max']:.3f}; the book's "
    f"{sil['book']:.3f} ranks {sil['rank']:.0f} of {n_draws}"
)
print(
    f"all 15 k valid in {all_k} of {n_draws} draws; "
    f"fewest valid: {int(draws['n_valid_k'].min())}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert paper.at["n_selected", "within"], "text: '650 lies within the draws'"
assert paper.at["n_valid_k", "within"], "text: '15 valid k lies within the draws'"
assert not paper.at["silhouette_k6", "within"], "text: '0.337 lies below every draw'"
assert 0.337 < sil["min"], "text: 'below every draw'"
assert round(sil_sds, 1) == 2.8, "text: 'about 2.8 SD below'"
assert sil["rank"] == 3 and sil["book"] < sil["median"], (
    "text: 'the book's silhouette is the third lowest of the draws'"
)
assert all_k == 21 and draws["n_valid_k"].min() == 7, "text: '21 of 24; as few as 7'"

# %% [markdown]
# The paper's 650 selected trials and its 15 valid $k$ lie within the draws. Its silhouette of
# 0.337 does not: every draw separates its six clusters better, and 0.337 lies about 2.8 standard
# deviations below the draws' mean. The book's 0.369, beside which chapter 3 sets the paper's
# 0.337, is the third lowest of the 24: the calibration rule picked a draw from the low end. All 15
# values of $k$ are valid in 21 of the 24 draws; in one only 7 are. That the paper's silhouette lies
# outside the model's spread says the model's clusters are better separated than the paper reports,
# whichever draw is taken; neither the book's value nor the paper's is more than one draw. The paper's 650 of 1500
# and 0.337 are themselves one draw of ten people, with no spread published.

# %% [markdown]
# ## What holds in every draw, and what varies
#
# The counts below are read off the table.

# %%
r2c, r2k = summary.loc["r2_contact_ratio"], summary.loc["r2_corrections"]
ari, nmi = summary.loc["ari_fc10"], summary.loc["nmi_participants"]
cap = summary.loc["capped_fraction"]
sparc_cols = [f"centre_sparc_{i}" for i in range(1, 7)]
rising = int((draws[sparc_cols].diff(axis=1).iloc[:, 1:] > 0).all(axis=1).sum())
high_ari = int((draws["ari_fc10"] >= 0.75).sum())
lowest_2 = int((draws[sparc_cols].idxmin(axis=1) == "centre_sparc_2").sum())
print(
    f"R² of SPARC, contact ratio alone: {r2c['min']:.2f} to {r2c['max']:.2f}; "
    f"corrections alone: at most {r2k['max']:.2f}"
)
print(f"share of bands the 20 Hz cap ends: {cap['min']:.2f} to {cap['max']:.2f}")
print(f"NMI(cluster, participant): {nmi['min']:.2f} to {nmi['max']:.2f}")
print(
    f"ARI fc 10 vs 20 Hz: median {ari['median']:.2f}, {ari['min']:.2f} to "
    f"{ari['max']:.2f};\n  the book's {ari['book']:.2f} "
    f"ranks {ari['rank']:.0f} of {n_draws}; 0.75 or more in {high_ari} draws"
)
print(
    f"the centres' SPARC rises with their PV in {rising} of {n_draws} draws "
    f"(the book's: {bool((book[sparc_cols].diff().iloc[1:] > 0).all())});\n"
    f"the second slowest centre has the lowest SPARC in {lowest_2} of {n_draws}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert (draws["r2_contact_ratio"] > 10 * draws["r2_corrections"]).all(), (
    "text: 'in every draw the contact ratio explains ten times more'"
)
assert round(r2c["min"], 2) == 0.39 and round(r2c["max"], 2) == 0.57, (
    "text: 0.39 to 0.57"
)
assert round(r2k["max"], 2) == 0.04, "text: 'at most 0.04'"
assert round(cap["min"], 2) == 0.10 and round(cap["max"], 2) == 0.21, "text: 0.10-0.21"
assert round(nmi["min"], 2) == 0.22 and round(nmi["max"], 2) == 0.40, "text: 0.22-0.40"
assert round(ari["median"], 2) == 0.62, "text: 'median 0.62'"
assert round(ari["min"], 2) == 0.42 and round(ari["max"], 2) == 0.86, (
    "text: 0.42 to 0.86"
)
assert high_ari == 3, "text: 'about 0.8 not for most draws (0.75 or more in 3)'"
assert ari["rank"] == 22 and round(ari["book"], 2) == 0.83, (
    "text: 'book 0.83, 22nd of 24'"
)
assert rising == 5 and (book[sparc_cols].diff().iloc[1:] > 0).all(), (
    "text: 'rises with PV in the book's draw, in 5 of 24'"
)
assert lowest_2 == 13, (
    "text: 'in 13 of the 24 the second slowest centre has the lowest'"
)
assert nmi["min"] > 0.2 and cap["max"] < 0.5, "text: 'tied to participants; a minority'"

# %% [markdown]
# **Holds in every draw.** What chapter 3 found SPARC to track on these segments: in every draw the
# contact ratio alone explains 0.39 to 0.57 of SPARC's variance across the selected trials and the
# corrective submovements alone at most 0.04, more than ten times less. The 20 Hz cap ends between
# 0.10 and 0.21 of the selected trials' bands, a minority, and the clusters are tied to the
# participants in every draw (NMI 0.22 to 0.40).
#
# **Varies.** How far the partition survives SPARC's cut-off at 10 Hz instead of 20 Hz: the
# adjusted Rand index spans 0.42 to 0.86 (median 0.62), and the book's 0.83 is the 22nd of 24;
# chapter 6's "adjusted Rand index about 0.8" holds for the book's draw, not for most draws (0.75
# or more in 3 of the 24). The order of the centres: in the book's draw the centres' SPARC rises
# with their PV, in only 5 of the 24 draws does it; in the others a faster centre has a lower SPARC
# than a slower one, and in 13 of the 24 the second slowest centre has the lowest SPARC of all six.
# A reading of the clusters as "the faster, the higher SPARC" rests on the draw.

# %% [markdown]
# ## The robot verdicts
#
# Each draw has its own six prototypes, and each arm its verdict on them (chapter 5: the velocity
# limits alone, the paper's question; chapter 9: every limit the arm carries, with the book's
# assumed acceleration limits). How many of the six each arm executes as recorded:

# %%
verdicts = summary.loc[[c for c in draws.columns if c.startswith("feasible")]]
verdicts = verdicts[["median", "min", "max", "book", "rank"]]
no_ur5 = int((draws["feasible_ur5"] == 0).sum())
fewer = {
    arm: int((draws[f"feasible_{arm}"] <= draws[f"feasible_velocity_{arm}"] - k).sum())
    for arm, k in [("simple6", 2), ("ur5", 2), ("panda", 1)]
}
print(f"UR5, every limit: none of the six in {no_ur5} of {n_draws} draws")
print(
    "draws where every limit leaves at least two fewer than the velocity limits:\n"
    f"  Simple6 {fewer['simple6']}, UR5 {fewer['ur5']}; at least one fewer: "
    f"Panda {fewer['panda']}"
)
verdicts.rename(index=sk.DRAW_QUANTITIES)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
v = verdicts
assert (
    v.loc[["feasible_velocity_simple6", "feasible_velocity_puma560"], "min"].eq(6).all()
), "text: 'Simple6 and the Puma 560 execute all six in every draw'"
assert (v.at["feasible_velocity_ur5", "min"], v.at["feasible_velocity_ur5", "max"]) == (
    4,
    6,
), "text: 'the UR5 four to six'"
assert (
    v.at["feasible_velocity_panda", "min"],
    v.at["feasible_velocity_panda", "max"],
) == (3, 5)
assert (
    v.at["feasible_velocity_panda", "book"]
    == 3
    < v.at["feasible_velocity_panda", "median"]
), "text: 'Panda three to five; the book's three is below the median four'"
assert no_ur5 == 23, "text: 'the UR5 none in 23 of 24'"
assert v.at["feasible_puma560", "min"] == 4 and v.at["feasible_puma560", "book"] == 6, (
    "text: 'the Puma 560 four to six; the book's six'"
)
assert v.at["feasible_simple6", "max"] == 2 == v.at["feasible_simple6", "book"], (
    "text: 'Simple6 at most two; the book's two'"
)
assert v.at["feasible_simple6", "median"] == 1 and v.at["feasible_simple6", "min"] == 0
assert fewer["simple6"] == fewer["ur5"] == n_draws, (
    "text: 'Simple6 and the UR5: at least two fewer in every draw'"
)
assert fewer["panda"] == 23, "text: 'the Panda fewer in 23 of the 24'"
assert (v.at["feasible_panda", "min"], v.at["feasible_panda", "max"]) == (1, 3), (
    "text: 'the Panda one to three'"
)

# %% [markdown]
# At the velocity limits, Simple6 and the Puma 560 execute all six prototypes in every draw; the
# UR5 four to six and the Panda three to five, where the book's three is below the median of four.
# Once acceleration counts, Simple6 executes fewer in every draw (none to two; the book's two is the
# most any draw gives, the median one), the UR5 none in 23 of the 24 draws, the Puma 560 four to
# six (the book's six), the Panda one to three. The direction of chapter 9's verdict holds across
# the draws: on Simple6 and the UR5 every limit leaves at least two fewer prototypes than the
# velocity limits in every draw, on the Panda fewer in 23 of the 24. The exact counts do not. The
# acceleration limits of Simple6 and the UR5 are the book's assumption, the same in every draw: the
# draws say nothing about them.

# %% [markdown]
# ## Another draw in one call
#
# [`sk.draw_results`](#skilllib.cohort.draw_results) runs the whole analysis on any draw: the
# generator, the CSV rounding, features, selection, the silhouette sweep, the cut-off comparison, the
# participants, the covariates and the four arms. Here seed 21, the draw with the fewest valid $k$;
# it gives its row of the table.

# %%
other = sk.draw_results(21)
print(
    f"seed 21: {other['n_selected']} selected, {other['n_valid_k']} valid k, "
    f"silhouette at k = 6 {other['silhouette_k6']:.3f}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
row = draws.loc[21]
assert all(abs(float(other[c]) - float(row[c])) < 1e-9 for c in sk.DRAW_QUANTITIES), (
    "text: 'it gives its row of the table'"
)
assert other["n_valid_k"] == draws["n_valid_k"].min(), "text: 'the fewest valid k'"

# %% [markdown]
# ## Summary
#
# - The book's draw (seed 9) was selected as the only one of ten seeds meeting every calibration
#   target; it is still the only one of 24 draws that does.
# - The paper's 650 selected trials and 15 valid $k$ lie within the model's spread; its silhouette
#   of 0.337 lies below every draw, about 2.8 standard deviations from their mean. The book's 0.369
#   is from the low end of the draws.
# - In every draw SPARC tracks the contact ratio far more than the corrections, the 20 Hz cap ends
#   a minority of bands, and the clusters are tied to the participants.
# - The cut-off's effect on the partition and the order of the centres' SPARC vary between draws;
#   the book's draw lies at the end of both that looks most stable and most orderly (a high ARI,
#   SPARC rising with PV).
# - The velocity verdicts of Simple6 and the Puma 560 hold in every draw; the UR5's and the Panda's
#   counts vary over a range of two; once the assumed acceleration limits count, Simple6 and the UR5
#   execute at least two fewer prototypes in every draw.
# - Both the paper's numbers and the book's are single draws: the paper's of one experiment, the
#   book's of one seed of a model calibrated to that experiment.
