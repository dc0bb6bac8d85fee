"""Shared fixtures and helpers: CoGiRo-like cables and robots (theory.md §8.1, §9.2), lumped
models built once per module, the test cables of the lumped chain tests (theory.md
§1.1, §7.2, §9.2), the command line run in this process, the exact cable's hard cases
(theory.md §11.3) and the fuzzers' hostile values and oracle (tests/test_fuzz*.py)."""

import io
import os
import subprocess
import sys
import warnings

# Under pytest-xdist every core runs a worker: one BLAS thread each (set before numpy loads
# OpenBLAS), else the workers' dense factorisations and eigen solves (the exact cable's)
# fight over the cores: a test of tests/test_cable_exact.py ran 8 times slower.
if "PYTEST_XDIST_WORKER" in os.environ:
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_var, "1")

# Commands run in subprocesses (`python -m dynstiff ...`, notebooks, gallery scripts) import
# the tree under test, not whatever version is installed in site-packages.
_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.environ["PYTHONPATH"] = os.pathsep.join(
    [_ROOT] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p and p != _ROOT])

import numpy as np
import pytest
import scipy.linalg
from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st

import dynstiff as ds
from dynstiff.errors import DynstiffError, PoleWarning
from dynstiff.lumped import LumpedLinearModel, LumpedMassModel, chain_equilibrium, chain_matrices
from dynstiff.params import Cable

# Property tests draw the same examples on every run (reproducible in CI); set
# HYPOTHESIS_PROFILE=random to draw new ones.
settings.register_profile("derandomized", derandomize=True, database=None)
settings.register_profile("random")
# mutation runs (benchmarks/mutation.py): a failing example is not shrunk, the failure is enough
settings.register_profile("mutation", derandomize=True, database=None,
                          phases=(Phase.explicit, Phase.reuse, Phase.generate))
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "derandomized"))

#: CoGiRo cable: 4 mm steel, 0.064 kg/m, area 8.2051e-6 m^2 (CoGiRo description, §C).
COGIRO_AREA = 8.2051e-6
COGIRO_MASS = 0.064
#: Anchor a_0 of CoGiRo (Table I) and attachment b_0 with the platform at (0, 0, 1) m.
A0 = np.array([-7.1775, -5.4361, 5.3911])
B0 = np.array([0.5032, -0.4928, 1.0])


def cogiro_cable(E=17e9, **kw):
    return ds.Cable(COGIRO_MASS, COGIRO_AREA * E, **kw)


def point_mass_robot(E=17e9, mass=20.0):
    """3-cable suspended point-mass robot shared by the robot, lumped and time-domain tests."""
    anchors = np.array([[-4.0, -3.0, 5.0], [4.5, -2.0, 5.2], [0.3, 4.0, 4.8]])
    pl = ds.Platform(mass, free_dofs=("x", "y", "z"))
    return ds.Robot(anchors, np.zeros((3, 3)), cogiro_cable(E), pl)


@pytest.fixture(scope="module")
def cogiro():
    return ds.load_scene("cogiro")


@pytest.fixture(scope="module")
def cogiro_eq(cogiro):
    return cogiro.equilibrium()


@pytest.fixture
def cable17():
    return cogiro_cable(17e9)


@pytest.fixture
def state300(cable17):
    """theory.md §9.2 cable at about 300 N."""
    return ds.unstretched_length_for_tension(A0, B0, 300.0, cable17)


def lumped_point_mass_frequencies(eq, n_seg, n_modes=None, fmax_hz=None):
    """Independent lumped-mass model of a whole point-mass robot: chains of ``n_seg`` segments
    (own Newton statics, dynstiff.lumped) sharing their end node with the platform point mass.
    Its lowest ``n_modes`` eigenfrequencies, or all below ``fmax_hz`` [Hz], ascending."""
    rob = eq.robot
    sz = 3 * (n_seg - 1)
    N = 3 + sz * rob.n_cables
    Kt, Mt = np.zeros((N, N)), np.zeros(N)
    Mt[:3] = rob.platform.mass
    off = 3
    for i, s in enumerate(eq.states):
        ch = chain_equilibrium(rob.anchors[i], s.end, s.unstretched_length, rob.cables[i], n_seg,
                               rob.g)
        K, m = chain_matrices(ch)
        idx = np.arange(3, 3 * n_seg + 3)            # interior nodes 1..N-1, then node N
        glob = np.concatenate([np.arange(off, off + sz), np.arange(3)])
        Kt[np.ix_(glob, glob)] += K.toarray()[np.ix_(idx, idx)]
        Mt[glob] += m[idx]
        off += sz
    kw = (dict(subset_by_index=[0, n_modes - 1]) if n_modes is not None
          else dict(subset_by_value=[-np.inf, (2 * np.pi * fmax_hz) ** 2]))
    lam = scipy.linalg.eigh(Kt, np.diag(Mt), eigvals_only=True, **kw)
    return np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi)


def linearised(robot, unstretched_lengths, segments, **kw):
    """The "lumped" rung: the lumped-mass robot linearised about its own equilibrium
    (``kw`` go to :meth:`LumpedMassModel.equilibrium`)."""
    m = LumpedMassModel(robot, unstretched_lengths, segments=segments)
    return LumpedLinearModel(m, m.equilibrium(**kw))


# ---------------------------------------------------- frequency-domain models of CoGiRo
@pytest.fixture(scope="module")
def cogiro_model(cogiro_eq):
    return ds.FrequencyModel(cogiro_eq)


@pytest.fixture(scope="module")
def cogiro_modes(cogiro_model):
    return ds.modes(cogiro_model, 8)


@pytest.fixture(scope="module")
def lumped(cogiro, cogiro_eq):
    """Lumped CoGiRo models by segment count, built once."""
    cache = {}

    def get(N):
        if N not in cache:
            cache[N] = linearised(cogiro.robot, cogiro_eq.unstretched_lengths, N)
        return cache[N]
    return get


# -------------------------------------------------- point-mass robot in the time domain
@pytest.fixture(scope="module")
def lengths0():
    return point_mass_robot().equilibrium(pose=[0.2, -0.1, 1.0]).unstretched_lengths


@pytest.fixture(scope="module")
def robot_model(lengths0):
    """Point-mass robot models by segment count, at their equilibrium."""
    cache = {}

    def get(N):
        if N not in cache:
            m = linearised(point_mass_robot(), lengths0, N)
            cache[N] = m
        return cache[N]
    return get


# ------------------------------------------------------ test cables of the lumped chain
# theory.md §1.1 test cable: 7 m horizontal, 5 m drop, L0 = 8.5 m
CABLE_11 = Cable(mass_per_length=0.064, EA=1.39e5)
A_11, B_11, L0_11 = np.zeros(3), np.array([7.0, 0.0, -5.0]), 8.5

# theory.md §9.2 cable (CoGiRo a0, b0 + (0, 0, 1))
A_92 = np.array([-7.1775, -5.4361, 5.3911])
B_92 = np.array([0.5032, -0.4928, 1.0])
CABLE_92 = Cable(mass_per_length=0.064, EA=8.2051e-6 * 17e9)

# beaded string: a taut chain without gravity (g = 0)
BEAD = Cable(mass_per_length=0.5, EA=2.0e4)
BEAD_L, BEAD_L0 = 3.0, 2.97


def beaded_string(n_segments, cable=BEAD):
    state = chain_equilibrium([0, 0, 0], [BEAD_L, 0, 0], BEAD_L0, cable, n_segments, g=0)
    tension = cable.EA * (BEAD_L / BEAD_L0 - 1)
    return state, tension


class _Stderr(io.StringIO):
    """A captured standard error that is a terminal or not (progress bars draw on one)."""

    def __init__(self, terminal):
        super().__init__()
        self.terminal = terminal

    def isatty(self):
        return self.terminal


def exact_float_poles(mu, omega_max):
    """The omegas [rad/s] below ``omega_max`` that sit exactly on a clamped pole in floats,
    w * w * mu_j == 1.0 (the float next to sqrt(1 / mu_j), or one of its neighbours), one
    per pole that has such a float; ``mu`` the exact cable's flexibility eigenvalues."""
    poles = []
    for m in np.asarray(mu)[1 / np.asarray(mu) < omega_max ** 2]:
        w = np.sqrt(1 / m)
        poles += [c for c in (w, np.nextafter(w, 0), np.nextafter(w, np.inf))
                  if c * c * m == 1.0][:1]
    return poles


def damped_explicit_limit(mm, c_ax):
    """The explicit step limit of theory.md §7.3 computed from the cables of a
    LumpedMassModel ``mm``: dt0 = l0 / sqrt(EA / m), reduced by the damping ratio of the
    highest axial chain mode, zeta = c_ax / (l0 sqrt(EA m)) (axial dashpots c_ax [N s]), to
    dt0 (sqrt(1 + zeta^2) - zeta); the least over the cables [s]."""
    out = []
    for cb, L0, N in zip(mm.robot.cables, mm.unstretched_lengths, mm.segments):
        l0 = L0 / N
        dt0 = l0 / np.sqrt(cb.EA / cb.mass_per_length)
        zeta = c_ax / (l0 * np.sqrt(cb.EA * cb.mass_per_length))
        out.append(dt0 * (np.sqrt(1.0 + zeta ** 2) - zeta))
    return min(out)


def run_cli(*args, cwd=None, in_subprocess=False, terminal=False):
    """The command line ``dynstiff ARGS`` with its output captured, as
    ``subprocess.CompletedProcess`` (returncode, stdout, stderr), run in folder ``cwd``.

    In this process by default: ``dynstiff.cli.main(ARGS)`` with stdout and stderr
    redirected and the interpreter's warning filters (what the tests of a command reach is
    then seen by coverage and mutation testing, and no interpreter starts); an exception
    leaving ``main`` is written to stderr as Python would, exit code 1, and fails the test
    unless ``--debug`` was given (a command fails with one line). ``in_subprocess=True``
    runs ``python -m dynstiff ARGS`` instead (the entry point itself, interrupts);
    ``terminal=True`` makes the captured stderr a terminal (the progress bars are drawn)."""
    import contextlib
    import traceback
    import warnings
    args = [str(a) for a in args]
    if in_subprocess:
        return subprocess.run([sys.executable, "-m", "dynstiff", *args], capture_output=True,
                              text=True, cwd=cwd)
    from dynstiff.cli import main
    out, err = io.StringIO(), _Stderr(terminal)
    with contextlib.ExitStack() as stack:
        if cwd is not None:
            stack.enter_context(contextlib.chdir(cwd))
        stack.enter_context(contextlib.redirect_stdout(out))
        stack.enter_context(contextlib.redirect_stderr(err))
        stack.enter_context(warnings.catch_warnings())
        warnings.resetwarnings()                    # the interpreter's filters, not the suite's
        warnings.simplefilter("default")            # "error" for dynstiff's warnings
        for category in (DeprecationWarning, PendingDeprecationWarning, ImportWarning,
                         ResourceWarning):
            warnings.simplefilter("ignore", category)
        try:
            code = main(args)
        except SystemExit as exc:                   # argparse's -h and --version
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        except Exception:                           # as the interpreter: traceback, exit 1
            traceback.print_exc(file=err)
            code = 1
    assert "Traceback" not in err.getvalue() or "--debug" in args, err.getvalue()[-2000:]
    return subprocess.CompletedProcess(["dynstiff", *args], code, out.getvalue(),
                                       err.getvalue())


def cli_help(monkeypatch, *args):
    """What ``dynstiff ARGS -h`` prints (exit 0), on one line: its whitespace collapsed to
    single blanks, the terminal wide enough that argparse wraps no phrase."""
    monkeypatch.setenv("COLUMNS", "2000")
    out = run_cli(*args, "-h")
    assert out.returncode == 0, out.stderr
    return " ".join(out.stdout.split())


@pytest.fixture
def no_traceback(monkeypatch):
    """Every command line run here (subprocess or in-process) may fail, but with one line:
    a traceback without --debug fails the test."""
    run = subprocess.run

    def checked(args, *a, **kw):
        out = run(args, *a, **kw)
        err = out.stderr.decode() if isinstance(out.stderr, bytes) else (out.stderr or "")
        assert "Traceback" not in err or "--debug" in args, err[-2000:]
        return out
    monkeypatch.setattr(subprocess, "run", checked)


def inverted_stewart_scene(path, mass_per_length=0.01, EA=1e5):
    """Scene file at ``path`` of the test robot written in CASPR's format
    (tests/data/caspr/InvertedStewart_*.xml: six cables from three exit points, its
    trajectories and workspace box), with light cables whose modes lie above the platform's
    (0.01 kg/m, EA 1e5 N: platform modes about 3-6 Hz, first cable mode about 20 Hz)."""
    from pathlib import Path

    from dynstiff.scenes import import_caspr, write_scene
    d = Path(__file__).parent / "data" / "caspr"
    sc = import_caspr(d / "InvertedStewart_bodies.xml", d / "InvertedStewart_cables.xml",
                      ds.Cable(mass_per_length, EA),
                      trajectories_xml=d / "InvertedStewart_trajectories.xml")
    return write_scene(path, sc.robot, sc.pose, name="inverted_stewart",
                       trajectories=sc.trajectories.values(), workspace_box=sc.workspace_box)


def inverted_stewart(mass=100.0, mass_per_length=1e-4, EA=1e7, inertia=(10.0, 10.0, 15.0)):
    """Six cables from three anchor points to three platform points, an octahedron: the NIST
    RoboCrane, an inverted Stewart platform (J. Albus, R. Bostelman, N. Dagalakis, "The NIST
    SPIDER, a robot crane", J. Res. NIST 97(3), 373-385, 1992; "The NIST RoboCrane",
    J. Robot. Syst. 10(5), 709-724, 1993). Anchors: an equilateral triangle of 6 m sides
    (the size of the SPIDER's "6 m version") 3 m above the ground; platform: an inverted
    triangle of 1.5 m sides; each anchor holds the cables to its two nearest platform
    vertices. The height and the platform's size are those of CASPR's RoboCrane model: the
    papers' abstracts give no number for them that we could check."""
    ang_a, ang_b = np.radians([210.0, 330.0, 90.0]), np.radians([270.0, 30.0, 150.0])
    ra, rb = 6.0 / np.sqrt(3.0), 1.5 / np.sqrt(3.0)
    a = np.c_[ra * np.cos(ang_a), ra * np.sin(ang_a), np.full(3, 3.0)]
    b = np.c_[rb * np.cos(ang_b), rb * np.sin(ang_b), np.zeros(3)]
    pairs = [(k, int(j)) for k in range(3)
             for j in np.argsort(np.linalg.norm(b[:, :2] - a[k, :2], axis=1))[:2]]
    return ds.Robot(np.array([a[k] for k, _ in pairs]), np.array([b[j] for _, j in pairs]),
                    ds.Cable(mass_per_length, EA),
                    ds.Platform(mass, inertia=np.diag(inertia)))


def assert_valid_html(text):
    """Assert ``text`` parses as HTML with every opened element closed in order (no script)
    and return its text content."""
    from html.parser import HTMLParser
    void = {"br", "img", "meta", "hr", "input", "link"}

    class Check(HTMLParser):
        def __init__(self):
            super().__init__()
            self.stack, self.text = [], []

        def handle_starttag(self, tag, attrs):
            assert tag != "script"
            if tag not in void:
                self.stack.append(tag)

        def handle_endtag(self, tag):
            assert self.stack and self.stack.pop() == tag, f"unbalanced </{tag}>"

        def handle_data(self, data):
            self.text.append(data)

    p = Check()
    p.feed(text)
    p.close()
    assert not p.stack, f"unclosed {p.stack}"
    return " ".join(p.text)


# ------------------------------------ the command line's tables and library calls
def _metadata(path):
    """The ``# key: value`` header of a CSV table written by the command line, decoded."""
    import json
    return {k: json.loads(v) for k, v in (line[2:].split(": ", 1) for line in
                                          path.read_text().splitlines()
                                          if line.startswith("# "))}


def _spy(monkeypatch, module, name, calls, limit=None):
    """Replace ``module.name`` by a wrapper that records (args, kwargs) of each call in
    ``calls`` and calls the real function (more than ``limit`` calls: an error, not a hang)."""
    real = getattr(module, name)

    def spy(*a, **kw):
        calls.append((a, kw))
        if limit is not None and len(calls) > limit:
            raise AssertionError(f"{name} called more than {limit} times")
        return real(*a, **kw)
    monkeypatch.setattr(module, name, spy)
    return real


# ----------------------------------------------------------- the exact cable's cases
# (anchor, end, L0, cable): the hard cases of theory.md §11.3
HARD = {
    "sagging 10x5 m, d/L 0.10": ((0, 0, 0), (10.0, 0, 5.0), 11.5, ds.Cable(1.0, 1e6)),
    "steep 60 deg sagging": ((0, 0, 0), (5.0, 0, 5 * np.sqrt(3)), 10.6, ds.Cable(1.0, 1e6)),
    "soft, axial mode among the first ten": ((0, 0, 0), (10.0, 0, -2.0), 9.8,
                                             ds.Cable(1.0, 2e3)),
}


# ------------------------------------------ hostile input (tests/test_fuzz*.py)
# examples of a fuzzer in the default tier and (most fuzzers) in the slow tier
FAST, LONG = 25, 2500

# values a hostile user might pass where a number, a vector or a count is expected
weird_scalars = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-1e3, 1e3), st.integers(-10**20, 10**20), st.booleans(), st.none(),
    st.text(max_size=4), st.complex_numbers(allow_nan=True, allow_infinity=True),
    st.lists(st.floats(-10, 10), max_size=4))
weird_vectors = st.one_of(
    weird_scalars, st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=3,
                            max_size=3),
    st.lists(st.floats(-20, 20), min_size=3, max_size=3), st.lists(st.text(max_size=2),
                                                                  min_size=3, max_size=3))


def _settings(n):
    return settings(max_examples=n, deadline=None, derandomize=n == FAST,
                    suppress_health_check=[HealthCheck.too_slow,
                                           HealthCheck.function_scoped_fixture])


def _all_finite(result):
    """Every number reachable in ``result`` (arrays, dataclass fields, tuples) is finite."""
    if isinstance(result, (np.ndarray, float, int, complex, np.number)):
        arr = np.asarray(result)
        return arr.dtype.kind not in "fc" or bool(np.all(np.isfinite(arr)))
    if isinstance(result, (list, tuple)):
        return all(_all_finite(r) for r in result)
    fields = getattr(result, "__dataclass_fields__", None)
    if fields:
        return all(_all_finite(getattr(result, f)) for f in fields
                   if isinstance(getattr(result, f), (np.ndarray, float, int, complex, tuple)))
    return True


def obey_the_rule(fn, names):
    """Call ``fn``; a dynstiff error must name one of ``names``; a result must be finite
    unless a PoleWarning said why."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = fn()
        except DynstiffError as exc:
            text = str(exc)
            assert any(n in text for n in names), f"error does not name {names}: {text}"
            assert isinstance(exc, (ValueError, RuntimeError, TypeError)), type(exc)
            return None
    if not any(issubclass(w.category, PoleWarning) for w in caught):
        assert _all_finite(result), f"non-finite result without a PoleWarning: {result!r}"
    return result


class PoleAtTheRoot:
    """A closed-form model with a cable pole planted at ``root_hz`` (J0 steps there, in
    ``cable_mode_count``) and K's eigenvalue along its
    null vector at that root set to ``null_eigenvalue`` [N/m] (the vector itself unchanged):
    what a root sitting on a cable pole looks like, with the platform moving (a small null
    eigenvalue) or at rest (a large one), theory.md §5.3. Its fused K and count
    (``dynamic_stiffness_and_count``, what the root search reads) are the model's own, so
    the search finds the model's roots."""

    def __init__(self, model, root_hz, null_eigenvalue):
        self._m, self._w = model, 2 * np.pi * root_hz
        ev, V = np.linalg.eigh(model.dynamic_stiffness(self._w)[0])
        v = V[:, np.argmin(np.abs(ev))]
        self._shift = (null_eigenvalue - ev[np.argmin(np.abs(ev))]) * np.outer(v, v)

    def __getattr__(self, name):
        return getattr(self._m, name)

    def undamped(self):
        return self

    def _at_root(self, omega):
        return np.abs(np.asarray(omega) - self._w) < 1e-12 * self._w

    def cable_mode_count(self, omega):
        return self._m.cable_mode_count(omega) + (np.asarray(omega) > self._w)

    def dynamic_stiffness(self, omega):
        K = self._m.dynamic_stiffness(omega)
        K[np.atleast_1d(self._at_root(omega))] += self._shift
        return K


class PoleAtTheRootCounted(PoleAtTheRoot):
    """:class:`PoleAtTheRoot` whose fused K and count (what a root search reads, and the
    sensitivities' null vectors) see the planted pole too."""

    def dynamic_stiffness_and_count(self, omega):
        return self.dynamic_stiffness(omega), self.cable_mode_count(omega)
