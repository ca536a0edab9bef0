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
# # SPARC from first principles
#
# The paper describes the skill of every demonstration by one number, the spectral arc length SPARC of
# its speed profile (Balasubramanian et al. 2015). This chapter builds that number from scratch: why
# intermittent movements are less smooth, how the Fourier spectrum of a speed profile reveals it, why
# the *length* of that spectrum's curve measures it, and how the integral of the definition becomes the
# sum that the code computes. It then tries the measure on the kinds of movement the experiment
# produces, 60 Hz samples and a contact that ends every trial at non-zero speed, chooses the parameters
# the rest of the book uses, and compares SPARC with the log dimensionless jerk.
#
# ```{note}
# This chapter uses no experiment data. Every speed profile in it is synthetic, generated here from
# minimum-jerk submovements (and, where said, noise).
# ```

# %%
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from skilllib.figures import plot_sparc_against, plot_sparc_spectra, plot_speeds_and_spectra
from skilllib.smoothness import (SPARC_PARAMS, ldlj, ldlj_many, minimum_jerk_speed, nfft, sparc,
                                 sparc_many, sparc_spectrum)

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
# loads (the paper's related work: Nelson 1983; Nagasaki 1989; Schaal 2002): one peak, no hesitation.
# Smoothness has been seen as the organising principle of motion (Hogan 1984) and as a mark of skill
# (Nagasaki 1989). In sensorimotor control a smooth movement is a *continual*, non-intermittent one
# (Balasubramanian et al. 2015): poor planning, poor execution or an unfamiliar task break a movement
# into submovements, and the speed dips between them.
#
# A convenient model of one smooth submovement is the minimum-jerk profile (Flash & Hogan 1985): a
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
# `sparc_spectrum` returns that spectrum with everything SPARC reads from it.

# %%
s = sparc_spectrum(one, FS)
print(f"N = {one.size} samples, nfft = {s.nfft}, grid step fs/nfft = {FS / s.nfft:.4f} Hz "
      f"(fs/N = {FS / one.size:.2f} Hz without padding)")
print(f"V^(0) = {s.Mf[0]:.3f}, largest V^ = {s.Mf.max():.3f}, V^ at 2 Hz = {np.interp(2, s.f, s.Mf):.4f}")

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
for label, v in noisy.items():
    s = sparc_spectrum(v, FS)
    print(f"{label:20s} cut-off {s.cutoff:5.2f} Hz   SPARC {s.sparc:.3f}")

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
for p in range(7):
    print(f"padlevel {p}: nfft = {nfft(two.size, p):5d}, SPARC = {sparc(two, FS, padlevel=p):.4f}")

# %% [markdown]
# The polygon is inscribed in the curve, so a finer grid makes it longer: the value falls quickly up to
# padlevel 3 or 4 and then changes only in the third decimal. Padlevel 4 is the authors' convention;
# whatever its value, it must be the same for every trial that is compared.

# %% [markdown]
# ## From the integral to the sum the code computes
#
# The definition of Balasubramanian et al. (2015) is
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
# This is what the authors' code computes, and `skilllib.sparc` with it (the test suite checks the two
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

# %% [markdown]
# The horizontal steps $1/K$ add up to exactly 1: that is the $-1$ every SPARC starts from. Everything
# below $-1$ comes from the vertical changes of the spectrum. Evaluating [](#eq-sparc) itself, as a
# Riemann sum in physical units (rad/s), gives the same number, because the substitution is exact:

# %%
w = 2 * np.pi * f[above[0]: above[-1] + 1]  # rad/s
integrand = np.sqrt((1 / w[-1]) ** 2 + (np.diff(band) / np.diff(w)) ** 2)
print(f"Riemann sum of the definition, in rad/s: {-np.sum(integrand * np.diff(w)):.12f}")

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
for c in (1.5, 2, 4):
    longer = movement([0.0], T=0.6 * c, D=0.1)
    print(f"duration x {c:3g} ({longer.size:3d} samples, nfft {nfft(longer.size):5d}): "
          f"difference {sparc(longer, FS) - base:+.1e}")

# %% [markdown]
# ## Sampled at 60 Hz
#
# The experiment records positions at 60 Hz, so the Nyquist frequency is 30 Hz and a movement of half a
# second has only 30 samples. That is enough: a smooth reaching movement has its energy below a few
# hertz, and the table of the minimum-jerk reference above shows 60 Hz values within a few thousandths
# of those at 1000 Hz. The short profiles do make the frequency grid coarse, which is why the padding
# matters.

# %%
for T in (0.3, 0.5, 1.0):
    v60, v1000 = (minimum_jerk_speed(np.arange(0, T, 1 / fs), 0, T) for fs in (60.0, 1000.0))
    print(f"T = {T} s: {v60.size:2d} samples at 60 Hz, SPARC {sparc(v60, 60.0):.4f} "
          f"(at 1000 Hz {sparc(v1000, 1000.0):.4f})")

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

# %% [markdown]
# For this book this means: the (PV, SPARC) clusters of the later chapters live in a range set by the
# contact as much as by intermittency; SPARC values should only be compared between trials recorded
# at the same rate, and even then differences of a few hundredths can be an effect of the sampling.

# %% [markdown]
# ## Which cut-off: the authors' 10 Hz or "0 to 20 Hz"?
#
# The KI 2020 paper says SPARC is computed "within the frequency range 0 to 20 Hz"; the authors' code
# uses a maximum cut-off $f_c$ = 10 Hz by default. With an adaptive cut-off, $f_c$ only matters when the
# spectrum is still above the threshold at $f_c$. Let us compute every profile of this chapter both ways.

# %%
clean = {**profiles, **{f"cut: {k}": v for k, v in cut.items() if k != "complete"},
         **{f"two, {d} s apart": movement([0, d]) for d in (0.6, 1.0)}}
table = pd.DataFrame({
    "cut-off (Hz), fc = 10": [sparc_spectrum(v, FS).cutoff for v in clean.values()],
    "SPARC, fc = 10 Hz": sparc_many(list(clean.values()), FS, fc=10.0),
    "SPARC, fc = 20 Hz": sparc_many(list(clean.values()), FS, fc=20.0)}, index=list(clean))
print(table.round(3))

# %% [markdown]
# For every noise-free profile, intermittent or truncated, the adaptive cut-off lies below 10 Hz and the
# two choices give the same value. Noise is another matter. Here are 200 noisy copies of the single
# submovement per noise level, each measured both ways:

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
print(pd.DataFrame(rows).T.rename_axis("noise (% of peak)").round(3))

# %% [markdown]
# Small noise changes nothing either way. Once the noise floor nears the threshold, a noise bump anywhere
# between 10 and 20 Hz that reaches it drags the band up to 20 Hz, two thirds of the Nyquist frequency,
# where differentiated position noise is strongest: with $f_c$ = 20 Hz SPARC falls further and more
# often than with 10 Hz. [](#fig-fc) shows the noisy copy (10 % noise) where the two differ most.

# %%
#| label: fig-fc
#| caption: "A copy of the submovement with speed noise of 10 % of its peak. With fc = 10 Hz (left) the band ends where the movement's spectrum fades below the threshold; with fc = 20 Hz (right) a noise bump between 10 and 20 Hz reaches the threshold and the band runs on through the noise."
fig, axes = plt.subplots(1, 2, figsize=(10, 3.2), sharey=True, layout="constrained")
for ax, fc in zip(axes, (10.0, 20.0)):
    plot_sparc_spectra({f"fc = {fc:g} Hz": sparc_spectrum(example, FS, fc=fc)}, ax=ax, fmax=30)

# %% [markdown]
# **The book uses the authors' defaults from here on**: $f_c$ = 10 Hz, amplitude threshold 0.05,
# padlevel 4, exported as `skilllib.smoothness.SPARC_PARAMS` so that every chapter and the pipeline use
# the same values. They are the parameters of the authors' published code and values; at 60 Hz the
# movement's own band ends below 10 Hz in every noise-free case above, so a wider maximum adds nothing
# but sensitivity to noise. Because the original recordings are not public, which cut-off the KI 2020
# authors actually ran cannot be checked; on noise-free profiles the two agree anyway.

# %%
print(dict(SPARC_PARAMS))

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

# %% [markdown]
# The same smooth movement gets values eight times larger at every doubling of its duration, and
# numbers that differ by $(2\pi)^3$ between Hz and rad/s (the cell above prints both ratios). For the
# drifting submovements the value mostly tracks the growing duration:

# %%
for d in (0.0, 0.3, 0.6, 1.0):
    v = movement([0, d])
    print(f"two submovements {d} s apart ({v.size / FS:.2f} s): SPARC {sparc(v, FS):.3f}, "
          f"squared version {squared_version(v, FS, 1.0):8.3f} (Hz)")

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
print(pd.DataFrame.from_dict(grid, orient="index").round(4))

# %% [markdown]
# In both readings the number depends on something other than the movement's shape (its duration and
# the unit of frequency, or the FFT grid), so neither can rank movements by smoothness. The definition,
# and the authors' code, have the square root; so does this book.

# %% [markdown]
# ## LDLJ beside SPARC
#
# The other established smoothness measure is the log dimensionless jerk (Balasubramanian et al.
# 2015), computed in the time domain from the second derivative of speed:
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

# %% [markdown]
# The difference is how they treat noise. A second derivative multiplies each frequency component by
# $(2\pi f)^2$, so the jerk integral is dominated by the noise at the highest frequencies, up to
# Nyquist. SPARC never looks past its cut-off. To compare two measures on different scales, [](#fig-noise)
# divides each one's change by the change it shows for real intermittency: one submovement against two,
# 0.5 s apart. With speed noise of 1 % of the peak, LDLJ has already moved by two thirds of that amount,
# at 3 % by more than all of it; SPARC changes by less than 0.01 up to 3 % noise, and at 10 % by less
# than a fifth of the change a second submovement makes.

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
# - The book uses the authors' parameters, $f_c$ = 10 Hz, threshold 0.05, padlevel 4 (`SPARC_PARAMS`).
#   At 60 Hz they give the same values as a 20 Hz maximum on noise-free profiles and are less
#   sensitive to noise.
# - The squared integrand printed in the KI 2020 paper can only be a typesetting slip: as an integral
#   it scales with the cube of the duration and with the frequency unit, as a sum with the FFT grid.
# - LDLJ measures the same intermittency but collapses with small amounts of measurement noise; SPARC
#   does not.
