"""
Which cable model does the robot need?
======================================

The model ladder runs from massless springs to the exact cable about its true catenary.
``recommend_model`` estimates each rung's frequency error over the band and picks the
cheapest one within the tolerance: for CoGiRo's 0.1-6 Hz band at 1 %, the massless rungs
miss the cable modes and the closed form is enough.
"""

import dynstiff as ds
from dynstiff.plot import plot_model_errors

scene = ds.load_scene("cogiro")
eq = scene.equilibrium()
rec = ds.recommend_model(eq, band_hz=(0.1, 6.0), rtol=1e-2)
print(rec.text())

# %%
# The predicted error of every rung, cheapest first; grey bars are models that miss the
# cable modes in the band:
fig = plot_model_errors(rec)
