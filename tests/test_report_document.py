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
import tomllib
import warnings
from dataclasses import replace
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from conftest import assert_valid_html, inverted_stewart_scene

import dynstiff as ds
from dynstiff.errors import ClosedFormWarning
from dynstiff.report.document import (
    cable_frame,
    input_rows,
    platform_mode_table,
    spread_note,
    title_rows,
)
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
    assert note == (f"No mode below {pm.searched_hz:.4g} Hz has more than half of its kinetic "
                    f"energy in the platform (largest share "
                    f"{round(100 * pm.modes.platform_share.max())}%): the platform's motion "
                    "is spread over many cable-dominated modes. Each DOF (x, z) is listed "
                    "with the mode that moves it most; the FRFs show the spread.")
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


WHEN = datetime.datetime(2024, 2, 29, 23, 5, 7, tzinfo=datetime.UTC)


def test_title_rows_of_a_scene_file_give_its_name_description_and_sha256(cogiro):
    """The title block of a scene read from a file: its name and description as the file
    states them, the version, the date, the file's path and the SHA-256 of its bytes."""
    toml = tomllib.loads(cogiro.path.read_text(encoding="utf-8"))["scene"]
    assert toml["description"]                       # a scene with a description
    digest = hashlib.sha256(Path(cogiro.path).read_bytes()).hexdigest()
    assert title_rows(cogiro, when=WHEN) == [
        ("scene", toml["name"]), ("description", toml["description"]),
        ("dynstiff version", ds.__version__), ("date", "2024-02-29 23:05:07 UTC"),
        ("input file", str(cogiro.path)), ("input file SHA-256", digest)]


def test_title_rows_of_a_scene_built_in_memory_say_so(cogiro, tmp_path):
    """A scene built in memory (no path), without a description: an empty description and
    the one input-file row saying so; likewise for a file that no longer exists."""
    sc = ds.scenes.loader.Scene(robot=cogiro.robot, pose=cogiro.pose, name="in memory")
    tail = [("dynstiff version", ds.__version__), ("date", "2024-02-29 23:05:07 UTC"),
            ("input file", "none (scene built in memory)")]
    assert title_rows(sc, when=WHEN) == [("scene", "in memory"), ("description", ""), *tail]
    gone = replace(cogiro, path=tmp_path / "gone.toml")
    assert title_rows(gone, when=WHEN)[2:] == tail


def test_input_rows_state_the_robot_and_the_settings_in_the_documented_format(cogiro):
    """Every row of the inputs, its label and its text, for inputs with more digits than
    the rows keep: mass and gravity to 6 significant digits, vectors "(x, y, z)" to 4,
    the inertia's rows to 5, joined by "; "; the settings as documented."""
    inertia = [[36.59812, 0.4531234, -3.012345], [0.4531234, 35.98234, 1.539876],
               [-3.012345, 1.539876, 25.43912]]
    pl = ds.Platform(91.0583721, [-0.0341234, -0.0129876, 0.264321], inertia)
    robot = replace(cogiro.robot, platform=pl)
    eq = robot.equilibrium(pose=ds.Pose([0.0123456, -0.0234567, 1.0345678],
                                        [0.00123456, -0.00234567, 0.0345678]))
    st = ds.analyses.settings.analysis_settings(
        cogiro, band_hz=(0.5, 20.0), forbidden_hz=(2.5, 4.0), rung="lumped", segments=12,
        model_rtol=0.02, margin=0.1, participation=0.2, frf_limit=5.0,
        damping=[0.02, 0.03, 0.5])
    rows = input_rows(eq, st)
    assert rows == [
        ("platform mass [kg]", "91.0584"),
        ("centre of mass, platform frame [m]", "(-0.03412, -0.01299, 0.2643)"),
        ("inertia about G, platform axes [kg m^2]",
         "(36.598, 0.45312, -3.0123); (0.45312, 35.982, 1.5399); (-3.0123, 1.5399, 25.439)"),
        ("free DOFs", "x, y, z, rx, ry, rz"),
        ("pose: position of P [m]", "(0.01235, -0.02346, 1.035)"),
        ("pose: rotation vector [rad]", "(0.001235, -0.002346, 0.03457)"),
        ("gravity [m/s^2]", "9.81"),
        ("tension limits [N]", "100 to 5000"),
        ("cable model", "lumped, 12 segments per cable, admissible frequency error 0.02"),
        ("band of interest [Hz]", "0.5-20"),
        ("forbidden band", "2.5-4 Hz, margin 10%, modes with platform share >= 20%, "
                           "receptance <= 5 x static"),
        ("damping", "platform modal ratio 0.02, cable loss factor 0.03 (axial and "
                    "transverse), cable viscous 0.5 N s/m^2"),
    ]
    assert rows[-1][1] == st.damping.text().removeprefix("damping: ")
    # no forbidden band: not checked; another rung: no segments
    rows = dict(input_rows(eq, replace(st, forbidden_hz=None, rung="dsm")))
    assert rows["forbidden band"] == "none (not checked)"
    assert rows["cable model"] == "dsm, admissible frequency error 0.02"


COLUMNS = ["mode", "freq [Hz]", "kind", "platform share [-]", "dominant dof", "carries",
           "massless freq [Hz]"]


def test_platform_mode_table_lists_each_platform_mode_and_the_dofs_it_carries(cogiro_eq):
    """CoGiRo: one row per platform mode, numbered from 1, with the modal result's numbers;
    a mode that carries no DOF says "-", one that carries two names both, in DOF order."""
    from dynstiff.analyses.platform_modes import find_platform_modes
    from dynstiff.robot.platform import DOF_NAMES
    pm = find_platform_modes(ds.FrequencyModel(cogiro_eq))
    m, k = pm.modes, pm.index
    t = platform_mode_table(pm)
    assert list(t.columns) == COLUMNS
    assert list(t["mode"]) == [int(j) + 1 for j in k]
    np.testing.assert_array_equal(t["freq [Hz]"], np.asarray(m.freq_hz)[k])
    np.testing.assert_array_equal(t["platform share [-]"], m.platform_share[k])
    np.testing.assert_array_equal(t["massless freq [Hz]"], np.asarray(m.massless_freq_hz)[k])
    assert list(t["kind"]) == [m.kind[j] for j in k]
    assert list(t["dominant dof"]) == [m.dominant_dof[j] for j in k]
    carried = [[d for d in DOF_NAMES if pm.carriers.get(d) == j] for j in k]
    assert any(len(c) == 0 for c in carried) and any(len(c) >= 2 for c in carried)
    assert list(t["carries"]) == [", ".join(c) if c else "-" for c in carried]


def test_a_search_without_modes_gives_the_columns_and_a_general_note():
    """No mode below the top of an incomplete search: the table has its columns and no row;
    the note names no DOF ("the free DOFs") and a largest share of 0 %."""
    from dynstiff.analyses.platform_modes import PlatformModes
    from dynstiff.results import ModalResult
    none = ModalResult(np.zeros(0), np.zeros((0, 6)), np.zeros(0), np.zeros((0, 8)), kind=(),
                       massless_freq_hz=np.zeros(0))
    for modes in (None, none):
        pm = PlatformModes(modes, np.zeros(0, int), {}, False, np.nan, 3.0, "ceiling reached")
        t = platform_mode_table(pm)
        assert list(t.columns) == COLUMNS and len(t) == 0
    assert spread_note(pm) == (
        "No mode below 3 Hz has more than half of its kinetic energy in the platform "
        "(largest share 0%): the platform's motion is spread over many cable-dominated "
        "modes. Each DOF (the free DOFs) is listed with the mode that moves it most; the "
        "FRFs show the spread.")


def test_cable_frame_lists_each_cable_in_order(cogiro, cogiro_eq):
    """One row per cable, in the robot's order: its anchor and attachment as "(x, y, z)" to
    4 significant digits, and its own mass per length, EA, loss factor, viscous damping."""
    cables = [replace(c, mass_per_length=0.05 + 0.001 * i, EA=1e5 * (i + 1),
                      loss_factor=0.01 * (i + 1), viscous_damping=0.1 * i)
              for i, c in enumerate(cogiro.robot.cables)]
    robot = replace(cogiro.robot, cables=cables)
    t = cable_frame(robot.equilibrium(pose=cogiro.pose))
    assert list(t.columns) == ["cable", "anchor A [m]", "attachment b [m]",
                               "mass per length [kg/m]", "EA [N]", "loss factor [-]",
                               "viscous damping [N s/m^2]"]
    n = len(cables)
    assert list(t["cable"]) == list(range(n)) and n == 8
    assert list(t["anchor A [m]"]) == [
        "(" + ", ".join(f"{x:.4g}" for x in a) + ")" for a in robot.anchors]
    assert list(t["attachment b [m]"]) == [
        "(" + ", ".join(f"{x:.4g}" for x in b) + ")" for b in robot.attachments]
    assert t["anchor A [m]"][0] == "(-7.178, -5.436, 5.391)"     # CoGiRo Table I, A0
    assert list(t["mass per length [kg/m]"]) == [0.05 + 0.001 * i for i in range(n)]
    assert list(t["EA [N]"]) == [1e5 * (i + 1) for i in range(n)]
    assert list(t["loss factor [-]"]) == [0.01 * (i + 1) for i in range(n)]
    assert list(t["viscous damping [N s/m^2]"]) == [0.1 * i for i in range(n)]


def test_the_default_date_is_now_in_utc_whatever_the_local_time_zone(cogiro, monkeypatch):
    """Without ``when`` the date is the present time in UTC, also on a machine whose local
    time is 5 h behind UTC (TZ=XST+05)."""
    import time
    monkeypatch.setenv("TZ", "XST+05")
    time.tzset()
    try:
        assert time.localtime().tm_gmtoff == -5 * 3600
        before = datetime.datetime.now(datetime.UTC).replace(microsecond=0)
        date = dict(title_rows(cogiro))["date"]
        after = datetime.datetime.now(datetime.UTC)
    finally:
        monkeypatch.undo()
        time.tzset()
    stamp = datetime.datetime.strptime(date, "%Y-%m-%d %H:%M:%S UTC").replace(
        tzinfo=datetime.UTC)
    assert before <= stamp <= after


def test_the_spread_note_is_given_up_to_a_largest_share_of_exactly_one_half():
    """"More than half" is strict: a largest platform share of exactly 0.5 gets the note,
    0.5001 none."""
    from dynstiff.analyses.platform_modes import PlatformModes
    from dynstiff.results import ModalResult

    def note(cable_fraction):
        m = ModalResult(np.array([1.0, 2.0]), np.zeros((2, 6)), np.array(cable_fraction),
                        np.zeros((2, 8)))
        return spread_note(PlatformModes(m, np.array([1]), {"x": 1}, True, 2.0, 2.5, ""))

    assert note([0.75, 0.5]) == (
        "No mode below 2.5 Hz has more than half of its kinetic energy in the platform "
        "(largest share 50%): the platform's motion is spread over many cable-dominated "
        "modes. Each DOF (x) is listed with the mode that moves it most; the FRFs show the "
        "spread.")
    assert note([0.75, 0.4999]) == ""
