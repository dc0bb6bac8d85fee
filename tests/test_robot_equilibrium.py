"""The equilibrium record (dynstiff/robot/equilibrium.py): its tensions, table and stiffness."""

import numpy as np
import pytest

import dynstiff as ds


def test_tensions_are_those_of_the_catenaries(cogiro_eq):
    eq = cogiro_eq
    np.testing.assert_array_equal(eq.tensions, [s.tension_at_end for s in eq.states])
    np.testing.assert_array_equal(eq.anchor_tensions, [s.tension_at_anchor for s in eq.states])
    # the anchors sit above the platform: the least tension is at B, the largest at A, and
    # they differ by about the weight of the cable above B (dT = w dz, theory.md §1.1)
    assert np.all(eq.min_tensions <= np.minimum(eq.tensions, eq.anchor_tensions) + 1e-12)
    assert np.all(eq.max_tensions >= np.maximum(eq.tensions, eq.anchor_tensions) - 1e-12)
    dz = np.array([s.anchor[2] - s.end[2] for s in eq.states])
    w = np.array([s.cable.mass_per_length * s.g for s in eq.states])
    np.testing.assert_allclose(eq.anchor_tensions - eq.tensions, w * dz, rtol=3e-3)
    for name in ("tensions", "anchor_tensions", "min_tensions", "max_tensions"):
        got = getattr(eq, name)                  # computed once, handed out as copies
        got[:] = 0.0
        assert np.all(getattr(eq, name) > 100.0), name


def test_table_has_units_and_one_row_per_cable(cogiro_eq):
    df = cogiro_eq.to_frame()
    assert len(df) == 8
    assert {"tension at B [N]", "tension at A [N]", "unstretched length [m]",
            "chord length [m]", "sag [m]", "lambda^2 [-]"} <= set(df.columns)
    np.testing.assert_array_equal(df["unstretched length [m]"], cogiro_eq.unstretched_lengths)
    r = repr(cogiro_eq)
    assert r.startswith("Equilibrium(8 cables") and len(r) < 160


def test_platform_stiffness_is_symmetric_at_a_full_equilibrium(cogiro_eq):
    """At a 6-DOF equilibrium the geometric stiffness is symmetric (theory.md §4), so the
    whole 6x6 platform stiffness is; it is positive definite for a stable pose."""
    K = cogiro_eq.platform_stiffness()
    assert np.abs(K - K.T).max() < 1e-9 * np.abs(K).max()
    assert np.linalg.eigvalsh(0.5 * (K + K.T)).min() > 0
    assert cogiro_eq.residual < 1e-10


def test_equilibria_compare_by_their_poses(cogiro):
    a = cogiro.robot.equilibrium(pose=[0.5, 0.0, 1.0])
    b = cogiro.robot.equilibrium(pose=ds.Pose([0.5, 0.0, 1.0]))
    assert a.pose == b.pose
    np.testing.assert_allclose(a.unstretched_lengths, b.unstretched_lengths, rtol=1e-14)
    with pytest.raises(AttributeError):
        a.pose = b.pose                                   # frozen record


def test_rich_display_holds_the_pose_and_the_tensions(cogiro_eq):
    from conftest import assert_valid_html
    text = assert_valid_html(cogiro_eq._repr_html_())
    for t in (*cogiro_eq.tensions, *cogiro_eq.anchor_tensions):
        assert f"{t:.5g}" in text
    assert str(np.round(cogiro_eq.pose.position, 4).tolist()) in text


def test_platform_stiffness_is_minus_the_wrench_derivative_off_equilibrium(cogiro_eq):
    """At fixed unstretched lengths and a pose off equilibrium (turned, moved: K_geo is not
    symmetric there), K = -dW/dx column by column, x = (dp, dtheta) with dtheta in the base
    frame (theory.md §4), against central differences of the wrench (step 1e-6)."""
    robot = cogiro_eq.robot
    L0 = cogiro_eq.unstretched_lengths
    pose = ds.Pose(cogiro_eq.pose.position + [0.02, -0.01, 0.01], [0.02, -0.03, 0.05])
    K = robot.platform_stiffness(pose, robot.cable_states(pose, L0))
    h = 1e-6
    fd = np.empty((6, 6))
    for k in range(6):
        dx = np.zeros(6)
        dx[k] = h
        wp, wm = (robot.wrench(p, robot.cable_states(p, L0))
                  for p in (pose.moved(dx), pose.moved(-dx)))
        fd[:, k] = -(wp - wm) / (2 * h)
    assert np.abs(K[3:, 3:] - K[3:, 3:].T).max() > 1.0          # off equilibrium
    np.testing.assert_allclose(K, fd, rtol=0, atol=2e-5 * np.abs(K).max())


def test_rich_display_title_header_and_note(cogiro):
    """The title rounds the pose to 4 decimals (m, rad); the header names each column with
    its unit; the note gives the statics residual."""
    import html
    eq = cogiro.robot.equilibrium(pose=ds.Pose([0.123456, -0.0987654, 1.0],
                                               [0.0123456, -0.0234567, 0.0345678]))
    text = html.unescape(eq._repr_html_())
    assert ("Equilibrium of 8 cables at P = [0.1235, -0.0988, 1.0] m, rotation "
            "[0.0123, -0.0235, 0.0346] rad") in text
    assert ("<tr><th>cable</th><th>tension at B [N]</th><th>tension at A [N]</th>"
            "<th>unstretched length [m]</th><th>sag [m]</th></tr>") in text
    assert f"statics residual {eq.residual:.2g}" in text


def test_table_columns_in_order(cogiro_eq):
    df = cogiro_eq.to_frame()
    assert list(df.columns) == ["cable", "tension at B [N]", "tension at A [N]",
                                "unstretched length [m]", "chord length [m]", "sag [m]",
                                "lambda^2 [-]"]
    np.testing.assert_array_equal(df["cable"], np.arange(8))


def test_plot_draws_on_the_axes_given(cogiro_eq):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    try:
        assert cogiro_eq.plot(ax=ax) is fig and ax.has_data()
    finally:
        plt.close(fig)


def test_one_cable_is_said_in_the_singular():
    """A 2 kg mass hanging on one cable (z free): the repr, the rich display's title and the
    refusal of a second free DOF say "1 cable"; the tension at the mass is its weight."""
    import html
    rob = ds.Robot([[0.0, 0.0, 5.0]], [[0.0, 0.0, 0.0]], ds.Cable(0.1, 1e6),
                   ds.Platform(2.0, free_dofs=("z",)))
    eq = rob.equilibrium(pose=[0.0, 0.0, 1.0])
    assert repr(eq).startswith("Equilibrium(1 cable, Pose(")
    assert eq.tensions[0] == pytest.approx(2.0 * 9.81, rel=1e-9)
    assert "Equilibrium of 1 cable at P = [0.0, 0.0, 1.0] m" in html.unescape(eq._repr_html_())
    assert repr(ds.load_scene("planar2").equilibrium()).startswith("Equilibrium(2 cables, ")
    with pytest.raises(ds.InvalidParameterError,
                       match=r"^anchors: 1 cable cannot hold a platform with 2 free DOFs "):
        ds.Robot([[0.0, 0.0, 5.0]], [[0.0, 0.0, 0.0]], ds.Cable(0.1, 1e6),
                 ds.Platform(2.0, free_dofs=("x", "z")))
