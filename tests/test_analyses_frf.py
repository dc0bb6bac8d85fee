"""Frequency response functions (dynstiff/analyses/frf.py, theory.md §4): reciprocity, peaks at the
eigenfrequencies, an exact pole, and channels on held DOFs refused by the closed-form and
the lumped model alike."""

import numpy as np
import pytest
from conftest import linearised

import dynstiff as ds
from dynstiff import compiled
from dynstiff.errors import InvalidParameterError, PoleWarning

# These tests check the algebra of undamped FRFs (symmetry, kinds, files, figures) across
# natural frequencies on purpose: the ResonanceWarning that says so is expected here.
pytestmark = pytest.mark.filterwarnings("ignore::dynstiff.errors.ResonanceWarning")


def test_receptance_is_symmetric(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    H = ds.frf(m, 2 * np.pi * np.linspace(0.2, 10, 200)).H
    np.testing.assert_allclose(H, H.transpose(0, 2, 1), rtol=1e-8, atol=1e-12 * np.abs(H).max())


def test_frf_peaks_sit_at_eigenfrequencies(cogiro):
    light = ds.Robot(cogiro.robot.anchors, cogiro.robot.attachments,
                     ds.Cable(0.064, cogiro.robot.cables[0].EA, loss_factor=1e-4),
                     cogiro.robot.platform, tension_limits=cogiro.robot.tension_limits)
    eq = light.equilibrium(pose=cogiro.pose)
    m = ds.FrequencyModel(eq)
    modes = ds.modes(m, 3)
    f1 = modes.freq_hz[0]
    f = np.linspace(0.9 * f1, 1.1 * f1, 20001)
    H = ds.frf(m, 2 * np.pi * f).H
    amp = np.abs(H).max(axis=(1, 2))
    assert f[np.argmax(amp)] == pytest.approx(f1, rel=2e-4)


def test_frf_exact_pole_warns_and_returns_inf(cogiro_eq):
    class Singular:
        """The closed-form model with an exactly singular K at the first frequency."""

        def __init__(self, model):
            self.model = model

        def __getattr__(self, name):
            return getattr(self.model, name)

        def dynamic_stiffness(self, omega):
            K = self.model.dynamic_stiffness(omega)
            K[0] = 0.0
            return K

    with pytest.warns(PoleWarning, match=r"e\.g\. 0\.159154943 Hz") as record:  # 1 rad/s
        H = ds.frf(Singular(ds.FrequencyModel(cogiro_eq)), [1.0, 2.0]).H
    # the warning points at the caller, not into the module
    assert not record[0].filename.replace("\\", "/").endswith("dynstiff/analyses/frf.py")
    assert np.all(np.isinf(H[0])) and np.all(np.isfinite(H[1]))


def test_frf_channel_on_held_dofs_only_raises_like_closed_form():
    """The point-mass four-cable robot has x, y, z free: a moment input or a rotation
    output named explicitly would give an FRF identically 0, so both models refuse it."""
    eq = ds.load_scene("fourcable").equilibrium()
    lumped = linearised(eq.robot, eq.unstretched_lengths, 2)
    for model in (lumped, ds.FrequencyModel(eq)):
        with pytest.raises(InvalidParameterError) as err:
            ds.frf(model, [1.0], inputs="mx")
        assert str(err.value) == ("inputs ['mx'] act on held DOFs only (free DOFs: "
                                  "('x', 'y', 'z')): their FRFs are identically 0")
        with pytest.raises(InvalidParameterError) as err:
            ds.frf(model, [1.0], outputs=["x", "rz"], point=[0.1, 0.0, 0.0])
        assert str(err.value) == ("outputs ['rz'] move with held DOFs only (free DOFs: "
                                  "('x', 'y', 'z'), point [0.1, 0.0, 0.0]): their FRFs are "
                                  "identically 0")
        with pytest.raises(InvalidParameterError, match=r"^point must have shape \(3,\)"):
            ds.frf(model, [1.0], point=[1.0, 2.0])
        assert ds.frf(model, [1.0], inputs="fz", outputs="z").H.shape == (1, 1, 1)


def test_mobility_and_accelerance_values(cogiro_eq):
    """Mobility = i omega H and accelerance = -omega^2 H (convention e^{i omega t},
    theory.md §4): a purely imaginary, respectively real, multiple of the receptance, which
    is real for the undamped robot."""
    m = ds.FrequencyModel(cogiro_eq)
    w = 2 * np.pi * np.array([0.7, 2.9])
    H = ds.frf(m, w, inputs=["fx", "mz"], outputs=["y", "rz"]).H
    mob = ds.frf(m, w, inputs=["fx", "mz"], outputs=["y", "rz"], kind="mobility")
    acc = ds.frf(m, w, inputs=["fx", "mz"], outputs=["y", "rz"], kind="accelerance")
    np.testing.assert_array_equal(mob.H.real, 0.0)
    np.testing.assert_allclose(mob.H.imag, w[:, None, None] * H.real, rtol=1e-15)
    np.testing.assert_allclose(acc.H.real, -(w**2)[:, None, None] * H.real, rtol=1e-15)
    assert mob.unit("y", "fx") == "m/(N s)" and acc.unit("rz", "mz") == "rad/(N m s^2)"


def test_channel_lists_are_checked_and_an_empty_grid_gives_an_empty_result(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    with pytest.raises(InvalidParameterError, match="names 'fz' twice"):
        ds.frf(m, [1.0], inputs=["fz", "fz"])
    with pytest.raises(InvalidParameterError, match="outputs must name at least one"):
        ds.frf(m, [1.0], outputs=[])
    with pytest.raises(InvalidParameterError, match="inputs must be a name or a list"):
        ds.frf(m, [1.0], inputs=3)
    empty = ds.frf(m, [], inputs="fz", outputs="z")
    assert empty.H.shape == (0, 1, 1) and empty.freq_hz.shape == (0,)
    with pytest.raises(InvalidParameterError, match="model must be a model of the ladder"):
        ds.frf(cogiro_eq, [1.0])


def test_frequency_grids_beyond_the_memory_guard_are_refused(cogiro_eq):
    m = ds.FrequencyModel(cogiro_eq)
    with pytest.raises(InvalidParameterError, match="more than max_frequencies = 10"):
        ds.frf(m, np.linspace(0.1, 1.0, 11), max_frequencies=10)
    assert ds.frf(m, np.linspace(0.1, 1.0, 10), max_frequencies=10).H.shape[0] == 10
    # the documented default: one million frequencies (refused before any work is done)
    with pytest.raises(InvalidParameterError, match="more than max_frequencies = 1000000;"):
        ds.frf(m, np.ones(1_000_001))


def test_output_point_moves_with_the_platform_rotation(cogiro_eq):
    """The translation of a platform point c is dp - [R_p c]x dtheta (theory.md §4): the
    FRF to point c follows from the FRFs at P, with the lever of c rotated by R_p."""
    eq = cogiro_eq.robot.equilibrium(pose=[0.3, -0.2, 1.1, 0.05, -0.03, 0.1])
    m = ds.FrequencyModel(eq)
    w = 2 * np.pi * np.array([0.9, 1.7])
    c = np.array([0.4, -0.25, 0.3])
    Hc = ds.frf(m, w, outputs=["x", "y", "z"], point=c).H
    HP = ds.frf(m, w).H                                    # (n, 6 outputs, 6 inputs)
    rc = eq.pose.matrix @ c
    lever = np.array([[0, -rc[2], rc[1]], [rc[2], 0, -rc[0]], [-rc[1], rc[0], 0]])
    expected = HP[:, :3, :] - lever @ HP[:, 3:, :]
    np.testing.assert_allclose(Hc, expected, rtol=1e-12, atol=1e-15 * np.abs(HP).max())
    assert np.abs(Hc - HP[:, :3, :]).max() > 1e-3 * np.abs(HP[:, :3, :]).max()


def test_frf_exactly_on_a_cable_pole_is_the_finite_limit(cogiro_eq):
    """A clamped-cable frequency is a pole of that cable's K_B (entries ~1e16 there in
    float64) but not of H, where it is an anti-resonance: the FRF at the pole is finite,
    equal to its limit from both sides, and no PoleWarning is issued."""
    import warnings
    m = ds.FrequencyModel(cogiro_eq)
    poles = ds.cable_natural_frequencies(cogiro_eq.states[0], 2)
    assert list(poles.family) == ["out-of-plane", "in-plane symmetric"]
    # the out-of-plane poles are harmonic (2 w is a pole too); the symmetric in-plane
    # (Irvine) pole is not, and there the plain LU of K is 6 % off
    for w_pole in 2 * np.pi * poles.freq_hz:
        assert np.abs(m.dynamic_stiffness(w_pole)).max() > 1e12
        with warnings.catch_warnings():
            warnings.simplefilter("error", PoleWarning)
            H = ds.frf(m, [w_pole * (1 - 1e-7), w_pole, w_pole * (1 + 1e-7)]).H
        assert np.all(np.isfinite(H[1]))
        np.testing.assert_allclose(H[1], 0.5 * (H[0] + H[2]), rtol=1e-6,
                                   atol=1e-9 * np.abs(H).max())


@pytest.mark.parametrize("rung", ["dsm", "spring"])
def test_numpy_fallback_equals_the_compiled_path(cogiro_eq, monkeypatch, rung):
    """Without numba the FRF is K(omega) batched then a real np.linalg.solve: the same H
    (to a few eps x cond K) as the compiled kernels, channels and output point included."""
    pytest.importorskip("numba")
    m = ds.build_model(cogiro_eq, rung)
    omega = 2 * np.pi * np.linspace(0.05, 12.0, 800)
    kw = {"inputs": ["fx", "fz", "mz"], "outputs": ["z", "rx"], "point": [0.2, 0.1, -0.3]}
    H = ds.frf(m, omega, **kw).H
    monkeypatch.setattr(compiled, "load", lambda name: None)
    H0 = ds.frf(m, omega, **kw).H
    assert H.dtype == H0.dtype == complex
    cond = np.linalg.cond(m.dynamic_stiffness(omega))
    err = np.abs(H - H0).max(axis=(1, 2)) / np.abs(H0).max(axis=(1, 2))
    assert np.all(err < 8 * np.finfo(float).eps * cond)
    assert err[cond < 1e3].max() < 1e-12


@pytest.mark.parametrize("damped", [False, True])
def test_numpy_path_isolates_an_exactly_singular_frequency(cogiro_eq, monkeypatch, damped):
    """Without the compiled kernels an exactly singular K(omega) at one frequency of the
    batch (real K, and complex K of a damped model) gives inf there and, at every other
    frequency, C K^-1 B solved on its own (theory.md §4)."""
    monkeypatch.setattr(compiled, "load", lambda name: None)
    m = ds.FrequencyModel(cogiro_eq)
    if damped:
        m = m.with_damping(platform_damping_ratio=0.02)
    omega = 2 * np.pi * np.array([0.8, 1.3, 2.1, 3.4])

    class Singular:
        def __getattr__(self, name):
            return getattr(m, name)

        def dynamic_stiffness(self, w):
            K = m.dynamic_stiffness(w)
            if len(w) == len(omega):         # the grid (frf also counts modes at its ends)
                K[2] = 0.0
            return K

    kw = {"inputs": ["fx", "mz"], "outputs": ["y", "z", "rx"]}
    with pytest.warns(PoleWarning):
        H = ds.frf(Singular(), omega, **kw).H
    assert H.dtype == complex and H.shape == (4, 3, 2)
    assert np.all(np.isinf(H[2]))
    K = m.dynamic_stiffness(omega)
    full = np.linalg.inv(K)
    ref = ds.frf(m, omega, **kw).H
    np.testing.assert_allclose(H[[0, 1, 3]], ref[[0, 1, 3]], rtol=1e-12)
    # the channels: y, z, rx of the free DOFs against fx, mz
    i_out, i_in = [1, 2, 3], [0, 5]
    np.testing.assert_allclose(H[[0, 1, 3]], full[[0, 1, 3]][:, i_out][:, :, i_in],
                               rtol=1e-10, atol=1e-14 * np.abs(full).max())


@pytest.mark.parametrize("n_points", [2, 40])
def test_an_undamped_frf_says_how_many_modes_it_crosses(n_points):
    """CoGiRo undamped from 2.5 to 3.5 Hz (above its first modes, so the count at the low
    end is not zero): the warning counts the natural frequencies strictly between the ends
    (eigenfrequencies) and names the ends in Hz; two frequencies are a range too."""
    m = ds.FrequencyModel(ds.load_scene("cogiro").equilibrium())
    f_all = ds.eigenfrequencies(m, fmax_hz=3.5)
    n = int(np.sum((f_all > 2.5) & (f_all < 3.5)))
    assert n > 0 and np.sum(f_all <= 2.5) > 0
    with pytest.warns(ds.ResonanceWarning) as rec:
        ds.frf(m, 2 * np.pi * np.linspace(2.5, 3.5, n_points), inputs=["fx"], outputs=["x"])
    said = [str(w.message) for w in rec if issubclass(w.category, ds.ResonanceWarning)]
    assert said[0].startswith(f"the FRF of this undamped model crosses {n} natural "
                              f"frequencies between 2.5 and 3.5 Hz: its peaks are")
