"""Benchmark: one cable's dynamic stiffness over 10,000 frequencies (target < 5 ms, one core).

Run:  python benchmarks/bench_cable_dsm.py
Prints the best-of-N wall time of each variant side by side, measured in the same run, and
the ratio to the plain undamped 3x3 matrix.
"""

import timeit

import numpy as np

import dynstiff as ds


def cases():
    anchor, end = np.array([-7.1775, -5.4361, 5.3911]), np.array([0.5032, -0.4928, 1.0])
    cable = ds.Cable(0.064, 8.2051e-6 * 17e9)
    damped = ds.Cable(0.064, 8.2051e-6 * 17e9, viscous_damping=0.05, loss_factor=0.01)
    s = ds.unstretched_length_for_tension(anchor, end, 300.0, cable)
    sd = ds.solve_catenary(anchor, end, s.unstretched_length, damped)
    w = np.linspace(0.0, 2 * np.pi * 50, 10_000)
    return {
        "3x3 undamped": lambda: ds.cable_dynamic_stiffness(s, w),
        "3x3 damped (complex)": lambda: ds.cable_dynamic_stiffness(sd, w),
        "6x6 undamped": lambda: ds.cable_dynamic_stiffness(s, w, ends="both"),
        "mode count J0": lambda: ds.cable_mode_count(s, w),
        "statics (solve_catenary)": lambda: ds.solve_catenary(anchor, end,
                                                              s.unstretched_length, cable),
    }


def main(repeat=7, number=20):
    results = {}
    for name, fn in cases().items():
        t = min(timeit.repeat(fn, repeat=repeat, number=number)) / number
        results[name] = t
    base = results["3x3 undamped"]
    print(f"{'case':<28s} {'time [ms]':>10s} {'ratio':>7s}")
    for name, t in results.items():
        print(f"{name:<28s} {1e3 * t:10.3f} {t / base:7.2f}")
    print(f"\n10,000-frequency 3x3 target 5 ms: {'met' if base < 5e-3 else 'NOT met'} "
          f"({1e3 * base:.2f} ms)")
    return results


if __name__ == "__main__":
    main()
