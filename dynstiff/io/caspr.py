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

    @property
    def tension_limits(self):
        """(t_min, t_max) [N] holding for every cable: the largest force_min and the smallest
        force_max (the limits of :class:`~dynstiff.Robot` are one pair for all cables)."""
        return float(self.force_min.max()), float(self.force_max.min())


def _parse(path, root_tags):
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


def _numbers(path, element, what, n=None):
    """The numbers in ``element``'s text (or attribute string ``element``), checked."""
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


def _read_body(path, inertia_convention, stacklevel):
    path, root = _parse(path, ("bodies_system", "links"))
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
    q = _numbers(path, joint.get("q_initial"), f"q_initial of the {jtype} joint", n_q) \
        if joint.get("q_initial") is not None else \
        np.array([0.0] * (n_q - 4) + [1.0, 0, 0, 0] if n_q in (4, 7) else [0.0] * n_q)
    phys = link.find("physical")
    if phys is None:
        raise CasprError(f"{path}: link {link.get('name')!r} has no <physical>")
    mass = _numbers(path, phys.find("mass"), "<mass>", 1)[0]
    com = _numbers(path, phys.find("com_location"), "<com_location>", 3)
    inertia = phys.find("inertia")
    if inertia is None:
        raise CasprError(f"{path}: missing <inertia>")
    if inertia.get("ref", "com") != "com":
        raise CasprError(f"{path}: <inertia ref={inertia.get('ref')!r}> is not supported, "
                         f"only ref=\"com\" (about the centre of mass)")
    v = {k: _numbers(path, inertia.find(k), f"<inertia><{k}>", 1)[0]
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
                      stacklevel=stacklevel + 1)
    parent = link.find("parent")
    origin = np.zeros(3)
    if parent is not None:
        num = (parent.findtext("num") or "0").strip()
        if num != "0":
            raise CasprError(f"{path}: the link's parent is link {num}, not the base (0)")
        if parent.find("location") is not None:
            origin = _numbers(path, parent.find("location"), "<parent><location>", 3)
    try:
        rotation = _rotation(jtype, q)
    except ValueError as exc:
        raise CasprError(f"{path}: q_initial: {exc}") from None
    position = origin + (q[:3] if "x" in free else 0.0)
    return dict(name=link.get("name", ""), mass=mass, center_of_mass=com, inertia=tensor,
                position=position, rotation=rotation, free_dofs=free, joint_type=jtype)


def _read_cables(path, cable_set, com):
    path, root = _parse(path, ("cables",))
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
        name = c.get("name", f"cable {k + 1}")
        where = f"cable {name!r}"
        points = c.findall("attachments/attachment")
        links = [a.findtext("link", "").strip() for a in points]
        if sorted(links) != ["0", "1"]:
            raise CasprError(
                f"{path}: {where} runs through links {links}; dynstiff needs one attachment on "
                f"the base (link 0) and one on the platform (link 1)")
        loc = {lk: _numbers(path, a.find("location"), f"{where} attachment location", 3)
               for lk, a in zip(links, points)}
        ref = c.get("attachment_reference", "joint").lower()
        if ref not in ("joint", "com"):
            raise CasprError(f"{path}: {where}: attachment_reference {ref!r} (expected "
                             f"'joint' or 'com')")
        anchors.append(loc["0"])
        attach.append(loc["1"] + (com if ref == "com" else 0.0))
        props = c.find("properties")
        fmin.append(_numbers(path, None if props is None else props.find("force_min"),
                             f"{where} <force_min>", 1)[0])
        fmax.append(_numbers(path, None if props is None else props.find("force_max"),
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
