"""The command line as Unix tools behave (issue 12): a light start-up, progress only on a terminal, an output
folder replaced as a whole (never mixed, never left half-written, never shared by two runs), bad options as
exit 2, Ctrl-C as exit 130 at any point, a closed stdout ending quietly."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

import skilllib
from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import trial_features
from skilllib.pipeline import MANIFEST, RUN_FILES, OutputError, main, output_folder
from skilllib.pipeline import _run as pipeline
from skilllib.prototypes import _kmeans as pt
from skilllib.recordings import recordings_from_frame, write_recordings

HEAVY = ("pandas", "sklearn", "roboticstoolbox", "matplotlib", "scipy")


@pytest.fixture(scope="module")
def small_file(tmp_path_factory) -> Path:
    """A file whose run is quick: 6 trials, one of them selected, so that the run stops before clustering
    (exit 3) after reading, features, results.json and the data figures: what these tests are about."""
    frame = generate_cohort(7, CohortModel(n_participants=2, n_trials=8, fs=100.0)).frame
    f = trial_features(recordings_from_frame(frame))
    keep = pd.concat([f[f.status == "selected"].head(1), f[f.status != "selected"].head(5)])
    frame = frame.merge(keep[["participant", "trial"]])
    assert (trial_features(recordings_from_frame(frame)).status == "selected").sum() == 1
    return write_recordings(frame, tmp_path_factory.mktemp("cli") / "rec.csv")


DONE = 3  # the exit status of a run on small_file: finished, too few selected trials for prototypes


def _run(capsys, *args: str) -> tuple[int, str, str]:
    code = main(["run", "--quiet", *args])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def _python(*args: str, **kw) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, timeout=600, **kw)


# --- start-up ----------------------------------------------------------------------------------------


@pytest.mark.slow  # a subprocess: left out of mutation testing (it would not see the mutant)
@pytest.mark.parametrize("argv", [["--help"], ["run", "--help"], ["--version"]])
def test_help_and_version_import_none_of_the_heavy_libraries(argv):
    """What makes --help take seconds is importing pandas, scikit-learn, roboticstoolbox, matplotlib or
    scipy; none of them may be imported for --help or --version (the time itself is a benchmark,
    benchmarks/bench_cli.py, not a test)."""
    code = (
        "import sys, runpy; sys.argv = ['skilllib', *sys.argv[1:]]\n"
        "try:\n    runpy.run_module('skilllib', run_name='__main__')\nexcept SystemExit:\n    pass\n"
        f"print('HEAVY', sorted(m for m in {HEAVY!r} if m in sys.modules))"
    )
    proc = _python("-c", code, *argv)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip().splitlines()[-1] == "HEAVY []"
    if argv == ["--version"]:
        assert proc.stdout.splitlines()[0] == f"skilllib {skilllib.__version__}"


def test_the_cli_default_k_is_the_papers():
    from skilllib.pipeline._cli import _parser
    from skilllib.pipeline._run import resolve_task

    args = _parser().parse_args(["run", "--out", "o"])
    assert args.k is None  # not given: the task's (here the paper's) k
    assert resolve_task(args.task, k=args.k).k == pt.DEFAULT_K == 6  # the paper's six clusters


# --- progress bars only on a terminal ----------------------------------------------------------------


@pytest.mark.slow  # a subprocess: left out of mutation testing (it would not see the mutant)
def test_no_progress_bars_when_stderr_is_not_a_terminal(tmp_path, small_file):
    proc = _python("-m", "skilllib", "run", "--data", str(small_file), "--out", str(tmp_path / "o"), "--no-figures")
    assert proc.returncode == DONE, proc.stderr
    assert proc.stderr == ""  # tqdm would write "features: 100%|..." with carriage returns


@pytest.mark.slow  # a subprocess: left out of mutation testing (it would not see the mutant)
def test_progress_bars_on_a_terminal(tmp_path, small_file):
    """With stderr on a pseudo-terminal the long steps show their bars (and --quiet hides them)."""
    import fcntl
    import pty
    import struct
    import termios

    def run_on_pty(*extra: str) -> str:
        leader, follower = pty.openpty()
        fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a 100-column terminal
        proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "skilllib",
                "run",
                "--data",
                str(small_file),
                "--out",
                str(tmp_path / f"o{len(extra)}"),
                "--no-figures",
                *extra,
            ],
            stdout=subprocess.DEVNULL,
            stderr=follower,
            close_fds=True,
        )
        os.close(follower)
        chunks = []
        while True:
            try:
                data = os.read(leader, 4096)
            except OSError:
                break
            if not data:
                break
            chunks.append(data)
        proc.wait(timeout=600)
        os.close(leader)
        return b"".join(chunks).decode(errors="replace")

    shown = run_on_pty()
    assert "features" in shown and " trial/s" in shown and "\r" in shown
    assert run_on_pty("--quiet") == ""


# --- the output folder -------------------------------------------------------------------------------


def test_a_reused_out_keeps_no_figure_of_the_earlier_run(tmp_path, capsys, small_file):
    out = tmp_path / "o"
    assert _run(capsys, "--data", str(small_file), "--out", str(out))[0] == DONE
    figures = set(json.loads((out / "results.json").read_text())["figures"])
    assert figures and all((out / f).exists() for f in figures)
    assert _run(capsys, "--data", str(small_file), "--out", str(out), "--no-figures")[0] == DONE
    assert {p.name for p in out.iterdir()} == {"results.json", MANIFEST}
    assert not list(tmp_path.glob(".o.partial-*")) and not list(tmp_path.glob(".o.old-*"))


def test_a_failed_run_leaves_the_earlier_results_as_they_were(tmp_path, capsys, small_file, monkeypatch):
    out = tmp_path / "o"
    assert _run(capsys, "--data", str(small_file), "--out", str(out), "--no-figures")[0] == DONE
    before = (out / "results.json").read_bytes()

    def broken(*args, **kwargs):
        raise RuntimeError("a figure could not be drawn")

    monkeypatch.setattr(pipeline, "_write_figures", broken)
    code, _, err = _run(capsys, "--data", str(small_file), "--out", str(out), "--k", "3")
    assert code == 1 and "a figure could not be drawn" in err
    assert (out / "results.json").read_bytes() == before  # not a half-written new one, not a mix
    assert not list(tmp_path.glob(".o.partial-*"))


def test_a_folder_with_other_files_is_refused_and_left_alone(tmp_path, capsys, small_file):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("do not delete")
    code, _, err = _run(capsys, "--data", str(small_file), "--out", str(out))
    assert code == 2 and "thesis.tex" in err and "did not write" in err
    assert (out / "thesis.tex").read_text() == "do not delete"


def test_what_a_run_writes_is_all_that_a_run_may_replace(tmp_path):
    """A folder a run wrote (its manifest lists every file) is replaced; one more file, and it is not."""
    out = tmp_path / "o"
    with output_folder(out) as fresh:
        for name in ("results.json", "a.png", *RUN_FILES[1:]):
            (fresh / name).write_bytes(b"x")
    assert json.loads((out / MANIFEST).read_text())["files"] == sorted(["results.json", "a.png", *RUN_FILES[1:]])
    with output_folder(out) as fresh:
        (fresh / "results.json").write_text("{}")
    assert {p.name for p in out.iterdir()} == {"results.json", MANIFEST}
    (out / "b.png").write_bytes(b"x")
    with pytest.raises(OutputError, match="b.png"), output_folder(out):
        pass


def test_another_tools_results_json_never_makes_a_folder_a_runs(tmp_path, capsys, small_file):
    """Issue 23: a results.json whose ``figures`` list names the user's thesis made the folder look like
    a run's, and the run deleted the thesis. Without the run's manifest nothing in a folder is a run's."""
    out = tmp_path / "d"
    out.mkdir()
    (out / "results.json").write_text(json.dumps({"figures": ["thesis.docx"]}))
    (out / "thesis.docx").write_text("years of work")
    code, _, err = _run(capsys, "--data", str(small_file), "--out", str(out), "--no-figures")
    assert code == 2 and "did not write" in err and "thesis.docx" in err
    assert (out / "thesis.docx").read_text() == "years of work"
    (out / "thesis.docx").unlink()  # another tool's results.json alone: refused too
    code, _, err = _run(capsys, "--data", str(small_file), "--out", str(out), "--no-figures")
    assert code == 2 and "results.json" in err and json.loads((out / "results.json").read_text())


def test_an_out_that_holds_the_input_is_refused(tmp_path, capsys, small_file):
    out = tmp_path / "d"
    out.mkdir()
    data = out / "trials.csv"
    data.write_bytes(small_file.read_bytes())
    code, _, err = _run(capsys, "--data", str(data), "--out", str(out), "--no-figures")
    assert code == 2 and "holds the input" in err
    assert data.read_bytes() == small_file.read_bytes()


@pytest.mark.parametrize("out", ["", ".", ".."])
def test_an_empty_out_or_the_current_folder_is_refused(tmp_path, capsys, small_file, monkeypatch, out):
    work = tmp_path / "work"
    work.mkdir()
    (work / "notes.txt").write_text("keep")
    monkeypatch.chdir(work)
    code, _, err = _run(capsys, "--data", str(small_file), "--out", out, "--no-figures")
    assert code == 2 and "--out" in err
    assert (work / "notes.txt").read_text() == "keep" and Path.cwd() == work
    assert sorted(p.name for p in work.iterdir()) == ["notes.txt"]  # nothing written, nothing renamed


def test_the_output_folder_is_checked_before_anything_is_computed(tmp_path, capsys, small_file, monkeypatch):
    """A foreign --out fails at once: the recordings are never read."""

    def must_not_run(*args, **kwargs):
        raise AssertionError("the data were read before the output folder was checked")

    monkeypatch.setattr(pipeline, "load_recordings", must_not_run)
    out = tmp_path / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("x")
    code, _, err = _run(capsys, "--data", str(small_file), "--out", str(out))
    assert code == 2 and "thesis.tex" in err


@pytest.mark.slow  # a subprocess killed mid-run
def test_sigterm_cleans_up_like_ctrl_c(tmp_path):
    """SIGTERM (as a cluster's job manager sends) ends the run with one line and exit 143, leaving the
    output folder as it was and no partial folder behind."""
    out = tmp_path / "o"
    proc = subprocess.Popen(
        [sys.executable, "-m", "skilllib", "run", "--out", str(out), "--no-figures", "--quiet"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    time.sleep(3.0)  # reading and computing (the default run takes several seconds)
    assert proc.poll() is None, "the run ended before it could be terminated"
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 143, err
    assert err.strip() == "error: terminated"
    assert not out.exists() and not list(tmp_path.glob(".o.partial-*"))


def test_a_second_run_on_a_folder_being_written_is_refused(tmp_path, capsys, small_file):
    out = tmp_path / "o"
    with output_folder(out) as fresh:  # the first run holds the folder's lock while it writes
        code, _, err = _run(capsys, "--data", str(small_file), "--out", str(out), "--no-figures")
        assert code == 2 and "another skilllib run" in err and f"pid {os.getpid()}" in err
        (fresh / "results.json").write_text("{}")
    assert (out / "results.json").read_text() == "{}"  # the first run's output, untouched by the second


def test_an_out_that_is_a_file_is_an_option_error(tmp_path, capsys, small_file):
    (tmp_path / "f").write_text("x")
    code, _, err = _run(capsys, "--data", str(small_file), "--out", str(tmp_path / "f"))
    assert code == 2 and "is not a folder" in err


# --- options, interruption, closed stdout ------------------------------------------------------------


@pytest.mark.parametrize("seed", ["-1", "4294967296", "1.5"])
def test_a_bad_seed_is_an_option_error(tmp_path, capsys, small_file, seed):
    with pytest.raises(SystemExit) as e:
        main(["run", "--data", str(small_file), "--out", str(tmp_path / "o"), "--seed", seed])
    assert e.value.code == 2 and "--seed" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_the_largest_seed_is_accepted(tmp_path, capsys, small_file):
    assert (
        _run(capsys, "--data", str(small_file), "--out", str(tmp_path / "o"), "--no-figures", "--seed", str(2**32 - 1))[
            0
        ]
        == DONE
    )


@pytest.mark.parametrize("where", ["start-up", "run"])
def test_ctrl_c_at_any_point_is_exit_130_with_one_line(tmp_path, capsys, small_file, monkeypatch, where):
    from skilllib.pipeline import _cli as cli

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(
        cli if where == "start-up" else pipeline, "_parser" if where == "start-up" else "compute", interrupt
    )
    code = main(["run", "--data", str(small_file), "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 130 and err == "error: interrupted\n"
    assert not (tmp_path / "o").exists() and not list(tmp_path.glob(".o.partial-*"))


@pytest.mark.slow  # a subprocess: left out of mutation testing (it would not see the mutant)
def test_sigint_to_a_running_command_is_exit_130_without_a_traceback(tmp_path, small_file):
    """SIGINT once the command runs its own code (pandas is imported inside main(): wait until the process
    has mapped it, Linux /proc): exit 130 and one line. The interpreter's own start-up, before skilllib's
    code, is Python's (a few tens of ms)."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "skilllib", "run", "--data", str(small_file), "--out", str(tmp_path / "o")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    maps = Path(f"/proc/{proc.pid}/maps")
    deadline = time.monotonic() + 120
    while proc.poll() is None and time.monotonic() < deadline:
        try:
            if "pandas/_libs" in maps.read_text():
                break
        except OSError:
            pass
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=600)
    if proc.returncode == DONE:  # the machine was fast enough to finish first
        pytest.skip("the run ended before the signal")
    assert proc.returncode == 130 and err.strip() == "error: interrupted" and "Traceback" not in err
    assert not (tmp_path / "o").exists() and not list(tmp_path.glob(".o.partial-*"))


@pytest.mark.slow  # a subprocess: left out of mutation testing (it would not see the mutant)
def test_a_closed_stdout_ends_quietly(tmp_path, small_file):
    """`skilllib run ... | head -0`: the summary cannot be written; no traceback, exit 141 (as SIGPIPE)."""
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "skilllib",
            "run",
            "--data",
            str(small_file),
            "--out",
            str(tmp_path / "o"),
            "--no-figures",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=600) == 141 and err == ""
    assert (tmp_path / "o" / "results.json").exists()  # the work was done; only the summary was not read


def test_a_dataframe_run_writes_text_ids(tmp_path, small_file):
    frame = pd.read_csv(small_file, dtype=str)
    first = frame.trial.isin(frame.trial.unique()[:3])
    frame = frame.assign(participant=frame.participant.where(~first, "01"))  # "01" beside "1": two participants
    res = pipeline.run(frame, tmp_path / "o", write_figures=False).results
    assert [t["participant"] for t in res["trials"]] == frame.drop_duplicates(
        ["participant", "trial"]
    ).participant.tolist()
    assert pd.DataFrame(res["trials"]).participant.nunique() == 2
