"""Eigenfrequency sensitivities (dynstiff/analyses/sensitivity.py, theory.md §16.1-§16.4)
against an analytic limit and against central differences of independent solves (new
statics, new model, new eigen search at p +- h and p +- h/2, Richardson-extrapolated)."""

import numpy as np
import pytest
from conftest import inverted_stewart

import dynstiff as ds
from dynstiff.analyses import sensitivity_statics
from dynstiff.analyses.sensitivity import frequency_sensitivities, sensitivities_at
from dynstiff.analyses.sensitivity_parameters import equilibrium_with, expand_parameters
from dynstiff.errors import InvalidParameterError


def central_difference(robot, pose, name, rung, n_modes, rel=1e-3, hold="pose",
                       tension_reference=None, unstretched_lengths=None, **model_options):
    """df/dp of the first ``n_modes`` frequencies by central differences of independent
    solves at steps h and h/2, Richardson-extrapolated (error O(h^4) plus the solves' noise,
    about 1e-10 / h relative); h = rel |p| (rel for a zero coordinate, rel / 10 rad)."""
    p = expand_parameters([name], robot, pose, hold, tension_reference,
                          unstretched_lengths)[0]
    h = rel * abs(p.value) if p.value else rel
    h = rel / 10 if p.unit == "rad" else h

    def diff(step):
        out = []
        for s in (step, -step):
            eq = equilibrium_with(robot, pose, [name], [p.value + s], hold, tension_reference,
                                  unstretched_lengths, tol=1e-12)
            out.append(ds.eigenfrequencies(ds.build_model(eq, rung, **model_options),
                                           n_modes=n_modes, rtol=1e-13))
        return (out[0] - out[1]) / (2 * step)
    return (4 * diff(h / 2) - diff(h)) / 3


def damping_difference(robot, pose, n_modes, h=1e-3):
    """d zeta / d eta at eta = 0 of the first ``n_modes`` damped roots (theory.md §5.4) from
    models with a loss factor h and 2 h, Richardson (zeta is odd in eta)."""
    def zeta(eta):
        e = equilibrium_with(robot, pose, ["loss_factor"], [eta])
        return ds.damped_modes(ds.FrequencyModel(e), n_modes=n_modes).damping_ratio
    return (4 * zeta(h) / h - zeta(2 * h) / (2 * h)) / 3


def assert_matches(s, fd, j, rtol=1e-6):
    """Every mode's derivative within rtol of the parameter's largest effect."""
    scale = np.abs(fd).max()
    err = np.abs(s.derivative[:, j] - fd).max() / scale
    assert err <= rtol, (s.parameters[j], err)


@pytest.fixture(scope="module")
def cogiro_dsm(cogiro):
    eq = cogiro.robot.equilibrium(pose=cogiro.pose, tol=1e-12)
    return eq, ds.FrequencyModel(eq)


def test_single_dof_mass_on_two_springs_has_the_closed_form_derivatives():
    """A point mass free in z on two symmetric inclined cables of negligible weight, spring
    rung: K = 2 [(EA + T) / L u_z^2 + (T / L)(1 - u_z^2)], T = m g / (2 u_z), so at the
    fixed pose dK/dEA = 2 u_z^2 / L and dK/dm = g / (u_z L); f = sqrt(K / m) / 2 pi."""
    A = np.array([[-3.0, 0.0, 4.0], [3.0, 0.0, 4.0]])
    m, EA = 20.0, 2e5
    rob = ds.Robot(A, np.zeros((2, 3)), ds.Cable(1e-9, EA),
                   ds.Platform(m, free_dofs=("z",)), tension_limits=(1.0, 1e5))
    eq = rob.equilibrium(pose=[0.0, 0.0, 0.0])
    L, uz = 5.0, 0.8
    T = m * rob.g / (2 * uz)
    K = 2 * ((EA + T) / L * uz**2 + T / L * (1 - uz**2))
    dfdK = 1.0 / (4 * np.pi * np.sqrt(K * m))
    s = frequency_sensitivities(ds.build_model(eq, "spring"), ["EA", "mass"], n_modes=1)
    np.testing.assert_allclose(s.freq_hz, np.sqrt(K / m) / (2 * np.pi), rtol=1e-8)
    np.testing.assert_allclose(s.derivative[0], [dfdK * 2 * uz**2 / L,
                                                 dfdK * (rob.g / (uz * L) - K / m)],
                               rtol=1e-8)


@pytest.mark.parametrize("names", [
    ["EA", "EA_3", "mass_per_length", "mass_per_length_6"],
    ["mass", "inertia", "inertia_xz", "com_y", "com_z"],
    ["pose_x", "pose_z", "pose_rx", "pose_rz"],
    ["anchor_2_y", "anchor_5_z", "attachment_1_x", "attachment_6_z", "t_min"]])
def test_closed_form_rung_matches_central_differences(cogiro, cogiro_dsm, names):
    """theory.md §16.1: every parameter kind, first 8 modes of CoGiRo (well separated)."""
    eq, model = cogiro_dsm
    s = frequency_sensitivities(model, names, n_modes=8)
    for j, name in enumerate(names):
        assert_matches(s, central_difference(cogiro.robot, eq.pose, name, "dsm", 8), j)


def test_reference_tensions_and_fixed_lengths_match_central_differences(cogiro):
    """The tension distribution's reference (at a fixed pose), and the unstretched lengths
    with the pose following (forward statics)."""
    rob = cogiro.robot
    t_ref = np.linspace(300.0, 600.0, 8)
    eq = rob.equilibrium(pose=cogiro.pose, tension_reference=t_ref, tol=1e-12)
    s = frequency_sensitivities(ds.FrequencyModel(eq), ["t_ref_2", "t_ref_7"], n_modes=6,
                                tension_reference=t_ref)
    for j, name in enumerate(s.parameters):
        assert_matches(s, central_difference(rob, eq.pose, name, "dsm", 6,
                                             tension_reference=t_ref), j)
    L0 = eq.unstretched_lengths
    names = ["L0_0", "L0_5", "EA", "mass"]
    s = frequency_sensitivities(ds.FrequencyModel(eq), names, n_modes=6, hold="lengths")
    for j, name in enumerate(names):
        # a 1 mm change of a 9 m cable moves the pose by about 0.3 mm and modes 4-6
        # (3.21-3.26 Hz) veer: the step stays well below (0.1 mm)
        assert_matches(s, central_difference(rob, eq.pose, name, "dsm", 6, rel=1e-5,
                                             hold="lengths", unstretched_lengths=L0), j)


@pytest.mark.parametrize("rung, options", [("exact", {"fmax_hz": 6.0}),
                                           ("lumped", {"segments": 8})])
def test_exact_and_lumped_rungs_match_central_differences(cogiro, rung, options):
    """theory.md §16.3: the exact cable's forms through its fields, the lumped rung's own
    equilibrium and finite eigenproblem."""
    rob = cogiro.robot
    eq = rob.equilibrium(pose=cogiro.pose, tol=1e-12)
    if rung == "lumped":
        options = {**options, "tol": 1e-13}
    names = ["EA", "inertia", "anchor_0_z"]     # statics, platform, geometry; all: slow tier
    s = frequency_sensitivities(ds.build_model(eq, rung, **options), names, n_modes=5)
    for j, name in enumerate(names):
        assert_matches(s, central_difference(rob, eq.pose, name, rung, 5, **options), j)


@pytest.mark.slow
@pytest.mark.parametrize("rung, options", [("exact", {"fmax_hz": 6.0}),
                                           ("lumped", {"segments": 8}),
                                           ("catenary", {}), ("spring", {})])
def test_every_rung_and_parameter_kind_matches_central_differences(cogiro, rung, options):
    rob = cogiro.robot
    eq = rob.equilibrium(pose=cogiro.pose, tol=1e-12)
    if rung == "lumped":
        options = {**options, "tol": 1e-13}
    names = ["EA_3", "mass_per_length", "mass", "inertia_xy", "com_x", "pose_x", "pose_ry",
             "anchor_4_x", "attachment_2_y", "t_min"]
    s = frequency_sensitivities(ds.build_model(eq, rung, **options), names, n_modes=6)
    for j, name in enumerate(names):
        rel = 1e-2 if name == "inertia_xy" else 1e-3     # a small effect: a larger step
        assert_matches(s, central_difference(rob, eq.pose, name, rung, 6, rel=rel,
                                             **options), j)


def cluster_difference(robot, pose, name, rung, clusters, rel=1e-4, **options):
    """One-sided derivatives of the sorted frequencies for an increase of p, from central
    differences: a cluster splits at first order into f + h mu_1 < f + h mu_2 at p + h and
    f - h mu_2 < f - h mu_1 at p - h, so the order of a cluster's roots at p - h is reversed
    before the difference (Richardson of h and h/2 as :func:`central_difference`)."""
    p = expand_parameters([name], robot, pose)[0]
    h = rel * abs(p.value) if p.value else rel
    flip = np.concatenate([g[::-1] for g in clusters])

    def diff(step):
        f = []
        for s in (step, -step):
            eq = equilibrium_with(robot, pose, [name], [p.value + s], tol=1e-12)
            f.append(ds.eigenfrequencies(ds.build_model(eq, rung, **options),
                                         n_modes=len(flip), rtol=1e-13))
        return (f[0] - f[1][flip]) / (2 * step)
    return (4 * diff(h / 2) - diff(h)) / 3


@pytest.mark.parametrize("rung, options, rel", [
    ("dsm", {}, 1e-4),
    ("exact", {"fmax_hz": 250.0}, 1e-4),   # a pair's cross terms: both vectors' fields
    # the lumped chains' stiff segments (EA / l0 ~ 1e7 N/m on 1e-4 kg nodes) leave the
    # lowest eigenvalues 3e-10 of rounding: a larger step keeps that noise below 1e-7
    ("lumped", {"segments": 4, "tol": 1e-13}, 1e-2)])
def test_a_cluster_of_coincident_modes_gives_the_derivatives_of_its_eigenvalues(rung,
                                                                                 options, rel):
    """The octahedron's two degenerate pairs (C3v): a parameter that breaks the symmetry
    (one cable's EA, one anchor) splits each pair at first order, and the two one-sided
    derivatives are the eigenvalues of the pair's 2x2 problem; a symmetric one (the
    platform mass) keeps them equal."""
    rob, pose = inverted_stewart(), ds.Pose([0.0, 0.0, 1.5])
    eq = rob.equilibrium(pose=pose, tol=1e-12)
    names = ["EA_0", "anchor_1_x", "mass"]
    s = frequency_sensitivities(ds.build_model(eq, rung, **options), names, n_modes=6)
    assert s.cluster.tolist() == [0, 1, 1, 2, 2, 3]
    clusters = [[0], [1, 2], [3, 4], [5]]
    for j, name in enumerate(names):
        fd = cluster_difference(rob, pose, name, rung, clusters, rel, **options)
        assert_matches(s, fd, j, rtol=1e-6)
    split = np.abs(s.derivative[2, :2] - s.derivative[1, :2]) / np.abs(s.derivative[:, :2]).max(0)
    assert np.all(split > 0.1)                           # the pair does split
    np.testing.assert_allclose(s.derivative[2, 2], s.derivative[1, 2], rtol=1e-9)


def test_a_cluster_has_the_damping_ratios_of_its_damped_roots():
    """The octahedron's degenerate pairs under a loss factor of every cable (which keeps the
    symmetry): d f = 0, d zeta of each pair the same for both, and each against the damped
    roots (theory.md §5.4) at eta = h and 2 h, Richardson; EA beside it has no d zeta."""
    rob, pose = inverted_stewart(), ds.Pose([0.0, 0.0, 1.5])
    eq = rob.equilibrium(pose=pose, tol=1e-12)
    s = frequency_sensitivities(ds.FrequencyModel(eq), ["loss_factor", "EA"], n_modes=6)
    assert s.cluster.tolist() == [0, 1, 1, 2, 2, 3]
    assert np.all(s.derivative[:, 0] == 0) and np.all(np.isnan(s.damping_derivative[:, 1]))
    ref = damping_difference(rob, eq.pose, 6)
    np.testing.assert_allclose(s.damping_derivative[:, 0], ref, rtol=1e-6)
    np.testing.assert_allclose(s.damping_derivative[[2, 4], 0], s.damping_derivative[[1, 3], 0],
                               rtol=1e-9)


def test_loss_factor_gives_the_damping_ratio_of_the_damped_root(cogiro):
    """d zeta / d eta at eta = 0 against the damped roots (theory.md §5.4) of models with
    eta = h and 2 h, Richardson (zeta is odd in eta); the undamped frequencies do not move."""
    rob = cogiro.robot
    eq = rob.equilibrium(pose=cogiro.pose)
    s = frequency_sensitivities(ds.FrequencyModel(eq), ["loss_factor"], n_modes=4)
    assert np.all(s.derivative == 0.0)
    np.testing.assert_allclose(s.damping_derivative[:, 0], damping_difference(rob, eq.pose, 4),
                               rtol=1e-6)


def test_the_statics_term_matters_and_the_comparison_catches_its_loss(cogiro, cogiro_dsm,
                                                                      monkeypatch):
    """A planted bug: without the change of the equilibrium (dy/dp = 0) the derivative with
    respect to the platform mass is wrong by far more than the tolerance (the tensions
    carry the weight), and the central-difference comparison fails."""
    eq, model = cogiro_dsm
    fd = central_difference(cogiro.robot, eq.pose, "mass", "dsm", 4)
    monkeypatch.setattr(sensitivity_statics.LinearisedEquilibrium, "derivatives",
                        lambda self, d: np.zeros((len(d), self.y.size)))
    s = frequency_sensitivities(model, ["mass"], n_modes=4)
    with pytest.raises(AssertionError):
        assert_matches(s, fd, 0)
    assert np.abs(s.derivative[:, 0] - fd).max() > 1e-2 * np.abs(fd).max()


def test_bad_requests_are_refused_before_any_work(cogiro, cogiro_dsm):
    eq, model = cogiro_dsm
    with pytest.raises(InvalidParameterError, match="'EA_9' is not a parameter"):
        frequency_sensitivities(model, ["EA_9"], n_modes=2)
    with pytest.raises(InvalidParameterError, match="needs the distribution's reference"):
        frequency_sensitivities(model, ["t_ref_1"], n_modes=2)
    with pytest.raises(InvalidParameterError, match="fixed pose"):
        frequency_sensitivities(model, ["pose_x"], n_modes=2, hold="lengths")
    with pytest.raises(InvalidParameterError, match="twice"):
        frequency_sensitivities(model, ["mass", "mass"], n_modes=2)
    other = cogiro.robot.equilibrium(pose=eq.pose, tension_reference=400.0)
    with pytest.raises(InvalidParameterError, match="not the distribution closest"):
        frequency_sensitivities(ds.FrequencyModel(other), ["EA"], n_modes=2)


def test_the_table_the_relative_values_and_the_tornado(cogiro_dsm):
    import matplotlib
    matplotlib.use("Agg")
    _, model = cogiro_dsm
    s = frequency_sensitivities(model, ["EA", "mass", "pose_z"], n_modes=3)
    df = s.to_frame()
    assert len(df) == 9 and set(df["parameter"]) == {"EA", "mass", "pose_z"}
    np.testing.assert_allclose(s.relative, 0.01 * s.derivative * s.values, rtol=1e-15)
    np.testing.assert_allclose(s.elasticity[:, 0], s.derivative[:, 0] * s.values[0]
                               / s.freq_hz)
    fig = s.plot(modes=(0, 1))
    assert len(fig.axes) == 2


def test_whole_clusters_extends_a_cut_to_the_end_of_its_cluster():
    from dynstiff.analyses.sensitivity import whole_clusters
    f = np.array([1.0, 2.0, 2.0 * (1 + 5e-9), 2.0 * (1 + 1e-8), 3.0])
    assert [whole_clusters(f, t) for t in (0, 1, 2, 3, 4, 5, 9)] == [0, 1, 4, 4, 4, 5, 5]
    assert whole_clusters(np.array([2.0, 2.0 * (1 + 2e-8)]), 1) == 1   # 2e-8 apart: two
    assert whole_clusters(np.array([2.0, 2.0, 3.0]), 1) == 2          # a pair cut after one


def test_the_table_and_tornado_name_what_they_show(cogiro_dsm):
    """The table's columns carry their units; each tornado panel is titled with its mode
    (counted from 1) and frequency, its axis says what the bars are, the zero line is
    grey, and the figure is 4.2 in wide per mode."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    _, model = cogiro_dsm
    s = frequency_sensitivities(model, ["EA", "mass"], n_modes=2)
    df = s.to_frame()
    assert list(df.columns) == ["mode", "freq [Hz]", "cluster", "platform share [-]",
                                "parameter", "value", "unit", "df/dp [Hz/unit]",
                                "df per 1 % [Hz]", "elasticity [-]", "dzeta/dp [1/unit]"]
    np.testing.assert_array_equal(df["df/dp [Hz/unit]"], s.derivative.ravel())
    fig = s.plot(modes=(0, 1))
    assert tuple(fig.get_size_inches()) == (8.4, 3.6)
    for k, ax in enumerate(fig.axes):
        assert len(ax.patches) == 2                      # one bar per parameter
        assert ax.get_title() == f"mode {k + 1}: {s.freq_hz[k]:.4g} Hz"
        assert ax.get_xlabel() == "change per +1 % of the parameter [Hz]"
        zero = [ln for ln in ax.get_lines() if list(ln.get_xdata()) == [0.0, 0.0]]
        assert zero and matplotlib.colors.to_rgb(zero[0].get_color()) == (0.3, 0.3, 0.3)
    plt.close(fig)


@pytest.mark.parametrize("rung, options", [("dsm", {}), ("exact", {}),
                                           ("lumped", {"segments": 4})])
def test_the_platform_share_is_the_modes(cogiro, rung, options):
    """The sensitivities' platform share of each mode is that of dynstiff.modes on the same
    model; below the first mode the result is empty, of its rung, with NaN shares."""
    eq = cogiro.robot.equilibrium(pose=cogiro.pose)
    model = ds.build_model(eq, rung, **options)
    s = frequency_sensitivities(model, ["EA"], n_modes=4)
    modes = ds.modes(model, n_modes=4)
    np.testing.assert_allclose(s.platform_share, 1.0 - modes.cable_energy_fraction,
                               rtol=1e-6, atol=1e-9)
    assert s.note == "" and s.rung == rung and s.hold == "pose"
    empty = frequency_sensitivities(model, ["EA"], fmax_hz=0.1)
    assert empty.freq_hz.size == 0 and empty.rung == rung and empty.note == ""
    assert frequency_sensitivities(model, ["EA"], n_modes=1, hold="lengths").hold == "lengths"
    with pytest.raises(InvalidParameterError, match="^hold must be 'pose' or 'lengths', got "
                                                    "'fixed'$"):
        frequency_sensitivities(model, ["EA"], n_modes=1, hold="fixed")
    assert empty.platform_share.dtype == float


def test_a_lumped_model_of_another_distribution_is_refused_at_its_pose(cogiro):
    """A lumped model built at a tension reference other than the one given: its lengths are
    not the distribution's at its pose, and holding the pose is refused, naming the fix."""
    eq = cogiro.robot.equilibrium(pose=cogiro.pose, tension_reference=np.full(8, 400.0))
    model = ds.build_model(eq, "lumped", segments=4)
    with pytest.raises(InvalidParameterError, match=r"not those of the tension distribution "
                       r"at its pose \(closest to tension_reference\); give the reference "
                       r"it was built with, or hold='lengths'$"):
        frequency_sensitivities(model, ["EA"], n_modes=2)
    s = frequency_sensitivities(model, ["EA"], n_modes=2,
                                tension_reference=np.full(8, 400.0))
    assert np.all(np.isfinite(s.derivative))


def test_the_lumped_rung_at_a_reference_distribution_matches_central_differences(cogiro):
    """The lumped rung's sensitivities at a tension reference other than the robot's (its
    equilibrium derivative takes that reference), against central differences of lumped
    models built at the perturbed parameters and the same reference."""
    rob = cogiro.robot
    t_ref = np.linspace(300.0, 600.0, 8)
    eq = rob.equilibrium(pose=cogiro.pose, tension_reference=t_ref, tol=1e-12)
    model = ds.build_model(eq, "lumped", segments=4, tol=1e-13)
    s = frequency_sensitivities(model, ["t_ref_2", "EA"], n_modes=4, tension_reference=t_ref)
    for j, name in enumerate(s.parameters):
        fd = central_difference(rob, eq.pose, name, "lumped", 4, rel=1e-3,
                                tension_reference=t_ref, segments=4, tol=1e-13)
        assert_matches(s, fd, j, rtol=1e-5)


def test_modes_with_the_platform_at_rest_on_a_cable_pole_are_said_and_left_nan():
    """planar2: two equal cables, the platform at their common end. The out-of-plane
    cable modes in opposition leave the platform at rest at the clamped cables' frequency,
    a pole of K: those modes (a coincident pair per harmonic) have NaN sensitivities and
    share, the note says why, and every other mode has finite ones."""
    eq = ds.load_scene("planar2").equilibrium()
    m = ds.FrequencyModel(eq)
    s = ds.frequency_sensitivities(m, ["EA", "mass_per_length"], fmax_hz=6.0)
    assert s.note == ("modes with the platform at rest on a cable pole (NaN): their "
                      "sensitivities are those of the clamped cable")
    f_pole = ds.cable_natural_frequencies(eq.states[0], 6, guard_rtol=None)
    at_pole = np.isnan(s.platform_share)
    assert at_pole.sum() == 4
    poles = f_pole.freq_hz[(np.array(f_pole.family) == "out-of-plane") & (f_pole.freq_hz < 6)]
    np.testing.assert_allclose(s.freq_hz[at_pole], np.repeat(poles, 2), rtol=1e-9)
    assert np.all(np.isnan(s.derivative[at_pole]))
    assert np.all(np.isfinite(s.derivative[~at_pole]))


def test_an_unstretched_length_is_reported_with_its_value():
    """At fixed lengths, L0_i's value is the equilibrium's unstretched length [m], so its
    per-1 % sensitivity is df/dL0 x L0 / 100; the clusters are integer labels."""
    eq = ds.load_scene("cogiro").equilibrium()
    m = ds.FrequencyModel(eq)
    s = ds.frequency_sensitivities(m, ["L0_0", "L0_3"], n_modes=3, hold="lengths")
    np.testing.assert_array_equal(s.values, eq.unstretched_lengths[[0, 3]])
    np.testing.assert_allclose(s.relative, s.derivative * s.values / 100, rtol=1e-12)
    assert s.cluster.dtype.kind == "i" and s.to_frame()["cluster"].dtype.kind == "i"


def test_the_repr_counts_modes_and_parameters(cogiro_dsm):
    """One mode and one parameter in the singular, more in the plural; the rung and what is
    held fixed."""
    _, model = cogiro_dsm
    one = frequency_sensitivities(model, ["mass"], n_modes=1)
    assert repr(one) == "SensitivityResult(1 mode x 1 parameter, dsm rung at fixed pose)"
    two = frequency_sensitivities(model, ["mass", "EA"], n_modes=2)
    assert repr(two) == "SensitivityResult(2 modes x 2 parameters, dsm rung at fixed pose)"


def test_a_loss_factor_beside_frequency_parameters_keeps_each_columns_meaning(cogiro_dsm):
    """Mixed parameters: each column is what it is alone, to rounding (the forms of all the
    parameters are one stacked product): the loss factor's d f = 0 and its d zeta; EA's and
    the mass's d f with d zeta NaN, not computed; for lone roots."""
    model = cogiro_dsm[1]
    both = frequency_sensitivities(model, ["EA", "loss_factor", "mass"], n_modes=6)
    for j, name in enumerate(["EA", "loss_factor", "mass"]):
        alone = frequency_sensitivities(model, [name], n_modes=6)
        np.testing.assert_allclose(both.derivative[:, j], alone.derivative[:, 0], rtol=1e-12)
        np.testing.assert_allclose(both.damping_derivative[:, j],
                                   alone.damping_derivative[:, 0], rtol=1e-12)
    assert np.all(both.derivative[:, 1] == 0) and np.all(both.damping_derivative[:, 1] > 0)
    assert np.all(np.isnan(both.damping_derivative[:, [0, 2]]))
    assert np.all(both.derivative[:, 0] > 0) and np.all(np.isfinite(both.derivative))
    assert len(set(both.cluster)) == 6                          # all lone roots


class _OtherRung:
    """A closed-form model under another rung's name (the interface of the ladder, no
    sensitivities)."""

    rung = "other"

    def __init__(self, model):
        self._m = model

    def __getattr__(self, name):
        return getattr(self._m, name)


def test_a_rung_without_sensitivities_is_refused_naming_the_rungs(cogiro_dsm):
    """Before any work: the rungs that have sensitivities, and the one given."""
    from dynstiff.errors import UnsupportedAnalysisError
    with pytest.raises(UnsupportedAnalysisError,
                       match=r"^frequency sensitivities need one of the rungs \('spring', "
                             r"'catenary', 'dsm', 'exact', 'lumped'\), got 'other'$"):
        frequency_sensitivities(_OtherRung(cogiro_dsm[1]), ["EA"], n_modes=2)


def test_the_tornado_draws_the_largest_changes_top_down_coloured_by_sign(cogiro_dsm):
    """As its docstring says: the 10 largest |change per 1 %| by default, the largest at the
    top, named on the axis, blue for a rise (a zero change too: the loss factor's) and red
    for a fall, a zero line 0.8 pt wide; one mode gives one panel."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgba
    names = ["EA", "mass_per_length", "loss_factor", "mass", "inertia", "com_z", "anchor_2_x",
             "anchor_5_y", "pose_z", "anchor_1_z", "t_min", "EA_3"]
    s = frequency_sensitivities(cogiro_dsm[1], names, n_modes=1)
    r = s.relative[0]
    assert np.any(r < 0) and np.any(r > 0) and np.sum(r == 0) == 1
    for n_shown, fig in ((10, s.plot()), (12, s.plot(n_parameters=12))):
        (ax,) = fig.axes
        widths = np.array([b.get_width() for b in ax.patches])
        top_down = np.argsort(np.abs(r))[::-1][:n_shown]
        np.testing.assert_array_equal(widths[::-1], r[top_down])
        assert [t.get_text() for t in ax.get_yticklabels()][::-1] == [names[j]
                                                                      for j in top_down]
        for b in ax.patches:
            assert b.get_facecolor() == to_rgba("tab:blue" if b.get_width() >= 0
                                                else "tab:red")
        zero = [ln for ln in ax.get_lines() if list(ln.get_xdata()) == [0.0, 0.0]]
        assert zero[0].get_linewidth() == 0.8
        plt.close(fig)
    assert 0.0 in widths                                # the loss factor, drawn in blue


@pytest.mark.parametrize("factor, moves", [(0.5, True), (2.0, False)])
def test_a_root_on_a_cable_pole_has_sensitivities_only_if_the_platform_moves(cogiro_dsm,
                                                                            factor, moves):
    """A pole planted at CoGiRo's 1st root (J0 steps there): with K's null eigenvalue at
    most 1e-6 of the massless stiffness's largest |eigenvalue| (0.5e-6 here) the platform
    moves and the root keeps the model's own sensitivities; above it (2e-6) the platform is
    at rest: NaN, and the note says why (theory.md §5.3)."""
    from conftest import PoleAtTheRootCounted
    model = cogiro_dsm[1]
    f = ds.eigenfrequencies(model, n_modes=3)
    ref = sensitivities_at(model, f, ["EA", "mass"])
    scale = np.abs(np.linalg.eigvalsh(model.massless_stiffness())).max()
    s = sensitivities_at(PoleAtTheRootCounted(model, f[0], factor * 1e-6 * scale), f,
                         ["EA", "mass"])
    np.testing.assert_allclose(s.derivative[1:], ref.derivative[1:], rtol=1e-12)
    if moves:
        np.testing.assert_allclose(s.derivative[0], ref.derivative[0], rtol=1e-6)
        assert s.platform_share[0] == pytest.approx(ref.platform_share[0], rel=1e-9)
        assert s.note == ""
    else:
        assert np.all(np.isnan(s.derivative[0])) and np.isnan(s.platform_share[0])
        assert s.note.startswith("modes with the platform at rest on a cable pole (NaN)")
