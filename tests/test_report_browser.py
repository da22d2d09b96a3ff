"""The HTML report in a real headless browser: no network, no console errors, a drawn 3-D view.

Needs a system Chromium (Debian: ``apt-get install chromium``) and playwright
(``pip install '.[browser]'``; only its driver is used, with the system browser, so no
browser download). Out of the default run; run it with ``python -m pytest -m browser``.
"""

import os
import shutil

import numpy as np
import pytest
from conftest import SHAPES

from plumbob.cli import main

pytestmark = pytest.mark.browser

CHROMIUM = next((p for p in (os.environ.get("PLUMBOB_CHROMIUM"), shutil.which("chromium"),
                             shutil.which("chromium-browser")) if p), None)


def _page_check(html_path: str) -> tuple[list[str], np.ndarray, list[str]]:
    """(console errors, screenshot of the 3-D view as RGB pixels, requests off the page)."""
    sync_api = pytest.importorskip("playwright.sync_api", reason="pip install '.[browser]'")
    from io import BytesIO

    import matplotlib.image as mpimg

    errors, requests = [], []
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=[
            "--no-sandbox", "--enable-unsafe-swiftshader", "--use-angle=swiftshader"])
        try:
            page = browser.new_page(viewport={"width": 1200, "height": 900})
            page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.on("request", lambda r: None if r.url.startswith(("file:", "data:", "blob:"))
                    else requests.append(r.url))
            page.route("http*://**", lambda route: route.abort())  # no network at view time
            page.goto(f"file://{os.path.abspath(html_path)}")
            page.wait_for_selector(".js-plotly-plot .main-svg", timeout=30_000)
            page.wait_for_timeout(1500)
            view = page.locator(".js-plotly-plot").first
            shot = view.screenshot()
        finally:
            browser.close()
    return errors, mpimg.imread(BytesIO(shot), format="png")[:, :, :3], requests


@pytest.mark.skipif(CHROMIUM is None, reason="no system Chromium (apt-get install chromium)")
@pytest.mark.parametrize("shape", ["stepped_cylinder.toml", "mace_assembly.toml", "part.stl"])
def test_report_renders_in_headless_chromium(tmp_path, capsys, shape):
    if shape.endswith(".stl"):
        import trimesh

        from plumbob.bodies.primitives import box

        tri = np.asarray(box(0.04, 0.02, 0.01).triangles)
        path = str(tmp_path / shape)
        trimesh.Trimesh(tri.reshape(-1, 3), np.arange(len(tri) * 3).reshape(-1, 3)).export(path)
    else:
        path = os.path.join(SHAPES, shape)
    out = tmp_path / "report.html"
    assert main(["report", path, "-o", str(out)]) == 0
    errors, pixels, requests = _page_check(str(out))
    assert errors == []
    assert requests == []
    # The WebGL canvas drew the body: the middle of the view holds its shaded colour, not
    # the blank grey-and-white of an empty scene.
    h, w = pixels.shape[:2]
    middle = pixels[h // 4: 3 * h // 4, w // 4: 3 * w // 4]
    tinted = np.ptp(middle, axis=2) > 0.1  # coloured, not the scene's pale grey-blue
    assert tinted.mean() > 0.02, tinted.mean()


@pytest.mark.skipif(CHROMIUM is None, reason="no system Chromium (apt-get install chromium)")
def test_a_failed_requirement_is_the_headline_a_reviewer_sees(tmp_path, capsys):
    """Rendered, the page's headline reads FAIL on the topples colour: a screenshot of
    the headline is mostly that red, and its text comes first on the page."""
    sync_api = pytest.importorskip("playwright.sync_api", reason="pip install '.[browser]'")
    from io import BytesIO

    import matplotlib.image as mpimg

    from plumbob.plot.style import STATUS_COLOURS

    out = tmp_path / "report.html"
    assert main(["report", os.path.join(SHAPES, "block.toml"), "-o", str(out),
                 "--require-tilt", "40"]) == 0
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        try:
            page = browser.new_page(viewport={"width": 1200, "height": 900})
            page.route("http*://**", lambda route: route.abort())
            page.goto(f"file://{out}")
            headline = page.locator("#headline")
            text = headline.inner_text()
            box = headline.bounding_box()
            first = page.locator("body").inner_text().split("\n")
            shot = mpimg.imread(BytesIO(headline.screenshot()), format="png")[:, :, :3]
        finally:
            browser.close()
    assert text.startswith("FAIL: required tilt 40° not met")
    assert box is not None and box["y"] < 200  # above the fold, under the title
    assert [line for line in first if line.strip()][1].startswith("FAIL")
    red = np.array([int(STATUS_COLOURS["topples"][i:i + 2], 16) / 255 for i in (1, 3, 5)])
    assert (np.abs(shot - red).max(axis=2) < 0.08).mean() > 0.5
