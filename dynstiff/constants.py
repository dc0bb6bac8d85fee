"""Named physical constants (SI units)."""

#: Standard gravity [m/s^2]. Passed explicitly to every function that needs gravity.
STANDARD_GRAVITY = 9.81
