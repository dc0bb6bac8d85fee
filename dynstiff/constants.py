"""Named physical constants (SI units)."""

#: Standard gravity [m/s^2]. Passed explicitly to every function that needs gravity.
STANDARD_GRAVITY = 9.81

#: Largest coordinate [m] of a point (anchors, attachments, poses): squares of lengths and
#: their products with forces stay finite.
MAX_COORDINATE = 1e100

#: Names of the six platform degrees of freedom, in the order used everywhere: translations
#: of the reference point P [m], then the small rotation vector [rad] (base axes).
DOF_NAMES = ("x", "y", "z", "rx", "ry", "rz")

#: Load channels on the platform, paired with ``DOF_NAMES``: forces [N] and moments [N m]
#: about P (base axes).
LOAD_NAMES = ("fx", "fy", "fz", "mx", "my", "mz")

#: Platform share of a mode's kinetic energy from which it is "global" [-]
#: (docs/theory.md §12.1).
GLOBAL_SHARE = 0.5

#: Platform share from which a mode is "mixed" (a cable mode that moves the platform) and is
#: held to the frequency margin of the design checks [-] (docs/theory.md §12.1).
PLATFORM_SHARE_THRESHOLD = 0.05
