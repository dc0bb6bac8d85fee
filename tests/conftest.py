"""Shared fixtures: CoGiRo-like cables (theory.md §8.1, §9.2)."""

import numpy as np
import pytest

import dynstiff as ds

#: CoGiRo cable: 4 mm steel, 0.064 kg/m, area 8.2051e-6 m^2 (CoGiRo description, §C).
COGIRO_AREA = 8.2051e-6
COGIRO_MASS = 0.064
#: Anchor a_0 of CoGiRo (Table I) and attachment b_0 with the platform at (0, 0, 1) m.
A0 = np.array([-7.1775, -5.4361, 5.3911])
B0 = np.array([0.5032, -0.4928, 1.0])


def cogiro_cable(E=17e9, **kw):
    return ds.Cable(COGIRO_MASS, COGIRO_AREA * E, **kw)


@pytest.fixture
def cable17():
    return cogiro_cable(17e9)


@pytest.fixture
def state300(cable17):
    """theory.md §9.2 cable at about 300 N."""
    return ds.unstretched_length_for_tension(A0, B0, 300.0, cable17)
