"""Refined frequency grids (dynstiff/analyses/freqgrid.py, theory.md §12.3)."""

import numpy as np
import pytest

from dynstiff.analyses.freqgrid import refined_grid
from dynstiff.errors import InvalidParameterError


def lorentz_peak(f, f0, zeta):
    """|H| of a single-DOF oscillator with unit static value (analytic)."""
    r = f / f0
    return 1.0 / np.abs(1 - r**2 + 2j * zeta * r)


@pytest.mark.parametrize("zeta", [1e-3, 5e-3, 2e-2])
def test_peak_of_a_resonance_does_not_depend_on_the_uniform_count(zeta):
    """The sampled peak of an oscillator of damping ratio zeta >= 1e-3 is within 0.1 % of
    its true top 1 / (2 zeta sqrt(1 - zeta^2)) with 10 or 5000 uniform points; a uniform
    grid of 300 points misses it by more than 5 % (what the refinement is for)."""
    f0 = 3.3171
    top = 1 / (2 * zeta * np.sqrt(1 - zeta**2))
    for n in (10, 5000):
        f = refined_grid((0.1, 12.0), n, [f0, 20.0])
        assert abs(lorentz_peak(f, f0, zeta).max() / top - 1) < 1e-3
    if zeta <= 5e-3:
        assert lorentz_peak(np.linspace(0.1, 12.0, 300), f0, zeta).max() < 0.95 * top


def test_grid_is_sorted_unique_inside_the_band():
    f = refined_grid((1.0, 2.0), 11, [0.5, 1.0, 1.5, 1.5, 2.0, 3.0])
    assert f[0] == 1.0 and f[-1] == 2.0 and np.all(np.diff(f) > 0)
    assert 1.5 in f and f.size > 11
    assert np.array_equal(refined_grid((1.0, 2.0), 11), np.linspace(1.0, 2.0, 11))


@pytest.mark.parametrize("kw, name", [(dict(band_hz=(2.0, 1.0)), "band_hz"),
                                      (dict(band_hz="x"), "band_hz"),
                                      (dict(n_points=1), "n_points"),
                                      (dict(rel_width=1e-7), "rel_min"),
                                      (dict(rel_width=-0.1), "^rel_width"),
                                      (dict(rel_min=0.0), "^rel_min"),
                                      (dict(rel_min=1e-3, rel_width=1e-3), "^rel_min")])
def test_bad_input_is_named(kw, name):
    args = dict(band_hz=(0.0, 1.0), n_points=10, **{})
    args.update(kw)
    with pytest.raises(InvalidParameterError, match=name):
        refined_grid(**args)


def test_the_grid_holds_every_mode_of_the_band_and_clusters_at_it():
    """Every mode inside the band is a point of the grid, with per_side points on each side
    within rel_width of it, the nearest at rel_min; modes outside the band add nothing."""
    modes = np.array([0.5, 2.0, 3.7, 11.0])
    g = refined_grid((1.0, 10.0), 50, modes, rel_width=0.03, rel_min=1e-6, per_side=10)
    base = refined_grid((1.0, 10.0), 50)
    for f in (2.0, 3.7):
        assert f in g
        near = g[np.abs(g / f - 1) <= 0.03 * (1 + 1e-12)]
        assert np.sum(near < f) >= 10 and np.sum(near > f) >= 10
        assert np.min(np.abs(g[g != f] / f - 1)) == pytest.approx(1e-6, rel=1e-6)
    assert not np.isin([0.5, 11.0], g).any() and g.min() == 1.0 and g.max() == 10.0
    assert g.size == base.size + 2 * 21 - np.isin([2.0, 3.7], base).sum()


def test_the_default_neighbourhood_is_3_percent_of_the_mode_from_1e_6():
    """The defaults (theory.md §12.3): 40 points a side, geometric from 1e-6 to 3e-2 of the
    mode, the outermost at exactly f (1 -+ 0.03)."""
    g = refined_grid((1.0, 10.0), 2, [5.0])
    d = np.sort(np.abs(g[(g != 5.0) & (g != 1.0) & (g != 10.0)] / 5.0 - 1.0))
    assert g.size == 2 + 81
    assert d.max() == pytest.approx(0.03, rel=1e-12)
    assert d.min() == pytest.approx(1e-6, rel=1e-9)


def test_modes_on_the_band_edges_count_and_those_just_outside_do_not():
    """A mode exactly at either end of the band is in it (its cluster's inner half is
    added); a mode 1 % outside is ignored even though its 3 % neighbourhood reaches in."""
    base = refined_grid((1.0, 10.0), 10)
    edges = refined_grid((1.0, 10.0), 10, [1.0, 10.0], per_side=5)
    assert edges.size == base.size + 2 * 5
    new = np.setdiff1d(edges, base)
    assert np.sum((new > 1.0) & (new <= 1.03 * (1 + 1e-12))) == 5
    assert np.sum((new < 10.0) & (new >= 9.7 * (1 - 1e-12))) == 5
    outside = refined_grid((1.0, 10.0), 10, [0.99, 10.1, np.nan, np.inf], per_side=5)
    np.testing.assert_array_equal(outside, base)
