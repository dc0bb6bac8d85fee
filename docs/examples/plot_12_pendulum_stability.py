"""
Parametric stability of a pendulum on two cables
================================================

An inverted pendulum held by two cables whose ends are moved harmonically (seed paper
004). The excitation modulates the pendulum's stiffness; its stability is read from
Floquet multipliers. With massless cables and no preload, much of the band is unstable;
a preload above the slack preload stabilises it everywhere.
"""

import matplotlib.pyplot as plt
import numpy as np

import dynstiff as ds
from dynstiff.timedomain import pendulum as pdl

scene = ds.load_scene("pendulum")
freq = np.linspace(0.5, 60.0, 240)                         # [Hz]
multipliers = {}
for preload in (0.0, 2066.0):
    m = pdl.from_scene(scene, preload=preload, n_masses=0)  # massless cables
    multipliers[preload] = pdl.floquet(m, freq, 0.02)      # ends moved 0.02 sin(2 pi f t)
    print(f"preload {preload:g} N: {100 * (1 - multipliers[preload].stable.mean()):.0f} % "
          "of the band unstable")

# %%
# The modulus of the pendulum's Floquet multiplier against the excitation frequency;
# above 1 the upright position is unstable:

fig, ax = plt.subplots(figsize=(8, 3.8), layout="constrained")
for (preload, fl), color in zip(multipliers.items(), ["C3", "C0"]):
    ax.semilogy(freq, fl.pendulum_abs, color=color, lw=1,
                label=f"preload {preload:g} N: {100 * (1 - fl.stable.mean()):.0f} % unstable")
ax.axhline(1.0, color="k", lw=0.8)
ax.set(xlabel="excitation frequency [Hz]", ylabel="|Floquet multiplier| [-]",
       title="pendulum on two excited cables, x0 = 0.02 m")
ax.legend()
plt.show()
