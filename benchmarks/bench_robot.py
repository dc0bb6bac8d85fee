"""Benchmark: CoGiRo robot-level analysis (targets: 10,000-frequency FRF well under 0.1 s;
first 40 eigenfrequencies well under 0.2 s).

Run:  python benchmarks/bench_robot.py
All cases are timed in the same run (best of N); ratios are to the K(omega) assembly.
"""

import timeit

import numpy as np

import dynstiff as ds


def main(repeat=5):
    scene = ds.load_scene("cogiro")
    eq = scene.equilibrium()
    m = ds.FrequencyModel(eq)
    w = 2 * np.pi * np.linspace(0.1, 12.0, 10_000)
    cases = {
        "K(omega), 10k freqs, 6x6": (lambda: m.dynamic_stiffness(w), 5),
        "FRF 6x6, 10k freqs": (lambda: ds.frf(m, w), 3),
        "FRF fz->z, 10k freqs": (lambda: ds.frf(m, w, inputs="fz", outputs="z"), 3),
        "40 eigenfrequencies (W-W)": (lambda: ds.eigenfrequencies(m, 40), 3),
        "40 modes + energy fractions": (lambda: ds.modes(m, 40), 1),
        "inverse statics (pose -> L0)": (lambda: scene.equilibrium(), 1),
        "forward statics (L0 -> pose)": (
            lambda: scene.robot.equilibrium(unstretched_lengths=eq.unstretched_lengths), 3),
    }
    res = {}
    for name, (fn, number) in cases.items():
        res[name] = min(timeit.repeat(fn, repeat=repeat, number=number)) / number
    base = res["K(omega), 10k freqs, 6x6"]
    print(f"{'case':<34s} {'time [ms]':>10s} {'ratio':>8s}")
    for name, t in res.items():
        print(f"{name:<34s} {1e3 * t:10.2f} {t / base:8.2f}")
    return res


if __name__ == "__main__":
    main()
