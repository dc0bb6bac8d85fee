"""The report page as a document (dynstiff/report/document.py, robot.py, html.py): title block,
inputs, verdicts, every platform mode's shape, the modes table to download; rendered in
headless Chromium (skipped where none is installed)."""

import base64
import datetime
import hashlib
import io
import re
import shutil
import subprocess
import warnings
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from conftest import assert_valid_html, inverted_stewart_scene

import dynstiff as ds
from dynstiff.errors import ClosedFormWarning
from dynstiff.report.document import platform_mode_table, spread_note
from dynstiff.report.robot import robot_report


class Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.imgs, self.links, self.captions, self._cap = [], [], [], False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img":
            self.imgs.append(a["src"])
        if tag == "a":
            self.links.append(a)
        self._cap = tag == "figcaption"

    def handle_data(self, data):
        if self._cap:
            self.captions.append(data)
            self._cap = False


def report(scene, out):
    robot_report(scene, out, n_points=150)
    text = (out / "report.html").read_text(encoding="utf-8")
    page = Page()
    page.feed(text)
    return text, page


def png_size(uri):
    from PIL import Image
    assert uri.startswith("data:image/png;base64,")
    im = Image.open(io.BytesIO(base64.b64decode(uri.split(",", 1)[1])))
    im.verify()
    return im.size


def check_document(scene, out):
    text, page = report(scene, out)
    words = assert_valid_html(text)
    eq = scene.equilibrium()
    st = ds.analyses.settings.analysis_settings(scene)
    checks = ds.design_checks(scene.robot, eq.pose, **st.check_options())
    pm = checks.platform
    # title block: version, a date of today, the input file and its hash
    assert f"dynstiff version {ds.__version__}" in re.sub(r"\s+", " ", words)
    today = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d")
    assert re.search(rf"date {today} \d\d:\d\d:\d\d UTC", re.sub(r"\s+", " ", words))
    assert hashlib.sha256(scene.path.read_bytes()).hexdigest() in words
    # inputs: platform mass and inertia, each cable's mass per length and EA, the pose
    rob = scene.robot
    assert f"{rob.platform.mass:.6g}" in words
    assert f"{rob.platform.inertia[0, 0]:.5g}" in words
    for c in rob.cables:
        assert f"{c.mass_per_length:.5g}" in words and f"{c.EA:.5g}" in words
    assert f"{eq.pose.position[2]:.4g}" in words and st.damping.text()[9:] in words
    # the checks: every row's verdict and reason
    for r in checks.rows:
        assert r["check"] in words and r["detail"] in words
    # every platform mode, in the table and as a figure
    assert pm.index.size >= 1
    shapes = [c for c in page.captions if c.startswith("Platform mode ")]
    assert [int(c.split()[2].rstrip(":")) for c in shapes] == [k + 1 for k in pm.index]
    assert len(page.imgs) == 1 + pm.index.size
    for uri in page.imgs:
        w, h = png_size(uri)
        assert w > 200 and h > 150
    # the full modes table to download, the same as the file beside the page
    (link,) = page.links
    assert link["download"] == "modes.csv"
    assert base64.b64decode(link["href"].split(",", 1)[1]).decode() == \
        (out / "modes.csv").read_text()
    assert "<script" not in text.lower()
    return text


@pytest.mark.slow
def test_cogiro_report_is_a_document(tmp_path):
    check_document(ds.load_scene("cogiro"), tmp_path)


def test_imported_caspr_robot_report_is_a_document(tmp_path):
    scene = ds.load_scene(inverted_stewart_scene(tmp_path / "stewart.toml"))
    check_document(scene, tmp_path / "out")


@pytest.mark.slow
def test_imported_ipanema_report_holds_its_high_platform_modes(tmp_path):
    """IPAnema 1 from CASPR with light cables (0.0095 kg/m, EA 1e5 N, 10-200 N): its platform
    modes include modes 13 and 22, above local cable modes; each has its shape."""
    from dataclasses import replace

    from dynstiff.scenes import import_caspr, write_scene
    d = Path(__file__).parent / "data" / "caspr"
    sc = import_caspr(d / "IPAnema_1_bodies.xml", d / "IPAnema_1_cables.xml",
                      ds.Cable(0.0095, 1e5))
    path = write_scene(tmp_path / "ipanema1.toml",
                       replace(sc.robot, tension_limits=(10.0, 200.0)), sc.pose,
                       name="ipanema1")
    text = check_document(ds.load_scene(path), tmp_path / "out")
    assert "Platform mode 13:" in text and "Platform mode 22:" in text


def test_spread_platform_motion_is_said():
    """planar2 with 3 kg/m cables (two 10 m cables of 30 kg on a 100 kg platform): no mode
    holds half its energy in the platform, so the note says the motion is spread and names
    the DOFs; CoGiRo's global modes do hold it, and get no note."""
    from dataclasses import replace

    from dynstiff.analyses.platform_modes import find_platform_modes
    sc = ds.load_scene("planar2")
    heavy = replace(sc.robot, cables=[replace(c, mass_per_length=3.0) for c in sc.robot.cables])
    # so heavy a cable is beyond the closed form's guard, which says so (not the subject)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.errors.ClosedFormWarning)
        pm = find_platform_modes(ds.FrequencyModel(heavy.equilibrium(pose=sc.pose)))
    assert pm.complete and pm.modes.platform_share.max() <= 0.5
    note = spread_note(pm)
    assert "spread over many cable-dominated modes" in note and "(x, z)" in note
    assert f"{pm.modes.platform_share.max():.0%}" in note
    table = platform_mode_table(pm)
    assert list(table["mode"]) == [k + 1 for k in pm.index]
    for d, k in pm.carriers.items():
        assert d in table.loc[table["mode"] == k + 1, "carries"].item()
    cogiro = find_platform_modes(ds.FrequencyModel(ds.load_scene("cogiro").equilibrium()))
    assert spread_note(cogiro) == ""


@pytest.mark.integration
def test_report_renders_in_headless_chromium(tmp_path):
    browser = shutil.which("chromium")
    if browser is None:
        pytest.skip("no chromium on this machine (Debian: apt-get install chromium)")
    scene = ds.load_scene(inverted_stewart_scene(tmp_path / "stewart.toml"))
    text, page = report(scene, tmp_path / "out")
    html_path = tmp_path / "out" / "report.html"
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             "--user-data-dir=" + str(tmp_path / "profile")]
    dom = subprocess.run([browser, *flags, "--dump-dom", html_path.as_uri()],
                         capture_output=True, text=True, timeout=120)
    assert dom.returncode == 0, dom.stderr
    # the browser parsed every figure and the download link intact
    srcs = re.findall(r'<img alt="[^"]*" src="([^"]+)"', dom.stdout)
    assert srcs == page.imgs and len(srcs) > 1
    assert 'download="modes.csv"' in dom.stdout
    assert "net::ERR" not in dom.stderr and "Uncaught" not in dom.stderr
    shot = tmp_path / "page.png"
    run = subprocess.run([browser, *flags, "--window-size=1200,3000",
                          f"--screenshot={shot}", html_path.as_uri()],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    from PIL import Image
    im = np.asarray(Image.open(shot).convert("L"))
    assert im.shape == (3000, 1200) and (im < 128).mean() > 0.01       # the page drew
    for uri in srcs:
        w, h = png_size(uri)
        assert w > 0 and h > 0


def test_an_incomplete_search_gives_an_empty_table_and_no_spread_note():
    from dynstiff.analyses.platform_modes import PlatformModes
    pm = PlatformModes(None, np.array([], int), {}, False, np.nan, 0.0, "ceiling reached")
    assert platform_mode_table(pm).empty and spread_note(pm) == ""


@pytest.mark.slow
def test_a_mode_below_the_first_platform_mode_that_moves_the_platform_is_named(tmp_path):
    """FAST (cables of 0.89 times the cabin's mass): the first platform mode (the carrier of
    a DOF) is at 0.77 Hz, while mode 1 at 0.156 Hz already holds 8 % of its energy in the
    cabin, above the checks' 5 % (its frequency is what the cabin's measurements see): the
    summary names it beside the first platform mode."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)   # the robot-level bound
        report(ds.load_scene("fast"), tmp_path)
    text = (tmp_path / "report.html").read_text()
    summary = text[text.index("Summary:"):].split("</p>")[0]
    m = re.search(r"the first at ([\d.]+) Hz \(the lowest mode the platform moves in, with "
                  r"a share of (\d+)%, is mode (\d+) at ([\d.]+) Hz\)", summary)
    assert m, summary
    first, share, mode, low = float(m[1]), int(m[2]), int(m[3]), float(m[4])
    assert mode == 1 and 5 <= share < 50 and low < 0.25 * first
    assert 0.12 <= low <= 0.2                         # the measured band (Li et al. 2024)
