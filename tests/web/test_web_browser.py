"""In Debian's headless chromium (Playwright): sign in, watch the robot move on the map,
trigger a scenario, and talk to the dialogue: a light switched on, a go_to behaviour queued,
a resident's heart rate read from the health store."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest
from playwright.sync_api import Page, expect, sync_playwright
from web_served import PASSWORD, Running, start_served

from amiro.environment.messages import HealthMeasurement
from amiro.web.server import WebServer

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@pytest.fixture
def site() -> Iterator[tuple[Running, str]]:
    running = start_served(speed=10.0)
    server = WebServer(running.served.app, "127.0.0.1", 0)
    server.start()
    yield running, server.url
    server.stop()
    running.loop.stop()
    running.served.stop()


@pytest.fixture
def page(tmp_path: Path) -> Iterator[Page]:
    with sync_playwright() as pw:
        context = pw.chromium.launch_persistent_context(
            str(tmp_path / "profile"), executable_path=CHROMIUM, headless=True, args=FLAGS
        )
        yield context.new_page()
        context.close()


def robot_pose(page: Page) -> str:
    return str(page.locator("#robot-pose").text_content())


def test_dashboard_in_a_real_browser(site: tuple[Running, str], page: Page) -> None:
    running, url = site
    measured = HealthMeasurement("maria", "heart_rate", 67.0, "2026-07-14T09:00:00+00:00")
    running.served.system.environment.health.add(measured)  # the simulated day is 07-15
    page.goto(url + "/")
    page.wait_for_url("**/login")
    page.fill("#password", "wrong")
    page.click("#login-button")
    expect(page.locator("#login-error")).to_contain_text("Wrong")
    page.fill("#password", PASSWORD)
    page.click("#login-button")
    page.wait_for_url(url + "/")
    expect(page.locator("#robot-pose")).to_contain_text("x ")
    start = robot_pose(page)

    page.click("#scenario-hydration")
    expect(page.locator("#action-result")).to_contain_text("Scenario hydration started")
    expect(page.locator("#current-task")).to_contain_text("hydration", timeout=15_000)
    page.wait_for_function(
        "start => document.querySelector('#robot-pose').textContent !== start",
        arg=start,
        polling=200,
        timeout=20_000,
    )
    assert robot_pose(page) != start  # the map follows the robot

    page.select_option("#chat-lang", "fr")
    page.fill("#chat-input", "allume la lumière dans la cuisine")
    page.click("#chat-send")
    expect(page.locator("#chat-reply")).to_contain_text("C'est fait")
    expect(page.locator("#transcript")).to_contain_text("allume la lumière dans la cuisine")
    expect(page.locator("#lights-kitchen")).to_have_attribute("aria-checked", "true")  # on

    page.select_option("#chat-lang", "en")
    page.fill("#chat-input", "go to the kitchen")
    page.click("#chat-send")
    expect(page.locator("#chat-reply")).to_contain_text("I am going to kitchen")
    page.wait_for_function(  # queued behind hydration, or running (English name)
        "() => /go to/.test(document.querySelector('#queue').textContent"
        " + document.querySelector('#current-task').textContent)",
        polling=200,
        timeout=10_000,
    )
    names = {r.name for r in running.served.system.engine.runs.values()}
    assert {"hydration", "go_to"} <= names

    page.select_option("#chat-user", "maria")  # the tablet by Maria's chair
    page.fill("#chat-input", "what was my heart rate yesterday")
    page.click("#chat-send")
    expect(page.locator("#chat-reply")).to_contain_text("Yesterday, your heart rate is 67")
