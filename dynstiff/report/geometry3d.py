"""The 3-D geometry behind the robot views: the sagging cables' paths at equilibrium and along
a mode shape (with the cables' own displacement fields), the platform drawn as the hull of
its attachment points, the exaggeration scale of a mode, and the checks of the views'
arguments.
"""

from numbers import Integral

import numpy as np

from dynstiff._vec import cross
from dynstiff.analyses.modes import cable_fields
from dynstiff.errors import InvalidParameterError
from dynstiff.models.dsm import FrequencyModel
from dynstiff.results import ModalResult

_SCALE_FRACTION = 0.05     # default: largest displacement 5 % of the bounding-box diagonal


# ------------------------------------------------------------------------ geometry
def _hull(points):
    """Outline of the platform from its attachment points, shape (n, 3) [m].

    Returns ``(path, faces)``: ``path`` a list of point indices, -1 separating the pieces of
    the polyline of the hull's edges (edges between coplanar facets left out); ``faces`` a
    list of index lists, one polygon each. Coincident points give an empty outline, collinear
    ones a segment, coplanar ones one polygon. Facets whose normals are within 1 degree and
    whose vertices lie within 1 % of the points' largest extent of one facet's plane are one
    face (a platform face measured with millimetre scatter stays one polygon).
    """
    from scipy.spatial import ConvexHull, QhullError
    uniq = np.unique(np.round(points, 12), axis=0, return_index=True)[1]
    uniq = np.sort(uniq)
    if uniq.size < 2:
        return [], []
    c = points[uniq] - points[uniq].mean(axis=0)
    _, sv, Vt = np.linalg.svd(c, full_matrices=False)
    tol = 1e-9 * max(sv[0], 1e-300)
    rank = int(np.sum(sv > tol))
    if rank == 1 or uniq.size == 2:
        t = c @ Vt[0]
        return [int(uniq[np.argmin(t)]), int(uniq[np.argmax(t)])], []
    if rank == 3:
        try:
            h = ConvexHull(points[uniq])
        except QhullError:                             # nearly flat: draw it as a polygon
            rank = 2
    if rank == 2:
        try:
            h = ConvexHull(c @ Vt[:2].T)
        except QhullError:
            return [], []
        loop = [int(uniq[v]) for v in h.vertices]         # counter-clockwise order
        return loop + loop[:1], [loop]
    # facets of one plane together (the docstring's rule)
    P = points[uniq]
    size = float(np.ptp(P, axis=0).max())
    planes, groups = [], []
    for simplex, eqn in zip(h.simplices, h.equations):
        eqn = eqn / np.linalg.norm(eqn[:3])
        for j, q in enumerate(planes):
            if (eqn[:3] @ q[:3] > np.cos(np.radians(1.0))
                    and np.abs(P[simplex] @ q[:3] + q[3]).max() < 1e-2 * size):
                groups[j].append(simplex)
                break
        else:
            planes.append(eqn)
            groups.append([simplex])
    path, faces, seen = [], [], set()
    for tris in groups:
        count = {}
        for tri in tris:
            for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                e = (min(a, b), max(a, b))
                count[e] = count.get(e, 0) + 1
        boundary = [e for e, n in count.items() if n == 1]
        faces.append(_chain(boundary, uniq))
        for a, b in boundary:
            if (a, b) not in seen:
                seen.add((a, b))
                path += [int(uniq[a]), int(uniq[b]), -1]
    return path[:-1], faces


def _chain(edges, uniq):
    """Vertex loop (original indices ``uniq[v]``) of a polygon given by its boundary edges,
    starting with the first edge: ``edges[0][0]``, then ``edges[0][1]``."""
    nxt = {}
    for a, b in edges:
        nxt.setdefault(a, []).append(b)
        nxt.setdefault(b, []).append(a)
    start = edges[0][0]
    loop, prev, cur = [start], None, start
    while True:
        cand = [v for v in nxt[cur] if v != prev]
        if not cand or cand[0] == start:
            break
        prev, cur = cur, cand[0]
        loop.append(cur)
        if len(loop) > len(nxt):
            break
    return [int(uniq[v]) for v in loop]


def path_points(B, path):
    """Polyline of the hull outline, shape (len(path), 3), NaN rows between pieces."""
    out = np.full((len(path), 3), np.nan)
    idx = np.asarray(path, dtype=int)
    ok = idx >= 0
    out[ok] = B[idx[ok]]
    return out


def _check_eq(eq):
    for a in ("robot", "pose", "states", "lever_arms"):
        if not hasattr(eq, a):
            raise InvalidParameterError(
                f"eq must be a dynstiff.Equilibrium, got {type(eq).__name__} (no {a!r})")


def _check_mode(modes, mode):
    if not isinstance(modes, ModalResult):
        raise InvalidParameterError(
            f"modes must be a dynstiff.ModalResult (from dynstiff.modes(model)), got "
            f"{type(modes).__name__}")
    if mode is None:
        raise InvalidParameterError(
            f"mode must be given with modes= (0-based index below {len(modes)}), got None")
    if isinstance(mode, bool) or not isinstance(mode, Integral):
        raise InvalidParameterError(f"mode must be an integer index, got {mode!r}")
    if not 0 <= mode < len(modes):
        raise InvalidParameterError(
            f"mode must be a 0-based index in [0, {len(modes) - 1}] ({len(modes)} modes), "
            f"got {mode!r}")
    return int(mode)


def _check_model(model, eq, modes):
    """``model`` a FrequencyModel built on ``eq``: its cable ends equal eq's within 1e-9 m
    (absolute); ``modes``, when given, with platform shapes of shape (n, 6)."""
    if not isinstance(model, FrequencyModel):
        raise InvalidParameterError(
            f"model must be the dynstiff.FrequencyModel of the modes, got "
            f"{type(model).__name__}")
    ends = np.array([s.end for s in model.equilibrium.states])
    if (ends.shape != (len(eq.states), 3)
            or not np.allclose(ends, [s.end for s in eq.states], rtol=0.0, atol=1e-9)):
        raise InvalidParameterError(
            "model must be built on the equilibrium eq (FrequencyModel(eq)); its cable ends "
            "differ from eq's")
    if modes is not None and modes.platform_shapes.shape[1] != 6:
        raise InvalidParameterError(
            f"modes: platform_shapes must have shape (n, 6), got "
            f"{modes.platform_shapes.shape}")


def positive_int(name, value, least):
    if isinstance(value, bool) or not isinstance(value, Integral) or value < least:
        raise InvalidParameterError(f"{name} must be an integer >= {least}, got {value!r}")
    return int(value)


def nonnegative(name, value):
    if isinstance(value, (bool, np.bool_)):
        raise InvalidParameterError(f"{name} must be a real number, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"{name} must be a real number, got {value!r}") from None
    if not np.isfinite(x) or x < 0:
        raise InvalidParameterError(f"{name} must be finite and >= 0, got {value!r}")
    return x


def _geometry(eq, modes, k, model, n_points, sag_scale):
    """Static points and unit mode displacements of everything drawn.

    Returns a dict: ``cables`` (n_cables, n_points, 3) profiles [m], ``cable_disp`` the same
    shape per unit scale (None without a mode), ``B`` (n, 3) attachment points and ``dB``
    their displacement, ``P`` and ``dP`` (3,), ``anchors`` (n, 3), ``path`` and ``faces``
    of the platform outline, ``kind`` and ``freq_hz`` of the mode, ``dynamic`` (bool: the
    cable fields from the model, not the quasi-static straight-line interpolation; False
    without a mode).
    """
    robot = eq.robot
    anchors = np.asarray(robot.anchors, dtype=float)
    B = np.array([s.end for s in eq.states])
    r = np.asarray(eq.lever_arms, dtype=float)
    P = np.asarray(eq.pose.position, dtype=float)
    cables = np.empty((len(eq.states), n_points, 3))
    chord_t = np.empty((len(eq.states), n_points))
    for i, s in enumerate(eq.states):
        prof = s.profile(n_points)
        prof[0], prof[-1] = s.anchor, s.end          # exact ends (solver residual ~1e-12)
        e = s.chord / s.chord_length
        t = (prof - s.anchor) @ e
        if sag_scale != 1.0:
            along = s.anchor + np.outer(t, e)
            prof = along + sag_scale * (prof - along)
        cables[i] = prof
        chord_t[i] = np.clip(t / s.chord_length, 0.0, 1.0)
    path, faces = _hull(B)
    geo = dict(cables=cables, cable_disp=None, B=B, dB=None, P=P, dP=None, anchors=anchors,
               path=path, faces=faces, kind=None, freq_hz=None, dynamic=False)
    if modes is None:
        return geo
    x6 = np.asarray(modes.platform_shapes[k], dtype=float)
    dB = x6[:3] + cross(x6[3:], r)
    disp = np.zeros_like(cables)
    if model is not None:
        _, field = cable_fields(model, modes, k, n_points)
        grid = np.linspace(0.0, 1.0, n_points)
        for i in range(len(eq.states)):
            for c in range(3):
                disp[i, :, c] = np.interp(chord_t[i], grid, field[i, :, c])
    else:                                            # quasi-static: straight-line motion
        disp = chord_t[:, :, None] * dB[:, None, :]
    geo.update(cable_disp=disp, dB=dB, dP=x6[:3].copy(), kind=modes.kind[k],
               freq_hz=float(modes.freq_hz[k]), dynamic=model is not None)
    return geo


def _default_scale(geo):
    """Scale that makes the largest displacement 5 % of the bounding-box diagonal; 1.0 when
    nothing moves (a purely local mode drawn without its cable field)."""
    pts = np.vstack([geo["anchors"], geo["B"], geo["P"][None, :]])
    size = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))
    largest = max(float(np.linalg.norm(geo["dB"], axis=1).max(initial=0.0)),
                  float(np.linalg.norm(geo["dP"])),
                  float(np.linalg.norm(geo["cable_disp"], axis=2).max(initial=0.0)))
    return _SCALE_FRACTION * size / largest if largest > 0 else 1.0


def prepare(eq, modes, mode, scale, n_points, model, sag_scale):
    _check_eq(eq)
    n_points = positive_int("n_points", n_points, 2)
    sag_scale = nonnegative("sag_scale", sag_scale)
    k = None
    if modes is not None:
        k = _check_mode(modes, mode)
    elif mode is not None:
        raise InvalidParameterError(f"mode={mode!r} needs modes= (a ModalResult), got None")
    if model is not None:
        _check_model(model, eq, modes)
    if scale is not None:
        scale = nonnegative("scale", scale)
    geo = _geometry(eq, modes, k, model, n_points, sag_scale)
    if modes is not None and scale is None:
        scale = _default_scale(geo)
    return geo, k, scale, sag_scale
