"""A marker template filled from each file's name (issue 24, item 2): ``marker="{hand}FTP"`` reads ``RFTP``
in the files of right-hand reaches and ``LFTP`` in the others.

Real files: two Vicon Nexus exports of the UE ADL database's forward reach (``data/real``), one with each
hand, copied into a temporary folder under other names.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from skilllib.recordings import DataFormatError, load_recordings, read_any, read_nexus

ADL = Path(__file__).resolve().parents[2] / "data" / "real" / "ue-adl-forward-reach"
OPTS = dict(up_axis="z", contact_height=-1.0)
PATTERN = r"(?P<participant>P\d+)_(?P<trial>(?P<hand>[LR])_\d)"


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    """``P01_L_1.csv.gz`` (ADL001FL1: the left hand reaches) and ``P01_R_2.csv.gz`` (ADL001FR1: the right)."""
    root = tmp_path / "adl"
    root.mkdir()
    shutil.copy(ADL / "ADL001FL1.csv.gz", root / "P01_L_1.csv.gz")
    shutil.copy(ADL / "ADL001FR1.csv.gz", root / "P01_R_2.csv.gz")
    return root


def _moving(rec, key) -> float:
    return float(np.ptp(rec.trial(*key).pos, axis=0).max())


def test_template_reads_the_moving_hand_of_each_file(folder):
    rec = load_recordings(folder, marker="{hand}FTP", name_pattern=PATTERN, **OPTS)
    assert rec.keys() == [("P01", "L_1"), ("P01", "R_2")]
    assert (rec.trials["status"] == "ok").all()
    for key, (name, hand) in zip(rec.keys(), [("P01_L_1", "L"), ("P01_R_2", "R")]):
        want = read_nexus(folder / f"{name}.csv.gz", marker=f"{hand}FTP")
        # up_axis z -> y: the book's (x, y, z) are the lab's (x, z, -y)
        np.testing.assert_allclose(rec.trial(*key).pos[:, 1], want["z"].to_numpy(), rtol=1e-12)
        assert _moving(rec, key) > 0.2  # the reaching fingertip moves about 0.24-0.27 m
    other = load_recordings(folder, marker="LFTP", name_pattern=PATTERN, **OPTS)
    assert _moving(other, ("P01", "R_2")) < 0.01  # the left fingertip of the right-hand reach stays still


def test_template_with_the_database_names_and_nested_groups(tmp_path):
    root = tmp_path / "adl"
    root.mkdir()
    for name in ("ADL001FL1", "ADL001FR1"):
        shutil.copy(ADL / f"{name}.csv.gz", root / f"{name}.csv.gz")
    rec = load_recordings(
        root, marker="{hand}FTP", name_pattern=r"(?P<participant>ADL\d+)F(?P<trial>(?P<hand>[LR])\d)", **OPTS
    )
    assert rec.keys() == [("ADL001", "L1"), ("ADL001", "R1")]
    assert min(_moving(rec, k) for k in rec.keys()) > 0.2


def test_a_field_the_pattern_does_not_have_is_one_clear_error(folder):
    with pytest.raises(
        DataFormatError,
        match=r"marker template '\{side\}FTP' names the field 'side', which the name pattern .* does not give "
        r"\(groups: participant, trial, hand\)",
    ):
        load_recordings(folder, marker="{side}FTP", name_pattern=PATTERN, **OPTS)
    with pytest.raises(DataFormatError, match=r"the file naming rule does not give \(groups: participant, trial\)"):
        read_any(folder, marker="{hand}FTP", **OPTS)
    with pytest.raises(DataFormatError, match=r"marker template '\{hand' cannot be read"):
        load_recordings(folder, marker="{hand", name_pattern=PATTERN, **OPTS)
    with pytest.raises(DataFormatError, match=r"\{0\} is not a group name"):
        load_recordings(folder, marker="{0}FTP", name_pattern=PATTERN, **OPTS)


def test_template_fields_participant_and_trial_without_a_pattern(tmp_path):
    root = tmp_path / "adl"
    root.mkdir()
    shutil.copy(ADL / "ADL001FR1.csv.gz", root / "P01_R.csv.gz")  # naming rule: participant P01, trial R
    rec = load_recordings(root, marker="{trial}FTP", **OPTS)
    assert rec.keys() == [("P01", "R")] and _moving(rec, ("P01", "R")) > 0.2


def test_a_group_not_taking_part_in_a_match_makes_that_file_invalid(folder):
    shutil.copy(ADL / "ADL001FR1.csv.gz", folder / "P01_X_3.csv.gz")
    pattern = r"(?P<participant>P\d+)_(?P<trial>(?:(?P<hand>[LR])|X)_\d)"
    rec = load_recordings(folder, marker="{hand}FTP", name_pattern=pattern, **OPTS)
    t = rec.trials.set_index("trial")
    assert t.loc["L_1", "status"] == "ok" and t.loc["R_2", "status"] == "ok"
    assert t.loc["X_3", "status"] == "invalid"
    assert "the name gives no 'hand' for the marker template '{hand}FTP'" in t.loc["X_3", "reason"]


def test_template_for_a_single_file(folder):
    path = folder / "P01_R_2.csv.gz"
    rec = load_recordings(path, marker="{hand}FTP", name_pattern=PATTERN, **OPTS)
    assert rec.keys() == [("P01", "R_2")] and _moving(rec, rec.keys()[0]) > 0.2
    with pytest.raises(DataFormatError, match=r"names the field 'hand', which the file naming rule does not give"):
        load_recordings(path, marker="{hand}FTP", **OPTS)
    rec = load_recordings(path, marker="RFTP", **OPTS)  # a plain name as before
    assert _moving(rec, rec.keys()[0]) > 0.2
