"""Pages to look at: the data against the geometry (contacts on both posed outlines and on the line of
action, the drive's disc on its eccentric circle), a self-contained file, the command line, and a
real headless browser (Debian's chromium driven by playwright, never a downloaded browser): the
page loads without console errors, the animation advances, the 3D canvas is not blank.

The browser test skips locally when chromium or playwright is absent; under CI (``CI`` set) it
runs or fails.
"""
import json
import math
import os
import re
import shutil

import numpy as np
import pytest

from gearkit.cli import main
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.pair import PairSpec
from gearkit.view import blocking_view, drive_view, pair_view, render, write_page

CHROMIUM = "/usr/bin/chromium"
ROUND = 1e-5  # mm: the page rounds coordinates to 1e-5 mm (each +-5e-6: a distance off by at most 7.1e-6)


FINE = 1e-5  # mm: chord tolerance of the exact reference outlines
#: a contact's distance from a posed exact outline: the reference's chords (FINE, with the sampler's
#: overshoot between probes), the rounding of the point (7.1e-6) and of the pose (5e-8 rad x 40 mm)
ON = 3 * FINE


def _posed(body, frame, loops=None):
    a, x, y = body["poses"][frame]
    c, s = math.cos(a), math.sin(a)
    out = []
    for loop in body["loops"] if loops is None else loops:
        p = np.asarray(loop).reshape(-1, 2)
        out.append(p @ np.array([[c, s], [-s, c]]) + (x, y))
    return out


def _dist(points, loops):
    return np.min([distances_to_polyline(points, lp, closed=True) for lp in loops], axis=0)


@pytest.fixture(scope="module")
def pair_data():
    return pair_view(PairSpec(13, 17, 2.0), cycles=2)


def test_contacts_lie_on_both_posed_outlines_and_the_line_of_action(pair_data):
    """Every contact point of every frame touches both bodies as drawn (within the drawing's chord
    tolerance), and an involute pair's contacts lie on the line of action: the common tangent of
    the base circles through the pitch point (distance from it ~ 0)."""
    anim = pair_data["anim"]
    driver, mate = anim["bodies"]
    assert anim["frames"] == 2 * 48 == len(driver["poses"]) == len(anim["contacts"])
    spec = PairSpec(13, 17, 2.0)
    from gearkit.pair import pair_geometry

    g = pair_geometry(spec)
    from gearkit.contact import pair_mesh

    mesh = pair_mesh(spec)
    exact = [[mesh.gear1.outline(FINE)], [mesh.gear2.outline(FINE)]]
    rb1 = g.gears[0].base_diameter / 2.0
    a = g.center_distance
    seen = 0
    for f in range(0, anim["frames"], 7):
        pts = np.asarray(anim["contacts"][f]).reshape(-1, 2)
        if not len(pts):
            continue
        seen += len(pts)
        assert _dist(pts, _posed(driver, f, exact[0])).max() <= ON
        assert _dist(pts, _posed(mate, f, exact[1])).max() <= ON
        # lines of action: the tangents of the base circle rb1 through the pitch point (driver at the
        # origin, mate on +y at a); this tight pair touches on both flanks, one line each
        alpha = math.acos(rb1 / (a * 13 / 30))  # working pressure angle
        d = np.min([np.abs(pts @ np.array([sign * math.sin(alpha), math.cos(alpha)]) - rb1) for sign in (1, -1)],
                   axis=0)
        assert d.max() <= ROUND
    assert seen > 0


def test_driver_turns_a_pitch_per_cycle_and_the_ratio_holds(pair_data):
    driver, mate = pair_data["anim"]["bodies"]
    p = np.asarray(driver["poses"])
    q = np.asarray(mate["poses"])
    assert p[48, 0] - p[0, 0] == pytest.approx(2 * math.pi / 13, abs=2e-7)  # poses rounded to 1e-7
    # the mate turns the other way by z1/z2 of it (the TE of a conjugate pair is zero)
    assert q[48, 0] - q[0, 0] == pytest.approx(-2 * math.pi / 17, abs=2e-7)


def test_3d_parts_move_with_the_bodies(pair_data):
    parts = pair_data["parts3d"]
    assert [p["name"] for p in parts] == ["pinion", "wheel"] and [p["body"] for p in parts] == [0, 1]
    import base64

    v = np.frombuffer(base64.b64decode(parts[0]["positions"]), dtype="<f4").reshape(-1, 3)
    f = np.frombuffer(base64.b64decode(parts[0]["indices"]), dtype="<u4").reshape(-1, 3)
    assert f.max() < len(v)
    r = np.hypot(v[:, 0], v[:, 1]).max()  # the pinion in its own frame, like its 2D outline
    assert r == pytest.approx(np.hypot(*np.asarray(pair_data["anim"]["bodies"][0]["loops"][0]).reshape(-1, 2).T).max(),
                              abs=0.02 * 2.0)


def test_drive_disc_orbits_on_its_eccentric_in_the_fixed_pin_ring():
    from gearkit.families.cycloidal import DriveSpec

    spec = DriveSpec(8, 7, 40.0, 3.0, 1.5)
    data = drive_view(spec, cycles=3)
    disc, pins = data["anim"]["bodies"]
    from gearkit.families.cycloidal import disc_profile

    exact = disc_profile(spec).outline(FINE)
    q = np.asarray(pins["poses"])
    assert np.ptp(q, axis=0).max() <= 1e-9  # the pin ring stands still
    centre = q[0, 1:]
    p = np.asarray(disc["poses"])
    # poses are rounded to 1e-7 (rad, mm): a radius off by at most 7.1e-8 mm
    assert np.hypot(*(p[:, 1:] - centre).T) == pytest.approx(np.full(len(p), 1.5), abs=1e-7)
    for f in range(0, len(p), 11):
        pts = np.asarray(data["anim"]["contacts"][f]).reshape(-1, 2)
        if len(pts):
            assert _dist(pts, _posed(disc, f, [exact])).max() <= ON
    assert [x["id"] for x in data["findings"]]


def test_blocking_page_has_the_map_and_the_recommended_pair():
    from gearkit.blocking import blocking_contour

    spec = PairSpec(13, 16, 1.0)
    contour = blocking_contour(spec, points=40)
    rec = contour.recommend("balanced")
    data = blocking_view(spec, contour, rec, cycles=1)
    w = data["map"]["window"]
    assert w[0] <= rec.x1 <= w[1] and w[2] <= rec.x2 <= w[3]
    assert data["map"]["region"] and any(ln["code"] == "B1" for ln in data["map"]["lines"])
    assert f"{rec.x1:.4f}" in data["subtitle"]


def test_page_is_self_contained_and_escapes_its_data(tmp_path):
    data = {"title": "</script><b>x</b>", "findings": [], "parts3d": [], "summary": [["a", "</script>"]]}
    html = render(data)
    assert html.count("</script>") == 2  # the data's own are escaped
    assert not re.search(r"<script[^>]+src=|<link[^>]+href=|https?://(?!www\.w3\.org)", html)
    payload = html.split("window.GEARKIT_DATA = ", 1)[1].split(";</script>", 1)[0]
    assert json.loads(payload.replace("<\\/", "</"))["title"] == data["title"]
    with pytest.raises(SpecError, match="html"):
        write_page(tmp_path / "x.txt", data)
    assert list(tmp_path.iterdir()) == []


def test_cli_view_and_blocking_pages(tmp_path, capsys):
    out = tmp_path / "pair.html"
    assert main(["view", "pair", "--z1", "11", "--z2", "15", "-m", "1", "--cycles", "1", "-o", str(out)]) == 0
    assert out.read_text().startswith("<!DOCTYPE html>")
    assert main(["view", "pair", "--z1", "11", "--z2", "15", "-m", "1", "-o", str(tmp_path / "p.png")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and ".html" in err[0]
    page = tmp_path / "b.html"
    assert main(["blocking", "--z1", "13", "--z2", "16", "--points", "40", "-o", str(page)]) == 0
    assert '"map"' in page.read_text()


# -- a real browser ---------------------------------------------------------------------------------
def _browser_or_skip():
    try:
        from playwright.sync_api import sync_playwright  # noqa: F401
    except ImportError:
        if os.environ.get("CI"):
            raise
        pytest.skip("playwright is not installed (pip install playwright; the browser is Debian's chromium)")
    if not shutil.which(CHROMIUM):
        if os.environ.get("CI"):
            raise RuntimeError(f"CI must provide {CHROMIUM} (apt-get install chromium)")
        pytest.skip(f"no browser at {CHROMIUM} (apt-get install chromium)")


ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
        "--disable-component-update", "--disable-sync"]

#: share of the 3D canvas that must differ from its background colour (the solids fill far more)
FILLED = 0.02


def test_page_runs_in_a_headless_browser(tmp_path):
    """Loads without console errors, the animation advances (two screenshots of the mesh differ),
    the 3D canvas shows the solids, and nothing is fetched from the network."""
    _browser_or_skip()
    from playwright.sync_api import sync_playwright

    path = tmp_path / "drive.html"
    from gearkit.families.cycloidal import DriveSpec

    write_page(path, drive_view(DriveSpec(8, 7, 40.0, 3.0, 1.5), cycles=2))
    minimal = tmp_path / "minimal.html"
    square = [0.0, 0.0, 10.0, 0.0, 10.0, 10.0, 0.0, 10.0]
    write_page(minimal, {"title": "one body", "anim": {"frames": 8, "fps": 30, "contacts": [], "path": [],
                                                        "bodies": [{"name": "plate", "loops": [square],
                                                                    "poses": [[k / 8, 0, 0] for k in range(8)]}]}})
    profile = tmp_path / "profile"
    profile.mkdir()
    with sync_playwright() as pw:
        ctx = pw.chromium.launch_persistent_context(str(profile), executable_path=CHROMIUM, headless=True,
                                                    args=ARGS, viewport={"width": 1280, "height": 900})
        try:
            page = ctx.new_page()
            errors, requests = [], []
            page.on("console", lambda msg: errors.append(msg.text) if msg.type == "error" else None)
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            page.on("request", lambda req: requests.append(req.url) if not req.url.startswith(("file:", "data:"))
                    else None)
            page.goto(path.as_uri())
            page.wait_for_function("document.body.getAttribute('data-frame') !== null", timeout=20000)
            mesh = page.locator("#mesh2d")
            first = mesh.screenshot()
            f0 = int(page.evaluate("document.body.getAttribute('data-frame')"))
            page.wait_for_function(f"Number(document.body.getAttribute('data-frame')) !== {f0}", timeout=20000)
            page.wait_for_timeout(300)
            second = mesh.screenshot()
            filled = page.evaluate("""() => {
                const c = document.getElementById('solid3d');
                const t = document.createElement('canvas'); t.width = c.width; t.height = c.height;
                const g = t.getContext('2d'); g.drawImage(c, 0, 0);
                const d = g.getImageData(0, 0, t.width, t.height).data;
                const bg = [d[0], d[1], d[2]]; let n = 0;
                for (let i = 0; i < d.length; i += 4)
                    if (Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 30) n++;
                return n / (d.length / 4);
            }""")
            webgl = page.evaluate("document.getElementById('glnote').textContent")
            page.screenshot(path=str(tmp_path / "page.png"))
            # the least a producer may give: one turning body, no contacts, no trace, no solids
            page.goto(minimal.as_uri())
            page.wait_for_function("Number(document.body.getAttribute('data-frame')) > 0", timeout=20000)
        finally:
            ctx.close()
    assert errors == []
    assert requests == []
    assert first != second
    assert filled >= FILLED
    assert "not available" not in webgl


#: replaces fillText on the page's canvases to note what the map draws: text, x, y, width, canvas size
MAP_TEXT_PROBE = """<script>(function () {
  var seen = [], fill = CanvasRenderingContext2D.prototype.fillText;
  CanvasRenderingContext2D.prototype.fillText = function (t, x, y) {
    if (this.canvas.id === "map") {
      seen.push([String(t), x, y, this.measureText(t).width, parseFloat(this.font), this.canvas.width,
                 this.canvas.height]);
      document.body.setAttribute("data-map-text", JSON.stringify(seen.slice(-60)));
    }
    return fill.apply(this, arguments);
  };
})();</script>
"""


def test_blocking_map_text_stays_on_its_canvas(tmp_path):
    """The blocking page's map, drawn by the system's headless browser: every tick label, axis name
    and point label lies on the canvas and no two overlap (the last x tick, '1.48' on 13/16, ran
    4.5 px past the canvas' right edge: it was placed 10 px left of its tick whatever its width)."""
    _browser_or_skip()
    from playwright.sync_api import sync_playwright

    from gearkit.blocking import blocking_contour

    spec = PairSpec(13, 16, 1.0)
    c = blocking_contour(spec, points=40, tol=1e-3)
    html = render(blocking_view(spec, c, c.recommend(), c.mark(0.5, 0.3), cycles=1))
    page_path = tmp_path / "map.html"
    page_path.write_text(html.replace("<script>window.GEARKIT_DATA", MAP_TEXT_PROBE + "<script>window.GEARKIT_DATA", 1))
    profile = tmp_path / "profile"
    profile.mkdir()
    with sync_playwright() as pw:  # waits for the map's frames (a dump of the DOM may come before the first)
        ctx = pw.chromium.launch_persistent_context(str(profile), executable_path=CHROMIUM, headless=True,
                                                    args=ARGS, viewport={"width": 1200, "height": 900})
        try:
            page = ctx.new_page()
            page.goto(page_path.as_uri())
            page.wait_for_function("document.body.getAttribute('data-map-text') !== null", timeout=20000)
            page.wait_for_timeout(300)  # a few frames more: the last one's texts are read
            texts = json.loads(page.evaluate("document.body.getAttribute('data-map-text')"))
        finally:
            ctx.close()
    frame = {}  # the last frame's texts (the map is drawn every frame)
    for t, x, y, w, size, cw, ch in texts:
        frame[(t, round(x), round(y))] = (x, y - 0.8 * size, x + w, y + 0.25 * size, cw, ch)
    boxes = list(frame.items())
    assert {"x1", "x2", "recommended", "marked"} <= {t for (t, _, _), _ in boxes}
    for k, ((t, _, _), (x0, y0, x1, y1, cw, ch)) in enumerate(boxes):
        assert 0 <= x0 and x1 <= cw and 0 <= y0 and y1 <= ch, (t, x0, x1, cw)
        for (u, _, _), (a0, b0, a1, b1, _, _) in boxes[k + 1:]:
            assert min(x1, a1) <= max(x0, a0) or min(y1, b1) <= max(y0, b0), (t, u)
