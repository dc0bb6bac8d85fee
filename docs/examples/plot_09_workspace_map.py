"""
A workspace map
===============

Statics, the first platform modes and the design checks of CoGiRo over a box of positions
(2 m steps, 10 modes each), with a forbidden band of 0-1.5 Hz: where the first platform
mode clears the band by its margin and every check passes, the position belongs to the
dynamic workspace. The map is an ``xarray.Dataset`` (``pip install "dynstiff[workspace]"``);
``workers=`` or ``client=`` run it on local processes or a Dask cluster with the same
numbers.
"""

import dynstiff as ds

scene = ds.load_scene("cogiro")
wmap = ds.workspace(scene.robot, box=(-4, 4, -3, 3, 0, 2), step=2.0, n_modes=10,
                    band_hz=(0.0, 1.5))
print(int(wmap["dynamic"].sum()), "of", wmap["dynamic"].size,
      "positions pass every check")
print(wmap.dynstiff.to_frame()[["x", "y", "z", "first_platform_hz", "band_margin",
                                "dynamic"]].head(8))

# %%
# Slices at the two heights: the first platform frequency, the margin to the forbidden
# band and the dynamic workspace:
fig = wmap.dynstiff.plot(n_slices=2)
