"""The page in a real headless Chromium: a failed run's timeline, "why?" in the chat, evidence highlighted.

Screenshots go to the test's tmp folder, and also to $HEXAR_SCREENSHOTS when set (docs/web is refreshed so).
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from hexar.events import read_recording
from tests.web.browser import chrome, served
from tests.web.helpers import HOSTILE_ERROR, HOSTILE_INSTRUCTION, HOSTILE_LOG

WAIT_S = 90
CHECKPOINTS: dict[str, Path] = {}  # the page's thread file, where a terminal conversation is written too


@pytest.fixture(scope="module")
def page(webroot: Path, tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Any, str]]:
    ck = tmp_path_factory.mktemp("threads") / "threads.sqlite"
    CHECKPOINTS["file"] = ck
    # served from the folder's parent with a relative path, as a person runs `hexar web runs`: the page then
    # shows `hexar chat webroot0/NAME --thread ID` (and the screenshots hold no machine path)
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(webroot.parent)
        with served(Path(webroot.name), ck) as url, chrome() as driver:
            driver.set_window_size(1440, 1250)
            yield driver, url


@pytest.fixture(scope="module")
def shots(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("screenshots")


def _shot(driver: Any, shots: Path, name: str) -> Path:
    out = shots / f"{name}.png"
    driver.save_screenshot(str(out))
    extra = os.environ.get("HEXAR_SCREENSHOTS")
    if extra:
        Path(extra).mkdir(parents=True, exist_ok=True)
        shutil.copy(out, Path(extra) / out.name)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    return out


def _open(driver: Any, url: str, name: str) -> None:
    from selenium.webdriver.support.ui import WebDriverWait

    driver.get(f"{url}#/run/{name}")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.execute_script("return document.body.dataset.ready"))


def _ask(driver: Any, question: str) -> Any:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    before = len(driver.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending)"))
    driver.find_element(By.ID, "chat-input").send_keys(question + "\n")
    WebDriverWait(driver, WAIT_S).until(
        lambda d: len(d.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending)")) > before)
    return driver.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending)")[-1]


def test_failed_run_why_and_its_evidence_on_the_timeline(page: tuple[Any, str], webroot: Path, shots: Path) -> None:
    from selenium.webdriver.common.by import By

    driver, url = page
    _open(driver, url, "bagfile_5_1")
    failed = read_recording(webroot / "bagfile_5_1").task().failed_skill
    assert failed is not None
    bar = driver.find_element(By.ID, f"skill-{failed.index}")
    assert bar.get_attribute("data-status") == "failed" and failed.error_msg in bar.text
    answer = _ask(driver, "why?")
    causes = [c.text for c in answer.find_elements(By.CSS_SELECTOR, ".chip")]
    assert causes == ["navigation.blocked_path"]
    assert "blocked" in answer.find_element(By.CSS_SELECTOR, ".answer").text
    link = next(a for a in answer.find_elements(By.CSS_SELECTOR, ".evlink") if "Failed to make progress" in a.text)
    assert not driver.find_elements(By.CSS_SELECTOR, "#events-body tr.hl")
    link.click()
    key = link.get_attribute("data-key")
    rows = driver.find_elements(By.CSS_SELECTOR, "#events-body tr.hl")
    assert [r.get_attribute("data-key") for r in rows] == [key]
    assert rows[0].is_displayed() and "Failed to make progress" in rows[0].text
    assert "hl" in driver.find_element(By.CSS_SELECTOR, f".tick[data-key='{key}']").get_attribute("class")
    assert driver.find_element(By.ID, "gantt-marker").is_displayed()
    # the path: one point per pose (a short run is not thinned), its covariance, the stop, and where it was
    log = read_recording(webroot / "bagfile_5_1")
    task = log.task()
    points = driver.find_element(By.ID, "path-line").get_attribute("points").split()
    assert len(points) == sum(1 for p in log.poses if task.created <= p.t <= task.last_update) + 1
    assert driver.find_elements(By.CSS_SELECTOR, "#path-svg ellipse")
    assert "failed" in driver.find_element(By.ID, "path-stop").get_attribute("class")
    assert "shown" in driver.find_element(By.ID, "path-marker").get_attribute("class")
    # a cause chip highlights every line cited for it
    answer.find_element(By.CSS_SELECTOR, ".chip").click()
    assert len(driver.find_elements(By.CSS_SELECTOR, "#events-body tr.hl")) == len(
        driver.find_elements(By.CSS_SELECTOR, "#events-body tr"))
    link.click()
    assert "backend none" in driver.find_element(By.ID, "backend").text
    _shot(driver, shots, "nav_failure")
    # all filtered lines on request, the cited ones still among them
    driver.find_element(By.ID, "all-lines").click()
    from selenium.webdriver.support.ui import WebDriverWait

    WebDriverWait(driver, WAIT_S).until(lambda d: d.find_elements(By.CSS_SELECTOR, "#events-body tr.filtered"))
    assert "kept by the navigation filter" in driver.find_element(By.ID, "lines-info").text


def test_ask_human_run_shows_its_steps_and_distance(page: tuple[Any, str], shots: Path) -> None:
    from selenium.webdriver.common.by import By

    driver, url = page
    _open(driver, url, "bagfile_12_1")
    card = driver.find_element(By.ID, "ask-human")
    assert "person_distance" in card.text
    answer = _ask(driver, "Why didn't you bring me the coffee?")
    assert [c.text for c in answer.find_elements(By.CSS_SELECTOR, ".chip")] == ["ask_human.person_too_far"]
    answer.find_elements(By.CSS_SELECTOR, ".evlink")[0].click()
    assert driver.find_elements(By.CSS_SELECTOR, "#events-body tr.hl")
    assert "shown" in driver.find_element(By.ID, "path-marker").get_attribute("class")
    # the suggestion a developer replaying a run clicks: the run's log lines, quoted with their nodes
    driver.find_element(By.XPATH, "//div[@class='suggest']/button[text()='What errors were there?']").click()
    from selenium.webdriver.support.ui import WebDriverWait

    WebDriverWait(driver, WAIT_S).until(lambda d: "My log holds" in d.find_elements(
        By.CSS_SELECTOR, ".msg.bot:not(.pending)")[-1].text)
    errors = driver.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending)")[-1]
    assert "My log holds" in errors.text and "error" in errors.text
    # thanks in the page's chat gets the reply the terminal chat gives, not a red refusal
    thanks = _ask(driver, "thanks!")
    assert "error" not in thanks.get_attribute("class")
    assert thanks.find_element(By.CSS_SELECTOR, ".answer").text == \
        "You're welcome. Ask me anything else about what I did."
    driver.execute_script("document.getElementById('path').scrollIntoView({block: 'start'})")
    _shot(driver, shots, "ask_human")


def test_pizza_and_tts_panels(page: tuple[Any, str], shots: Path) -> None:
    from selenium.webdriver.common.by import By

    driver, url = page
    _open(driver, url, "bagfile_20_1")
    rows = driver.find_elements(By.CSS_SELECTOR, "#pizza .wrow")
    assert len(rows) >= 3 and "Margherita" in driver.find_element(By.ID, "pizza").text
    answer = _ask(driver, "Why did you recommend a Margherita?")
    assert [c.text for c in answer.find_elements(By.CSS_SELECTOR, ".chip")] == ["pizza.ingredients"]
    driver.execute_script("document.getElementById('pizza').scrollIntoView({block: 'end'})")
    _shot(driver, shots, "pizza")
    _open(driver, url, "bagfile_19_1")
    said = driver.find_element(By.CSS_SELECTOR, "#tts .said").text
    unsaid = driver.find_element(By.CSS_SELECTOR, "#tts .unsaid").text
    assert said and unsaid and said.startswith("Hello everyone")


def test_runs_list_filters_by_outcome(page: tuple[Any, str]) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select, WebDriverWait

    driver, url = page
    driver.get(url + "#/")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.find_elements(By.CSS_SELECTOR, "tr.run"))
    everything = len(driver.find_elements(By.CSS_SELECTOR, "tr.run"))
    Select(driver.find_element(By.ID, "filter-outcome")).select_by_value("failed")
    badges = [b.text for b in driver.find_elements(By.CSS_SELECTOR, "tr.run .badge")]
    assert badges and set(badges) == {"failed"} and len(badges) < everything


def test_hostile_recorded_text_stays_text(page: tuple[Any, str]) -> None:
    from selenium.webdriver.common.by import By

    driver, url = page
    _open(driver, url, "hostile_run")
    assert driver.title == "HEXAR · see why"
    assert HOSTILE_ERROR in driver.find_element(By.ID, "skill-0").text
    assert HOSTILE_INSTRUCTION in driver.find_element(By.CSS_SELECTOR, ".instruction").text
    assert not driver.find_elements(By.CSS_SELECTOR, "main img[src='x'], main script")
    _ask(driver, "What happened?")
    driver.find_element(By.ID, "all-lines").click()
    from selenium.webdriver.support.ui import WebDriverWait

    WebDriverWait(driver, WAIT_S).until(lambda d: HOSTILE_LOG in d.find_element(By.ID, "events-body").text)
    assert driver.title == "HEXAR · see why"
    assert not driver.find_elements(By.CSS_SELECTOR, "main img[src='x'], main script")


def test_bad_recording_shows_one_line_not_a_traceback(page: tuple[Any, str], webroot: Path) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    driver, url = page
    driver.get(f"{url}#/run/corrupt_run")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.find_elements(By.CSS_SELECTOR, "p.error"))
    errors = [e.text for e in driver.find_elements(By.CSS_SELECTOR, "p.error")]
    assert len(errors) == 1 and errors[0].startswith("ERROR: cannot read") and "\n" not in errors[0]
    assert "Traceback" not in driver.find_element(By.TAG_NAME, "body").text


def test_a_conversation_started_in_the_terminal_continues_in_the_page(page: tuple[Any, str], webroot: Path) -> None:
    from selenium.webdriver.common.by import By

    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    driver, url = page
    # what `hexar chat webroot0/bagfile_19_1 --checkpoints FILE` does, from the folder the page is served from
    terminal = Session(RunSettings(recording=Path(webroot.name) / "bagfile_19_1", llm="none"),
                       checkpoints=CHECKPOINTS["file"])
    first = terminal.ask("why did you stop talking")
    _open(driver, url, f"bagfile_19_1?thread={first['thread']}")
    from selenium.webdriver.support.ui import WebDriverWait

    WebDriverWait(driver, WAIT_S).until(lambda d: d.find_elements(By.CSS_SELECTOR, "#chat-log .msg.bot"))
    assert first["thread"] in driver.find_element(By.ID, "thread-info").text
    assert first["answer"][:40] in driver.find_element(By.ID, "chat-log").text
    deeper = _ask(driver, "why?")  # the page goes on in the same thread: one level deeper
    assert deeper.text.startswith("Here is what I recorded")


def test_a_fleet_by_robot_and_date_opens_a_run_by_its_path(suite: Path, tmp_path: Path) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    fleet = tmp_path / "fleet"
    shutil.copytree(suite / "bagfile_5_1", fleet / "tiago-1" / "2026-11-30" / "bagfile_5_1")
    shutil.copytree(suite / "bagfile_10_1", fleet / "tiago-2" / "bagfile_5_1")  # the same name, another robot
    with served(fleet, tmp_path / "t.sqlite") as url, chrome() as driver:
        driver.get(url + "#/")
        WebDriverWait(driver, WAIT_S).until(lambda d: len(d.find_elements(By.CSS_SELECTOR, "tr.run")) == 2)
        rows = driver.find_elements(By.CSS_SELECTOR, "tr.run")
        assert [r.get_attribute("data-name") for r in rows] == ["tiago-1/2026-11-30/bagfile_5_1",
                                                                "tiago-2/bagfile_5_1"]
        rows[0].click()
        WebDriverWait(driver, WAIT_S).until(lambda d: d.execute_script("return document.body.dataset.ready"))
        assert driver.find_element(By.ID, "skill-0").get_attribute("data-status") == "failed"
        answer = _ask(driver, "why?")
        assert [c.text for c in answer.find_elements(By.CSS_SELECTOR, ".chip")] == ["navigation.blocked_path"]
        assert "tiago-1/2026-11-30/bagfile_5_1" in driver.find_element(By.TAG_NAME, "body").text
