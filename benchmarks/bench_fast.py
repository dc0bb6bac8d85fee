"""Benchmark: the exact cable rung (theory.md §11) against the closed form ("dsm", theory.md
§3) at the scale of the FAST telescope's feed support (scene ``fast``: six ~325 m cables
weighing 0.89 x the 30 t cabin; about 40 cable modes per hertz), side by side in one run
(repeats interleaved, the minimum kept).

1. Every natural frequency below 0.4 Hz (the scene's band), builds included, and the
   largest relative difference of the closed form's from the exact rung's.
2. A 2,000-frequency 6x6 receptance over 0.02-0.4 Hz (``ds.frf``) of the scene's damped
   model (``ds.scene_model``), builds excluded.
3. A small workspace map: 9 poses (x, y in -40, 0, 40 m at the bottom of the focal
   surface), 12 modes and the design checks per pose (``ds.workspace``, serial).

Set OPENBLAS_NUM_THREADS=1 on a shared machine.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_fast.py
"""

import warnings

import numpy as np
from bench_exact import interleaved  # the same interleaved timing (benchmarks/ on the path)

import dynstiff as ds
from dynstiff.errors import ClosedFormWarning

FMAX_HZ = 0.4
N_FRF = 2_000
REPEATS = 3


def main():
    warnings.simplefilter("ignore", ClosedFormWarning)   # the rungs are compared below
    sc = ds.load_scene("fast")
    eq = sc.equilibrium()

    def modes(rung):
        m = ds.build_model(eq, rung, **({"fmax_hz": 1.05 * FMAX_HZ} if rung == "exact" else {}))
        return ds.eigenfrequencies(m, fmax_hz=FMAX_HZ)
    t, f = interleaved({r: (lambda r=r: modes(r)) for r in ("dsm", "exact")}, REPEATS)
    err = float(np.max(np.abs(f["dsm"] / f["exact"] - 1)))
    print(f"modes below {FMAX_HZ} Hz: {f['exact'].size} (closed form {f['dsm'].size}); "
          f"largest closed form vs exact {err:.2e}")
    print(f"  closed form {t['dsm']:.3f} s, exact {t['exact']:.3f} s "
          f"(ratio {t['exact'] / t['dsm']:.1f})")

    omega = 2 * np.pi * np.linspace(0.02, FMAX_HZ, N_FRF)
    models = {r: ds.scene_model(sc, rung=r) for r in ("dsm", "exact")}   # scene's damping
    t, _ = interleaved({k: (lambda m=m: ds.frf(m, omega)) for k, m in models.items()}, REPEATS)
    print(f"FRF, {N_FRF} frequencies, 6x6: closed form {t['dsm']:.3f} s, exact "
          f"{t['exact']:.3f} s (ratio {t['exact'] / t['dsm']:.1f})")

    poses = [[x, y, 138.33] for x in (-40.0, 0.0, 40.0) for y in (-40.0, 0.0, 40.0)]
    robot = sc.robot
    robot = type(robot)(robot.anchors, robot.attachments, robot.cables, robot.platform,
                        g=robot.g, tension_limits=(1.0, robot.tension_limits[1]),
                        name=robot.name)
    t, out = interleaved({r: (lambda r=r: ds.workspace(robot, poses, n_modes=12,
                                                        band_hz=sc.forbidden_band_hz,
                                                        rung=r, **({"fmax_hz": 2.5}
                                                                   if r == "exact" else {})))
                          for r in ("dsm", "exact")}, repeats=1)
    f_d = np.asarray(out["dsm"]["freq"])
    f_x = np.asarray(out["exact"]["freq"])
    print(f"workspace map, {len(poses)} poses x 12 modes + checks: closed form "
          f"{t['dsm']:.2f} s, exact {t['exact']:.2f} s (ratio {t['exact'] / t['dsm']:.1f}); "
          f"largest closed form vs exact {np.nanmax(np.abs(f_d / f_x - 1)):.2e}")


if __name__ == "__main__":
    main()
