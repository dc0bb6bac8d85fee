"""Argument checks shared by the public functions (dynstiff/_validate.py): typed errors that
name the argument, the expectation and the value found."""

import numpy as np
import pytest

from dynstiff._validate import (
    count,
    flag,
    index,
    omega_array,
    point,
    positive_scalar,
    real_array,
    unstretched_lengths,
)
from dynstiff.errors import DynstiffError, InvalidParameterError


def test_errors_are_typed_and_subclass_builtins():
    assert issubclass(InvalidParameterError, ValueError)
    assert issubclass(InvalidParameterError, DynstiffError)


@pytest.mark.parametrize("value, match", [
    ("abc", "g must be a real number"), (np.nan, "g must be finite"), (-1.0, "g must be > 0"),
    (0.0, "g must be > 0"), (True, "g must be a real number, got True"),
    (np.bool_(True), "g must be a real number")])
def test_positive_scalar(value, match):
    with pytest.raises(InvalidParameterError, match=match):
        positive_scalar("g", value)
    assert positive_scalar("g", 0.0, allow_zero=True) == 0.0


def test_omega_array_real_and_complex():
    np.testing.assert_array_equal(omega_array(2.0), [2.0])
    with pytest.raises(InvalidParameterError, match=r"omega must be finite and >= 0.*index 1"):
        omega_array([1.0, -1.0])
    with pytest.raises(InvalidParameterError, match="1-D"):
        omega_array(np.ones((2, 2)))
    z = omega_array([1.0 + 0.1j], complex_ok=True)
    assert z.dtype == complex and z[0] == 1.0 + 0.1j
    with pytest.raises(InvalidParameterError, match=r"^omega must be finite \[rad/s\], got"):
        omega_array([np.nan + 1j], complex_ok=True)         # complex: no sign to check
    assert omega_array([1.0], complex_ok=True).dtype == float     # real stays real
    with pytest.raises(InvalidParameterError,          # by default complex is refused
                       match=r"^omega must be real angular frequencies \[rad/s\], got complex"):
        omega_array([1.0 + 0.1j])


def test_point_and_lengths():
    with pytest.raises(InvalidParameterError, match=r"anchor must have shape \(3,\)"):
        point("anchor", [1, 2])
    with pytest.raises(InvalidParameterError,
                       match=r"^anchor must be finite, got \[1\.0, nan, 2\.0\]$"):
        point("anchor", [1.0, np.nan, 2.0])
    with pytest.raises(InvalidParameterError,
                       match=r"^anchor must be a sequence of 3 real numbers, got 'abc'$"):
        point("anchor", "abc")
    with pytest.raises(InvalidParameterError, match="unstretched_lengths must be 2 finite"):
        unstretched_lengths([1.0, 0.0], 2)
    with pytest.raises(InvalidParameterError, match="unstretched_lengths"):
        unstretched_lengths("ab", 2)
    np.testing.assert_array_equal(unstretched_lengths((1, 2), 2), [1.0, 2.0])


def test_omega_is_bounded_so_that_omega_squared_stays_finite():
    from dynstiff._validate import MAX_OMEGA
    assert np.isfinite(MAX_OMEGA**2 * 1e6)
    omega_array([MAX_OMEGA])
    with pytest.raises(InvalidParameterError, match="omega must be <= 1e\\+150"):
        omega_array([1.0, 1e300])


def test_subnormal_scalars_are_refused():
    with pytest.raises(InvalidParameterError, match="EA must be 0 or at least"):
        positive_scalar("EA", 2.225073858507203e-309)
    assert positive_scalar("EA", 2.3e-308) == 2.3e-308
    with pytest.raises(InvalidParameterError, match="unstretched_lengths"):
        unstretched_lengths([1.0, 2.2e-311], 2)


def _cogiro():
    import dynstiff as ds
    return ds, ds.load_scene("cogiro")


@pytest.mark.parametrize("name, call", [
    ("anchors", lambda ds, sc: ds.Robot(np.ones((8, 3), bool), sc.robot.attachments,
                                        sc.robot.cables, sc.robot.platform)),
    ("attachments", lambda ds, sc: ds.Robot(sc.robot.anchors, sc.robot.attachments.tolist()[:7]
                                            + [[0.0, True, 0.0]], sc.robot.cables,
                                            sc.robot.platform)),
    ("tension_limits", lambda ds, sc: ds.Robot(sc.robot.anchors, sc.robot.attachments,
                                               sc.robot.cables, sc.robot.platform,
                                               tension_limits=(True, 100.0))),
    ("pose", lambda ds, sc: sc.robot.equilibrium(pose=[True, False, True])),
    ("pose", lambda ds, sc: sc.robot.equilibrium(pose=[0, 0, 1, 0, 0, True])),
    ("pose rotation", lambda ds, sc: ds.Pose([0, 0, 1], [0, 0, np.bool_(True)])),
    ("center_of_mass", lambda ds, sc: ds.Platform(10.0, center_of_mass=[0, 0, True])),
    ("inertia", lambda ds, sc: ds.Platform(10.0, inertia=True)),
    ("end", lambda ds, sc: ds.solve_catenary([0, 0, 0], [True, 0, 1], 2.0, ds.Cable(0.1, 1e5))),
    ("unstretched_lengths", lambda ds, sc: sc.robot.equilibrium(unstretched_lengths=[True] * 8)),
    ("omega", lambda ds, sc: ds.FrequencyModel(sc.equilibrium()).dynamic_stiffness([True])),
    ("omega", lambda ds, sc: ds.FrequencyModel(sc.equilibrium()).dynamic_stiffness(
        np.array([1.0, 2.0]) > 1.5)),
])
def test_booleans_are_not_numbers_in_arrays_either(name, call):
    """numpy reads True as 1.0 in an array: a position [True, False, True] was a pose at
    (1, 0, 1) m, a tension limit True one of 1 N. Each is refused naming the argument."""
    ds, sc = _cogiro()
    with pytest.raises(InvalidParameterError,
                       match=f"^{name} must be real numbers, not booleans, got "):
        call(ds, sc)


def test_numbers_next_to_booleans_are_still_numbers():
    np.testing.assert_array_equal(point("end", np.array([1, 0, 2])), [1.0, 0.0, 2.0])
    np.testing.assert_array_equal(omega_array(np.arange(3)), [0.0, 1.0, 2.0])
    assert unstretched_lengths([np.float32(2.5), 3], 2).dtype == np.float64
    assert unstretched_lengths([5, 6, 7], 3).dtype == np.float64
    tiny = np.finfo(float).tiny                  # the least normal float is still a length
    assert unstretched_lengths([tiny, 1.0], 2)[0] == tiny
    with pytest.raises(InvalidParameterError, match="unstretched_lengths must be 2 finite"):
        unstretched_lengths([tiny / 2, 1.0], 2)


@pytest.mark.parametrize("kw, message", [
    (dict(tension_limits=("a", 5)),
     r"tension_limits must be \(t_min, t_max\) \[N\], got \('a', 5\)"),
    (dict(tension_limits=5), r"tension_limits must be \(t_min, t_max\) \[N\], got 5$"),
    (dict(tension_limits=(1, 2, 3)), r"tension_limits must be \(t_min, t_max\) \[N\], got"),
    (dict(tension_limits=None), r"tension_limits must be \(t_min, t_max\) \[N\], got None"),
    (dict(anchors="abc"), r"anchors must be a finite \(n, 3\) array \[m\], got 'abc'"),
    (dict(anchors=[[1, 2, 3], [1, 2]]), r"anchors must be a finite \(n, 3\) array \[m\], got"),
    (dict(attachments="abc"), r"attachments must be a finite \(n, 3\) array \[m\], got 'abc'"),
])
def test_a_robot_of_text_or_ragged_arrays_is_refused_naming_the_argument(kw, message):
    """Before, numpy's own ValueError or TypeError came out ("could not convert string to
    float: 'a'", "'int' object is not iterable"), naming nothing."""
    ds, sc = _cogiro()
    args = dict(anchors=sc.robot.anchors, attachments=sc.robot.attachments,
                cables=sc.robot.cables, platform=sc.robot.platform) | kw
    with pytest.raises(InvalidParameterError, match="^" + message):
        ds.Robot(**args)


@pytest.mark.parametrize("kw, message", [
    (dict(center_of_mass="abc"), r"center_of_mass must be 3 finite numbers \[m\], got 'abc'"),
    (dict(inertia=["a"]), r"inertia must be a finite 3x3 tensor \[kg m\^2\], got \['a'\]"),
    (dict(free_dofs="xyz"), "free_dofs must be a sequence of names from .*, not one string"),
])
def test_a_platform_of_text_is_refused_naming_the_argument(kw, message):
    import dynstiff as ds
    with pytest.raises(InvalidParameterError, match="^" + message):
        ds.Platform(10.0, **kw)


def test_band_and_index():
    from dynstiff._validate import band, index
    assert band([0, 2]) == (0.0, 2.0) and type(band((np.float32(1), 3))[0]) is float
    for bad, msg in [((1.0, 1.0), "with 0 <= low < high"), ((-1, 2), "with 0 <= low < high"),
                     ((0, np.nan), "with 0 <= low < high"), (None, r"\(low, high\) \[Hz\], got"),
                     ((0, 1, 2), r"\(low, high\) \[Hz\], got"), ((0, True), "not booleans")]:
        with pytest.raises(InvalidParameterError, match="^band_hz must be .*" + msg):
            band(bad)
    assert index("k", np.int32(2), 3) == 2
    for bad in (3, -1, True, 1.0, "1", None):
        with pytest.raises(InvalidParameterError, match=r"^k must be an integer in \[0, 3\)"):
            index("k", bad, 3)


@pytest.mark.parametrize("call, name", [
    (lambda ds, sc: ds.proximity_warnings(ds.modes(ds.FrequencyModel(sc.equilibrium()),
                                                   n_modes=4), warn="no"), "warn"),
    (lambda ds, sc: ds.calibrate(sc, [2.2], strict="no"), "strict"),
    (lambda ds, sc: ds.workspace(sc.robot, [sc.pose.position], n_modes=3, progress="no"),
     "progress"),
    (lambda ds, sc: ds.workspace(sc.robot, [sc.pose.position], n_modes=3, resume="no"),
     "resume"),
    (lambda ds, sc: sc.robot.platform_stiffness(sc.pose, sc.equilibrium().states,
                                                symmetric_part="no"), "symmetric_part")])
def test_worded_flags_are_refused_before_any_work(call, name):
    """A non-empty string is true in Python: strict="no" made the calibration strict,
    progress="no" printed the progress, resume="no" asked for a checkpoint to resume."""
    ds, sc = _cogiro()
    with pytest.raises(InvalidParameterError, match=f"^{name} must be True or False, got 'no'"):
        call(ds, sc)


def test_tension_reference_is_one_or_n_finite_tensions():
    from dynstiff._validate import tension_reference
    assert tension_reference(500, 8).shape == () and float(tension_reference(500, 8)) == 500.0
    np.testing.assert_array_equal(tension_reference([1.0, 2.0, 3.0], 3), [1.0, 2.0, 3.0])
    for bad, match in (([1.0, 2.0], "one tension or 3 finite tensions"),
                       ([1.0, np.nan, 2.0], "finite"), ([1 + 1j] * 3, "one tension or 3"),
                       ("abc", "one tension or 3"), (True, "not booleans")):
        with pytest.raises(InvalidParameterError, match="^tension_reference must be .*" + match):
            tension_reference(bad, 3)


def test_a_count_takes_its_least_value_and_refuses_one_less():
    """count(name, value, least): the bound is inclusive, as its message says (>= least)."""
    assert count("n_modes", 1) == 1 and count("workers", 0, least=0) == 0
    assert type(count("n", np.int64(5), least=5)) is int
    with pytest.raises(InvalidParameterError, match=r"^n_modes must be an integer >= 1, got 0$"):
        count("n_modes", 0)
    with pytest.raises(InvalidParameterError, match=r"^n must be an integer >= 5, got 4$"):
        count("n", 4, least=5)


def test_an_index_takes_zero_and_a_flag_keeps_its_truth():
    assert index("mode", 0, 3) == 0 and index("mode", np.int64(2), 3) == 2
    with pytest.raises(InvalidParameterError,
                       match=r"^mode must be an integer in \[0, 3\), got 3$"):
        index("mode", 3, 3)
    assert flag("html", True) is True and flag("html", np.bool_(True)) is True
    assert flag("html", False) is False


def test_the_bound_in_a_scalars_message_is_the_one_it_checks():
    with pytest.raises(InvalidParameterError, match=r"^eta must be >= 0, got -1\.0$"):
        positive_scalar("eta", -1.0, allow_zero=True)
    with pytest.raises(InvalidParameterError, match=r"^EA must be > 0, got 0\.0$"):
        positive_scalar("EA", 0.0)


def test_a_real_array_refuses_text_and_complex_numbers_by_name():
    """The default expectation is "real numbers"; a complex array is refused (never cut to
    its real part with a ComplexWarning)."""
    with pytest.raises(InvalidParameterError, match=r"^x must be real numbers, got 'abc'$"):
        real_array("x", "abc")
    with pytest.raises(InvalidParameterError, match=r"^x must be real numbers, got array"):
        real_array("x", np.array([1.0 + 1e-3j]))


@pytest.mark.parametrize("value", [[1.0, 2.0, 3.0], [1.0, np.nan], [1.0, np.inf]])
def test_unstretched_lengths_of_the_wrong_count_or_not_finite_are_refused(value):
    with pytest.raises(InvalidParameterError,
                       match=r"^unstretched_lengths must be 2 finite positive lengths"):
        unstretched_lengths(value, 2)
