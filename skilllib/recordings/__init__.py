"""Every input, read as labs write it, becomes one validated :class:`Recordings`.

The one door is :func:`load_recordings` (a CSV, a Parquet file or folder, a C3D or TRC file, a folder of
one-trial files, or a DataFrame; column names, units and the vertical axis mapped on the way). Behind it:
the long table and its checks (``_recordings``, ``_checks``), CSV text cells with their lines (``_csv``),
Parquet (``_parquet``), C3D (``_c3d``), TRC (``_trc``), Vicon Nexus CSV exports (``_nexus``), folders of
trials (``_folder``), the mapping to the book's frame (``_mapping``) and time stamps (``_timing``: the rate,
jitter, dropped frames, gaps).
Problems with a file raise :class:`DataFormatError`; problems with a trial mark it ``invalid``.
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_c3d": ["c3d_events", "read_c3d"],
        "_columns": ["COLUMNS", "ID_COLUMNS", "POSITION_COLUMNS"],
        "_cut": ["cut_trials", "piece_name"],
        "_checks": [
            "check_corpus_units",
            "corpus_rate",
            "MAX_KNOWN_RANGE_M",
            "MAX_RANGE_M",
            "MAX_TYPICAL_SPEED",
            "MIN_SAMPLES",
        ],
        "_csv": ["detect_sep", "file_ids", "parse_sep", "read_table", "record_lines", "SEPARATORS"],
        "_defects": [
            "FILL_METHODS",
            "frozen_samples",
            "gap_runs",
            "jump_samples",
            "MAX_ACCELERATION",
            "MAX_GAP_S",
            "Repair",
            "repair_trial",
            "stale_leading",
        ],
        "_errors": ["DataFormatError", "MAX_QUOTE", "quote"],
        "_folder": ["FileProblem", "read_folder", "SkippedFile"],
        "_load": ["load_recordings", "read_any", "read_csv_table", "single_file_ids"],
        "_mapping": [
            "contact_from_height",
            "map_frame",
            "parse_columns",
            "TIME_UNIT_FACTORS",
            "UNIT_FACTORS",
            "up_axis_rotation",
            "UP_AXIS_ROTATIONS",
        ],
        "_nexus": ["is_nexus", "NEXUS_SECTIONS", "read_nexus"],
        "_parquet": ["is_parquet", "parquet_files", "read_parquet"],
        "_recordings": [
            "EVENT_COLUMNS",
            "events_frame",
            "format_recordings",
            "natural_key",
            "read_recordings",
            "Recordings",
            "recordings_from_frame",
            "sort_ids",
            "write_recordings",
        ],
        "_runs": ["first_true", "Runs"],
        "_timing": [
            "gap_after_contact",
            "grid_jitter",
            "Irregularity",
            "irregularity",
            "JITTER_TOLERANCE",
            "MAX_GAP_INTERVALS",
            "MIN_RATE_HZ",
            "MIXED_FRACTION",
            "RATE_TOLERANCE",
            "REGULAR_JITTER",
            "regular_mean_interval",
            "resample_uniform",
            "time_quantum",
            "time_unit_advice",
            "TRIM",
        ],
        "_trc": ["read_trc", "write_trc"],
    },
)
