"""Benchmark: CoGiRo robot-level analysis (targets: 10,000-frequency FRF under 10 ms, see
bench_frf.py; all modes below 10 Hz to 1e-10 under 10 ms).

Run:  python benchmarks/bench_robot.py
All cases are timed in the same run, as the minimum over interleaved repeats (the machine is
shared); ratios are to the K(omega) assembly. The eigenfrequencies below 10 Hz are checked
against a run at rtol 1e-13 (largest relative difference printed).
"""

import time

import numpy as np

import dynstiff as ds


def main(repeat=7):
    scene = ds.load_scene("cogiro")
    eq = scene.equilibrium()
    m = ds.FrequencyModel(eq)
    w = 2 * np.pi * np.linspace(0.1, 12.0, 10_000)
    cases = {
        "K(omega), 10k freqs, 6x6": (lambda: m.dynamic_stiffness(w), 5),
        "FRF 6x6, 10k freqs": (lambda: ds.frf(m, w), 3),
        "FRF fz->z, 10k freqs": (lambda: ds.frf(m, w, inputs="fz", outputs="z"), 3),
        "40 eigenfrequencies (W-W)": (lambda: ds.eigenfrequencies(m, 40), 3),
        "all modes < 10 Hz, rtol 1e-10": (
            lambda: ds.eigenfrequencies(m, fmax_hz=10.0, rtol=1e-10), 3),
        "40 modes + energy fractions": (lambda: ds.modes(m, 40), 1),
        "inverse statics (pose -> L0)": (lambda: scene.equilibrium(), 1),
        "forward statics (L0 -> pose)": (
            lambda: scene.robot.equilibrium(unstretched_lengths=eq.unstretched_lengths), 3),
    }
    for fn, _ in cases.values():                  # warm up (and compile) once
        fn()
    res = dict.fromkeys(cases, np.inf)
    for _ in range(repeat):                         # interleaved
        for name, (fn, number) in cases.items():
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            res[name] = min(res[name], (time.perf_counter() - t0) / number)
    base = res["K(omega), 10k freqs, 6x6"]
    print(f"{'case':<34s} {'time [ms]':>10s} {'ratio':>8s}")
    for name, t in res.items():
        print(f"{name:<34s} {1e3 * t:10.2f} {t / base:8.2f}")
    f = ds.eigenfrequencies(m, fmax_hz=10.0, rtol=1e-10)
    f_ref = ds.eigenfrequencies(m, fmax_hz=10.0, rtol=1e-13)
    print(f"{len(f)} modes below 10 Hz; largest relative difference to rtol 1e-13: "
          f"{np.abs(f / f_ref - 1).max():.1e}")
    return res


if __name__ == "__main__":
    main()
