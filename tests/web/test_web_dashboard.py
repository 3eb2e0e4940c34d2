"""The dashboard as a carer sees it, in Debian's headless chromium (Playwright): the map's
doors, the timeline of a hydration run, the health chart, the layout at 800 px and on
Pepper's 1280x800 tablet, the page in French and Romanian, the fall button preempting.

One served system (with ``amiro serve``'s demo health data) and one signed-in browser for
the module.  With ``AMIRO_WEB_SHOTS=DIR`` the tests also save the screenshots that
docs/web.md shows (``AMIRO_WEB_SHOTS=docs/img``).
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import BrowserContext, Locator, Page, expect, sync_playwright
from test_web_browser import CHROMIUM, FLAGS
from web_served import PASSWORD, Running, start_served

from amiro.behavior.task import task_types
from amiro.web.server import WebServer

SHOTS = os.environ.get("AMIRO_WEB_SHOTS")
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def site() -> Iterator[tuple[Running, str]]:
    running = start_served(speed=10.0, demo=True)
    server = WebServer(running.served.app, "127.0.0.1", 0)
    server.start()
    yield running, server.url
    server.stop()
    running.loop.stop()
    running.served.stop()


@pytest.fixture(scope="module")
def context(
    site: tuple[Running, str], tmp_path_factory: pytest.TempPathFactory
) -> Iterator[BrowserContext]:
    _, url = site
    profile = tmp_path_factory.mktemp("profile")
    with sync_playwright() as pw:
        ctx = pw.chromium.launch_persistent_context(
            str(profile),
            executable_path=CHROMIUM,
            headless=True,
            args=FLAGS,
            viewport={"width": 1280, "height": 800},
            locale="en-GB",
        )
        page = ctx.new_page()
        page.goto(url + "/login")
        page.fill("#password", PASSWORD)
        page.click("#login-button")
        page.wait_for_url(url + "/")
        page.close()
        yield ctx
        ctx.close()


@pytest.fixture(scope="module")
def page(context: BrowserContext, site: tuple[Running, str]) -> Page:
    page = context.new_page()
    page.goto(site[1] + "/")
    page.wait_for_selector("body[data-ready=true]", timeout=15_000)
    return page


def shot(target: Page | Locator, name: str, **kwargs: Any) -> None:
    if SHOTS:
        if isinstance(target, Page):
            target.evaluate("window.scrollTo(0, 0)")
        Path(SHOTS).mkdir(parents=True, exist_ok=True)
        target.screenshot(path=str(Path(SHOTS) / name), **kwargs)


def wait_until(check: Any, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while not check():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.1)


PIXELS_ALONG = """([a, b, n]) => {
  const c = document.getElementById('map'), ctx = c.getContext('2d'), k = c.width / c.clientWidth;
  const out = [];
  for (let i = 1; i < n; i++) {
    const x = a[0] + (b[0] - a[0]) * i / n, y = a[1] + (b[1] - a[1]) * i / n;
    out.push(Array.from(ctx.getImageData(Math.round(x * k), Math.round(y * k), 1, 1).data));
  }
  return out;
}"""


def test_the_map_draws_every_door_open_or_closed(site: tuple[Running, str], page: Page) -> None:
    running, _ = site
    world = running.served.system.world
    running.served.gateway.call(lambda: world.set_door("bedroom_door", False)).result(5)
    page.wait_for_function(
        "() => window.amiroScene && window.amiroScene.doors.some("
        "d => d.name === 'bedroom_door' && !d.open)",
        timeout=10_000,
    )
    scene = page.evaluate("window.amiroScene")
    assert {d["name"] for d in scene["doors"]} == {d.name for d in world.home.doors}
    for door in scene["doors"]:
        pixels = page.evaluate(PIXELS_ALONG, [door["a"], door["b"], 12])
        red = sum(r > 180 and g < 90 and b < 90 for r, g, b, _ in pixels)
        green = sum(g > 120 and r < 80 and b < 110 for r, g, b, _ in pixels)
        if door["open"]:
            assert door["name"] != "bedroom_door"
            assert green >= 3 and red == 0, (door["name"], pixels)  # a dashed green opening
        else:
            assert door["name"] == "bedroom_door"
            assert red == len(pixels), (door["name"], pixels)  # a solid red panel
    # room labels are drawn after (above) the furniture, people and robot
    assert (
        scene["layers"][-1] == "labels"
        and scene["layers"].index("furniture") < len(scene["layers"]) - 1
    )
    assert {label["room"] for label in scene["labels"]} == set(world.home.rooms)
    assert scene["robot"] is not None and [p["name"] for p in scene["people"]] == ["maria"]
    fitted = scene["scale"]
    page.click("#zoom-in")
    assert page.evaluate("window.amiroScene.scale") == pytest.approx(fitted * 1.25)
    page.click("#zoom-fit")
    assert page.evaluate("window.amiroScene.scale") == pytest.approx(fitted)
    page.check("#lidar")
    page.wait_for_function("() => window.amiroScene.scan > 50", timeout=10_000)
    shot(page.locator("#map-card"), "web-map.png")
    page.uncheck("#lidar")
    page.wait_for_timeout(700)  # longer than a poll: no scan comes back once switched off
    assert page.evaluate("window.amiroScene.scan") == 0
    running.served.gateway.call(lambda: world.set_door("bedroom_door", True)).result(5)


def test_health_chart_has_both_blood_pressure_series_on_dated_axes(page: Page) -> None:
    page.select_option("#health-user", "maria")
    page.select_option("#health-metric", "blood_pressure")
    page.wait_for_function(
        "() => window.amiroChart && window.amiroChart.metric === 'blood_pressure'"
        " && window.amiroChart.series.length === 2",
        timeout=10_000,
    )
    chart = page.evaluate("window.amiroChart")
    days = page.evaluate(
        "async () => (await (await fetch('/api/health/maria/blood_pressure?days=14')).json())"
        ".days.filter(d => d.count).map(d => d.day)"
    )
    assert [s["name"] for s in chart["series"]] == ["systolic", "diastolic"]
    assert all(s["points"] == len(days) for s in chart["series"]) and len(days) == 14
    assert chart["unit"] == "mmHg" and chart["ranges"] == 2
    assert len(chart["xTicks"]) >= 3 and {t["day"] for t in chart["xTicks"]} <= set(days)
    for tick in chart["xTicks"]:  # "3 Jul": the day of the month and the month's name
        assert str(int(tick["day"][8:])) in tick["label"] and "Jul" in tick["label"]
    expect(page.locator("#demo-badge")).to_be_visible()
    expect(page.locator("#health-latest")).to_contain_text("mmHg")
    expect(page.locator("#health-latest")).to_contain_text("/")  # systolic/diastolic
    shot(page.locator("#health-card"), "web-health.png")


@pytest.mark.parametrize(
    ("width", "height", "name"), [(800, 900, "web-800.png"), (1280, 800, "web-1280x800.png")]
)
def test_the_page_fits_the_screen(page: Page, width: int, height: int, name: str) -> None:
    page.set_viewport_size({"width": width, "height": height})
    page.wait_for_timeout(300)  # the canvases follow their cards
    overflow = page.evaluate(
        "() => [document.documentElement.scrollWidth, document.documentElement.clientWidth,"
        " Math.max(...[...document.querySelectorAll('.card, canvas, header')]"
        ".map(e => e.getBoundingClientRect().right))]"
    )
    scroll_width, client_width, rightmost = overflow
    assert scroll_width <= client_width and rightmost <= client_width, overflow
    shot(page, name, full_page=width == 800)
    page.evaluate("window.scrollTo(0, document.body.scrollHeight)")
    box = page.locator("#estop").bounding_box()  # the stop button stays in view
    assert box is not None and box["y"] >= 0 and box["y"] + box["height"] <= height
    assert box["x"] + box["width"] <= width
    page.evaluate("window.scrollTo(0, 0)")
    page.set_viewport_size({"width": 1280, "height": 800})


def test_the_timeline_shows_each_step_of_a_hydration_run(
    site: tuple[Running, str], page: Page
) -> None:
    running, _ = site
    engine = running.served.system.engine
    page.click("#scenario-hydration")
    expect(page.locator("#action-result")).to_contain_text("priority 5")
    wait_until(lambda: any(r.name == "hydration" and r.done for r in engine.runs.values()), 90)
    run = next(r for r in engine.runs.values() if r.name == "hydration")
    finished = page.locator(f"#timeline li[data-type=graph_finished][data-graph='{run.id}']")
    expect(finished).to_contain_text(run.outcome or "", timeout=10_000)
    assert len(run.records) >= 5  # search, approach, remind, listen, watch, ack...
    english = page.evaluate("async () => (await import('/static/i18n.js')).strings('en')")
    for record in run.records:
        started = page.locator(f"#timeline li[data-type=task_started][data-task={record.task_id}]")
        ended = page.locator(f"#timeline li[data-type=task_finished][data-task={record.task_id}]")
        expect(started.first).to_contain_text(english[f"w_{record.type}"])
        expect(ended.first).to_contain_text(english[f"w_{record.type}"])
    said = running.served.gateway.transcript[0]["text"]
    expect(page.locator("#timeline li[data-type=say]").first).to_contain_text(said)
    expect(page.locator("#timeline li[data-type=notification]").first).to_contain_text("hydration")
    shot(page.locator("#timeline-card"), "web-timeline.png")


@pytest.mark.parametrize(
    ("lang", "estop", "say"),
    [("fr", "Arrêt d'urgence", "Le robot dit"), ("ro", "Oprire de urgență", "Robotul spune")],
)
def test_every_string_in_french_and_romanian(page: Page, lang: str, estop: str, say: str) -> None:
    # amiro's own task types (tests register fakes of their own in the same registry)
    ours = sorted(n for n, c in task_types().items() if c.__module__.startswith("amiro."))
    page.select_option("#ui-lang", lang)
    try:
        expect(page.locator("#estop")).to_have_text(estop)
        missing = page.evaluate(
            """async ([lang, ours]) => {
              const m = await import('/static/i18n.js');
              const en = Object.keys(m.strings('en')), other = m.strings(lang);
              const untranslated = en.filter(k => !other[k]);
              const wrong = [...document.querySelectorAll('[data-i18n]')]
                .filter(e => e.textContent !== other[e.dataset.i18n]).map(e => e.dataset.i18n);
              const label = (t) => document.querySelector(`[data-task-type="${t}"]`)?.textContent;
              const tasks = ours.filter(t => !other[`w_${t}`] || label(t) !== other[`w_${t}`]);
              return {untranslated, wrong, tasks, html: document.documentElement.lang};
            }""",
            [lang, ours],
        )
        assert missing == {"untranslated": [], "wrong": [], "tasks": [], "html": lang}
        assert {"MoveTo", "Sequence"} <= set(ours)
        expect(page.locator("#timeline")).to_contain_text(say)
        expect(page.locator("#lights-kitchen")).to_contain_text(":")
        if lang == "fr":
            shot(page, "web-fr.png", full_page=True)
    finally:
        page.select_option("#ui-lang", "en")


def test_the_fall_button_preempts_a_running_hydration(
    site: tuple[Running, str], page: Page
) -> None:
    running, _ = site
    engine = running.served.system.engine
    page.click("#scenario-hydration")
    wait_until(lambda: (engine.current() or {}).get("name") == "hydration")
    page.click("#fall")
    expect(page.locator("#action-result")).to_contain_text("priority 100")
    wait_until(lambda: (engine.current() or {}).get("name") == "fall")
    assert engine.current()["priority"] == 100  # type: ignore[index]
    waiting = [q["name"] for q in engine.queue_snapshot()]
    assert "hydration" in waiting  # put aside, it resumes after the fall
    expect(page.locator("#current-task")).to_contain_text("fall", timeout=5_000)
