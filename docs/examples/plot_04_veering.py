"""
Global modes along a path
=========================

The modes of CoGiRo at seven poses on a straight path from the centre of the workspace;
each global mode is tracked from pose to pose by its shape (MAC). Where a track meets the
cluster of local cable modes (grey dots), the two families veer apart.
"""

import numpy as np

import dynstiff as ds
from dynstiff.plot import plot_veering

scene = ds.load_scene("cogiro")
poses = np.linspace([0.0, 0.0, 1.0], [4.0, 2.0, 1.0], 7)       # [m]
sw = ds.sweep(scene.robot, poses=poses, n_modes=24)
print(sw.veering_table())

# %%
# The tracked global modes against the arc length of the path, the local modes as grey
# dots:
fig = plot_veering(sw)
