"""A map's arguments checked before its first pose (dynstiff/maps/arguments.py, theory.md
§13.8), called directly: the poses and layout returned, and every refusal in its own words,
the size counted over poses, orientations and parameter values."""

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.maps.arguments import validate_arguments


@pytest.fixture(scope="module")
def robot():
    return ds.load_scene("cogiro").robot


def call(robot, **kw):
    args = dict(poses=None, box=None, step=None, orientations=None, parameter=None,
                values=None, n_modes=4, rung="dsm", chunk_size=5, workers=None, client=None,
                damping=ds.Damping(), max_modes=2000, max_poses=200_000)
    args.update(kw)
    return validate_arguments(robot, **args)


def test_poses_and_a_box_give_their_poses_and_layout(robot):
    X, layout, values = call(robot, poses=[[0, 0, 1], [1, 0, 1, 0, 0, 0.1]])
    np.testing.assert_array_equal(X, [[0, 0, 1, 0, 0, 0], [1, 0, 1, 0, 0, 0.1]])
    assert layout == {"kind": "poses"} and values is None
    X, layout, _ = call(robot, box=(0, 1, 0, 0, 1, 1), step=1.0,
                        orientations=[[0, 0, 0], [0, 0, 0.1]])
    assert layout["kind"] == "grid" and X.shape == (4, 6)
    np.testing.assert_array_equal(X[:, 5], [0, 0.1, 0, 0.1])
    _, _, values = call(robot, poses=[[0, 0, 1]], parameter="EA", values=[1e5, 2e5])
    np.testing.assert_array_equal(values, [1e5, 2e5])
    call(robot, poses=[[0, 0, 1]], client=object())          # a client alone is fine
    call(robot, poses=[[0, 0, 1]], workers=2)


@pytest.mark.parametrize("kw, message", [
    ({"poses": [[0, 0, 1]], "chunk_size": 0}, "^chunk_size must be an integer >= 1, got 0$"),
    ({"poses": [[0, 0, 1]], "parameter": "EA"}, "^parameter= and values= go together$"),
    ({"poses": [[0, 0, 1]], "parameter": "EA", "values": "abc"},
     "^values must be a non-empty 1-D sequence of finite numbers, got 'abc'$"),
    ({"poses": [[0, 0, 1]], "parameter": "EA", "values": [2e5, True]},
     "^values must be a non-empty 1-D sequence"),
    ({"poses": [[0, 0, 1]], "parameter": "EA", "values": [-1.0]}, "EA"),
    ({"box": (0, 1, 0, 1, 1, 1), "step": 1.0, "orientations": [[0, 0, 0]],
      "poses": None}, None),
    ({"poses": [[0, 0, 1]], "orientations": [[0, 0, 0]]},
     "^orientations= goes with box=; give each pose its rotation in poses=$"),
    ({"poses": [[0, 0, 1]], "workers": "2"}, "^workers must be an integer >= 1, got '2'$"),
    ({"poses": [[0, 0, 1]], "workers": 0}, "^workers must be an integer >= 1, got 0$"),
    ({"poses": [[0, 0, 1]], "workers": 2, "client": object()},
     r"^give workers= \(local processes\) or client= \(Dask\), not both$"),
])
def test_each_refusal_in_its_own_words(robot, kw, message):
    if message is None:
        call(robot, **kw)
        return
    with pytest.raises(InvalidParameterError, match=message):
        call(robot, **kw)


def test_the_size_is_counted_over_poses_orientations_and_values(robot):
    with pytest.raises(InvalidParameterError,
                       match=r"^box \[0.0, 1.0, 0.0, 0.0, 1.0, 1.0\] with step 1.0 m x 2 "
                             r"orientations x 3 values gives 12 poses, more than "
                             r"max_poses=11 "):
        call(robot, box=(0, 1, 0, 0, 1, 1), step=1.0, orientations=[[0, 0, 0], [0, 0, 0.1]],
             parameter="EA", values=[1e5, 2e5, 3e5], max_poses=11)
    with pytest.raises(InvalidParameterError,
                       match=r"^box \[0.0, 1.0, 0.0, 0.0, 1.0, 1.0\] with step 1.0 m gives 2 "
                             r"poses, more than max_poses=1 "):
        call(robot, box=(0, 1, 0, 0, 1, 1), step=1.0, orientations=[[0, 0, 0]], max_poses=1)
    with pytest.raises(InvalidParameterError,
                       match=r"^2 poses x 3 values gives 6 poses, more than max_poses=5 "):
        call(robot, poses=[[0, 0, 1], [1, 0, 1]], parameter="EA", values=[1e5, 2e5, 3e5],
             max_poses=5)
    with pytest.raises(InvalidParameterError, match=r"^2 poses gives 2 poses, more than "
                                                    r"max_poses=1 "):
        call(robot, poses=[[0, 0, 1], [1, 0, 1]], max_poses=1)
    with pytest.raises(InvalidParameterError, match=r"^1 poses x 2 values gives 2 poses"):
        call(robot, poses=[[0, 0, 1]], parameter="EA", values=[1e5, 2e5], max_poses=1)
    call(robot, poses=[[0, 0, 1], [1, 0, 1]], parameter="EA", values=[1e5, 2e5, 3e5],
         max_poses=6)


def test_limits_of_the_grid_and_of_the_modes(robot):
    from dynstiff.maps.arguments import box_grid
    assert len(box_grid((0, 9999, 0, 0, 0, 0), 1.0)[0]) == 10_000
    with pytest.raises(InvalidParameterError, match=r"gives 10001 points along one axis of "
                                                    r"box \[0.0, 10000.0, 0.0"):
        box_grid((0, 10000, 0, 0, 0, 0), 1.0)
    call(robot, poses=[[0, 0, 1]], n_modes=5, max_modes=5)
    with pytest.raises(InvalidParameterError, match="^n_modes must be at most max_modes=5"):
        call(robot, poses=[[0, 0, 1]], n_modes=6, max_modes=5)
    with pytest.raises(InvalidParameterError, match=r"^give exactly one of poses= \(a list of "
                                                    r"poses\) or box="):
        call(robot)
