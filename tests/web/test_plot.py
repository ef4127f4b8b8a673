"""`--plot FILE.png`: the path with its covariance, the trips, the stop point and the skill timeline."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.events import EventLog, read_recording
from hexar.web.plot import STATUS_COLOURS, build
from hexar.web.runview import pose_at
from tests.web.helpers import HOSTILE_ERROR, hostile_recording

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _one_skill_run(out: Path, skill: str, instruction: str = "go", error: str = "x") -> EventLog:
    """A recording of one task of one skill that ran and failed, with a straight path of poses."""
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns

    b = BagBuilder()
    t0 = sec_ns(1_741_600_000)
    for t, status in ((t0, "Running"), (t0 + sec_ns(6), "failed")):
        b.task_info(t, {"instruction": instruction, "task_id": "d1", "task_status": "valid", "task_error_msg": "",
                        "skill_sequence": [{"skill": skill, "params": {}, "status": status, "error_msg": error}]})
    for i in range(30):
        b.pose(t0 + i * 200_000_000, 0.1 * i, 0.0, 0.0, 0.02, 0.02, 0.01)
    return read_recording(b.write(out))


def _ask(suite: Path, name: str, capsys: pytest.CaptureFixture[str], png: Path) -> dict[str, object]:
    capsys.readouterr()
    assert main(["ask", str(suite / name), "What happened?", "--llm", "none", "--json", "--plot", str(png)]) == 0
    result: dict[str, object] = json.loads(capsys.readouterr().out)
    assert png.read_bytes()[:8] == PNG_MAGIC and png.stat().st_size > 20_000
    return result


def test_navigation_failure_marks_the_stop_and_the_cited_lines(suite: Path, tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    result = _ask(suite, "bagfile_5_1", capsys, tmp_path / "nav.png")
    log = read_recording(suite / "bagfile_5_1")
    task = log.task()
    fig = build(log, task, result)
    failed = task.failed_skill
    assert failed is not None and failed.skill == "navigate_to_zone"
    # the path is the recorded poses, in order
    assert fig.path is not None
    xs, ys = fig.path.get_data()
    inside = [p for p in log.poses if task.created <= p.t <= task.last_update]
    assert len(xs) >= len(inside) > 10 and list(xs)[-1] == pytest.approx(inside[-1].x)
    # it stopped where AMCL put it when the skill failed, which is not where it started
    stop = pose_at(log, failed.time_of("failed") or 0)
    assert fig.stop is not None and stop is not None
    sx, sy = fig.stop.get_data()
    assert (float(sx[0]), float(sy[0])) == pytest.approx((stop.x, stop.y))
    assert (stop.x - xs[0]) ** 2 + (stop.y - ys[0]) ** 2 > 1.0
    assert "navigate_to_zone failed" in str(fig.stop.get_label())
    # the failed skill is red on the timeline, with a failure marker; one dashed line per cited time
    assert fig.bars[failed.index].get_facecolor()[:3] == pytest.approx(_rgb(STATUS_COLOURS["failed"]))
    assert fig.failure is not None
    assert len(fig.evidence) == len({e["t"] for e in result["evidence"]}) >= 3  # type: ignore[attr-defined]
    assert len(fig.begins) == 1 and fig.ellipses


def test_poor_localisation_draws_wide_covariance(suite: Path, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    result = _ask(suite, "bagfile_8_1", capsys, tmp_path / "loc.png")
    assert result["causes"] == ["navigation.poor_localisation"]
    log = read_recording(suite / "bagfile_8_1")
    poor = build(log, log.task(), result)
    nav = read_recording(suite / "bagfile_5_1")
    calm = build(nav, nav.task())
    # 2-sigma ellipses: a covariance above the 0.2 threshold is wider than 4 * sqrt(0.2) m
    assert max(e.width for e in poor.ellipses) > 4 * 0.2 ** 0.5
    assert max(e.width for e in calm.ellipses) < 4 * 0.2 ** 0.5
    assert poor.covariance is not None and max(poor.covariance.get_ydata()) > 0.2
    # a successful task ends where the last pose is, and every trip is drawn
    assert poor.stop is not None and "ended here" in str(poor.stop.get_label())
    assert len(poor.begins) == len(poor.ends) >= 2


def test_ask_human_run_stops_at_the_failed_request(suite: Path, tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    result = _ask(suite, "bagfile_12_1", capsys, tmp_path / "ask.png")
    log = read_recording(suite / "bagfile_12_1")
    task = log.task()
    fig = build(log, task, result)
    failed = task.failed_skill
    assert failed is not None and failed.skill == "ask_human_for_help"
    assert fig.stop is not None and "ask_human_for_help failed" in str(fig.stop.get_label())
    assert fig.bars[failed.index].get_facecolor()[:3] == pytest.approx(_rgb(STATUS_COLOURS["failed"]))
    assert fig.bars[0].get_facecolor()[:3] == pytest.approx(_rgb(STATUS_COLOURS["succeeded"]))


def test_inspect_plot_draws_the_latest_task(suite: Path, tmp_path: Path) -> None:
    png = tmp_path / "inspect.png"
    assert main(["inspect", str(suite / "bagfile_19_1"), "--plot", str(png)]) == 0
    assert png.read_bytes()[:8] == PNG_MAGIC


def test_hostile_text_is_drawn_not_parsed(tmp_path: Path) -> None:
    """Mathtext would raise on an unbalanced `$` in an error message; recorded text is drawn verbatim."""
    log = read_recording(hostile_recording(tmp_path / "hostile"))
    fig = build(log, log.task(), {"answer": "a $b", "causes": [], "evidence": []})
    fig.save(tmp_path / "h.png")
    texts = [t.get_text() for ax in fig.figure.axes for t in ax.texts]
    assert any(HOSTILE_ERROR[:40] in t for t in texts)
    assert (tmp_path / "h.png").read_bytes()[:8] == PNG_MAGIC


def test_a_dollar_in_a_skill_name_is_drawn_not_parsed(tmp_path: Path) -> None:
    """The stop point's legend names the failed skill; a legend reads `$...$` as mathtext."""
    skill = "go$\\frac{$_to"  # two dollars: mathtext between them, and unbalanced
    log = _one_skill_run(tmp_path / "dollar", skill, error="x$")
    fig = build(log, log.task(), {"answer": "", "causes": [], "evidence": []})
    fig.save(tmp_path / "d.png")
    legend = [t.get_text() for ax in fig.figure.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    assert any(skill in t.replace("\\$", "$") for t in legend)
    assert (tmp_path / "d.png").read_bytes()[:8] == PNG_MAGIC


@pytest.mark.parametrize(("args", "message"), [
    (["ask", "RUN", "why?", "--llm", "none", "--plot", "/definitely/not/here/x.png"], "cannot write the figure"),
    (["ask", "RUN", "--questions", "Q", "--llm", "none", "--plot", "x.png"], "--plot draws one answer"),
    (["inspect", "/definitely/not/here", "--plot", "x.png"], "recording not found"),
])
def test_bad_plot_input_is_one_line(suite: Path, args: list[str], message: str,
                                    capsys: pytest.CaptureFixture[str]) -> None:
    args = [str(suite / "bagfile_5_1") if a == "RUN" else a for a in args]
    capsys.readouterr()
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR:") and message in err and err.count("\n") == 1


def _rgb(hex_colour: str) -> tuple[float, float, float]:
    return tuple(int(hex_colour[i:i + 2], 16) / 255 for i in (1, 3, 5))  # type: ignore[return-value]


def test_a_control_character_in_recorded_text_is_drawn_as_its_escape(tmp_path: Path) -> None:
    """Recorded strings reach the figure as `hexar.safe_text.visible` shows them everywhere else: a C1 control
    (U+0085) in a skill name is drawn as its escape, not as a glyph the font lacks."""
    import warnings

    log = _one_skill_run(tmp_path / "ctl", "go\x85to", instruction="go\x1b[31m")
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        fig = build(log, log.task(), {"answer": "stopped\x85here", "causes": [], "evidence": []})
        fig.save(tmp_path / "c.png")
    assert not [w for w in seen if "missing from font" in str(w.message)]
    texts = [t.get_text() for ax in fig.figure.axes for t in ax.texts] + [t.get_text() for t in fig.figure.texts]
    assert any("go\\x85to" in t for t in texts) and not any("\x85" in t or "\x1b" in t for t in texts)
