"""Shared fixtures: CoGiRo-like cables (theory.md §8.1, §9.2)."""

import numpy as np
import pytest
import scipy.linalg

import dynstiff as ds
from dynstiff.lumped import LumpedLinearModel, LumpedMassModel, chain_equilibrium, chain_matrices

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
