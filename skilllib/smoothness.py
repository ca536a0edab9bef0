"""Movement smoothness: SPARC and LDLJ (Balasubramanian et al. 2015).

Placeholder core; the full module (spectrum companion, batched version, LDLJ, validation)
is being written in issue 3.
"""
from __future__ import annotations

import numpy as np


def sparc(speed, fs: float, fc: float = 10.0, amp_th: float = 0.05, padlevel: int = 4) -> float:
    """Spectral arc length of a speed profile (m/s) sampled at ``fs`` Hz."""
    v = np.asarray(speed, dtype=float)
    nfft = int(2 ** (np.ceil(np.log2(len(v))) + padlevel))
    f = np.arange(0, fs, fs / nfft)
    mf = np.abs(np.fft.fft(v, nfft))
    mf = mf / mf.max()
    keep = f <= fc
    f_sel, mf_sel = f[keep], mf[keep]
    idx = np.nonzero(mf_sel >= amp_th)[0]
    f_sel, mf_sel = f_sel[idx[0] : idx[-1] + 1], mf_sel[idx[0] : idx[-1] + 1]
    return float(-np.sum(np.sqrt((np.diff(f_sel) / (f_sel[-1] - f_sel[0])) ** 2 + np.diff(mf_sel) ** 2)))
