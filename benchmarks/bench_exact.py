"""Benchmark: the exact cable rung (theory.md §11) against the closed form ("dsm", theory.md
§3) and the lumped model (theory.md §7) on CoGiRo, side by side in one run (repeats
interleaved across the models, the minimum kept).

1. All natural frequencies below 10 Hz (``ds.eigenfrequencies(model, fmax_hz=10)``): the
   time of each rung, the exact model's build time (fmax_hz = 10.5) and each model's
   largest relative error against the exact rung over the exact rung's modes. The lumped
   model converges as O(N^-2) (theory.md §7.2); its N for 1e-6 is extrapolated from its error
   at the largest N measured, and its time from the measured growth with N.
2. A 10,000-frequency 6x6 FRF below 10 Hz (``ds.frf(model, omega)``), builds excluded (the
   exact rung also with its K(omega) in one block of frequencies instead of cache-sized
   blocks, `exact_model.BLOCK_ELEMENTS`). The
   lumped model's condensation is one sparse LU per frequency (cost linear in the number of
   frequencies): it is timed on 1,000 frequencies of the same band and scaled by 10.

Set OPENBLAS_NUM_THREADS=1 on a shared machine (threaded BLAS on small matrices under load
is many times slower).

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_exact.py
"""

import time

import numpy as np

import dynstiff as ds
from dynstiff.models import exact as exact_model
from dynstiff.models.ladder import build_model

FMAX_HZ = 10.0
EXACT_BAND_HZ = 10.5
SEGMENTS = (10, 20, 40)
#: Larger chains, timed with fewer repeats, for the growth of the lumped cost with N.
SEGMENTS_LARGE = (160, 320)
N_FRF = 10_000
N_FRF_LUMPED = {10: 1_000, 20: 1_000, 40: 1_000, 160: 100, 320: 100}
TARGET = 1e-6
REPEATS = 5


def interleaved(jobs, repeats=REPEATS):
    """Run every job once per round, ``repeats`` rounds; the minimum time [s] of each job
    and its last result."""
    best = {k: np.inf for k in jobs}
    out = {}
    for _ in range(repeats):
        for k, fn in jobs.items():
            t0 = time.perf_counter()
            out[k] = fn()
            best[k] = min(best[k], time.perf_counter() - t0)
    return best, out


def frequency_error(f, ref):
    """Largest |f_k / ref_k - 1| over the modes of ``ref`` (inf if f has fewer)."""
    if f.size < ref.size:
        return np.inf
    return float(np.max(np.abs(f[:ref.size] / ref - 1.0)))


def _lumped_jobs(eq, segments):
    return {f"lumped N={N}": (lambda N=N: build_model(eq, "lumped", N)) for N in segments}


def eigen_section(eq):
    """Build and modes below FMAX_HZ of every model; returns {name: (build + modes [s],
    error vs exact)} and the frequencies."""
    jobs = {"exact": lambda: build_model(eq, "exact", fmax_hz=EXACT_BAND_HZ),
            "dsm": lambda: build_model(eq, "dsm"), **_lumped_jobs(eq, SEGMENTS)}
    t_build, models = interleaved(jobs)
    big = _lumped_jobs(eq, SEGMENTS_LARGE)
    tb, mb = interleaved(big, repeats=2)
    t_build.update(tb)
    models.update(mb)

    def modes(m):
        return lambda: ds.eigenfrequencies(m, fmax_hz=FMAX_HZ)

    t_eig, freqs = interleaved({k: modes(models[k]) for k in jobs})
    te, fb = interleaved({k: modes(models[k]) for k in big}, repeats=2)
    t_eig.update(te)
    freqs.update(fb)
    ref = freqs["exact"]
    print(f"CoGiRo, all {ref.size} natural frequencies below {FMAX_HZ:g} Hz (minimum of "
          f"{REPEATS} interleaved repeats; N >= {SEGMENTS_LARGE[0]}: 2)")
    print(f"  {'model':<16s}{'build [ms]':>11s}{'modes [ms]':>11s}{'total [ms]':>11s}"
          f"{'n < 10 Hz':>10s}{'err vs exact':>14s}")
    rows = {}
    for k in models:
        tot = t_build[k] + t_eig[k]
        rows[k] = (tot, frequency_error(freqs[k], ref))
        print(f"  {k:<16s}{1e3 * t_build[k]:11.2f}{1e3 * t_eig[k]:11.2f}{1e3 * tot:11.2f}"
              f"{freqs[k].size:10d}{rows[k][1]:14.2e}")
    for n1, n2 in (SEGMENTS[-2:], SEGMENTS_LARGE):
        f1, f2 = freqs[f"lumped N={n1}"][:ref.size], freqs[f"lumped N={n2}"][:ref.size]
        rich = (4 * f2 - f1) / 3
        tr = rows[f"lumped N={n1}"][0] + rows[f"lumped N={n2}"][0]
        rows[f"Richardson N={n1},{n2}"] = (tr, frequency_error(rich, ref))
        print(f"  lumped N={n1},{n2} Richardson: {1e3 * tr:9.1f} ms, vs exact "
              f"{frequency_error(rich, ref):.2e}")
    print(f"  ratio exact / dsm: modes {t_eig['exact'] / t_eig['dsm']:.2f}, build + modes "
          f"{rows['exact'][0] / rows['dsm'][0]:.2f}   (goal <= 10)")
    return rows


def growth(times, n1, n2):
    """Exponent p of time ~ N^p between N = n1 and n2, at least 1 (the lumped model's work
    is at least linear in N; a measured p < 1 is timing noise or fixed overhead)."""
    p = np.log(times[f"lumped N={n2}"] / times[f"lumped N={n1}"]) / np.log(n2 / n1)
    return max(1.0, float(p))


def at_target(rows):
    """N of the plain lumped model for TARGET (O(N^-2) from its error at the largest N)."""
    n = SEGMENTS_LARGE[-1]
    return n * np.sqrt(rows[f"lumped N={n}"][1] / TARGET)


def frf_section(eq):
    """6x6 FRF below FMAX_HZ of every model, builds excluded; returns {name: time [s] for
    N_FRF frequencies}."""
    w = 2 * np.pi * np.linspace(0.01, FMAX_HZ, N_FRF)
    models = {"dsm": build_model(eq, "dsm"),
              "exact": build_model(eq, "exact", fmax_hz=EXACT_BAND_HZ)}
    jobs = {k: (lambda m=m: ds.frf(m, w)) for k, m in models.items()}

    def one_block():                    # the exact rung without its frequency blocks
        saved, exact_model.BLOCK_ELEMENTS = exact_model.BLOCK_ELEMENTS, 2**62
        try:
            return ds.frf(models["exact"], w)
        finally:
            exact_model.BLOCK_ELEMENTS = saved

    jobs["exact, 1 block"] = one_block
    for N in SEGMENTS + SEGMENTS_LARGE:
        m = build_model(eq, "lumped", N)
        w_l = 2 * np.pi * np.linspace(0.01, FMAX_HZ, N_FRF_LUMPED[N])
        jobs[f"lumped N={N}"] = (lambda m=m, w_l=w_l: ds.frf(m, w_l))
    t, _ = interleaved(jobs, repeats=3)
    print(f"\n6x6 FRF at {N_FRF} frequencies 0.01-{FMAX_HZ:g} Hz (builds excluded; minimum "
          f"of 3; lumped: one sparse LU per frequency, timed on fewer frequencies, scaled)")
    for k in jobs:
        n = N_FRF_LUMPED.get(int(k.split("=")[1]), N_FRF) if k.startswith("lumped") else N_FRF
        t[k] *= N_FRF / n
        note = f"  ({n} frequencies x {N_FRF // n})" if n != N_FRF else ""
        print(f"  {k:<16s}{1e3 * t[k]:11.1f} ms   x{t[k] / t['dsm']:8.1f} of dsm{note}")
    print(f"  ratio exact / dsm: {t['exact'] / t['dsm']:.2f}; exact in frequency blocks / "
          f"in one block: {t['exact'] / t['exact, 1 block']:.2f}")
    return t


def main():
    eq = ds.load_scene("cogiro").equilibrium()
    rows = eigen_section(eq)
    n1, n2 = SEGMENTS_LARGE
    n_t = at_target(rows)
    t_ex = rows["exact"][0]
    tot = {k: v[0] for k, v in rows.items()}
    p = growth(tot, n1, n2)
    t_t = tot[f"lumped N={n2}"] * (n_t / n2) ** p
    print(f"\nlumped at equal accuracy, modes below {FMAX_HZ:g} Hz (build + modes), "
          f"against the exact rung's {1e3 * t_ex:.1f} ms:")
    for N in SEGMENTS + SEGMENTS_LARGE:
        print(f"  N={N:<4d} error {rows[f'lumped N={N}'][1]:.1e}: lumped / exact = "
              f"{tot[f'lumped N={N}'] / t_ex:7.1f}")
    r = rows[f"Richardson N={n1},{n2}"]
    print(f"  Richardson N={n1},{n2}, error {r[1]:.1e}: lumped / exact = {r[0] / t_ex:.1f}")
    print(f"  plain lumped, N for {TARGET:g} by O(N^-2) from N={n2}: {n_t:.0f}; time ~ "
          f"N^{p:.2f} (N={n1}-{n2}): {t_t:.1f} s, lumped / exact = {t_t / t_ex:.0f}"
          f"   (goal >= 100)")
    t = frf_section(eq)
    q = growth(t, n1, n2)
    t_l = t[f"lumped N={n2}"] * (n_t / n2) ** q
    print(f"  lumped at N={n_t:.0f} (time ~ N^{q:.2f}, N={n1}-{n2}): {t_l:.0f} s, "
          f"lumped / exact = {t_l / t['exact']:.0f};  measured: N={n2} / exact = "
          f"{t[f'lumped N={n2}'] / t['exact']:.0f}, N=40 / exact = "
          f"{t['lumped N=40'] / t['exact']:.0f}")


if __name__ == "__main__":
    main()
