"""
Calibrating the cable modulus
=============================

The Young's modulus of CoGiRo's steel cables is known only to lie between 17 and 120 GPa,
and it moves every platform frequency. Given measured platform frequencies,
``ds.calibrate`` fits the axial stiffness EA of every cable by least squares and gives its
95 % interval (theory.md §15.6). The "measurement" here comes from an independent model,
lumped-mass cables at a modulus the fit does not know, with 0.5 % random error.
"""

from dataclasses import replace

import matplotlib.pyplot as plt
import numpy as np

import dynstiff as ds
from dynstiff.analyses.measured import massless_pairing

scene = ds.load_scene("cogiro")
AREA = 8.2051e-6                       # cable cross-section [m^2]
E_HIDDEN = 52e9                        # [Pa], the modulus of the 'measured' robot


def with_E(robot, E):
    return replace(robot, cables=[replace(c, EA=AREA * E) for c in robot.cables])


def platform_frequencies(robot, rung, n=4, **kw):
    """The first n platform modes, continued from the massless-cable modes [Hz]."""
    m = ds.build_model(robot.equilibrium(scene.pose), rung, **kw)
    md = ds.modes(m, fmax_hz=12.0)
    return md.freq_hz[massless_pairing(md, m, n)]


f_true = platform_frequencies(with_E(scene.robot, E_HIDDEN), "lumped", segments=10)
rng = np.random.default_rng(7)
measured = ds.MeasuredModes(f_true * (1 + 0.005 * rng.standard_normal(f_true.size)))

res = ds.calibrate(scene, measured, parameters="EA", pairing="massless")  # as measured
print(res.text())
E_fit, E_lo, E_hi = res.estimate[0] / AREA, res.ci_low[0] / AREA, res.ci_high[0] / AREA

# %%
# Left: the model's error against each measured frequency before (17 GPa) and after the
# fit. Right: the four platform frequencies of the closed-form model across the modulus
# range, the measured ones (dotted) and the fitted modulus with its interval.

E_grid = np.array([17, 25, 35, 50, 70, 95, 120]) * 1e9
curves = np.array([platform_frequencies(with_E(scene.robot, E), "dsm") for E in E_grid])
fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
res.plot(ax=axes[0])
for k in range(curves.shape[1]):
    axes[1].plot(E_grid / 1e9, curves[:, k], "o-", color=f"C{k}", label=f"platform mode {k + 1}")
    axes[1].axhline(measured.freq_hz[k], color=f"C{k}", ls=":", lw=1)
axes[1].axvspan(E_lo / 1e9, E_hi / 1e9, color="0.7", alpha=0.5, label="fitted, 95 %")
axes[1].set(xlabel="E [GPa]", ylabel="frequency [Hz]",
            title=f"E = {E_fit / 1e9:.1f} GPa (hidden: {E_HIDDEN / 1e9:g} GPa)")
axes[1].legend(fontsize="small")
plt.show()
