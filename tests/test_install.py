"""A real install: the wheel of this checkout in a fresh virtual environment runs the default pipeline
from another folder (issue 12). Slow (a wheel build and a venv); the dependencies are not downloaded:
the fresh environment sees this project's site-packages through a path file, which does not run the
editable install's finder, so ``skilllib`` itself can only come from the installed wheel."""

from __future__ import annotations

import json
import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

import pytest

import skilllib

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    tmp = tmp_path_factory.mktemp("install")
    wheels = tmp / "wheels"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--quiet",
            "--no-deps",
            "--no-build-isolation",
            "--wheel-dir",
            str(wheels),
            str(ROOT),
        ],
        check=True,
        capture_output=True,
    )
    env_dir = tmp / "venv"
    venv.EnvBuilder(with_pip=False).create(env_dir)  # this pip installs into it (--python)
    py = env_dir / "bin" / "python"
    site = subprocess.run(
        [str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    (Path(site) / "deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")  # numpy, pandas, ... only
    wheel = next(wheels.glob("skilllib-*.whl"))
    subprocess.run(
        [sys.executable, "-m", "pip", "--python", str(py), "install", "--quiet", "--no-deps", "--no-index", str(wheel)],
        check=True,
        capture_output=True,
    )
    return env_dir


@pytest.mark.slow
def test_the_wheel_runs_the_default_pipeline_from_another_folder(installed, tmp_path):
    py = installed / "bin" / "python"
    where = subprocess.run(
        [str(py), "-c", "import skilllib; print(skilllib.__file__, skilllib.__version__)"],
        cwd=tmp_path,
        check=True,
        capture_output=True,
        text=True,
    ).stdout.split()
    assert Path(where[0]).is_relative_to(installed) and where[1] == skilllib.__version__
    out = tmp_path / "results"
    done = subprocess.run(
        [str(installed / "bin" / "skilllib"), "run", "--out", str(out), "--no-figures"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    res = json.loads((out / "results.json").read_text())
    assert res["dataset"]["n_trials"] == 1500 and res["n_selected"] > 600 and res["skilllib_version"] == where[1]
    version = subprocess.run([str(py), "-m", "skilllib", "--version"], cwd=tmp_path, capture_output=True, text=True)
    assert version.stdout.strip() == f"skilllib {skilllib.__version__}"


@pytest.mark.slow
def test_the_wheel_ships_the_license_the_types_marker_and_the_cohort(installed):
    site = next((installed / "lib").glob("python3*/site-packages"))
    dist = next(site.glob("skilllib-*.dist-info"))
    assert "BSD" in (dist / "licenses" / "LICENSE").read_text()
    meta = (dist / "METADATA").read_text()
    assert "License-Expression: BSD-3-Clause" in meta and "Requires-Dist: roboticstoolbox-python" in meta
    assert (site / "skilllib" / "py.typed").exists()
    shipped = site / "skilllib" / "datasets" / "cohort.csv"
    assert shipped.read_bytes() == (ROOT / "data" / "cohort.csv").read_bytes()
