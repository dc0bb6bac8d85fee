"""
Following a line through quasi-static cable lengths
===================================================

The four-cable robot is commanded along a straight line by winding its cables to the
lengths the sagging-cable inverse statics give at every point (no dynamics in the
command); the lumped-mass model steps the motion in time and shows how far the platform
strays from the line.
"""

import dynstiff as ds
from dynstiff.plot import plot_tracking
from dynstiff.timedomain.trajectory import line, track

scene = ds.load_scene("fourcable")
path = line([0.0, 0.0, 0.15], [0.2, 0.1, 0.15], speed=0.1, ramp=0.5)
tr = track(scene.robot, path, segments=1, dt=2e-3, settle=0.5)
print(f"largest deviation from the desired path: {tr.max_deviation * 1e3:.3f} mm")

# %%
# The deviation from the path (left axis) and the simulated and desired positions (right):
fig = plot_tracking(tr)
