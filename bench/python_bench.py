#!/usr/bin/python3
"""OADEV of 11.52 M samples (8 h at 400 Hz) on a 62-point log τ grid, from Python (issue 24):

  imunoise.allantools.oadev   the allantools call, imunoise's C++ estimator underneath
  imunoise.deviation          the same curve with EDF-based intervals (one thread and all)
  numpy reference             allantools' own algorithm written out in numpy here: per τ,
                              x[2m:] - 2 x[m:-m] + x[:-2m] and the mean of its squares
                              (allantools is not a Debian package and PyPI is unreachable
                              here, so allantools itself cannot run beside it; the issue
                              measured allantools at 2.32 s for this job on this machine kind)

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_bench.py [SAMPLES]

Prints one Markdown table for bench/RESULTS.md; best of 3 runs each (after one warm-up).
"""
import sys
import time

import numpy as np

import imunoise
import imunoise.allantools as allantools

N = int(sys.argv[1]) if len(sys.argv) > 1 else 11_520_000
RATE = 400.0


def log_grid(n, points=62):
    """The first k for which unique(round(logspace(0, log10(n/4), k))) has POINTS factors."""
    for k in range(points, 4 * points):
        m = np.unique(np.round(np.logspace(0, np.log10(n // 4), k))).astype(np.int64)
        if len(m) >= points:
            return m[:points]
    raise RuntimeError("no grid")


def numpy_oadev(phase, m_values, rate):
    out = np.empty(len(m_values))
    for i, m in enumerate(m_values):
        d = phase[2 * m:] - 2.0 * phase[m:-m] + phase[:-2 * m]
        out[i] = np.sqrt(np.mean(d * d) / 2.0) * rate / m
    return out


def best_of(fn, runs=3):
    fn()
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t)
    return min(times), result


def main():
    y = np.random.default_rng(1).standard_normal(N) * 1e-3
    m = log_grid(N + 1)
    taus = m / RATE
    t_compat, (tc, dc, _, _) = best_of(
        lambda: allantools.oadev(y, rate=RATE, data_type="freq", taus=taus))
    t_dev1, dev = best_of(lambda: imunoise.deviation(y, "oadev", rate=RATE, taus=list(m),
                                                     threads=1))
    t_dev, _ = best_of(lambda: imunoise.deviation(y, "oadev", rate=RATE, taus=list(m)))
    phase = allantools.frequency2phase(y, RATE)
    t_np, ref = best_of(lambda: numpy_oadev(phase, m, RATE), runs=1)
    assert len(tc) == len(m) == 62
    assert np.allclose(dc, ref, rtol=1e-9) and np.allclose(dev.value, ref, rtol=1e-9)
    print(f"{N} samples, {len(m)} τ (m = {m[0]} … {m[-1]}); numpy {np.__version__}")
    print()
    print("| call | wall s | vs numpy reference | vs allantools (2.32 s, issue 24) |")
    print("|---|---|---|---|")
    for name, t in (("imunoise.allantools.oadev", t_compat),
                    ("imunoise.deviation, 1 thread, with intervals", t_dev1),
                    ("imunoise.deviation, all cores, with intervals", t_dev),
                    ("numpy reference (allantools' algorithm)", t_np)):
        print(f"| {name} | {t:.3f} | {t_np / t:.1f}× | {2.32 / t:.1f}× |")


if __name__ == "__main__":
    main()
