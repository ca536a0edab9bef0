"""The task as data: task files, presets, results.json's task block, and their errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from skilllib.features import PAPER_SELECTION, EndRule, SpeedThreshold, Window, parse_end, parse_start
from skilllib.task import KEYS, PAPER_TASK, Task, TaskError, load_task, preset_names


def write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "task.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_the_paper_preset_is_the_default_task():
    t = load_task("paper")
    assert "paper" in preset_names()
    assert t.to_dict() == PAPER_TASK.to_dict()
    assert t.resolved_selection() == PAPER_SELECTION
    assert (t.start.text(), t.end.text(), t.features, t.k) == ("speed:0.05", "contact", ("pv", "sparc"), 6)


def test_a_lab_task_file_is_read_whole(tmp_path):
    p = write(
        tmp_path,
        """name = "forward reach"
[read]
marker = "{hand}FTP"
name_pattern = '(?P<participant>ADL\\d+)_(?P<hand>[LR])(?P<trial>\\d)'
units = "mm"
up_axis = "z"
max_gap = 0.05
contact_below = true
columns = { time = "t" }
[segment]
start = "speed:3%"
end = "offset:3%"
hold = 0.2
split = true
lowpass = 10
[select]
windows = "none"
[cluster]
features = ["pv", "sparc", "ldlj"]
k = 4
scaling = "standard"
seed = 7
[sparc]
fc = 10
sensitivity = ["fc=6", "fc=10,amp_th=0.1"]
[robot]
name = "ur5"
qd_max = [3.0, 3.0, 3.0, 3.0, 3.0, 3.0]
qdd_max = 8
""",
    )
    t = load_task(p)
    assert t.name == "forward reach"
    assert t.read["marker"] == "{hand}FTP" and t.read["units"] == "mm" and t.read["max_gap"] == 0.05
    assert t.read["contact_below"] is True and t.read["columns"] == {"time": "t"}
    assert t.start.threshold == SpeedThreshold(speed=None, fraction=0.03)
    assert t.end == EndRule("offset", SpeedThreshold(speed=None, fraction=0.03), 0.2)
    assert t.split and t.lowpass == 10.0 and t.resolved_selection() == ()
    assert t.features == ("pv", "sparc", "ldlj") and (t.k, t.scaling, t.seed) == (4, "standard", 7)
    assert t.fc == 10.0 and t.sensitivity == ({"fc": 6.0}, {"fc": 10.0, "amp_th": 0.1})
    assert t.robot == "ur5" and t.qd_max == (3.0,) * 6 and t.qdd_max == 8.0


def test_a_task_round_trips_through_toml_and_results_json(tmp_path):
    t = PAPER_TASK.with_options(start="speed:5%", end="height-above:0.62", windows=["pv=0.4:"], features="pv,ldlj")
    again = load_task(write(tmp_path, t.to_toml()))
    assert again.to_dict() == t.to_dict()
    results = tmp_path / "results.json"
    results.write_text(json.dumps({"schema_version": 2, "task": t.to_dict()}))
    assert load_task(results).to_dict() == t.to_dict()
    assert load_task(results).resolved_selection() == (Window("pv", 0.4, None),)


def test_the_end_rule_keeps_the_hold_when_only_the_rule_changes():
    t = PAPER_TASK.with_options(hold=0.25).with_options(end="offset")
    assert t.end == EndRule("offset", None, 0.25)
    assert t.end.offset_threshold(t.start) == SpeedThreshold(0.05)


@pytest.mark.parametrize(
    "text, expected",
    [
        ('[segment]\nstart = "speed:0.05"\nstrat = 1\n', "line 3: [segment] strat: unknown key; [segment] takes"),
        ('name = "x"\n[cluster]\nk = 1\n', "line 3: [cluster] k = 1: use an integer of at least 2"),
        ('[cluster]\nfeatures = ["pv", "smoothness"]\n', "line 2: [cluster] features: unknown feature 'smoothness'"),
        ('[segment]\nend = "offset:150%"\n', "line 2: [segment] end: 'offset:150%': the offset speed must be"),
        ('[segment]\nend = "stop"\n', "'stop' is not an end rule: use contact, offset"),
        ('[select]\nwindows = ["pv=0.9:0.2"]\n', "line 2: [select] windows: 'pv=0.9:0.2': the lower bound 0.9"),
        ("[robots]\nname = 'ur5'\n", "line 1: [robots]: unknown section 'robots'"),
        ('[read]\nunits = "inch"\n', "line 2: [read] units = 'inch': use m, cm or mm"),
        ('[read]\nname_pattern = "(?P<participant"\n', "line 2: [read] name_pattern = '(?P<participant': not a"),
        ('[robot]\nname = "r2d2"\n', "line 2: [robot] name = 'r2d2': use simple6"),
        ("[sparc]\namp_th = 2\n", "line 2: [sparc] amp_th = 2: use a fraction between 0 and 1"),
        ('[segment]\nstart = "event:Go"\nend = "offset"\n', "line 3: [segment] end: 'offset' takes the start's"),
        ("[segment\nstart = 1\n", "not a valid TOML task file"),
    ],
)
def test_a_bad_task_file_names_its_line_and_what_is_allowed(tmp_path, text, expected):
    p = write(tmp_path, text)
    with pytest.raises(TaskError) as e:
        load_task(p)
    assert str(e.value).startswith(str(p))
    assert expected in str(e.value)


def test_a_missing_task_names_the_presets(tmp_path):
    with pytest.raises(TaskError, match="no such task file .* preset: .*paper"):
        load_task(tmp_path / "nope.toml")
    (tmp_path / "r.json").write_text('{"schema_version": 2}')
    with pytest.raises(TaskError, match="no 'task' block"):
        load_task(tmp_path / "r.json")


def test_every_key_of_a_task_file_is_documented_in_the_cli_page():
    text = (Path(__file__).resolve().parents[2] / "docs" / "cli.md").read_text()
    missing = [f"{s}.{k}" for s, keys in KEYS.items() for k in keys if f"`{k}`" not in text]
    assert not missing


@pytest.mark.parametrize(
    "text",
    [
        "speed:0.05",
        "speed:5%",
        "event:Foot Strike",
        "contact",
        "offset",
        "offset:0.02",
        "offset:3%",
        "event:touch",
        "height-above:0.62",
        "height-below:-0.1",
    ],
)
def test_rules_read_back_from_their_own_text(text):
    kind = text.partition(":")[0]
    rule = parse_start(text) if kind == "speed" or (kind == "event" and "Foot" in text) else parse_end(text)
    again = parse_start(rule.text()) if rule.__class__.__name__ == "StartRule" else parse_end(rule.text())
    assert again == rule and rule.text() == text


def test_task_is_frozen():
    with pytest.raises(AttributeError):
        PAPER_TASK.k = 3  # type: ignore[misc]
    assert isinstance(PAPER_TASK, Task)


def test_an_end_rule_given_over_a_task_keeps_the_tasks_hold(tmp_path):
    from skilllib.pipeline._run import resolve_task

    p = write(tmp_path, '[segment]\nend = "offset:5%"\nhold = 0.25\n')
    assert resolve_task(p, end="offset:3%").end.hold_s == 0.25
    assert resolve_task(p, end="offset:3%", hold=0.05).end.hold_s == 0.05
    assert resolve_task(p).name == "task" and resolve_task(p, k=3).name == "task + options"  # the file's name
