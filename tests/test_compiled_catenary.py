"""Compiled Newton of the batched catenaries (dynstiff/compiled/catenary.py, theory.md
§13.6) against the numpy Newton of dynstiff/cable/catenary_batch.py it replaces: the same
(H, V0, L0) to round-off from straight and warm starts, deep sag and a start on the hanging
branch included, the same taut-branch verdicts, and CoGiRo inverse statics and map numbers
equal to those of the numpy path."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.cable import catenary_batch
from dynstiff.cable.catenary_batch import taut_catenaries

cc = pytest.importorskip("dynstiff.compiled.catenary", exc_type=ImportError)
G = 9.81


def _random_cables(rng, n):
    A = np.zeros((n, 3))
    span = rng.uniform(1.0, 20.0, n)
    phi = rng.uniform(0, 2 * np.pi, n)
    B = np.stack([span * np.cos(phi), span * np.sin(phi), rng.uniform(-8.0, 8.0, n)], 1)
    t = rng.uniform(30.0, 5000.0, n)
    EA = rng.choice([1.39487e5, 9.8461e5, 2e4], n)
    w0 = np.full(n, 0.064 * G)
    return A, B, t, EA, w0


def test_compiled_newton_equals_the_numpy_newton():
    """500 random cables (spans 1-20 m, tensions 30-5000 N, three moduli): the same cables
    converge to the taut branch, with (H, V0, L0) equal to 1e-12 (relative, V0 against
    the end tension), cold and from a perturbed warm start."""
    rng = np.random.default_rng(3)
    A, B, t, EA, w0 = _random_cables(rng, 500)
    ref = taut_catenaries(A, B, t, EA, w0, compiled=False)
    got = taut_catenaries(A, B, t, EA, w0)
    np.testing.assert_array_equal(got[4], ref[4])
    assert (~ref[4]).sum() > 400
    ok = ~ref[4]
    np.testing.assert_allclose(got[0][ok], ref[0][ok], rtol=1e-12, atol=0)
    np.testing.assert_allclose(got[2][ok], ref[2][ok], rtol=1e-12, atol=0)
    np.testing.assert_array_less(np.abs(got[1] - ref[1])[ok], 1e-12 * t[ok])
    warm = (ref[0] * 1.05, ref[1] - 0.02 * t, ref[2] * 0.999)
    warm = tuple(np.where(ok, w, 1.0) for w in warm)
    ref_w = taut_catenaries(A, B, t, EA, w0, start=warm, compiled=False)
    got_w = taut_catenaries(A, B, t, EA, w0, start=warm)
    np.testing.assert_array_equal(got_w[4], ref_w[4])
    ok = ~ref_w[4]
    np.testing.assert_allclose(got_w[2][ok], ref_w[2][ok], rtol=1e-12, atol=0)


def test_compiled_newton_rejects_the_hanging_branch():
    """Started on the long hanging solution with the same end tension, both Newtons stop
    there and flag it (not taut); the retry from the straight cable finds the taut one."""
    A = np.zeros((1, 3))
    B = np.array([[10.0, 0.0, 0.0]])
    EA, w0 = np.array([1.39487e5]), np.array([0.064 * G])
    taut = taut_catenaries(A, B, np.array([40.0]), EA, w0, compiled=False)
    d = B - A
    args = (np.hypot(d[:, 0], d[:, 1]), d[:, 2], np.linalg.norm(d, axis=1), np.array([40.0]),
            EA, w0)
    for L0 in (taut[2] * 1.6, taut[2] * 2.5):
        H0, V00 = np.array([5.0]), -0.5 * w0 * L0
        ref = catenary_batch._newton(*args, H0, V00, L0)
        got = cc.newton_taut(*args, H0, V00, L0, 1e-13, 40)
        assert got[3][0] == ref[3][0]
        if np.isfinite(ref[4][0]) and ref[4][0] <= 1e-13:
            np.testing.assert_allclose(got[2], ref[2], rtol=1e-12)
    again = taut_catenaries(A, B, np.array([40.0]), EA, w0,
                            start=(np.array([5.0]), -0.5 * w0 * taut[2] * 2.5, taut[2] * 2.5))
    np.testing.assert_allclose(again[2], taut[2], rtol=1e-12)


def test_cogiro_statics_equal_the_numpy_path(monkeypatch):
    """Inverse statics of 30 CoGiRo poses (warm-started along the list, as a map does):
    tensions and unstretched lengths equal to 1e-12 with the numpy Newton."""
    robot = ds.load_scene("cogiro").robot
    rng = np.random.default_rng(5)
    poses = [ds.Pose(p) for p in rng.uniform([-4.5, -3.0, 0.6], [4.5, 3.0, 2.8], (30, 3))]

    def run():
        out, prev = [], None
        for p in poses:
            prev = robot.equilibrium(pose=p, start=prev)
            out.append(np.concatenate([prev.tensions, prev.unstretched_lengths]))
        return np.array(out)
    fast = run()
    plain = catenary_batch.taut_catenaries
    monkeypatch.setattr(catenary_batch, "taut_catenaries",
                        lambda *a, **k: plain(*a, **{**k, "compiled": False}))
    from dynstiff.robot import statics
    monkeypatch.setattr(statics, "taut_catenaries", catenary_batch.taut_catenaries)
    monkeypatch.setattr(statics, "_compiled_fixed_point", lambda *a, **k: None)  # numpy loop
    np.testing.assert_allclose(fast, run(), rtol=1e-12, atol=0)
