"""Reader of CASPR robot models (XML bodies and cables files) for single-body robots.

CASPR (Lau et al., https://github.com/darwinlau/CASPR, a MATLAB toolbox) describes a cable
robot by two XML files:

* a *bodies* file, root ``<bodies_system><links>`` (or a bare ``<links>`` in older models),
  with one ``<link_rigid>`` per body: its ``<joint type=... q_initial=...>``, ``<mass>`` [kg],
  ``<com_location>`` [m, link frame], ``<inertia ref="com">`` (Ixx .. Iyz [kg m^2]) and the
  ``<parent><location>`` of the joint [m, base frame];
* a *cables* file, root ``<cables default_cable_set=...>`` with named ``<cable_set id=...>``
  of ``<cable_ideal>`` (or another ``cable_*`` element) holding ``force_min``/``force_max``
  [N] and two ``<attachment>`` s: ``<link>0</link>`` the base (anchor A_i, base frame) and
  ``<link>1</link>`` the platform (attachment b_i, link frame; relative to the joint, or to
  the centre of mass when ``attachment_reference="com"``).

The joint's ``q_min`` / ``q_max`` (when given) bound the workspace: their translation part,
moved by the joint's parent location, is :attr:`CasprModel.workspace_box` (theory.md §15.8).
Cables may share anchor or attachment points; a cable that leaves the base over a rotating
pulley (``<base_rotating_pulley>``, CAROCA's ``with_rotating_pulleys`` set) is refused:
dynstiff clamps each cable at a fixed exit point, and the pulley's exit point moves with the
pose. Trajectories and operational spaces: :mod:`dynstiff.io.caspr_motion`.

Only single-body robots are read (theory.md §15.1): the joint types whose pose is a position
and/or an orientation of one rigid body, ``SPATIAL_EULER_XYZ`` (q = x y z alpha beta gamma,
R = R_x(alpha) R_y(beta) R_z(gamma)), ``SPATIAL`` / ``SPATIAL_QUATERNION`` (q = x y z e0 e1
e2 e3, e0 real), ``T_XYZ`` (translations, orientation held), ``S_EULER_XYZ``,
``S_FIXED_XYZ`` (R = R_z(gamma) R_y(beta) R_x(alpha)) and ``SPHERICAL`` (quaternion),
whose three rotations turn about the joint, the translation held. Multi-link, planar and
other models raise :class:`CasprError`. CASPR holds no cable mass or axial stiffness: the
caller gives them (:meth:`dynstiff.Robot.from_caspr`).

Products of inertia: CASPR's code enters the printed Ixy, Ixz, Iyz as tensor entries, but the
CoGiRo data printed at G and at P side by side obey the parallel-axis rule only if they are
products of inertia P_xy = int x y dm, whose tensor entry is -P_xy (theory.md §15.2). The
convention is the argument ``inertia_convention``: ``"products"`` (default, tensor entry =
-printed value) or ``"tensor"`` (tensor entry = printed value, CASPR's code); a file with
nonzero off-diagonal values warns with :class:`InertiaConventionWarning` naming it.
"""

import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from dynstiff.errors import DynstiffError, DynstiffWarning

__all__ = [
    "INERTIA_CONVENTIONS",
    "JOINT_TYPES",
    "CasprError",
    "CasprModel",
    "InertiaConventionWarning",
    "joint_pose",
    "read_caspr",
]

#: Meanings of CASPR's printed off-diagonal inertia values Ixy, Ixz, Iyz.
INERTIA_CONVENTIONS = ("products", "tensor")

#: Single-body joint types read: name -> (number of q values, free DOFs).
JOINT_TYPES = {
    "SPATIAL_EULER_XYZ": (6, ("x", "y", "z", "rx", "ry", "rz")),
    "SPATIAL": (7, ("x", "y", "z", "rx", "ry", "rz")),
    "SPATIAL_QUATERNION": (7, ("x", "y", "z", "rx", "ry", "rz")),
    "T_XYZ": (3, ("x", "y", "z")),
    "S_EULER_XYZ": (3, ("rx", "ry", "rz")),
    "S_FIXED_XYZ": (3, ("rx", "ry", "rz")),
    "SPHERICAL": (4, ("rx", "ry", "rz")),
}


class CasprError(DynstiffError, ValueError):
    """A CASPR file is malformed or describes a robot dynstiff does not model; the message
    names the file and what is wrong."""

class InertiaConventionWarning(DynstiffWarning, UserWarning):
    """Off-diagonal inertia values were read under a stated convention (products of inertia
    or tensor entries) that the file itself cannot confirm."""


@dataclass(frozen=True)
class CasprModel:
    """A single-body CASPR robot as plain data (SI units).

    Attributes
    ----------
    name : str
        The link's name.
    mass : float
        [kg].
    center_of_mass : ndarray, shape (3,)
        G in the platform frame [m] (origin at the joint, the reference point P).
    inertia : ndarray, shape (3, 3)
        Tensor about G, platform axes [kg m^2], off-diagonal entries per ``convention``.
    anchors : ndarray, shape (n, 3)
        Cable exit points A_i [m, base frame].
    attachments : ndarray, shape (n, 3)
        Attachment points b_i [m, platform frame, from P].
    force_min, force_max : ndarray, shape (n,)
        Tension limits of each cable [N].
    position : ndarray, shape (3,)
        P at ``q_initial`` [m, base frame].
    rotation : ndarray, shape (3,)
        Platform orientation at ``q_initial``, rotation vector [rad].
    free_dofs : tuple of str
        The joint's degrees of freedom.
    joint_type, cable_set, convention : str
    cable_names : tuple of str
    origin : ndarray, shape (3,)
        The joint's parent location [m, base frame]: P = origin + translation part of q.
    q_min, q_max : ndarray or None
        The joint's bounds (``q_min`` / ``q_max`` attributes), or None when not given.
    """

    name: str
    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    anchors: np.ndarray
    attachments: np.ndarray
    force_min: np.ndarray
    force_max: np.ndarray
    position: np.ndarray
    rotation: np.ndarray
    free_dofs: tuple
    joint_type: str
    cable_set: str
    cable_names: tuple
    convention: str
    origin: np.ndarray = None
    q_min: object = None
    q_max: object = None

    @property
    def workspace_box(self):
        """(x0, x1, y0, y1, z0, z1) [m] of P: the translation part of ``q_min`` and ``q_max``
        moved by ``origin``; None when the joint has no translation or no bounds."""
        if self.q_min is None or self.q_max is None or "x" not in self.free_dofs:
            return None
        lo, hi = self.origin + self.q_min[:3], self.origin + self.q_max[:3]
        return tuple(float(v) for pair in zip(lo, hi) for v in pair)

    @property
    def tension_limits(self):
        """(t_min, t_max) [N] holding for every cable: the largest force_min and the smallest
        force_max (the limits of :class:`~dynstiff.Robot` are one pair for all cables)."""
        return float(self.force_min.max()), float(self.force_max.min())


def parse_root(path, root_tags):
    """(Path, root element) of the XML file ``path``, whose root must be one of
    ``root_tags``; :class:`CasprError` otherwise (shared by the CASPR readers)."""
    import xml.etree.ElementTree as ET
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise CasprError(f"{path}: not well-formed XML ({exc})") from None
    if root.tag not in root_tags:
        raise CasprError(f"{path}: root element <{root.tag}>, expected one of "
                         f"{['<' + t + '>' for t in root_tags]}")
    return path, root


def read_numbers(path, element, what, n=None):
    """The numbers in ``element``'s text (or attribute string ``element``), checked: ``n``
    of them (any number when None), all finite; :class:`CasprError` naming ``what``."""
    text = element if isinstance(element, str) else (element.text if element is not None
                                                     else None)
    if text is None:
        raise CasprError(f"{path}: missing {what}")
    count = "some" if n is None else f"{n}"
    expected = f"{what} must be {count} finite number{'' if n == 1 else 's'}, got " \
        f"{text.strip()!r}"
    try:
        vals = np.array([float(v) for v in text.split()], dtype=float)
    except ValueError:
        raise CasprError(f"{path}: {expected}") from None
    if (n is not None and vals.size != n) or not np.all(np.isfinite(vals)):
        raise CasprError(f"{path}: {expected}")
    return vals


def _rotation(joint_type, q):
    """Rotation vector [rad] of the joint's orientation coordinates q (CASPR's definitions)."""
    from scipy.spatial.transform import Rotation
    if joint_type in ("SPATIAL_EULER_XYZ", "S_EULER_XYZ"):
        return Rotation.from_euler("XYZ", q[-3:]).as_rotvec()    # R_x R_y R_z (intrinsic)
    if joint_type == "S_FIXED_XYZ":
        return Rotation.from_euler("xyz", q[-3:]).as_rotvec()    # R_z R_y R_x (fixed axes)
    if joint_type in ("SPATIAL", "SPATIAL_QUATERNION", "SPHERICAL"):
        e = q[-4:]
        if not 0.5 < np.linalg.norm(e) < 2.0:
            raise ValueError(f"quaternion {e.tolist()} is far from unit length")
        return Rotation.from_quat([e[1], e[2], e[3], e[0]]).as_rotvec()
    return np.zeros(3)                                             # T_XYZ


def joint_pose(joint_type, origin, q):
    """Pose of the platform for joint coordinates ``q`` (CASPR's definitions, module notes).

    Parameters
    ----------
    joint_type : str
        One of :data:`JOINT_TYPES`.
    origin : array_like, shape (3,)
        The joint's parent location [m].
    q : array_like, shape (n_q,)
        Joint coordinates [m, rad; quaternions unitless].

    Returns
    -------
    position : ndarray, shape (3,)
        P [m, base frame].
    rotation : ndarray, shape (3,)
        Rotation vector [rad].

    Raises
    ------
    ValueError
        A quaternion far from unit length.
    """
    q = np.asarray(q, dtype=float)
    free = JOINT_TYPES[joint_type][1]
    return (np.asarray(origin, float) + (q[:3] if "x" in free else 0.0),
            _rotation(joint_type, q))


def _bounds(path, joint, jtype, n_q):
    """The joint's q_min and q_max, or (None, None) when either is absent."""
    if joint.get("q_min") is None or joint.get("q_max") is None:
        return None, None
    lo = read_numbers(path, joint.get("q_min"), f"q_min of the {jtype} joint", n_q)
    hi = read_numbers(path, joint.get("q_max"), f"q_max of the {jtype} joint", n_q)
    if np.any(lo > hi):
        raise CasprError(f"{path}: q_min {lo.tolist()} exceeds q_max {hi.tolist()} of the "
                         f"{jtype} joint")
    return lo, hi


def _read_body(path, inertia_convention, stacklevel):
    path, root = parse_root(path, ("bodies_system", "links"))
    links = root if root.tag == "links" else root.find("links")
    if links is None:
        raise CasprError(f"{path}: <bodies_system> holds no <links>")
    bodies = [e for e in links if e.tag.startswith("link")]
    if len(bodies) != 1:
        raise CasprError(
            f"{path}: {len(bodies)} links; dynstiff models one rigid platform (a single-link "
            f"CASPR robot), multi-link robots are not supported")
    link = bodies[0]
    if link.tag != "link_rigid":
        raise CasprError(f"{path}: <{link.tag}> is not supported, only <link_rigid>")
    joint = link.find("joint")
    jtype = None if joint is None else joint.get("type")
    if jtype not in JOINT_TYPES:
        raise CasprError(
            f"{path}: joint type {jtype!r} is not supported (planar and one-axis joints have "
            f"no spatial platform); supported: {list(JOINT_TYPES)}")
    n_q, free = JOINT_TYPES[jtype]
    q = read_numbers(path, joint.get("q_initial"), f"q_initial of the {jtype} joint", n_q) \
        if joint.get("q_initial") is not None else \
        np.array([0.0] * (n_q - 4) + [1.0, 0, 0, 0] if n_q in (4, 7) else [0.0] * n_q)
    phys = link.find("physical")
    if phys is None:
        raise CasprError(f"{path}: link {link.get('name')!r} has no <physical>")
    mass = read_numbers(path, phys.find("mass"), "<mass>", 1)[0]
    com = read_numbers(path, phys.find("com_location"), "<com_location>", 3)
    inertia = phys.find("inertia")
    if inertia is None:
        raise CasprError(f"{path}: missing <inertia>")
    if inertia.get("ref", "com") != "com":
        raise CasprError(f"{path}: <inertia ref={inertia.get('ref')!r}> is not supported, "
                         f"only ref=\"com\" (about the centre of mass)")
    v = {k: read_numbers(path, inertia.find(k), f"<inertia><{k}>", 1)[0]
         for k in ("Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz")}
    if inertia_convention not in INERTIA_CONVENTIONS:
        raise CasprError(f"inertia_convention must be one of {INERTIA_CONVENTIONS}, got "
                         f"{inertia_convention!r}")
    s = -1.0 if inertia_convention == "products" else 1.0
    tensor = np.array([[v["Ixx"], s * v["Ixy"], s * v["Ixz"]],
                       [s * v["Ixy"], v["Iyy"], s * v["Iyz"]],
                       [s * v["Ixz"], s * v["Iyz"], v["Izz"]]])
    if any(v[k] != 0 for k in ("Ixy", "Ixz", "Iyz")):
        what = ("products of inertia (tensor entry = -printed value)"
                if inertia_convention == "products" else
                "tensor entries (CASPR's code; products of inertia would change sign)")
        warnings.warn(f"{path}: Ixy, Ixz, Iyz read as {what}: inertia_convention="
                      f"{inertia_convention!r}", InertiaConventionWarning,
                      stacklevel=stacklevel)
    parent = link.find("parent")
    origin = np.zeros(3)
    if parent is not None:
        num = (parent.findtext("num") or "0").strip()
        if num != "0":
            raise CasprError(f"{path}: the link's parent is link {num}, not the base (0)")
        if parent.find("location") is not None:
            origin = read_numbers(path, parent.find("location"), "<parent><location>", 3)
    try:
        position, rotation = joint_pose(jtype, origin, q)
    except ValueError as exc:
        raise CasprError(f"{path}: q_initial: {exc}") from None
    q_min, q_max = _bounds(path, joint, jtype, n_q)
    return dict(name=link.get("name", ""), mass=mass, center_of_mass=com, inertia=tensor,
                position=position, rotation=rotation, free_dofs=free, joint_type=jtype,
                origin=origin, q_min=q_min, q_max=q_max)


def _read_cables(path, cable_set, com):
    path, root = parse_root(path, ("cables",))
    sets = {s.get("id"): s for s in root.findall("cable_set")}
    if not sets:
        raise CasprError(f"{path}: no <cable_set>")
    chosen = cable_set if cable_set is not None else root.get("default_cable_set")
    if chosen is None:
        if len(sets) > 1:
            raise CasprError(f"{path}: no default_cable_set; give cable_set, one of "
                             f"{list(sets)}")
        chosen = next(iter(sets))
    if chosen not in sets:
        raise CasprError(f"{path}: cable set {chosen!r} not found; sets: {list(sets)}")
    anchors, attach, fmin, fmax, names = [], [], [], [], []
    for k, c in enumerate(e for e in sets[chosen] if e.tag.startswith("cable")):
        name = c.get("name", f"cable {k}")
        where = f"cable {name!r}"
        other = [e.tag for e in c.findall("attachments/*") if e.tag != "attachment"]
        if other:
            plain = [k for k, st in sets.items()
                     if all(e.tag == "attachment" for e in st.findall("*/attachments/*"))]
            raise CasprError(
                f"{path}: {where} of set {chosen!r} is attached through <{other[0]}> (a "
                f"pulley whose exit point moves with the pose); dynstiff clamps each cable "
                f"at a fixed exit point: choose a set of plain <attachment>s"
                + (f", one of {plain}" if plain else " (this file has none)"))
        points = c.findall("attachments/attachment")
        links = [a.findtext("link", "").strip() for a in points]
        if sorted(links) != ["0", "1"]:
            raise CasprError(
                f"{path}: {where} runs through links {links}; dynstiff needs one attachment on "
                f"the base (link 0) and one on the platform (link 1)")
        loc = {lk: read_numbers(path, a.find("location"), f"{where} attachment location", 3)
               for lk, a in zip(links, points)}
        ref = c.get("attachment_reference", "joint").lower()
        if ref not in ("joint", "com"):
            raise CasprError(f"{path}: {where}: attachment_reference {ref!r} (expected "
                             f"'joint' or 'com')")
        anchors.append(loc["0"])
        attach.append(loc["1"] + (com if ref == "com" else 0.0))
        props = c.find("properties")
        fmin.append(read_numbers(path, None if props is None else props.find("force_min"),
                             f"{where} <force_min>", 1)[0])
        fmax.append(read_numbers(path, None if props is None else props.find("force_max"),
                             f"{where} <force_max>", 1)[0])
        names.append(name)
    if not anchors:
        raise CasprError(f"{path}: cable set {chosen!r} holds no cable")
    return dict(anchors=np.array(anchors), attachments=np.array(attach),
                force_min=np.array(fmin), force_max=np.array(fmax), cable_set=chosen,
                cable_names=tuple(names))


def read_caspr(bodies_xml, cables_xml, cable_set=None, inertia_convention="products",
               stacklevel=2):
    """Read a single-body CASPR robot.

    Parameters
    ----------
    bodies_xml, cables_xml : str or Path
        CASPR's ``*_bodies.xml`` and ``*_cables.xml``.
    cable_set : str, optional
        Id of the ``<cable_set>`` (default: the file's ``default_cable_set``, or its only set).
    inertia_convention : {"products", "tensor"}
        Meaning of the printed Ixy, Ixz, Iyz (module notes, theory.md §15.2).
    stacklevel : int
        Of the :class:`InertiaConventionWarning`, for callers that wrap this function.

    Returns
    -------
    CasprModel

    Raises
    ------
    CasprError
        Malformed XML, missing elements, a multi-link or planar model, an unknown cable set.
    FileNotFoundError

    Warns
    -----
    InertiaConventionWarning
        When the off-diagonal inertia values are not all zero.
    """
    body = _read_body(bodies_xml, inertia_convention, stacklevel + 1)
    cables = _read_cables(cables_xml, cable_set, body["center_of_mass"])
    return CasprModel(**body, **cables, convention=inertia_convention)
