"""A wrong plan on the page (issue 24), in a real headless Chromium: scenario 3's robot reported "succeeded" on a
plan that goes to the wrong rooms; the page must not show it as a green success, the planner's finding must be
among the explainers' findings, the runs list's filters must find it, and causes read as words."""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.web.browser import chrome, served

WAIT_S = 90
PLAN_WRONG = "planner.plan_not_fulfilling_request"


@pytest.fixture(scope="module")
def page(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Any, str]]:
    root = tmp_path_factory.mktemp("wrongplan")
    for name in ("bagfile_1_1", "bagfile_3_1", "bagfile_5_1", "bagfile_10_1", "bagfile_20_1"):
        shutil.copytree(suite / name, root / name)
    shutil.copytree(suite / "bagfile_5_2", root / "crashed")
    (root / "crashed" / "metadata.yaml").unlink()  # a recording cut short is on the page too
    (root / ".venv" / "bin").mkdir(parents=True)  # and a folder with no recording is not
    with served(root, tmp_path_factory.mktemp("threads") / "t.sqlite") as url, chrome() as driver:
        driver.set_window_size(1440, 1250)
        yield driver, url


def _runs(driver: Any, url: str) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    driver.get(url + "#/")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.find_elements(By.CSS_SELECTOR, "tr.run"))
    # causes are found in the background: wait until every row has them
    WebDriverWait(driver, WAIT_S).until(lambda d: not d.find_elements(By.CSS_SELECTOR, "tr.run td.causes .muted"))


def _rows(driver: Any) -> dict[str, Any]:
    from selenium.webdriver.common.by import By

    return {r.get_attribute("data-name"): r for r in driver.find_elements(By.CSS_SELECTOR, "tr.run")}


def test_runs_list_shows_the_wrong_plan_and_finds_it_by_cause(page: tuple[Any, str]) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select

    driver, url = page
    _runs(driver, url)
    rows = _rows(driver)
    assert set(rows) == {"bagfile_1_1", "bagfile_3_1", "bagfile_5_1", "bagfile_10_1", "bagfile_20_1", "crashed"}
    badge = rows["bagfile_3_1"].find_element(By.CSS_SELECTOR, ".badge")
    assert badge.text == "wrong plan" and "succeeded" not in badge.get_attribute("class")
    assert rows["bagfile_10_1"].find_element(By.CSS_SELECTOR, ".badge").text == "succeeded"
    # causes as words, their ids on hover
    cause = rows["bagfile_1_1"].find_element(By.CSS_SELECTOR, "td.causes")
    assert "planner.invalid_skill" not in cause.text and "a skill the robot does not have" in cause.text
    assert cause.find_element(By.CSS_SELECTOR, ".cause").get_attribute("title") == "planner.invalid_skill"
    # the cause filter names causes in words and finds the wrong plan
    select = Select(driver.find_element(By.ID, "filter-cause"))
    option = next(o for o in select.options if o.get_attribute("value") == PLAN_WRONG)
    assert option.text == "the plan did not do what was asked"
    select.select_by_value(PLAN_WRONG)
    assert set(_rows(driver)) == {"bagfile_3_1"}
    select.select_by_value("")
    Select(driver.find_element(By.ID, "filter-outcome")).select_by_value("wrong plan")
    assert set(_rows(driver)) == {"bagfile_3_1"}


def test_the_run_page_of_a_wrong_plan_shows_the_planner_finding(page: tuple[Any, str]) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    driver, url = page
    driver.get(f"{url}#/run/bagfile_3_1")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.execute_script("return document.body.dataset.ready"))
    head = driver.find_element(By.CSS_SELECTOR, ".runhead h1 .badge")
    assert head.text == "wrong plan"
    assert "its plan did not match the request" in driver.find_element(By.ID, "wrong-plan").text
    findings = driver.find_elements(By.CSS_SELECTOR, "#findings article")
    first = findings[0]
    assert first.find_element(By.TAG_NAME, "h3").text.startswith("planner")
    assert [c.text for c in first.find_elements(By.CSS_SELECTOR, ".chip")] == [PLAN_WRONG]
    assert "did not match your request" in first.find_element(By.CSS_SELECTOR, ".answer").text
    assert "the plan did not do what was asked" in first.find_element(By.CSS_SELECTOR, ".meaning").text
    assert "Ask me again, saying exactly what to do and where." in first.text
    # the chat on the same page says the same
    driver.find_element(By.ID, "chat-input").send_keys("what happened?\n")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending) .chip"))
    chips = driver.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending) .chip")
    assert [c.text for c in chips] == [PLAN_WRONG]
    out = Path(os.environ.get("HEXAR_SCREENSHOTS") or driver.capabilities.get("tmp", "/nonexistent"))
    if out.parent.is_dir():
        out.mkdir(parents=True, exist_ok=True)
        driver.save_screenshot(str(out / "wrong_plan.png"))


def test_the_path_legend_names_only_what_is_drawn(page: tuple[Any, str]) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    driver, url = page
    driver.get(f"{url}#/run/bagfile_20_1")  # a pizza run: poses, but no trip
    WebDriverWait(driver, WAIT_S).until(lambda d: d.execute_script("return document.body.dataset.ready"))
    legend = driver.find_element(By.ID, "path-legend").text
    assert "trip began" not in legend and "trip ended" not in legend
    assert not driver.find_elements(By.CSS_SELECTOR, "#path-svg circle.begin")
    driver.get(f"{url}#/run/bagfile_5_1")
    WebDriverWait(driver, WAIT_S).until(lambda d: d.execute_script("return document.body.dataset.ready") and
                                        d.find_elements(By.ID, "path-legend"))
    legend = driver.find_element(By.ID, "path-legend").text
    assert "trip began" in legend and driver.find_elements(By.CSS_SELECTOR, "#path-svg circle.begin")
