"""The numerical core of :mod:`skilllib.smoothness` (private): input checks, the authors' frequency
grid, the band and its arc length, and the batched spectra behind ``sparc_many`` and ``sparc_bands``.

Short profiles get a direct DFT of the kept bins only (matrix products about the centre of the
samples), long ones batched FFTs; both share :func:`_band` and :func:`_arc_length`, which implement
the discrete SPARC sum of the book's chapter 1 (eq-sparc-sum).
"""

from __future__ import annotations

import contextlib
import math
import sys
from collections.abc import Iterator, Sequence
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

try:  # installed with scikit-learn
    from threadpoolctl import ThreadpoolController
except ImportError:  # pragma: no cover
    ThreadpoolController = None

_CHUNK = 65536  # profiles packed at a time in the *_many functions (bounds memory)
_CACHE_ELEMENTS = 2**15  # rows x bins per spectral batch: temporaries stay small (cache, no mmap)
_DFT_FACTOR = 3.0  # direct DFT when L * n_bins < _DFT_FACTOR * nfft * log2(nfft) (measured crossover)


# --- input checks ------------------------------------------------------------------------------


def _check_fs(fs: float) -> float:
    fs = float(fs)  # Hz
    if not (np.isfinite(fs) and fs > 0):
        raise ValueError(f"fs must be a finite sampling frequency > 0 Hz; got {fs}")
    return fs


def _check_params(fc: float, amp_th: float, padlevel: float, fs: float) -> None:
    """ValueError for a bad parameter. fc must not exceed the Nyquist frequency fs / 2: the authors' code
    would then run the band into the mirror image of the spectrum (bins between fs / 2 and fs), which
    belongs to no frequency of the movement."""
    if not float(fc) >= 0:  # also catches NaN
        raise ValueError(f"fc must be a cut-off frequency >= 0 Hz; got {fc}")
    if fc > fs / 2:
        raise ValueError(
            f"fc = {fc:g} Hz lies above the Nyquist frequency {fs / 2:g} Hz of samples at {fs:g} Hz "
            f"(the band would run into the mirror image of the spectrum); use fc <= {fs / 2:g} Hz"
        )
    if not np.isfinite(amp_th):
        raise ValueError(f"amp_th must be a finite amplitude threshold; got {amp_th}")
    if not np.isfinite(padlevel):
        raise ValueError(f"padlevel must be finite; got {padlevel}")


def _as_speed(speed: ArrayLike, what: str = "speed", min_len: int = 1) -> np.ndarray:
    """``speed`` as a 1-D float array (m/s); ValueError naming the problem otherwise."""
    try:
        v = np.asarray(speed, dtype=float)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{what} must be a 1-D array of numbers (m/s): {err}") from None
    if v.ndim != 1:
        raise ValueError(f"{what} must be 1-D (one speed profile, m/s); got shape {v.shape}")
    if v.size == 0:
        raise ValueError(f"{what} is empty: no samples")
    bad = np.flatnonzero(~np.isfinite(v))
    if bad.size:
        raise ValueError(f"{what} contains NaN or infinite values (first at sample {bad[0]})")
    if v.size < min_len:
        raise ValueError(f"{what} has {v.size} samples; at least {min_len} needed")
    if not np.any(v):
        raise ValueError(f"{what} is zero everywhere: no movement, its spectrum cannot be normalised")
    return v


# --- the frequency grid --------------------------------------------------------------------------


def _nffts(n: np.ndarray, padlevel: float) -> np.ndarray:
    out = np.power(2.0, np.ceil(np.log2(n)) + padlevel).astype(np.int64)
    if np.any(out < 1):
        raise ValueError(f"padlevel {padlevel} gives nfft < 1 for {np.min(n)} samples")
    return out


def frequencies(n_fft: int, fs: float) -> np.ndarray:
    """The authors' frequency grid (Hz): ``arange(0, fs, fs/nfft)``, bin k at k fs / nfft."""
    return np.arange(0, fs, fs / n_fft)


def _n_kept(f: np.ndarray, fc: float) -> int:
    """Number of bins with f <= fc (a prefix of the grid; fc <= fs / 2 keeps it within the grid)."""
    return int(np.searchsorted(f, fc, side="right"))


# --- band and arc length (shared by every path) ----------------------------------------------------


def _band(above: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """First and last bin of each row of ``above`` (rows x bins <= fc: magnitude >= amp_th).

    The last one is the adaptive cut-off omega_c. Returns (first, last, ok); ok is False for rows
    with no bin at or above the threshold."""
    first = above.argmax(axis=1)
    last = above.shape[1] - 1 - above[:, ::-1].argmax(axis=1)
    return first, last, above[np.arange(len(first)), first]


def _arc_length(A: np.ndarray, peak: np.ndarray, first: np.ndarray, last: np.ndarray) -> np.ndarray:
    """Arc length of each row's normalised spectrum Mf = A / peak over its band [first, last].

    The discrete SPARC integral (chapter 1, eq-sparc-sum): sum_k sqrt(du**2 + dMf_k**2), u = (f - f_first) /
    (f_last - f_first); the bins are equally spaced, so du = 1 / (last - first). Computed as
    sum_k sqrt((peak du)**2 + dA_k**2) / peak. A band of one bin has an empty sum (0), as in the
    authors' code. ``A``: the bins up to fc (at least up to max(last)); every row is summed over all of its
    columns (outside the band with weight zero), so its value depends on its own samples only."""
    n = last - first
    k_end = A.shape[1]  # all columns given, so that a row's sum does not depend on the other rows' bands
    terms = A[:, 1:k_end] - A[:, : k_end - 1]
    terms *= terms
    terms += (peak / np.maximum(n, 1))[:, None] ** 2
    np.sqrt(terms, out=terms)
    k = np.arange(k_end - 1)
    inside = k < last[:, None]
    if first.any():
        inside &= k >= first[:, None]
    return terms.sum(axis=1, where=inside) / peak


# --- many profiles, batched ---------------------------------------------------------------------------------


def _pack(block: Sequence[ArrayLike], start: int, min_len: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Concatenate a block of 1-D profiles: (flat values followed by one 0.0, lengths).

    ValueError names the index of a bad profile."""
    try:
        lengths = np.fromiter(map(len, block), dtype=np.int64, count=len(block))
        flat = np.concatenate([*block, [0.0]], dtype=float)
        ok = flat.ndim == 1 and flat.size == lengths.sum() + 1
    except (TypeError, ValueError):
        ok = False
    if not ok:  # find and name the offending profile (error path only)
        for i, x in enumerate(block):
            _as_speed(x, f"speeds[{start + i}]", min_len)
        raise ValueError("speeds must be a sequence of 1-D speed profiles (m/s)")
    short = np.flatnonzero(lengths < min_len)
    if short.size:
        _as_speed(block[short[0]], f"speeds[{start + short[0]}]", min_len)
    bad = np.flatnonzero(~np.isfinite(flat))
    if bad.size:
        i = int(np.searchsorted(np.cumsum(lengths), bad[0], side="right"))
        _as_speed(block[i], f"speeds[{start + i}]", min_len)
    return flat, lengths


def _blocks(speeds: Sequence[ArrayLike] | np.ndarray):
    """Yield (start, block) over ``speeds`` in blocks of _CHUNK profiles."""
    if not isinstance(speeds, (Sequence, np.ndarray)):
        speeds = list(speeds)
    for start in range(0, len(speeds), _CHUNK):
        yield start, speeds[start : start + _CHUNK]


@lru_cache(maxsize=32)
def _dft_matrices(n_fft: int, L: int, k: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of omega_k m_j for bins k' < k and the first ceil(L/2) samples j, with the time
    origin at the centre of the L samples (m_j = j - (L-1)/2), phases reduced in integers."""
    j = np.arange((L + 1) // 2)
    r = np.outer(2 * j - (L - 1), np.arange(k)) % (2 * n_fft)  # omega_k m_j = pi r / nfft
    phase = (np.pi / n_fft) * r
    C, S = np.cos(phase), np.sin(phase[: L // 2])
    C.setflags(write=False)
    S.setflags(write=False)
    return C, S


def _power(P: np.ndarray, n_fft: int, k: int, signed: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """|X|**2 of the rows of P (zero padded to nfft) at bins 0..k-1, and its maximum over the whole
    spectrum; ``signed`` flags rows with negative values.

    Short profiles: a direct DFT of the kept bins only, about the centre of the L samples, where
    sum_j v_j e^{-i w m_j} = sum (v_j + v_-j) cos(w m_j) - i sum (v_j - v_-j) sin(w m_j) halves the
    work; |X| does not depend on the time origin. Long profiles: batched FFTs."""
    L = P.shape[1]
    if L * k < _DFT_FACTOR * n_fft * math.log2(max(n_fft, 2)):
        C, S = _dft_matrices(n_fft, L, k)
        h, R = L // 2, P[:, ::-1]
        even = P[:, : C.shape[0]] + R[:, : C.shape[0]]
        if L % 2:
            even[:, h] = P[:, h]  # the centre sample, m = 0, counted once
        # einsum's own loops, not BLAS: BLAS rounds a row differently with the number of rows beside it
        A2 = np.square(np.einsum("rj,jk->rk", even, C))
        if h:
            A2 += np.square(np.einsum("rj,jk->rk", P[:, :h] - R[:, :h], S))
        peak2 = A2[:, 0].copy()  # for v >= 0 the DC bin is the maximum
        if signed.any():
            X = np.fft.rfft(P[signed], n_fft, axis=1)
            peak2[signed] = (X.real**2 + X.imag**2).max(axis=1)
        return A2, peak2
    # the whole spectrum only when the band passes Nyquist
    X = np.fft.rfft(P, n_fft, axis=1) if k <= n_fft // 2 + 1 else np.fft.fft(P, n_fft, axis=1)
    A2 = X.real**2 + X.imag**2
    return A2[:, :k].copy(), A2.max(axis=1)


def _sparc_block(
    flat: np.ndarray,
    lengths: np.ndarray,
    start: int,
    fs: float,
    fc: float,
    amp_th: float,
    padlevel: float,
    bands: bool = False,
) -> np.ndarray:
    """SPARC of each profile of one packed block: grouped by nfft, in row batches that fit in cache.

    Returns (n, 3): SPARC, band end (Hz) and capped (1.0 / 0.0); the last two only when ``bands`` (else
    NaN), since the capped test needs the bins above fc up to Nyquist as well. The threshold test
    Mf >= amp_th is made on squares, |X|**2 >= (amp_th * peak)**2, so that square roots are taken only
    inside the bands."""
    out = np.full((lengths.size, 3), np.nan)
    offsets = np.cumsum(lengths) - lengths
    n_ffts = _nffts(lengths, padlevel)
    scale = np.maximum.reduceat(np.abs(flat[:-1]), offsets)  # SPARC is amplitude invariant
    zero = np.flatnonzero(scale == 0)
    if zero.size:
        raise ValueError(f"speeds[{start + zero[0]}] is zero everywhere: no movement, no spectrum to normalise")
    signed = np.minimum.reduceat(flat[:-1], offsets) < 0
    th2 = amp_th**2 if amp_th > 0 else -np.inf
    # grouped by nfft and length: a profile's value then depends on its own samples only, not on which
    # other profiles share its batch (the partitions of skilllib.features give the in-memory values)
    for n_fft, length in map(tuple, np.unique(np.column_stack([n_ffts, lengths]), axis=0).tolist()):
        group = np.flatnonzero((n_ffts == n_fft) & (lengths == length))
        L = int(min(length, n_fft))  # np.fft.fft(v, nfft) crops when nfft < N
        col = np.arange(L)
        f = frequencies(n_fft, fs)
        k = _n_kept(f, fc)
        k_eval = n_fft // 2 + 1 if bands else k  # up to Nyquist for the capped test (k <= that)
        step = max(8, _CACHE_ELEMENTS // max(k_eval, L))
        for rows in (group[i : i + step] for i in range(0, group.size, step)):
            idx = np.where(col < lengths[rows, None], offsets[rows, None] + col, flat.size - 1)
            P = flat[idx]  # flat ends with a 0.0 (see _pack): the zero padding
            P /= scale[rows, None]
            A2, peak2 = _power(P, n_fft, k_eval, signed[rows])
            reach = A2 >= (th2 * peak2)[:, None]
            first, last, ok = _band(reach[:, :k])
            bad = ~ok | (peak2 == 0)
            if bad.any():
                j = int(np.argmax(bad))
                raise ValueError(
                    f"speeds[{start + rows[j]}] is zero over its first nfft = {n_fft} samples: no spectrum to normalise"
                    if peak2[j] == 0
                    else f"speeds[{start + rows[j]}]: "
                    f"no spectral magnitude at or above amp_th = {amp_th} up to fc = {fc} Hz"
                )
            A = np.sqrt(A2[:, :k])
            out[rows, 0] = -_arc_length(A, np.sqrt(peak2), first, last) + 0.0
            if bands:
                out[rows, 1] = f[last]
                out[rows, 2] = reach[:, k:].any(axis=1)
    return out


_controller: tuple[int, ThreadpoolController] | None = None  # (len(sys.modules) when made, controller)


def _thread_pools() -> ThreadpoolController | None:
    """threadpoolctl's view of the loaded thread pools (None without threadpoolctl). It lists only the
    libraries loaded when it is made (scikit-learn brings its OpenMP, SciPy its own BLAS), so it is made
    again once more modules have been imported (0.5 ms), and otherwise reused."""
    global _controller
    if ThreadpoolController is None:  # pragma: no cover
        return None
    if _controller is None or _controller[0] != len(sys.modules):
        _controller = (len(sys.modules), ThreadpoolController())
    return _controller[1]


@contextlib.contextmanager
def single_threaded(user_api: str | None = None) -> Iterator[None]:
    """Limit the thread pools to one thread while inside; the limits are restored on leaving.

    A context manager and, as ``@single_threaded()``, a decorator (the pools are looked up at each call).
    Without threadpoolctl (installed with scikit-learn) it does nothing.

    Small problems gain nothing from threads and lose badly when the cores are busy: SPARC's batched
    matrix products 3x on two cores (BLAS), K-means on a few hundred points 0.55 s vs 7.8 s on two loaded
    cores (OpenMP); on 68,000 points 2 threads moved K-means centres by 1e-15 (the order of an OpenMP
    reduction), so one thread is also reproducible.

    Parameters
    ----------
    user_api : str or None
        The pools to limit (text): ``"blas"``, ``"openmp"``, or None for both.

    Returns
    -------
    contextlib.AbstractContextManager
        A context manager (also usable as a decorator) that yields None.
    """
    pools = _thread_pools()
    if pools is None:  # pragma: no cover
        yield
        return
    with pools.limit(limits=1, user_api=user_api):
        yield
