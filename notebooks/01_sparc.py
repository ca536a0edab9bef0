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
# # SPARC from first principles
#
# The paper describes the skill of every demonstration by one number, the spectral arc length SPARC of
# its speed profile [@balasubramanian2015]. This chapter builds that number from scratch: why
# intermittent movements are less smooth, how the Fourier spectrum of a speed profile reveals it, why
# the *length* of that spectrum's curve measures it, and how the integral of the definition becomes the
# sum that the code computes. It then tries the measure on the kinds of movement the experiment
# produces, 60 Hz samples and a contact that ends every trial at non-zero speed, shows how the maximum
# cut-off decides the value on short segments, chooses the parameters the rest of the book uses, and
# compares SPARC with the log dimensionless jerk.
#
# ```{note}
# Every speed profile in this chapter is synthetic, generated here from minimum-jerk submovements (and,
# where said, noise). One section also reads the book's synthetic cohort (chapter 3), which stands in
# for the paper's unpublished recordings. Every number the text states is checked by a hidden cell of
# the notebook, so the book does not build when a statement stops being true.
# ```

# %% tags=["hide-input"]

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import skilllib.cohort
import skilllib.datasets
from skilllib.recordings import _recordings as data
from skilllib.features import _table as features
from skilllib.figures import plot_sparc_against, plot_sparc_spectra, plot_speeds_and_spectra, threshold_bound
from skilllib.smoothness import (
    SPARC_PARAMS,
    ldlj,
    ldlj_many,
    minimum_jerk_segment,
    minimum_jerk_speed,
    nfft,
    sparc,
    sparc_bands,
    sparc_many,
    sparc_spectrum,
)

FS = 60.0  # Hz, the sampling rate of the experiment


def movement(onsets, T=0.6, D=0.1, fs=FS):
    """Speed (m/s) of minimum-jerk submovements of duration T (s) and amplitude D (m) starting at
    ``onsets`` (s), sampled at fs from the first onset to the end of the last submovement."""
    t = np.arange(0, max(onsets) + T, 1 / fs)
    return minimum_jerk_speed(t[:, None], np.asarray(onsets), T, D).sum(axis=1)


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
# mid-time. Intermittency is a sum of such submovements, each starting before the previous one ends.

# %%
#| label: fig-submovements
#| caption: One minimum-jerk submovement (0.6 s, 0.1 m) and the same submovement followed by a second one 0.3 s or 0.5 s later, sampled at 60 Hz. The further apart, the deeper the dip between them.
one = movement([0.0])
profiles = {"one submovement": one, "two, 0.3 s apart": movement([0, 0.3]),
            "two, 0.5 s apart": movement([0, 0.5])}
fig, ax = plt.subplots(figsize=(5.5, 3.2))
for label, v in profiles.items():
    ax.plot(np.arange(v.size) / FS, v, ".-", ms=3, label=label)
ax.set(xlabel="time t (s)", ylabel="speed v (m/s)", ylim=(0, 0.47))
ax.legend(frameon=False, loc="upper right")
print(f"peak speed of one submovement: {one.max():.3f} m/s (1.875 D/T = {1.875 * 0.1 / 0.6:.3f})")


def dip(v):
    """Lowest speed between the first and the last local maximum of a profile (m/s)."""
    peaks = np.flatnonzero((v[1:-1] > v[:-2]) & (v[1:-1] >= v[2:])) + 1
    return v[peaks[0]: peaks[-1] + 1].min()


# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert abs(one.max() - 1.875 * 0.1 / 0.6) < 0.002, "text: peak 1.875 D/T (to the 60 Hz sampling)"
assert dip(profiles["two, 0.5 s apart"]) < dip(profiles["two, 0.3 s apart"]), "caption: further apart, deeper dip"

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
# the frequencies $f_k = k f_s / n_{\mathrm{fft}}$; we come back to $n_{\mathrm{fft}}$ below.
# [`sparc_spectrum`](#skilllib.smoothness.sparc_spectrum) returns that spectrum with everything SPARC reads from it.

# %%
s = sparc_spectrum(one, FS)
print(f"N = {one.size} samples, nfft = {s.nfft}, grid step fs/nfft = {FS / s.nfft:.4f} Hz "
      f"(fs/N = {FS / one.size:.2f} Hz without padding)")
print(f"V^(0) = {s.Mf[0]:.3f}, largest V^ = {s.Mf.max():.3f}, V^ at 2 Hz = {np.interp(2, s.f, s.Mf):.4f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert s.Mf[0] == s.Mf.max() == 1.0, "text: the normalised spectrum starts at 1 and stays below"

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
plot_speeds_and_spectra(profiles, FS, fmax=8)
for label, v in profiles.items():
    print(f"{label:18s} SPARC = {sparc(v, FS):.3f}")
print(f"ripple period 1/Δ: {1 / 0.3:.1f} Hz (Δ = 0.3 s), {1 / 0.5:.1f} Hz (Δ = 0.5 s)")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
values = [sparc(v, FS) for v in profiles.values()]
assert values[0] > values[1] > values[2], "text: each further separation lengthens the arc (ranks the three)"

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
# threshold. [](#fig-cutoff) shows the same movement with speed noise of 1 % and of 20 % of its peak
# speed.

# %%
#| label: fig-cutoff
#| caption: "One submovement without noise and with Gaussian speed noise of 1 % and 20 % of its peak speed. The 1 % noise floor stays far below the threshold (dashed) and changes nothing; at 20 % noise bumps reach the threshold and the band runs on to the last of them (dot), but never beyond fc (dotted)."
rng = np.random.default_rng(1)
noisy = {"no noise": one}
for level in (0.01, 0.20):
    noisy[f"noise {level:.0%} of peak"] = np.abs(one + rng.normal(0, level * one.max(), one.size))
plot_speeds_and_spectra(noisy, FS, fmax=15)
noisy_spectra = {label: sparc_spectrum(v, FS) for label, v in noisy.items()}
for label, s in noisy_spectra.items():
    print(f"{label:20s} cut-off {s.cutoff:5.2f} Hz   SPARC {s.sparc:.3f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
clean_, small, large = noisy_spectra.values()
assert small.cutoff == clean_.cutoff and abs(small.sparc - clean_.sparc) < 1e-3, "caption: 1 % changes nothing"
assert clean_.cutoff < large.cutoff <= SPARC_PARAMS["fc"], "caption: 20 % runs the band on, never beyond fc"

# %% [markdown]
# ## Zero padding
#
# $N$ samples over $T$ seconds resolve the spectrum only every $1/T$ Hz: a 0.6 s movement at 60 Hz
# gives one point per 1.67 Hz, far too coarse to follow its curve. Appending zeros to the signal does
# not change $V(\omega)$, but it makes the FFT evaluate it on a finer grid. The authors pad to
# $n_{\mathrm{fft}} = 2^{\lceil \log_2 N \rceil + \text{padlevel}}$ with padlevel 4, a grid at least
# 16 times finer than $1/T$. With less padding the polygon cuts the ripples' corners and SPARC is
# too close to $-1$ ([](#fig-padding)).

# %%
#| label: fig-padding
#| caption: "The spectrum of two submovements 0.5 s apart evaluated on the FFT grids of padlevel 0, 2 and 4: the polygon through the points is what SPARC measures."
two = profiles["two, 0.5 s apart"]
fig, ax = plt.subplots(figsize=(5.5, 3.2))
for p in (0, 2, 4):
    s = sparc_spectrum(two, FS, padlevel=p)
    ax.plot(s.f_sel, s.Mf_sel, ".-", ms=4, lw=1, label=f"padlevel {p}: nfft {s.nfft}, SPARC {s.sparc:.3f}")
ax.set(xlim=(0, 3), xlabel="frequency f (Hz)", ylabel=r"normalised magnitude $|V(f)|/V(0)$")
ax.legend(frameon=False)
by_pad = {p: sparc(two, FS, padlevel=p) for p in range(7)}
for p, value in by_pad.items():
    print(f"padlevel {p}: nfft = {nfft(two.size, p):5d}, SPARC = {value:.4f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert round(FS / one.size, 2) == 1.67, "text: a 0.6 s movement at 60 Hz, one point per 1.67 Hz"
assert by_pad[0] > by_pad[2] > by_pad[4] and by_pad[0] - by_pad[4] > 0.2, "text: less padding, too close to -1"
assert max(abs(by_pad[p] - by_pad[4]) for p in (5, 6)) < 0.01, "text: beyond padlevel 4 only the third decimal"

# %% [markdown]
# The polygon is inscribed in the curve, so a finer grid makes it longer: the value falls quickly up to
# padlevel 3 or 4 and then changes only in the third decimal. Padlevel 4 is the authors' convention;
# whatever its value, it must be the same for every trial that is compared.

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
trial = minimum_jerk_speed(np.arange(0, 0.8, 1 / FS), 0, 1.0, 0.2)  # contact at 80 % of the movement
N = trial.size
n_fft = 2 ** (int(np.ceil(np.log2(N))) + SPARC_PARAMS["padlevel"])
f = np.arange(n_fft) * FS / n_fft  # Hz
V_hat = np.abs(np.fft.fft(trial, n_fft))
V_hat = V_hat / V_hat.max()
print(f"1. N = {N} samples, nfft = 2^(ceil(log2 {N}) + 4) = {n_fft}, grid step {FS / n_fft:.4f} Hz")
fc = SPARC_PARAMS["fc"]
print(f"2. V^(0) = {V_hat[0]:.3f}; bins with f <= fc = {fc:g} Hz: {np.sum(f <= fc)}")

# %%
low = V_hat[f <= fc]
above = np.flatnonzero(low >= SPARC_PARAMS["amp_th"])
K = above[-1] - above[0]
band = low[above[0]: above[-1] + 1]
print(f"3. band: bins {above[0]} to {above[-1]}, K = {K} intervals, cut-off f_K = {f[above[-1]]:.3f} Hz")
terms = np.sqrt(1 / K**2 + np.diff(band) ** 2)
print(f"4. sum of the K terms: {terms.sum():.6f}; the horizontal parts alone: {K * (1 / K):.1f}")
print(f"5. SPARC by hand {-terms.sum():.12f}\n   skilllib.sparc {sparc(trial, FS):.12f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert abs(-terms.sum() - sparc(trial, FS)) < 1e-12, "text: the sum by hand is skilllib's value"

# %% [markdown]
# The horizontal steps $1/K$ add up to exactly 1: that is the $-1$ every SPARC starts from. Everything
# below $-1$ comes from the vertical changes of the spectrum. Evaluating [](#eq-sparc) itself, as a
# Riemann sum in physical units (rad/s), gives the same number, because the substitution is exact:

# %%
w = 2 * np.pi * f[above[0]: above[-1] + 1]  # rad/s
integrand = np.sqrt((1 / w[-1]) ** 2 + (np.diff(band) / np.diff(w)) ** 2)
print(f"Riemann sum of the definition, in rad/s: {-np.sum(integrand * np.diff(w)):.12f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert abs(-np.sum(integrand * np.diff(w)) - sparc(trial, FS)) < 1e-12, "text: the same number"

# %% [markdown]
# Two limiting cases follow from the sum. A single sample is an impulse: its spectrum is flat, every
# vertical step is zero and SPARC is exactly $-1$. And if the grid step $f_s / n_{\mathrm{fft}}$ were
# larger than $f_c$, the band would be bin 0 alone, $K = 0$, and the sum empty: the authors' code then
# returns 0, and `skilllib` does the same. With padlevel 4 at 60 Hz the step is at most
# $60/16$ Hz, below $f_c$, so this cannot happen in this book.

# %%
print(f"one sample at 60 Hz: SPARC = {sparc([0.3], FS):.12f}")
print(f"largest grid step at 60 Hz (N = 1): {FS / nfft(1):.2f} Hz; "
      f"one sample at 1000 Hz (step {1000 / nfft(1):.1f} Hz > fc): SPARC = {sparc([0.3], 1000.0):g}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert sparc([0.3], FS) == -1.0 and sparc([0.3], 1000.0) == 0.0, "text: exactly -1; 0 for a one-bin band"
assert FS / nfft(1) == 60 / 16 < SPARC_PARAMS["fc"], "text: step at most 60/16 Hz, below fc"

# %% [markdown]
# ## The minimum-jerk reference
#
# A single minimum-jerk movement is the smoothest movement the measure meets in practice. Its SPARC is
# about $-1.40$ whatever its duration and sampling rate; the small differences come from where the
# frequency grid falls relative to the threshold crossing. The value for a 1 s movement at 100 Hz is
# the authors' published $-1.4058$.

# %%
ref = pd.DataFrame({f"{fs:g} Hz": [sparc(minimum_jerk_speed(np.arange(0, T, 1 / fs), 0, T), fs)
                                   for T in (0.5, 1.0, 1.5)] for fs in (60.0, 100.0, 1000.0)},
                   index=pd.Index([0.5, 1.0, 1.5], name="duration T (s)"))
print(ref.round(4))
print(f"1 s at 100 Hz: {ref.loc[1.0, '100 Hz']:.10f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert ref.to_numpy().min() > -1.41 and ref.to_numpy().max() < -1.39, "text: about -1.40 at any T and rate"
assert abs(ref.loc[1.0, "100 Hz"] - -1.4058293244214655) < 1e-12, "text: the authors' published -1.4058"

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
drift = {"two submovements": sparc_many([movement([0, d]) for d in delays], FS),
         "three submovements": sparc_many([movement([0, d, 2 * d]) for d in delays], FS)}
plot_sparc_against(delays, drift, "delay between onsets (s)")
print(pd.DataFrame(drift, index=pd.Index(delays, name="delay (s)")).iloc[::4].round(3))

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
two_d, three_d = (pd.Series(v, index=delays) for v in drift.values())
assert two_d[0.2] > two_d[0.0], "text: at 0.2 s a little smoother than one submovement"
assert (np.diff(two_d[delays >= 0.3]) < 0).all() and (three_d[delays >= 0.3] < two_d[delays >= 0.3]).all(), (
    "text: once separated SPARC falls steadily, faster with three")

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
base = sparc(one, FS)
print(f"amplitude x 10:    difference {sparc(10 * one, FS) - base:.1e}")
print(f"amplitude x 0.003: difference {sparc(0.003 * one, FS) - base:.1e}")
stretched = {}
for c in (1.5, 2, 4):
    longer = movement([0.0], T=0.6 * c, D=0.1)
    stretched[c] = sparc(longer, FS) - base
    print(f"duration x {c:3g} ({longer.size:3d} samples, nfft {nfft(longer.size):5d}): "
          f"difference {stretched[c]:+.1e}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert sparc(10 * one, FS) == base == sparc(0.003 * one, FS), "text: exactly amplitude invariant"
assert max(abs(stretched[2]), abs(stretched[4])) < 1e-5, "text: 2 or 4 times longer agree to a few millionths"
assert 1e-3 < abs(stretched[1.5]) < 1e-2, "text: 1.5 times longer, a few thousandths"

# %% [markdown]
# ## Sampled at 60 Hz
#
# The experiment records positions at 60 Hz, so the Nyquist frequency is 30 Hz and a movement of half a
# second has only 30 samples. That is enough: a smooth reaching movement has its energy below a few
# hertz, and the table of the minimum-jerk reference above shows 60 Hz values within a few thousandths
# of those at 1000 Hz. The short profiles do make the frequency grid coarse, which is why the padding
# matters.

# %%
rate_gap = []
for T in (0.3, 0.5, 1.0):
    v60, v1000 = (minimum_jerk_speed(np.arange(0, T, 1 / fs), 0, T) for fs in (60.0, 1000.0))
    rate_gap.append(sparc(v60, 60.0) - sparc(v1000, 1000.0))
    print(f"T = {T} s: {v60.size:2d} samples at 60 Hz, SPARC {sparc(v60, 60.0):.4f} "
          f"(at 1000 Hz {sparc(v1000, 1000.0):.4f})")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert max(map(abs, rate_gap)) < 5e-3, "text: 60 Hz values within a few thousandths of 1000 Hz ones"

# %% [markdown]
# ## A profile that ends at contact
#
# Every trial of the experiment ends when the spoon touches the box, at a contact speed of 0.3 to
# 0.7 m/s: the speed profile is cut during the deceleration, at a sizeable fraction of its peak. A
# profile that ends with a jump to zero has a spectrum that decays slowly, like $1/f$, with side lobes.
# The band reaches higher and the arc is longer: a perfectly smooth but truncated movement scores well
# below $-1.40$ ([](#fig-contact)).

# %%
#| label: fig-contact
#| caption: "A 1 s minimum-jerk movement sampled at 60 Hz, complete and cut at contact when its speed has fallen to 25 %, 50 % and 75 % of the peak. The cut adds side lobes to the spectrum and lengthens the band."
t = np.arange(0, 1.0, 1 / FS)
full = minimum_jerk_speed(t, 0, 1.0, 0.2)
cut = {"complete": full}
for r in (0.25, 0.50, 0.75):
    end = np.flatnonzero((t > 0.5) & (full < r * full.max()))[0]  # first sample below r * peak
    cut[f"contact at {r:.0%} of peak"] = full[:end]
plot_speeds_and_spectra(cut, FS, fmax=12)
for label, v in cut.items():
    s = sparc_spectrum(v, FS)
    print(f"{label:22s} {v.size} samples, last speed {v[-1] / full.max():4.0%} of peak, "
          f"cut-off {s.cutoff:4.2f} Hz, SPARC {s.sparc:.3f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
truncated = [sparc(v, FS) for label, v in cut.items() if label != "complete"]
assert max(truncated) < sparc(full, FS) - 0.1, "text: a truncated movement scores well below -1.40"

# %% [markdown]
# The truncated values are not only lower, they also jump. As the contact speed rises, side lobes of the
# spectrum rise above the threshold one after the other, and each time the band suddenly takes in one
# more lobe. Where the jumps fall depends on the sampling: shifting the 60 Hz samples by half a sample
# period moves them ([](#fig-contact-sweep)).

# %%
#| label: fig-contact-sweep
#| caption: "SPARC of the 1 s minimum-jerk movement cut at contact, against the speed at contact in % of the peak speed: sampled at 60 Hz, at 60 Hz shifted by half a sample period, and at 1000 Hz."
fractions = np.round(np.arange(0.20, 0.801, 0.01), 2)
sweep = {}
for label, fs, shift in (("60 Hz", 60.0, 0.0), ("60 Hz, shifted half a sample", 60.0, 0.5),
                         ("1000 Hz", 1000.0, 0.0)):
    tt = np.arange(shift / fs, 1.0, 1 / fs)
    vv = minimum_jerk_speed(tt, 0, 1.0, 0.2)
    ends = [np.flatnonzero((tt > 0.5) & (vv < r * vv.max()))[0] for r in fractions]
    sweep[label] = sparc_many([vv[:e] for e in ends], fs)
plot_sparc_against(100 * fractions, sweep, "speed at contact (% of peak)")
gap = np.abs(sweep["60 Hz"] - sweep["60 Hz, shifted half a sample"])
print(f"range at 60 Hz: {sweep['60 Hz'].min():.3f} to {sweep['60 Hz'].max():.3f}; largest change from "
      f"the half-sample shift: {gap.max():.3f} (at {100 * fractions[gap.argmax()]:.0f} % of peak)")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert 0.01 < gap.max() < 0.1, "text: differences of a few hundredths can be an effect of the sampling"
assert round(sweep["60 Hz"].min(), 2) == -1.63 and round(sweep["60 Hz"].max(), 2) == -1.52, (
    "summary: a movement cut at contact scores between about -1.52 and -1.63")

# %% [markdown]
# For this book this means: the (PV, SPARC) clusters of the later chapters live in a range set by the
# contact as much as by intermittency; SPARC values should only be compared between trials recorded
# at the same rate, and even then differences of a few hundredths can be an effect of the sampling.

# %% [markdown]
# ## Which cut-off: the authors' 10 Hz or the paper's "0 to 20 Hz"?
#
# The KI 2020 paper [@maldonado2020] computes SPARC "within the frequency range 0 to 20 Hz". That is the default of the
# SPARC authors' MATLAB code (`SpectralArcLength`, parameters [0.05, 20, 4]); their Python code, whose
# computation `skilllib` reproduces, defaults to a maximum cut-off $f_c$ = 10 Hz. With an adaptive
# cut-off, $f_c$ matters only when the spectrum still reaches the threshold at $f_c$. For the profiles of
# this chapter so far, 0.6 s and longer and free of noise, it does not: both settings give every one of
# them the same value.

# %%
clean = {**profiles, **{f"cut: {k}": v for k, v in cut.items() if k != "complete"},
         **{f"two, {d} s apart": movement([0, d]) for d in (0.6, 1.0)}}
b10, b20 = (sparc_bands(list(clean.values()), FS, fc=fc) for fc in (10.0, 20.0))
table = pd.DataFrame({"cut-off (Hz), fc = 10": b10.band_end_hz, "SPARC, fc = 10 Hz": b10.sparc,
                      "SPARC, fc = 20 Hz": b20.sparc}, index=list(clean))
print(table.round(3))

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert (b10.band_end_hz < 10).all() and not b10.capped.any(), "text: every band ends below 10 Hz"
assert np.allclose(b10.sparc, b20.sparc, atol=1e-12), "text: both settings give the same value"

# %% [markdown]
# ### Short segments cut at contact
#
# The experiment's segments are different. They run from movement onset to a contact that cuts the
# movement at a sizeable fraction of its peak speed, and at 60 Hz they are short: the synthetic cohort's
# segments (chapter 3) hold the numbers of samples printed at the end of this section. A short profile has
# a wide spectrum: $N$ samples over $T = N/f_s$ seconds resolve it only every $1/T$ Hz, and a band up to
# $f_c$ holds only about $f_c T$ independent spectral values (4 below 20 Hz for a 0.2 s segment). The cut
# at contact adds side lobes that decay slowly. Such a spectrum can still reach the threshold at 10 Hz,
# and then the cap, not the threshold, ends the band.
#
# `skilllib.smoothness.minimum_jerk_segment(n, r, fs)` makes the cleanest test: one minimum-jerk bell,
# segmented like a trial from where its speed reaches 5 % of its peak to where a contact cuts it at a
# fraction $r$ of its peak, and stretched to fill $n$ samples at 60 Hz. Every $n$ has the same shape,
# and SPARC, which ignores the time scale, should give every $n$ the same value ([](#fig-short)).

# %%
#| label: fig-short
#| caption: "One minimum-jerk shape cut at contact at 30, 50 and 70 % of its peak speed, sampled with n = 6 to 40 samples at 60 Hz (generated profiles). Left, SPARC with fc = 20 Hz (solid) and 10 Hz (dashed); open markers where fc, not the threshold, ended the band; dotted, the highest SPARC a band ended by the threshold can have. Right, the last frequency of the band."
ns = np.arange(6, 41)
short = {}
fig, (ax, ax_end) = plt.subplots(1, 2, figsize=(10, 3.6), layout="constrained")
for i, r in enumerate((0.3, 0.5, 0.7)):
    segs = [minimum_jerk_segment(int(n), r, FS) for n in ns]
    for fc, ls in ((20.0, "-"), (10.0, "--")):
        b = short[r, fc] = sparc_bands(segs, FS, fc=fc)
        for a, y in ((ax, b.sparc), (ax_end, b.band_end_hz)):
            a.plot(ns, y, ls, color=f"C{i}", lw=1, label=f"cut at {r:.0%}, fc = {fc:g} Hz")
            a.scatter(ns[~b.capped], y[~b.capped], s=9, color=f"C{i}")
            a.scatter(ns[b.capped], y[b.capped], s=12, facecolor="white", edgecolor=f"C{i}", zorder=3)
ax.axhline(threshold_bound(), color="0.3", ls=":", lw=1)
ax.set(xlabel="segment length n (samples at 60 Hz)", ylabel="SPARC")
ax_end.set(xlabel="segment length n (samples at 60 Hz)", ylabel="band end (Hz)")
ax_end.legend(fontsize=7, frameon=False, ncol=2)


def stable_from(values, tol=0.01):
    """Shortest n from which SPARC stays within tol of its value at the longest n."""
    off = np.abs(values - values[-1]) > tol
    return int(ns[np.flatnonzero(off)[-1] + 1]) if off.any() else int(ns[0])


stable = pd.DataFrame({f"fc = {fc:g} Hz": {f"cut at {r:.0%}": stable_from(short[r, fc].sparc)
                                           for r in (0.3, 0.5, 0.7)} for fc in (10.0, 20.0)})
print("SPARC at n = 40:", {f"cut at {r:.0%}": round(float(short[r, 20.0].sparc[-1]), 3) for r in (0.3, 0.5, 0.7)})
print("shortest n from which SPARC stays within 0.01 of that value:")
print(stable)

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
for r in (0.3, 0.5, 0.7):
    assert abs(short[r, 20.0].sparc[-1] - short[r, 10.0].sparc[-1]) < 1e-9, "text: long segments, one value"
    assert stable.loc[f"cut at {r:.0%}", "fc = 10 Hz"] > stable.loc[f"cut at {r:.0%}", "fc = 20 Hz"] + 3, (
        "text: 10 Hz needs longer segments than 20 Hz")
    assert short[r, 10.0].sparc[0] > short[r, 10.0].sparc[-1] + 0.25, "text: the shortest look much smoother"
    assert short[r, 10.0].capped[:5].all() and not short[r, 20.0].capped[-10:].any(), "text: capped when short"
assert stable.loc["cut at 70%"].tolist() == [22, 14], "text: 22 samples with 10 Hz, 14 with 20 Hz (70 %)"
assert (stable.loc["cut at 70%"] >= stable.max()).all(), "text: lower contact speeds, lower limits"

# %% [markdown]
# Long segments give each shape one value under both settings. Below some length the band reaches the
# cap, and SPARC rises towards $-1$ the shorter the segment, although the shape has not changed: the
# shorter segment merely looks smoother. For a contact at 70 % of the peak speed, SPARC stays within 0.01
# of its long-segment value down to 22 samples (0.37 s at 60 Hz) with $f_c$ = 10 Hz, and down to 14 samples
# with 20 Hz; for contacts at lower speeds both limits are lower (table above).
#
# ### A bound that only a capped band can break
#
# The polygon of [](#eq-sparc-sum) runs from $(0, \hat V_0)$ to $(1, \hat V_K)$ and is at least as long as
# the straight chord between them, so
#
# $$
# \mathrm{SPARC} \le -\sqrt{1 + (\hat V_0 - \hat V_K)^2} .
# $$ (eq-chord)
#
# For a speed profile $\hat V_0 = 1$. When the threshold ends the band, the last bin is the last one
# still at or above it, so $\hat V_K$ is just above $\bar V$ = 0.05 on a finely padded grid, and SPARC is
# at most about $-\sqrt{1 + 0.95^2} = -1.379$ (the dotted line of [](#fig-short)). A band that the cap ends
# stops where the spectrum is still high, and its SPARC can rise above that line: such values are made by
# the cap, not by the movement.

# %%
ends = {cap: [] for cap in (False, True)}
for (r, fc), b in short.items():
    segs = [minimum_jerk_segment(int(n), r, FS) for n in ns]
    for v, capped in zip(segs, b.capped):
        sp = sparc_spectrum(v, FS, fc=fc)
        ends[bool(capped)].append((sp.Mf_sel[-1], sp.sparc))
for capped, rows_ in ends.items():
    a = np.array(rows_)
    print(f"{'capped' if capped else 'ended by the threshold'}: {len(a)} bands, V^ at the band end "
          f"{a[:, 0].min():.3f}-{a[:, 0].max():.3f}, highest SPARC {a[:, 1].max():.3f}")
print(f"bound for amp_th = 0.05: {threshold_bound():.3f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
unc, cap = np.array(ends[False]), np.array(ends[True])
assert round(-np.hypot(1, 0.95), 3) == round(threshold_bound(), 3) == -1.379, "text: -sqrt(1 + 0.95^2) = -1.379"
assert unc[:, 0].max() < 0.06 and (unc[:, 1] <= threshold_bound() + 1e-3).all(), "text: threshold-ended bands stay below"
assert cap[:, 1].max() > threshold_bound() + 0.1, "text: capped bands can rise above the line"

# %% [markdown]
# ### On the book's cohort
#
# The synthetic cohort of chapter 3 has segments of exactly this kind. Computed with both settings, its
# trials' bands end as follows (chapter 4 repeats the whole clustering with both settings):

# %%
COHORT = skilllib.datasets.cohort_path()  # the book's synthetic cohort, shipped with skilllib
rec = data.read_recordings(COHORT)
by_fc = {fc: features.trial_features(rec, sparc_params={"fc": fc}) for fc in (10.0, 20.0)}
valid = by_fc[20.0][by_fc[20.0].status != "invalid"]
sel_n = valid.loc[valid.status == "selected", "n"]
print(f"segment lengths: {valid.n.min()}-{valid.n.max()} samples (selected trials {sel_n.min()}-{sel_n.max()}, "
      f"median {sel_n.median():g})")
cohort_rows = {}
for fc, f in by_fc.items():
    v, sel = f[f.status != "invalid"], f[f.status == "selected"]
    cohort_rows[f"fc = {fc:g} Hz"] = {
        "selected trials capped": sel.sparc_capped.mean(),
        "valid trials above -1.379": int((v.sparc > threshold_bound()).sum()),
        "corr(SPARC, duration), selected": np.corrcoef(sel.sparc, sel.duration)[0, 1]}
cohort_table = pd.DataFrame(cohort_rows).T
print(cohort_table.round(3))

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
c10, c20 = cohort_table.loc["fc = 10 Hz"], cohort_table.loc["fc = 20 Hz"]
assert c10["selected trials capped"] > 0.6 and c20["selected trials capped"] < 0.25, (
    "text: 10 Hz caps most selected trials' bands, 20 Hz a minority")
assert c10["valid trials above -1.379"] > 100 and c20["valid trials above -1.379"] < 10, (
    "text: more than a hundred above the line at 10 Hz, a few at 20 Hz")
assert c10["corr(SPARC, duration), selected"] < -0.6 < c20["corr(SPARC, duration), selected"], (
    "text: at 10 Hz SPARC follows the duration more closely")
assert sel_n.max() <= 30, "text: the selected segments are short"

# %% [markdown]
# On the cohort's short segments the 10 Hz cap ends the band of most selected trials, and more than a
# hundred trials score above the line only a capped band can cross; with 20 Hz the cap ends a minority
# of bands. At 10 Hz SPARC also follows the segment's duration much more closely (correlation printed
# above). Chapter 3 shows what SPARC measures on these data.
#
# ### Noise
#
# A wider cap has a price. Here are 200 noisy copies of the single submovement per noise level, each
# measured both ways:

# %%
rng = np.random.default_rng(2)
rows = {}
for level in (0.01, 0.03, 0.10, 0.20):
    copies = [np.abs(one + rng.normal(0, level * one.max(), one.size)) for _ in range(200)]
    s10, s20 = sparc_many(copies, FS, fc=10.0), sparc_many(copies, FS, fc=20.0)
    rows[f"{level:.0%}"] = {"mean SPARC, fc = 10 Hz": s10.mean(), "mean SPARC, fc = 20 Hz": s20.mean(),
                            "copies that differ": np.mean(np.abs(s10 - s20) > 1e-9)}
    if level == 0.10:
        example = copies[np.argmax(s10 - s20)]
noise_fc = pd.DataFrame(rows).T.rename_axis("noise (% of peak)")
print(noise_fc.round(3))
speed_noise = skilllib.cohort.CohortModel().noise_sd * FS / np.sqrt(2)  # m/s per axis, central differences
print(f"the cohort's speed noise: {1e3 * speed_noise:.1f} mm/s per axis, "
      f"{speed_noise / sel.pv.median():.2%} of the median peak speed of its selected trials")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert (noise_fc.loc[["1%", "3%"], "copies that differ"] == 0).all(), "text: small noise changes nothing"
n10 = noise_fc.loc["10%"]
assert n10["copies that differ"] > 0.2 and n10["mean SPARC, fc = 20 Hz"] < n10["mean SPARC, fc = 10 Hz"] - 0.05, (
    "text: at 10 % noise 20 Hz falls further and more often")
assert speed_noise / sel.pv.median() < 0.01, "text: the cohort's noise is far below 1 % of the peak speed"

# %% [markdown]
# Small noise changes nothing either way. Once the noise floor nears the threshold, a noise bump between
# 10 and 20 Hz that reaches it drags the band up to 20 Hz, two thirds of the Nyquist frequency, where
# differentiated position noise is strongest: with $f_c$ = 20 Hz SPARC falls further and more often.
# [](#fig-fc) shows the noisy copy (10 % noise) where the two differ most. The cohort's position noise
# (0.03 mm, the device's resolution) gives speed noise far below 1 % of the peak speed (printed above),
# where neither setting reacts; recordings with more noise are low-pass filtered before they are
# differentiated.

# %%
#| label: fig-fc
#| caption: "A copy of the submovement with speed noise of 10 % of its peak (generated). With fc = 10 Hz (left) the band ends where the movement's spectrum fades below the threshold; with fc = 20 Hz (right) a noise bump between 10 and 20 Hz reaches the threshold and the band runs on through the noise."
fig, axes = plt.subplots(1, 2, figsize=(10, 3.2), sharey=True, layout="constrained")
for ax, fc in zip(axes, (10.0, 20.0)):
    plot_sparc_spectra({f"fc = {fc:g} Hz": sparc_spectrum(example, FS, fc=fc)}, ax=ax, fmax=30)

# %% [markdown]
# ### The book's choice
#
# **The book uses $f_c$ = 20 Hz**, with the authors' amplitude threshold 0.05 and padlevel 4, exported as
# `skilllib.smoothness.SPARC_PARAMS` so that every chapter and the pipeline use the same values:
#
# 1. It is what the paper states ("0 to 20 Hz") and the SPARC authors' MATLAB default. The original
#    recordings are not public, so which cut-off the KI 2020 authors ran cannot be checked; their text is
#    the best evidence.
# 2. The adaptive cut-off is meant to end the band where the movement's spectrum fades. On segments as
#    short as the experiment's, 10 Hz ends most bands itself, and SPARC then reports the segment's length
#    more than its shape ([](#fig-short) and the cohort table above). With 20 Hz the threshold ends most
#    bands, and SPARC keeps its meaning on segments down to about 14 samples.
# 3. The price is sensitivity to noise above 10 Hz. It does not arise at the cohort's noise level; for
#    noisy recordings the positions are low-pass filtered first, and `python -m skilllib run --sensitivity
#    fc=10` shows how much a result depends on the choice.
#
# Trials whose band the cap still ends at 20 Hz are flagged, `sparc_capped`, in the feature table and in
# the pipeline's results.json; their SPARC depends on $f_c$ and says more about their length than about
# their smoothness.

# %%
print(dict(SPARC_PARAMS))

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert SPARC_PARAMS["fc"] == 20.0 and SPARC_PARAMS["amp_th"] == 0.05 and SPARC_PARAMS["padlevel"] == 4, (
    "text: the book uses fc = 20 Hz, threshold 0.05, padlevel 4")

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

# %%
def squared_version(v, fs, unit=2 * np.pi):
    """Riemann sum of the squared integral on the SPARC band; unit 2 pi: rad/s, 1: Hz."""
    s = sparc_spectrum(v, fs)
    w = unit * s.f_sel
    return -np.sum(((1 / w[-1]) ** 2 + (np.diff(s.Mf_sel) / np.diff(w)) ** 2) ** 2 * np.diff(w))


sq = {}
for T in (0.5, 1.0, 2.0):
    v = minimum_jerk_speed(np.arange(0, T, 1 / FS), 0, T)
    sq[T] = squared_version(v, FS, 1.0), squared_version(v, FS)
    print(f"minimum jerk, T = {T} s: SPARC {sparc(v, FS):.4f}   squared version "
          f"{sq[T][0]:9.4f} (Hz)  {sq[T][1]:9.6f} (rad/s)")
print(f"ratio T = 1 s to T = 0.5 s: {sq[1.0][0] / sq[0.5][0]:.2f}; Hz to rad/s: {sq[1.0][0] / sq[1.0][1]:.1f}"
      f" = (2 pi)^3 = {(2 * np.pi) ** 3:.1f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert abs(sq[1.0][0] / sq[0.5][0] - 8) < 0.1 and abs(sq[2.0][0] / sq[1.0][0] - 8) < 0.1, "text: eight times"
assert abs(sq[1.0][0] / sq[1.0][1] - (2 * np.pi) ** 3) < 1e-6 * (2 * np.pi) ** 3, "text: (2 pi)^3"

# %% [markdown]
# The same smooth movement gets values eight times larger at every doubling of its duration, and
# numbers that differ by $(2\pi)^3$ between Hz and rad/s (the cell above prints both ratios). For the
# drifting submovements the value mostly tracks the growing duration:

# %%
drifting_sq = []
for d in (0.0, 0.3, 0.6, 1.0):
    v = movement([0, d])
    drifting_sq.append(squared_version(v, FS, 1.0))
    print(f"two submovements {d} s apart ({v.size / FS:.2f} s): SPARC {sparc(v, FS):.3f}, "
          f"squared version {drifting_sq[-1]:8.3f} (Hz)")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert (np.diff(drifting_sq) < 0).all(), "text: the squared value grows in size with the duration"

# %% [markdown]
# Reading the square into the dimensionless sum [](#eq-sparc-sum) instead, with
# $(1/K^2 + \Delta\hat V_k^2)$ in place of its square root, fails differently. Each term is now of the
# order of $1/K^2$, so the sum is of the order of $1/K$, and $K$, the number of bins in the band, is set
# by the FFT grid: it halves with every padlevel less, and it changes with the number of samples $N$
# between two powers of two, where $n_{\mathrm{fft}}$ stays the same. Below, the same minimum-jerk shape
# lasting 0.55 to 1.05 s at 60 Hz (33 to 63 samples, one $n_{\mathrm{fft}}$) keeps its SPARC while the
# squared sum changes with the duration and with padlevel.

# %%
def squared_sum(v, fs, padlevel=SPARC_PARAMS["padlevel"]):
    """The discrete sum eq-sparc-sum with the printed square instead of the square root."""
    s = sparc_spectrum(v, fs, padlevel=padlevel)
    K = s.f_sel.size - 1
    return -np.sum(1 / K**2 + np.diff(s.Mf_sel) ** 2)


grid = {}
for T in (0.55, 0.8, 1.05):
    v = minimum_jerk_speed(np.arange(0, T, 1 / FS), 0, T)
    grid[f"{T} s, N = {v.size}"] = {"nfft": nfft(v.size), "SPARC": sparc(v, FS),
                                    **{f"squared, padlevel {p}": squared_sum(v, FS, p) for p in (3, 4)}}
grid_table = pd.DataFrame.from_dict(grid, orient="index")
print(grid_table.round(4))

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert np.ptp(grid_table["SPARC"]) < 0.01, "text: the shape keeps its SPARC"
assert (grid_table["squared, padlevel 3"] / grid_table["squared, padlevel 4"]).between(1.8, 2.2).all(), (
    "text: the squared sum doubles with each padlevel less")
assert grid_table["squared, padlevel 4"].iloc[-1] < 1.5 * grid_table["squared, padlevel 4"].iloc[0], (
    "text: and changes with N at one nfft")

# %% [markdown]
# In both readings the number depends on something other than the movement's shape (its duration and
# the unit of frequency, or the FFT grid), so neither can rank movements by smoothness. The definition,
# and the authors' code, have the square root; so does this book.

# %% [markdown]
# ## LDLJ beside SPARC
#
# The other established smoothness measure is the log dimensionless jerk
# [@balasubramanian2015], computed in the time domain from the second derivative of speed:
#
# $$
# \mathrm{LDLJ} = -\ln \left| -\frac{(t_2 - t_1)^3}{v_{\mathrm{peak}}^2} \int_{t_1}^{t_2}
# \left(\frac{d^2 v}{dt^2}\right)^2 dt \right| .
# $$ (eq-ldlj)
#
# Both are dimensionless and both fall with intermittency. `skilllib` reproduces the authors' published
# values for their test signal, a Gaussian bell $e^{-5t^2}$ sampled at 100 Hz:

# %%
tg = np.arange(-1, 1, 0.01)
gauss = np.exp(-5 * tg**2)
print(f"SPARC {sparc(gauss, 100.0):.5f}, LDLJ {ldlj(gauss, 100.0):.5f}, "
      f"|DLJ| {np.exp(-ldlj(gauss, 100.0)):.5f}")

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert round(sparc(gauss, 100.0), 5) == -1.41403 and round(ldlj(gauss, 100.0), 5) == -5.81636, (
    "text: the authors' published values")

# %% [markdown]
# The difference is how they treat noise. A second derivative multiplies each frequency component by
# $(2\pi f)^2$, so the jerk integral is dominated by the noise at the highest frequencies, up to
# Nyquist. SPARC never looks past its cut-off. To compare two measures on different scales, [](#fig-noise)
# divides each one's change by the change it shows for real intermittency: one submovement against two,
# 0.5 s apart. With speed noise of 1 % of the peak, LDLJ has already moved by about two thirds of that
# amount, at 3 % by more than all of it; SPARC changes by less than 0.01 up to 3 % noise, and at 10 % by
# about a third of the change a second submovement makes (with the 20 Hz cut-off; 10 Hz would let less of
# the noise in, as the previous section showed).

# %%
#| label: fig-noise
#| caption: "Change of SPARC and LDLJ of one minimum-jerk submovement (0.6 s, 60 Hz) with added speed noise (standard deviation in % of the peak speed; mean of 50 noisy copies per level), divided by each measure's change from one submovement to two submovements 0.5 s apart."
rng = np.random.default_rng(3)
levels = np.array([0, 0.1, 0.3, 1, 2, 3, 5, 10])  # % of peak speed
copies = [[np.abs(one + rng.normal(0, lv / 100 * one.max(), one.size)) for _ in range(50)] for lv in levels]
noise = pd.DataFrame({"SPARC": [sparc_many(c, FS).mean() for c in copies],
                      "LDLJ": [ldlj_many(c, FS).mean() for c in copies]},
                     index=pd.Index(levels, name="noise (% of peak)"))
intermittency = {"SPARC": sparc(two, FS) - sparc(one, FS), "LDLJ": ldlj(two, FS) - ldlj(one, FS)}
relative = (noise - noise.iloc[0]) / pd.Series(intermittency)
plot_sparc_against(levels, relative.to_dict("list"), "speed noise (% of peak)",
                   "change / change for a second submovement")
print("change from one to two submovements:", {k: round(v, 3) for k, v in intermittency.items()})
print(noise.round(3))
print("change from no noise, relative to that:\n", relative.round(2).loc[[1, 3, 10]])

# %% tags=["remove-cell"]
# checks of the claims above (not shown on the site; the build fails when one stops holding)
assert 0.55 < relative.loc[1, "LDLJ"] < 0.8 and relative.loc[3, "LDLJ"] > 1, "text: LDLJ two thirds at 1 %, all at 3 %"
assert (noise.loc[:3, "SPARC"] - noise.loc[0, "SPARC"]).abs().max() < 0.01, "text: SPARC < 0.01 up to 3 %"
assert 0.25 < relative.loc[10, "SPARC"] < 0.42, "text: at 10 % about a third"

# %% [markdown]
# The experiment's speeds come from differentiated positions and carry such noise. That is the reason
# the paper, and this book, use SPARC.

# %% [markdown]
# ## Summary
#
# - SPARC is minus the length of the curve of the normalised Fourier magnitude spectrum of the speed,
#   over a band that ends where the spectrum fades below a threshold. The spectrum of a smooth bell
#   falls monotonically; each further submovement adds ripples and length.
# - After the substitution $u = \omega/\omega_c$ the integral is an arc length over $[0, 1]$, so
#   SPARC $\le -1$, has no unit and ignores amplitude and duration. The code evaluates it as the length
#   of a polygon through the FFT bins of the band, [](#eq-sparc-sum), with horizontal steps $1/K$.
# - A minimum-jerk movement scores about $-1.40$ at any duration and sampling rate; separated
#   submovements score lower and lower; a movement cut at contact scores between about $-1.52$ and
#   $-1.63$, in steps that depend on the contact speed and on the sampling grid.
# - Zero padding to $2^{\lceil\log_2 N\rceil + 4}$ bins is needed for short 60 Hz profiles.
# - On long profiles the maximum cut-off does not matter. On segments of a few dozen samples cut at
#   contact it does: the cap ends the band, SPARC rises with shortness alone, and values above
#   $-\sqrt{1 + (1 - \bar V)^2} \approx -1.379$ can only come from the cap. At 10 Hz that happens to most
#   of the cohort's selected trials, at 20 Hz to a minority.
# - The book therefore uses the paper's $f_c$ = 20 Hz with the authors' threshold 0.05 and padlevel 4
#   (`SPARC_PARAMS`), flags the trials whose band the cap still ends (`sparc_capped`), and lets the
#   pipeline compare settings (`--sensitivity`). The price, sensitivity to noise above 10 Hz, does not
#   arise at the cohort's noise level.
# - The squared integrand printed in the KI 2020 paper can only be a typesetting slip: as an integral
#   it scales with the cube of the duration and with the frequency unit, as a sum with the FFT grid.
# - LDLJ measures the same intermittency but collapses with small amounts of measurement noise; SPARC
#   does not.
