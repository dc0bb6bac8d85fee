"""Benchmark: the CoGiRo 6x6 receptance at 10,000 frequencies, beside numpy's floor.

Cases, timed in one run as the minimum over interleaved repeats (the machine is shared, so
the minimum and the ratios are what compare), each as a ratio to ``np.linalg.inv`` of a
(10000, 6, 6) real array (the goal: the whole FRF faster than that inverse alone):

* ``ds.frf(model, omega)``: the "dsm" rung, undamped (the default CoGiRo scene), 6x6;
* the same with one channel (fz -> z);
* K(omega) alone (``model.dynamic_stiffness``), numpy, batched;
* the numpy path of the FRF (K(omega), then a real ``np.linalg.solve``), the reference
  the compiled kernel is checked against: the largest difference of H, relative to the
  largest |H| at each frequency, is printed.

Run:  python benchmarks/bench_frf.py
"""

import sys
import time

import numpy as np

import dynstiff as ds


def _numpy_frf(model, omega):
    K = model.dynamic_stiffness(omega)
    return np.linalg.solve(K, np.broadcast_to(np.eye(6), K.shape)).astype(complex)


def main(repeat=15, n=10_000):
    model = ds.build_model(ds.load_scene("cogiro").equilibrium(), "dsm")
    omega = 2 * np.pi * np.linspace(0.1, 12.0, n)
    A = np.random.default_rng(0).standard_normal((n, 6, 6))
    cases = {
        f"np.linalg.inv ({n},6,6)": lambda: np.linalg.inv(A),
        "FRF 6x6 (ds.frf)": lambda: ds.frf(model, omega),
        "FRF fz->z (ds.frf)": lambda: ds.frf(model, omega, inputs="fz", outputs="z"),
        "K(omega) alone (numpy)": lambda: model.dynamic_stiffness(omega),
        "FRF 6x6, numpy path": lambda: _numpy_frf(model, omega),
    }
    for fn in cases.values():                      # warm up (and compile) once
        fn()
    best = dict.fromkeys(cases, np.inf)
    for _ in range(repeat):                        # interleaved
        for name, fn in cases.items():
            t0 = time.perf_counter()
            fn()
            best[name] = min(best[name], time.perf_counter() - t0)
    H = ds.frf(model, omega).H
    H0 = _numpy_frf(model, omega)
    err = (np.abs(H - H0).max(axis=(1, 2)) / np.abs(H0).max(axis=(1, 2))).max()
    base = best[f"np.linalg.inv ({n},6,6)"]
    print(f"{'case':<28s} {'time [ms]':>10s} {'/ inv':>8s}")
    for name, t in best.items():
        print(f"{name:<28s} {1e3 * t:10.2f} {t / base:8.2f}")
    try:
        import numba
        engine = f"numba {numba.__version__}"
    except ImportError:
        engine = "numpy (numba absent)"
    print(f"FRF engine: {engine}; max |H - H_numpy| / max|H| per frequency: {err:.1e}")
    return best, err


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
