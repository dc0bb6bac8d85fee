"""Tests of the whole-robot lumped-mass model (dynstiff.models.lumped_robot): the residual and
its analytic tangent, statics, inputs, and a model without hidden state.

References: theory.md §4 (J_i, K_geo, M_p), §7.1 (lumped model), §7.2 (O(N^-2)), §1.1
(lumped nodes lie on the elastic catenary). The numbers asserted were measured with this
model and the closed-form robot statics (not published values); each comment gives the
measured value behind its tolerance."""

import dataclasses

import numpy as np
import pytest
from conftest import point_mass_robot

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import LumpedLinearModel, LumpedMassModel


def central_difference_jacobian(model, pose, interior, h=1e-6):
    """-dR/dx by central differences (platform moved by Pose.moved, nodes additively)."""
    K = np.zeros((model.n_dof, model.n_dof))
    for k in range(model.n_dof):
        e = np.zeros(model.n_dof)
        e[k] = h
        K[:, k] = -(model.residual(*model.displaced(pose, interior, e))
                    - model.residual(*model.displaced(pose, interior, -e))) / (2 * h)
    return K


@pytest.mark.parametrize("case", ["point mass", "6 dof", "pinned", "planar"])
def test_tangent_equals_central_difference_jacobian(cogiro, cogiro_eq, case):
    """Analytic sparse tangent (element K_e, slaved end nodes J_i, K_geo of the rotating lever
    arms) = central-difference Jacobian of the residual, away from equilibrium (where the
    geometric rotation block is not symmetric) as well as at it."""
    if case == "point mass":
        rob = point_mass_robot()
        L0 = rob.equilibrium(pose=[0.2, -0.1, 1.0]).unstretched_lengths
        start = None
    else:
        dofs = {"6 dof": ("x", "y", "z", "rx", "ry", "rz"), "pinned": ("rx", "ry", "rz"),
                "planar": ("x", "z", "ry")}[case]
        rob = dataclasses.replace(
            cogiro.robot, platform=dataclasses.replace(cogiro.robot.platform, free_dofs=dofs))
        L0, start = cogiro_eq.unstretched_lengths, cogiro.pose   # held DOFs at the scene pose
    model = LumpedMassModel(rob, L0, segments=4)
    st = model.equilibrium(initial_pose=start)
    rng = np.random.default_rng(1)
    pose, interior = model.displaced(st.pose, st.interior, 1e-3 * rng.standard_normal(model.n_dof))
    K = model.tangent_stiffness(pose, interior).toarray()
    K_fd = central_difference_jacobian(model, pose, interior)
    nf = model.n_free
    scale = np.abs(K).max()
    assert np.abs(K - K_fd).max() < 1e-8 * scale                 # measured 1e-10 to 3e-10
    Kp, Kp_fd = K[:nf, :nf], K_fd[:nf, :nf]
    assert np.abs(Kp - Kp_fd).max() < 1e-8 * np.abs(Kp).max()
    if sum(d.startswith("r") for d in rob.platform.free_dofs) >= 2:
        # off equilibrium the rotation block is non-symmetric (measured ~1e-3): the check
        # above covers the full K_geo, not only its symmetric part
        assert np.abs(Kp - Kp.T).max() > 1e-5 * np.abs(Kp).max()
        K_eq = LumpedLinearModel(model, st).matrices()[0].toarray()
        assert np.abs(K_eq - K_eq.T).max() < 1e-11 * np.abs(K_eq).max()   # measured 3e-13


# ------------------------------------------------------------------------------- errors
@pytest.mark.parametrize("segments, match", [
    (0, "segments"), (-3, "segments"), (2.5, "segments"), (True, "segments"),
    ([30] * 7, "segments"), ([30] * 7 + [0], r"^segments must be >= 1 for every cable, got "
                                             r"\[30, 30, 30, 30, 30, 30, 30, 0\]$"),
    ("30", "segments")])
def test_bad_segments(cogiro, cogiro_eq, segments, match):
    with pytest.raises(InvalidParameterError, match=match):
        LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=segments)


@pytest.mark.parametrize("lengths", [np.full(7, 10.0), np.r_[np.full(7, 10.0), -1.0],
                                     np.r_[np.full(7, 10.0), np.nan], "ten"])
def test_bad_lengths(cogiro, lengths):
    with pytest.raises(InvalidParameterError, match="unstretched_lengths"):
        LumpedMassModel(cogiro.robot, lengths, segments=10)


def test_other_bad_inputs(cogiro, cogiro_eq, lumped):
    with pytest.raises(InvalidParameterError, match="^robot must be a dynstiff.Robot, got "
                                                    "Platform$"):
        LumpedMassModel(cogiro.robot.platform, cogiro_eq.unstretched_lengths)
    with pytest.raises(InvalidParameterError, match="n_modes"):
        ds.eigenfrequencies(lumped(20), 0)
    with pytest.raises(InvalidParameterError, match="inputs"):
        ds.frf(lumped(20), [1.0], inputs="fq")
    with pytest.raises(InvalidParameterError, match="omega"):
        ds.frf(lumped(20), [-1.0])


def test_per_cable_segments(cogiro, cogiro_eq):
    segs = [10, 12, 14, 16, 10, 12, 14, 16]
    model = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=segs)
    st = model.equilibrium()
    assert [len(t) for t in st.tensions] == segs
    assert model.n_dof == 6 + 3 * sum(n - 1 for n in segs)
    one = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=1)
    assert list(one.segments) == [1] * 8 and one.n_dof == 6       # no interior node


def test_the_lumped_model_holds_no_hidden_state(cogiro, cogiro_eq):
    """equilibrium() returns a state and changes nothing in the model; the linearisation is
    built on a given state, and the analyses refuse the unlinearised model by name."""
    mm = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=4)
    before = {k: (id(v), v.tobytes() if isinstance(v, np.ndarray) else v)
              for k, v in vars(mm).items() if not isinstance(v, ds.Robot)}
    st = mm.equilibrium(initial_pose=cogiro.pose)
    mm.equilibrium(tol=1e-6)
    after = {k: (id(v), v.tobytes() if isinstance(v, np.ndarray) else v)
             for k, v in vars(mm).items() if not isinstance(v, ds.Robot)}
    assert before == after and not hasattr(mm, "state")
    lin = LumpedLinearModel(mm, st)
    assert lin.equilibrium is st and lin.pose is st.pose
    with pytest.raises(InvalidParameterError, match="linearise"):
        ds.eigenfrequencies(mm, 3)


def test_stacked_residual_equals_the_per_cable_loop(cogiro, cogiro_eq):
    """All chains at once (equal N) and cable by cable (any N) give the same forces, off
    equilibrium and with slack segments."""
    model = LumpedMassModel(cogiro.robot, cogiro_eq.unstretched_lengths, segments=6)
    st = model.equilibrium(initial_pose=cogiro.pose)
    rng = np.random.default_rng(7)
    pose, interior = model.displaced(st.pose, st.interior,
                                     2e-2 * rng.standard_normal(model.n_dof))
    nodes, _ = model.full_nodes(pose, interior)
    inner1, F1, t1 = model._chain_forces_stacked(nodes)
    inner2, F2, t2 = model._chain_forces_loop(nodes)
    assert np.abs(inner1 - inner2).max() < 1e-12 * np.abs(inner1).max()
    assert np.abs(F1 - F2).max() < 1e-12 * np.abs(F1).max()
    assert t1 == t2
    from dynstiff.models.lumped_statics import segment_forces
    T = [segment_forces(x, model.segment_lengths[i], cogiro.robot.cables[i].EA)[2]
         for i, x in enumerate(nodes)]
    assert any(np.any(t == 0.0) for t in T)                     # slack segments among them




def test_residual_scales_are_the_platform_size_and_the_weight(cogiro, cogiro_eq):
    """Moments are divided by the platform's size, max |b_i| and |r_G| (0.59 m for CoGiRo's
    attachments halved), or 1 m for a point mass; forces by the weight m_p g + sum m L0 g
    plus the largest tension."""
    rob = dataclasses.replace(cogiro.robot, attachments=0.5 * cogiro.robot.attachments)
    L0 = cogiro_eq.unstretched_lengths
    model = LumpedMassModel(rob, L0, segments=3)
    arm, weight = model.residual_scales()
    assert arm == max(np.linalg.norm(rob.attachments, axis=1).max(),
                      np.linalg.norm(rob.platform.center_of_mass)) < 1.0
    W = rob.g * (rob.platform.mass + sum(c.mass_per_length * l for c, l in zip(rob.cables, L0)))
    assert weight == pytest.approx(W, rel=1e-15)
    R = np.zeros(model.n_dof)
    R[3] = 2.0                                                    # a moment about x [N m]
    assert model.relative_residual(R, 100.0) == pytest.approx(2.0 / arm / (W + 100.0),
                                                              rel=1e-15)
    R[3], R[-1] = 0.0, 3.0                                        # a force on a node [N]
    assert model.relative_residual(R, 100.0) == pytest.approx(3.0 / (W + 100.0), rel=1e-15)
    point = LumpedMassModel(point_mass_robot(), np.full(3, 6.0), segments=3)
    assert point.residual_scales()[0] == 1.0


def test_the_repr_gives_cables_segments_and_lengths():
    """One cable in the singular, its segments and its unstretched length to 1e-6 m."""
    rob = ds.Robot([[0.0, 0.0, 5.0]], [[0.0, 0.0, 0.0]], ds.Cable(0.1, 1e6),
                   ds.Platform(2.0, free_dofs=("z",)))
    model = LumpedMassModel(rob, [4.123456789], segments=4)
    assert repr(model) == ("LumpedMassModel(1 cable, segments [4], unstretched lengths "
                           "[4.123457] m)")
