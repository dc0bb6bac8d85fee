"""Benchmark: cost of each rung of the model ladder, and how it grows with the number of
frequencies, segments and cables. All measured side by side in one run (best of 3).

Run:  python benchmarks/bench_ladder.py
"""

import timeit

import numpy as np

import dynstiff as ds
from dynstiff.models.ladder import build_model


def best(fn, number=1, repeat=3):
    return min(timeit.repeat(fn, number=number, repeat=repeat)) / number


def main():
    eq = ds.load_scene("cogiro").equilibrium()
    print("CoGiRo, first 40 natural frequencies (build + solve) [ms]")
    base = None
    for rung, N in [("spring", None), ("catenary", None), ("dsm", None), ("lumped", 10),
                    ("lumped", 20), ("lumped", 40), ("lumped", 80)]:
        n = 40 if rung in ("dsm", "lumped") else 6      # the massless rungs have 6 modes
        t = best(lambda: ds.eigenfrequencies(build_model(eq, rung, N or 30), n))
        base = base or t
        print(f"  {rung + (f' N={N}' if N else ''):<14s} {1e3 * t:9.2f}   x{t / base:8.1f}")
    print("\nFRF fz->z against the number of frequencies [ms]")
    dsm = build_model(eq, "dsm")
    lum = build_model(eq, "lumped", 10)
    for nf in (100, 1000, 10000):
        w = 2 * np.pi * np.linspace(0.5, 8, nf)
        td = best(lambda: ds.frf(dsm, w, "fz", "z"))
        tl = best(lambda: ds.frf(lum, w, "fz", "z"), repeat=1) if nf <= 1000 else np.nan
        print(f"  n = {nf:6d}: dsm {1e3 * td:9.2f}   lumped N=10 {1e3 * tl:9.2f}   "
              f"ratio {tl / td:7.1f}")
    print("\nCables: 3-cable point mass vs 8-cable CoGiRo, dsm, first 20 frequencies [ms]")
    ang = np.radians([90, 210, 330])
    A = np.column_stack([8 * np.cos(ang), 8 * np.sin(ang), np.full(3, 6.0)])
    rob3 = ds.Robot(A, np.zeros((3, 3)), ds.Cable(0.064, 1.4e5),
                    ds.Platform(50, free_dofs=("x", "y", "z")))
    eq3 = rob3.equilibrium(pose=[0, 0, 1.0])
    t3 = best(lambda: ds.eigenfrequencies(ds.FrequencyModel(eq3), 20))
    t8 = best(lambda: ds.eigenfrequencies(ds.FrequencyModel(eq), 20))
    print(f"  3 cables {1e3 * t3:8.2f}   8 cables {1e3 * t8:8.2f}   ratio {t8 / t3:5.2f}")


if __name__ == "__main__":
    main()
