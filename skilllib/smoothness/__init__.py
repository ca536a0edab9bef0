"""Smoothness of a speed profile: SPARC and LDLJ (Balasubramanian et al. 2015), the paper's Eq. (1).

:func:`sparc` (one profile), :func:`sparc_many` (many at once, batch-invariant), :func:`sparc_bands`
(with how each band ended), :func:`sparc_spectrum` (the spectrum behind it), :func:`ldlj`; the
minimum-jerk profile the chapters and the cohort use (:func:`minimum_jerk_speed`); generated
profiles and measurements of the SPARC chapters (private ``_profiles``: :func:`minimum_jerk_submovements`,
:func:`cut_at_contact`, :func:`noisy_copies`, ...). The numerical core
(zero-padded real FFT, the adaptive band, the arc length) is the private ``_spectral``.
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_measures": [
            "DEFAULT_AMP_TH",
            "DEFAULT_FC",
            "DEFAULT_PADLEVEL",
            "ldlj",
            "ldlj_many",
            "ldlj_rows",
            "minimum_jerk_segment",
            "minimum_jerk_speed",
            "nfft",
            "sparc",
            "sparc_bands",
            "SparcBands",
            "sparc_many",
            "SPARC_PARAMS",
            "sparc_spectrum",
            "SparcSpectrum",
        ],
        "_profiles": [
            "cut_at_contact",
            "minimum_jerk_submovements",
            "noisy_copies",
            "sparc_squared_integral",
            "sparc_squared_sum",
            "speed_dip",
            "stable_from",
        ],
        "_spectral": ["single_threaded"],
    },
)
