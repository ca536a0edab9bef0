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
#   enumerator: "1.%s"
# ---
# # SPARC from first principles
#
# The paper describes the skill of every demonstration by one number, the spectral arc length SPARC of
# its speed profile [@balasubramanian2015]. This chapter builds that number from scratch: why
# intermittent movements are less smooth, how the Fourier spectrum of a speed profile reveals it, why
# the *length* of that spectrum's curve measures it, and how the integral of the definition becomes the
# sum that the code computes, checked against the authors' code and their published values. It ends
# with the squared integrand that the KI 2020 paper prints, and why it cannot be meant. Chapter 2 then
# tries the measure on the kinds of movement the experiment produces (60 Hz samples, a contact that
# ends every trial at non-zero speed, noise) and chooses the parameters the rest of the book uses.
#
# ```{note}
# Every speed profile in this chapter is synthetic, generated here from minimum-jerk submovements (and,
# where said, noise); this chapter does not use the book's cohort. Every number the text states is
# checked by a hidden cell of the notebook, so the book does not build when a statement stops being
# true.
# ```

# %% tags=["hide-input"] jupyter={"source_hidden": true}
import functools

import numpy as np
import pandas as pd

import skilllib as sk
import skilllib.figures as skf

pd.set_option("display.width", 88)
FS = 60.0  # Hz, the sampling rate of the experiment
# speed (m/s) of 0.6 s, 0.1 m minimum-jerk submovements starting at the given onsets (s)
movement = functools.partial(sk.minimum_jerk_submovements, fs=FS, T=0.6, D=0.1)

# %% [markdown]
# ## Smooth movements and intermittency
#
# Point-to-point arm movements of healthy people have bell-shaped speed profiles, across speeds and
# loads [the paper's related work: @nelson1983; @nagasaki1989; @schaal2002]: one peak, no hesitation.
# Smoothness has been seen as the organising principle of motion [@hogan1984] and as a mark of skill
# [@nagasaki1989]. In sensorimotor control a smooth movement is a *continual*, non-intermittent one
# [@balasubramanian2015]: poor planning, poor execution or an unfamiliar task break a movement
# into submovements, and the speed dips between them.
#
# A convenient model of one smooth submovement is the minimum-jerk profile [@flash1985]: a
# movement of amplitude $D$ (m) and duration $T$ (s) has speed
# $v(t) = \frac{D}{T}\, 30\, \tau^2 (1-\tau)^2$, $\tau = t/T \in [0, 1]$, with its peak $1.875\,D/T$ at
# mid-time. Intermittency is a sum of such submovements, each starting before the previous one ends
# ([`skilllib.minimum_jerk_submovements`](#skilllib.smoothness.minimum_jerk_submovements)).

# %%
#| label: fig-submovements
#| caption: One minimum-jerk submovement (0.6 s, 0.1 m) and the same submovement followed by a second one 0.3 s or 0.5 s later, sampled at 60 Hz. The further apart, the deeper the dip between them.
one = movement([0.0])
profiles = {
    "one submovement": one,
    "two, 0.3 s apart": movement([0, 0.3]),
    "two, 0.5 s apart": movement([0, 0.5]),
}
fig = skf.plot_speed_profiles(profiles, FS)
print(
    f"peak speed of one submovement: {one.max():.3f} m/s "
    f"(1.875 D/T = {1.875 * 0.1 / 0.6:.3f})"
)
dips = {label: sk.speed_dip(v) for label, v in list(profiles.items())[1:]}
for label, d in dips.items():
    print(f"{label}: lowest speed between the two peaks {d:.3f} m/s")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert abs(one.max() - 1.875 * 0.1 / 0.6) < 0.002, (
    "text: peak 1.875 D/T (to the sampling)"
)
assert dips["two, 0.5 s apart"] < dips["two, 0.3 s apart"], (
    "caption: further, deeper dip"
)

# %% [markdown]
# A measure of smoothness should rank the three movements of [](#fig-submovements), and it should not
# care how far or how fast the hand went: only the *shape* of the profile matters.

# %% [markdown]
# ## From the speed profile to its spectrum
#
# The Fourier magnitude spectrum of the speed profile is
#
# $$
# V(\omega) = \left| \int_0^{T} v(t)\, e^{-j\omega t}\, dt \right|, \qquad
# \hat V(\omega) = \frac{V(\omega)}{V(0)} .
# $$ (eq-spectrum)
#
# Because a speed is never negative, $V(0) = \int_0^T v\,dt$ is the distance travelled and no other
# frequency can exceed it ($|\int v e^{-j\omega t}dt| \le \int v\,dt$): the normalised spectrum
# $\hat V$ starts at 1 and stays below. Dividing by $V(0)$ removes the amplitude. A smooth bell has a
# spectrum that falls from 1 to almost 0 within a few hertz and stays there.
#
# The computer sees $N$ samples $v_n = v(n/f_s)$, so it takes the discrete Fourier transform (FFT) at
# the frequencies $f_k = k f_s / n_{\mathrm{fft}}$, after appending zeros to the $N$ samples up to
# $n_{\mathrm{fft}} = 2^{\lceil \log_2 N \rceil + 4}$ ("padlevel" 4, the authors' convention; chapter 2
# shows why the padding matters, [](#fig-padding)).
# [`sparc_spectrum`](#skilllib.smoothness.sparc_spectrum) returns that spectrum with everything SPARC
# reads from it.

# %%
s = sk.sparc_spectrum(one, FS)
print(
    f"N = {one.size} samples, nfft = {s.nfft}, grid step fs/nfft = {FS / s.nfft:.4f} Hz"
)
print(f"(fs/N = {FS / one.size:.2f} Hz without padding)")
print(
    f"V^(0) = {s.Mf[0]:.3f}, largest V^ = {s.Mf.max():.3f}, "
    f"V^ at 2 Hz = {np.interp(2, s.f, s.Mf):.4f}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert s.Mf[0] == s.Mf.max() == 1.0, (
    "text: the normalised spectrum starts at 1, stays below"
)
assert s.nfft == 2 ** (int(np.ceil(np.log2(one.size))) + 4), (
    "text: nfft with padlevel 4"
)

# %% [markdown]
# ## Why the arc length measures intermittency
#
# Take two identical submovements $v_1$, the second one $\Delta$ seconds after the first. Shifting a
# signal by $\Delta$ multiplies its transform by $e^{-j\omega\Delta}$, so
#
# $$
# V(\omega) = V_1(\omega)\,\left|1 + e^{-j\omega\Delta}\right| = 2 V_1(\omega)\left|\cos\frac{\omega\Delta}{2}\right|,
# \qquad \hat V(\omega) = \hat V_1(\omega) \left|\cos \pi f \Delta\right| .
# $$ (eq-two)
#
# The smooth spectrum of one submovement is now modulated by a ripple with a zero every $1/\Delta$ Hz.
# The further apart the submovements, the faster the ripple, and every ripple adds length to the curve
# $\hat V(f)$. The spectrum of a single bell falls monotonically, the short way down from 1 to 0; each
# hesitation adds bumps. The
# *length of the curve* of the normalised spectrum therefore measures intermittency: that is SPARC, with
# a minus sign so that smoother is larger ([](#fig-arc)).

# %%
#| label: fig-arc
#| caption: "Left: the three movements of the previous figure. Right: their normalised magnitude spectra; the thick part is the band whose arc length SPARC measures, the dot its adaptive cut-off. The second submovement adds a ripple with zeros every 1/Δ Hz and lengthens the curve."
skf.plot_speeds_and_spectra(profiles, FS, fmax=8)
values = {label: sk.sparc(v, FS) for label, v in profiles.items()}
for label, value in values.items():
    print(f"{label:18s} SPARC = {value:.3f}")
for delta in (0.3, 0.5):
    print(f"ripple period 1/Δ for Δ = {delta} s: {1 / delta:.1f} Hz")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
v1, v2, v3 = values.values()
assert v1 > v2 > v3, "text: each further separation lengthens the arc (ranks the three)"

# %% [markdown]
# ## Where the arc stops: the adaptive cut-off
#
# Beyond a few hertz a real spectrum holds only measurement noise. Its curve wiggles endlessly, and an
# arc length taken over all frequencies would measure the noise. SPARC therefore stops the arc at an
# adaptive cut-off $\omega_c$: the last frequency at which $\hat V$ still reaches an amplitude threshold
# $\bar V$ (`amp_th`), but never beyond a maximum $\omega_c^{\max}$ (`fc`):
#
# $$
# \omega_c = \min\left\{ \omega_c^{\max},\; \min\{\omega : \hat V(r) < \bar V \;\; \forall\, r > \omega\} \right\}.
# $$ (eq-cutoff)
#
# The threshold adapts the band to the movement: a slow movement has its energy at low frequencies and
# a short band, a fast one a longer band. The maximum protects the arc from noise that stays above the
# threshold. The book uses $\bar V$ = 0.05 and $\omega_c^{\max} / 2\pi = f_c$ = 20 Hz
# (`SPARC_PARAMS`; chapter 2 shows how the choice of $f_c$ matters on short segments).
# [](#fig-cutoff) shows the same movement with speed noise of 1 % and of 20 % of its peak speed
# ([`skilllib.noisy_copies`](#skilllib.smoothness.noisy_copies)).

# %%
#| label: fig-cutoff
#| caption: "One submovement without noise and with Gaussian speed noise of 1 % and 20 % of its peak speed. The 1 % noise floor stays far below the threshold (dashed) and changes nothing; at 20 % noise bumps reach the threshold and the band runs on to the last of them (dot), but never beyond fc (dotted)."
rng = np.random.default_rng(1)
noisy = {"no noise": one}
for level in (0.01, 0.20):
    noisy[f"noise {level:.0%} of peak"] = sk.noisy_copies(one, level, rng=rng)
skf.plot_speeds_and_spectra(noisy, FS, fmax=15)
noisy_spectra = {label: sk.sparc_spectrum(v, FS) for label, v in noisy.items()}
for label, s in noisy_spectra.items():
    print(f"{label:20s} cut-off {s.cutoff:5.2f} Hz   SPARC {s.sparc:.3f}")
print(f"parameters: {dict(sk.SPARC_PARAMS)}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
clean_, small, large = noisy_spectra.values()
assert small.cutoff == clean_.cutoff, "caption: 1 % changes nothing"
assert abs(small.sparc - clean_.sparc) < 1e-3, "caption: 1 % changes nothing"
fc_max = sk.SPARC_PARAMS["fc"]
assert clean_.cutoff < large.cutoff <= fc_max, "caption: 20 % runs on, never beyond fc"
assert sk.SPARC_PARAMS["fc"] == 20.0 and sk.SPARC_PARAMS["amp_th"] == 0.05, (
    "text: the book uses amp_th 0.05 and fc = 20 Hz"
)

# %% [markdown]
# ## From the integral to the sum the code computes
#
# The definition of @balasubramanian2015 is
#
# $$
# \mathrm{SPARC} = -\int_0^{\omega_c} \left[ \left(\frac{1}{\omega_c}\right)^2 +
# \left(\frac{d\hat V(\omega)}{d\omega}\right)^2 \right]^{1/2} d\omega .
# $$ (eq-sparc)
#
# Substitute the normalised frequency $u = \omega / \omega_c \in [0, 1]$: $d\omega = \omega_c\, du$ and
# $d\hat V / d\omega = \frac{1}{\omega_c}\, d\hat V / du$, so the $\omega_c$ cancel:
#
# $$
# \mathrm{SPARC} = -\int_0^{1} \sqrt{1 + \left(\frac{d\hat V}{du}\right)^2}\; du .
# $$ (eq-sparc-u)
#
# This is the length of the curve $u \mapsto \hat V(u)$ on $[0, 1]$. It has no unit, it does not depend
# on the amplitude (through $\hat V$) nor on the time scale (through $u$), and since
# $\sqrt{1 + x^2} \ge 1$ it is at least 1: **SPARC $\le -1$**, with equality only for a flat spectrum,
# that of a single impulse.
#
# On the FFT grid the band is a set of $K+1$ equally spaced bins $f_0 < \dots < f_K = \omega_c / 2\pi$,
# from the first bin at or above the threshold (bin 0 for any speed) to the last one at or above it,
# $f_K \le f_c$. Their
# normalised frequencies are $u_k = (f_k - f_0)/(f_K - f_0) = k/K$, and the length of the polygon
# through the points $(u_k, \hat V_k)$ approximates [](#eq-sparc-u):
#
# $$
# \mathrm{SPARC} \approx -\sum_{k=0}^{K-1} \sqrt{(u_{k+1} - u_k)^2 + (\hat V_{k+1} - \hat V_k)^2}
# = -\sum_{k=0}^{K-1} \sqrt{\frac{1}{K^2} + (\hat V_{k+1} - \hat V_k)^2} .
# $$ (eq-sparc-sum)
#
# This is what the authors' code computes, and [`skilllib.sparc`](#skilllib.smoothness.sparc) with it (the test suite checks the two
# against each other to $10^{-9}$ on generated bells, overlapping submovements, noisy and truncated
# profiles and single samples, with other parameters and sampling rates). Here it is by hand on one trial
# like those of the experiment: a 1 s minimum-jerk movement cut at contact at 0.8 s, at 60 Hz.

# %%
# contact at 80 % of the movement's duration
trial = sk.minimum_jerk_speed(np.arange(0, 0.8, 1 / FS), 0, 1.0, 0.2)
N = trial.size
n_fft = 2 ** (int(np.ceil(np.log2(N))) + sk.SPARC_PARAMS["padlevel"])
f = np.arange(n_fft) * FS / n_fft  # Hz
V_hat = np.abs(np.fft.fft(trial, n_fft))
V_hat = V_hat / V_hat.max()
print(
    f"1. N = {N} samples, nfft = 2^(ceil(log2 {N}) + 4) = {n_fft}, "
    f"grid step {FS / n_fft:.4f} Hz"
)
fc = sk.SPARC_PARAMS["fc"]
print(f"2. V^(0) = {V_hat[0]:.3f}; bins with f <= fc = {fc:g} Hz: {np.sum(f <= fc)}")

# %%
low = V_hat[f <= fc]
above = np.flatnonzero(low >= sk.SPARC_PARAMS["amp_th"])
K = above[-1] - above[0]
band = low[above[0] : above[-1] + 1]
print(
    f"3. band: bins {above[0]} to {above[-1]}, K = {K} intervals, "
    f"cut-off f_K = {f[above[-1]]:.3f} Hz"
)
terms = np.sqrt(1 / K**2 + np.diff(band) ** 2)
by_hand = -terms.sum()
print(
    f"4. sum of the K terms: {terms.sum():.6f}; "
    f"the horizontal parts alone: {K * (1 / K):.1f}"
)
print(f"5. SPARC by hand {by_hand:.12f}\n   skilllib.sparc {sk.sparc(trial, FS):.12f}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert abs(by_hand - sk.sparc(trial, FS)) < 1e-12, (
    "text: the sum by hand is skilllib's value"
)

# %% [markdown]
# The horizontal steps $1/K$ add up to exactly 1: that is the $-1$ every SPARC starts from. Everything
# below $-1$ comes from the vertical changes of the spectrum. Evaluating [](#eq-sparc) itself, as a
# Riemann sum in physical units (rad/s), gives the same number, because the substitution is exact:

# %%
w = 2 * np.pi * f[above[0] : above[-1] + 1]  # rad/s
integrand = np.sqrt((1 / w[-1]) ** 2 + (np.diff(band) / np.diff(w)) ** 2)
riemann = -np.sum(integrand * np.diff(w))
print(f"Riemann sum of the definition, in rad/s: {riemann:.12f}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert abs(riemann - sk.sparc(trial, FS)) < 1e-12, "text: the same number"

# %% [markdown]
# Two limiting cases follow from the sum. A single sample is an impulse: its spectrum is flat, every
# vertical step is zero and SPARC is exactly $-1$. And if the grid step $f_s / n_{\mathrm{fft}}$ were
# larger than $f_c$, the band would be bin 0 alone, $K = 0$, and the sum empty: the authors' code then
# returns 0, and `skilllib` does the same. With padlevel 4 at 60 Hz the step is at most
# $60/16$ Hz, below $f_c$, so this cannot happen in this book.

# %%
single_60, single_1000 = sk.sparc([0.3], FS), sk.sparc([0.3], 1000.0)
largest_step = FS / sk.nfft(1)  # Hz
print(f"one sample at 60 Hz: SPARC = {single_60:.12f}")
print(f"largest grid step at 60 Hz (N = 1): {largest_step:.2f} Hz")
print(
    f"one sample at 1000 Hz (step {1000 / sk.nfft(1):.1f} Hz > fc): "
    f"SPARC = {single_1000:g}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert single_60 == -1.0 and single_1000 == 0.0, (
    "text: exactly -1; 0 for a one-bin band"
)
assert largest_step == 60 / 16 < sk.SPARC_PARAMS["fc"], (
    "text: step at most 60/16 Hz, below fc"
)

# %% [markdown]
# ## The minimum-jerk reference
#
# A single minimum-jerk movement is the usual reference of smoothness: the profile that minimises the
# squared jerk of a point-to-point movement. It is not SPARC's maximum: two submovements that still
# overlap score a little higher (next section). Its SPARC is about $-1.40$ whatever its duration and
# sampling rate; the small differences come from where the frequency grid falls relative to the
# threshold crossing. The value for a 1 s movement at 100 Hz is
# the authors' published $-1.4058$.

# %%
durations = [0.5, 1.0, 1.5]  # s
ref = pd.DataFrame(
    {
        f"{fs:g} Hz": [
            sk.sparc(sk.minimum_jerk_speed(np.arange(0, T, 1 / fs), 0, T), fs)
            for T in durations
        ]
        for fs in (60.0, 100.0, 1000.0)
    },
    index=pd.Index(durations, name="duration T (s)"),
)
print(ref.round(4))
print(f"1 s at 100 Hz: {ref.loc[1.0, '100 Hz']:.10f}")

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert ref.to_numpy().min() > -1.41, "text: about -1.40 at any T and rate"
assert ref.to_numpy().max() < -1.39, "text: about -1.40 at any T and rate"
assert abs(ref.loc[1.0, "100 Hz"] - -1.4058293244214655) < 1e-12, (
    "text: published -1.4058"
)

# %% [markdown]
# ## Two and three submovements drifting apart
#
# Now let a second (and third) submovement start later and later. While they overlap almost entirely
# the profile is still one bell and SPARC hardly moves; once they separate, the ripples of
# [](#eq-two) appear and SPARC falls steadily, faster with three submovements than with two
# ([](#fig-drift)).

# %%
#| label: fig-drift
#| caption: SPARC of two and three minimum-jerk submovements (0.6 s, 0.1 m each) against the delay between consecutive onsets, sampled at 60 Hz.
delays = np.round(np.arange(0, 1.01, 0.05), 2)
drift = {
    "two submovements": sk.sparc_many([movement([0, d]) for d in delays], FS),
    "three submovements": sk.sparc_many([movement([0, d, 2 * d]) for d in delays], FS),
}
skf.plot_sparc_against(delays, drift, "delay between onsets (s)")
drift_table = pd.DataFrame(drift, index=pd.Index(delays, name="delay (s)"))
print(drift_table.iloc[::4].round(3))

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
two_d, three_d = drift_table["two submovements"], drift_table["three submovements"]
assert two_d[0.2] > two_d[0.0], "text: at 0.2 s a little smoother than one submovement"
apart = delays >= 0.3
assert (np.diff(two_d[apart]) < 0).all(), "text: once separated SPARC falls steadily"
assert (three_d[apart] < two_d[apart]).all(), "text: faster with three"

# %% [markdown]
# Up to a delay of 0.2 s (a third of the submovement's duration) the sum of two submovements is itself a
# smooth single-peaked profile, and SPARC rightly calls it smooth, even a little smoother than one
# submovement: it measures the shape of the speed profile, not a hidden count of submovements.

# %% [markdown]
# ## Amplitude and duration
#
# Scaling the speed by any factor scales $V(\omega)$ by the same factor and leaves $\hat V$ unchanged:
# SPARC is exactly amplitude invariant. Stretching the movement in time compresses its spectrum, which
# [](#eq-sparc-u) undoes. On the computer this holds to the sampling: the movement 2 or 4 times longer,
# sampled at the same rate, has 2 or 4 times more samples and a 2 or 4 times larger $n_{\mathrm{fft}}$,
# so its grid lines up with the original one and SPARC agrees to a few millionths; 1.5 times longer, the
# grids do not line up, and the difference grows to a few thousandths.

# %%
base = sk.sparc(one, FS)
scaled = {c: sk.sparc(c * one, FS) - base for c in (10, 0.003)}
for c, diff in scaled.items():
    print(f"amplitude x {c:g}: difference {diff:.1e}")
stretched = {}
for c in (1.5, 2, 4):
    longer = movement([0.0], T=0.6 * c)
    stretched[c] = sk.sparc(longer, FS) - base
    print(
        f"duration x {c:3g} ({longer.size:3d} samples, "
        f"nfft {sk.nfft(longer.size):5d}): "
        f"difference {stretched[c]:+.1e}"
    )

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert all(d == 0 for d in scaled.values()), "text: exactly amplitude invariant"
assert max(abs(stretched[2]), abs(stretched[4])) < 1e-5, (
    "text: 2 or 4 times, a few millionths"
)
assert 1e-3 < abs(stretched[1.5]) < 1e-2, "text: 1.5 times longer, a few thousandths"

# %% [markdown]
# ## The squared integrand printed in the KI 2020 paper
#
# Equation (1) of the KI 2020 paper prints the integrand of [](#eq-sparc) squared instead of under a
# square root:
#
# $$
# -\int_0^{\omega_c} \left[ \left(\frac{1}{\omega_c}\right)^2 + \left(\frac{d\hat V}{d\omega}\right)^2 \right]^{2} d\omega .
# $$ (eq-squared)
#
# Read literally, this is no longer an arc length and no longer dimensionless: with $\omega$ in rad/s
# the integrand has units s$^4$ and the integral s$^3$. The substitution $u = \omega/\omega_c$ leaves a
# factor $\omega_c^{-3}$, so the value scales with the cube of the duration and depends on whether
# frequency is measured in Hz or rad/s.
# [`skilllib.sparc_squared_integral`](#skilllib.smoothness.sparc_squared_integral) evaluates it as a
# Riemann sum on SPARC's band.

# %%
sq = {}
for T in (0.5, 1.0, 2.0):
    v = sk.minimum_jerk_speed(np.arange(0, T, 1 / FS), 0, T)
    sq[T] = {u: sk.sparc_squared_integral(v, FS, u) for u in ("Hz", "rad/s")}
    print(
        f"minimum jerk, T = {T} s: SPARC {sk.sparc(v, FS):.4f}, squared version "
        f"{sq[T]['Hz']:8.4f} (Hz), {sq[T]['rad/s']:9.6f} (rad/s)"
    )
ratio_T = sq[1.0]["Hz"] / sq[0.5]["Hz"]
ratio_unit = sq[1.0]["Hz"] / sq[1.0]["rad/s"]
print(
    f"ratio T = 1 s to T = 0.5 s: {ratio_T:.2f}; Hz to rad/s: {ratio_unit:.1f} "
    f"= (2 pi)^3 = {(2 * np.pi) ** 3:.1f}"
)

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert abs(ratio_T - 8) < 0.1, "text: eight times"
assert abs(sq[2.0]["Hz"] / sq[1.0]["Hz"] - 8) < 0.1, "text: eight times"
assert abs(ratio_unit - (2 * np.pi) ** 3) < 1e-6 * (2 * np.pi) ** 3, "text: (2 pi)^3"

# %% [markdown]
# The same smooth movement gets values eight times larger at every doubling of its duration, and
# numbers that differ by $(2\pi)^3$ between Hz and rad/s (the cell above prints both ratios). For the
# drifting submovements the value mostly tracks the growing duration:

# %%
drifting_sq = []
for d in (0.0, 0.3, 0.6, 1.0):
    v = movement([0, d])
    drifting_sq.append(sk.sparc_squared_integral(v, FS, "Hz"))
    print(
        f"two submovements {d} s apart ({v.size / FS:.2f} s): "
        f"SPARC {sk.sparc(v, FS):.3f}, "
        f"squared version {drifting_sq[-1]:8.3f} (Hz)"
    )

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert (np.diff(drifting_sq) < 0).all(), (
    "text: the squared value grows with the duration"
)

# %% [markdown]
# Reading the square into the dimensionless sum [](#eq-sparc-sum) instead, with
# $(1/K^2 + \Delta\hat V_k^2)$ in place of its square root
# ([`skilllib.sparc_squared_sum`](#skilllib.smoothness.sparc_squared_sum)), fails differently. Each term
# is now of the order of $1/K^2$, so the sum is of the order of $1/K$, and $K$, the number of bins in
# the band, is set by the FFT grid: it halves with every padlevel less, and it changes with the number
# of samples $N$ between two powers of two, where $n_{\mathrm{fft}}$ stays the same. Below, the same
# minimum-jerk shape lasting 0.55 to 1.05 s at 60 Hz (33 to 63 samples, one $n_{\mathrm{fft}}$) keeps
# its SPARC while the squared sum changes with the duration and with padlevel.

# %%
grid = {}
for T in (0.55, 0.8, 1.05):
    v = sk.minimum_jerk_speed(np.arange(0, T, 1 / FS), 0, T)
    grid[f"{T} s, N = {v.size}"] = {
        "nfft": sk.nfft(v.size),
        "SPARC": sk.sparc(v, FS),
        **{
            f"squared, padlevel {p}": sk.sparc_squared_sum(v, FS, padlevel=p)
            for p in (3, 4)
        },
    }
grid_table = pd.DataFrame.from_dict(grid, orient="index")
print(grid_table.round(4))

# %% tags=["remove-cell"] jupyter={"source_hidden": true}
# checks of the claims above (hidden; the build fails when one stops holding)
assert np.ptp(grid_table["SPARC"]) < 0.01, "text: the shape keeps its SPARC"
halving = grid_table["squared, padlevel 3"] / grid_table["squared, padlevel 4"]
assert halving.between(1.8, 2.2).all(), (
    "text: the squared sum doubles with each padlevel less"
)
sq4 = grid_table["squared, padlevel 4"]
assert sq4.iloc[-1] < 1.5 * sq4.iloc[0], "text: and changes with N at one nfft"

# %% [markdown]
# In both readings the number depends on something other than the movement's shape (its duration and
# the unit of frequency, or the FFT grid), so neither can rank movements by smoothness. The definition,
# and the authors' code, have the square root; so does this book.

# %% [markdown]
# ## Summary
#
# - SPARC is minus the length of the curve of the normalised Fourier magnitude spectrum of the speed,
#   over a band that ends where the spectrum fades below a threshold. The spectrum of a smooth bell
#   falls monotonically; each further submovement adds ripples and length.
# - After the substitution $u = \omega/\omega_c$ the integral is an arc length over $[0, 1]$, so
#   SPARC $\le -1$, has no unit and ignores amplitude and duration. The code evaluates it as the length
#   of a polygon through the FFT bins of the band, [](#eq-sparc-sum), with horizontal steps $1/K$;
#   by hand it gives `skilllib`'s value to the last digit.
# - A minimum-jerk movement scores about $-1.40$ at any duration and sampling rate (the authors'
#   published $-1.4058$ at 1 s and 100 Hz); separated submovements score lower and lower.
# - The squared integrand printed in the KI 2020 paper can only be a typesetting slip: as an integral
#   it scales with the cube of the duration and with the frequency unit, as a sum with the FFT grid.
#
# Chapter 2 measures what the experiment's recordings do to this number (zero padding, the 60 Hz rate,
# the contact that cuts every trial, noise), chooses the maximum cut-off $f_c$ and compares SPARC with
# the log dimensionless jerk.
