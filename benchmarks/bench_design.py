"""Benchmark: the cost of designing for frequency (theory.md §16.8), side by side in one run
(best of 5, single-threaded BLAS).

* Sensitivities of 20 modes x 10 parameters against the modes themselves, per rung: the
  goal is at most 2x. "Modes" is :func:`dynstiff.modes` (frequencies, shapes, energies) of
  the built model; the sensitivities start from the frequencies (``sensitivities_at``) and
  include the linearised statics, the null vectors and the modal masses.
* Optimal tensions at CoGiRo poses along a line (every 0.5 m from (-4, -2, 1) to
  (4, 2, 1) m), cold and warm-started from the neighbour (a map's chunk): the goal is at
  most 100 ms per pose.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_design.py
"""

import os
import time
import timeit

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import dynstiff as ds  # noqa: E402
from dynstiff.analyses.sensitivity import sensitivities_at  # noqa: E402

PARAMETERS = ["EA", "mass_per_length", "mass", "inertia", "com_z", "pose_x", "pose_y",
              "pose_z", "anchor_1_z", "t_min"]


def best(fn, repeat=5):
    """Best wall time of ``repeat`` runs [s]."""
    return min(timeit.repeat(fn, number=1, repeat=repeat))


def cpu(fn, repeat=5):
    """Best CPU time of this process over ``repeat`` runs [s] (on a shared machine the wall
    time also counts the waits for a core)."""
    out = np.inf
    for _ in range(repeat):
        t = time.process_time()
        fn()
        out = min(out, time.process_time() - t)
    return out


def sensitivities():
    eq = ds.load_scene("cogiro").equilibrium()
    print("CoGiRo central pose, 20 modes x 10 parameters [ms]")
    print(f"  {'rung':<12s} {'modes':>8s} {'sens.':>8s} {'ratio':>6s}   (CPU: modes, sens., "
          f"ratio)")
    for rung, kw in (("dsm", {}), ("exact", {"fmax_hz": 12.0}), ("lumped", {"segments": 20})):
        m = ds.build_model(eq, rung, **kw)
        f = ds.eigenfrequencies(m, n_modes=20)
        ds.modes(m, n_modes=20)
        sensitivities_at(m, f, PARAMETERS)
        tm = best(lambda: ds.modes(m, n_modes=20))
        ts = best(lambda: sensitivities_at(m, f, PARAMETERS))
        cm = cpu(lambda: ds.modes(m, n_modes=20))
        cs = cpu(lambda: sensitivities_at(m, f, PARAMETERS))
        print(f"  {rung:<12s} {1e3 * tm:8.2f} {1e3 * ts:8.2f} {ts / tm:6.2f}   ({1e3 * cm:.2f}, "
              f"{1e3 * cs:.2f}, {cs / cm:.2f})")
    m = ds.build_model(eq, "dsm")
    tf = best(lambda: ds.eigenfrequencies(m, n_modes=20))
    ts = best(lambda: ds.frequency_sensitivities(m, PARAMETERS, n_modes=20))
    print(f"  dsm: frequencies alone {1e3 * tf:.2f} ms; frequencies + sensitivities "
          f"{1e3 * ts:.2f} ms")


def optimal_tensions():
    rob = ds.load_scene("cogiro").robot
    line = [[x, 0.5 * x, 1.0] for x in np.arange(-4.0, 4.01, 0.5)]
    ds.optimal_tensions(rob, line[0])                   # compiled kernels loaded
    print("\nOptimal tensions along a line of 17 CoGiRo poses [ms per pose]")
    for warm in (False, True):
        times, cpus, evals, prev = [], [], [], None
        for p in line:
            t, c = timeit.default_timer(), time.process_time()
            opt = ds.optimal_tensions(rob, p, start=prev if warm else None)
            times.append(timeit.default_timer() - t)
            cpus.append(time.process_time() - c)
            evals.append(opt.evaluations)
            prev = opt
        times, cpus = 1e3 * np.array(times), 1e3 * np.array(cpus)
        print(f"  {'warm' if warm else 'cold'}: wall median {np.median(times):6.1f}, mean "
              f"{times.mean():6.1f}, largest {times.max():6.1f}; CPU median "
              f"{np.median(cpus):6.1f}, largest {cpus.max():6.1f}; equilibria per pose "
              f"{np.mean(evals):.1f}")
    eq = rob.equilibrium(pose=line[8])
    from dynstiff.analyses.platform_modes import find_platform_modes
    t1 = best(lambda: rob.equilibrium(pose=line[8], start=eq))
    t2 = best(lambda: find_platform_modes(ds.FrequencyModel(eq)))
    print(f"  one evaluation's parts: statics (warm) {1e3 * t1:.1f} ms, platform modes "
          f"{1e3 * t2:.1f} ms")


if __name__ == "__main__":
    sensitivities()
    optimal_tensions()
