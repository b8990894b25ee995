"""allantools-compatible functions over imunoise's C++ estimators.

The calls allantools users write keep working with ``import imunoise.allantools as allantools``:
each function takes ``(data, rate=1.0, data_type="phase", taus=None)`` and returns
``(taus, devs, errs, ns)`` as allantools documents them:

- ``data_type``: ``"phase"`` (phase/time-error samples x, e.g. seconds) or ``"freq"``
  (fractional-frequency or rate samples y, integrated to phase x = tau0 * cumsum(y) from 0).
- ``taus``: ``None`` or ``[]`` (octave), ``"octave"`` (m = 1, 2, 4, …, 2^floor(log2 N)),
  ``"decade"`` (1, 2, 4 × 10^k), ``"all"`` (every m up to N), ``"log10"`` (about ten per decade),
  or an array of tau values in seconds, rounded to m = round(tau * rate). N is the number of
  phase points (allantools' data after integration); m must be 0 < m < N, ≤ N/3 for
  MTOTDEV/TTOTDEV/HTOTDEV, even for Thêo1; duplicates go; points with ns ≤ 1 are dropped.
- ``errs``: allantools' simple error estimate dev / sqrt(ns) (Thêo1: dev / sqrt(N − m)), not a
  confidence interval — for those use :func:`imunoise.deviation`, which gives EDF-based bounds.
- ``ns``: allantools' term counts: ADEV floor((N−1)/m)−1, OADEV N−2m, MDEV and TDEV N−3m+1,
  HDEV floor((N−1)/m)−2, OHDEV N−3m, TOTDEV N−2, MTOTDEV and TTOTDEV N−3m+1, HTOTDEV N−3m
  (its m = 1 point is OHDEV's), Thêo1 (N−m)·m/2.
- returned ``taus`` are m / rate (also for Thêo1, as allantools; imunoise.deviation reports
  Thêo1 at its effective tau 0.75·m/rate).

The deviations themselves are imunoise's (NIST SP 1065 / Stable32 definitions, checked
against their tables); for the total family and Thêo1 these are the unbiased-by-default
estimators without bias correction, as allantools computes them.
"""
from __future__ import annotations

import numpy as np

from . import _core

__all__ = ["adev", "oadev", "mdev", "tdev", "hdev", "ohdev", "totdev", "mtotdev", "ttotdev",
           "htotdev", "theo1", "frequency2phase", "phase2frequency", "tau_generator"]


def frequency2phase(freqdata, rate):
    """Phase from fractional-frequency data: x_0 = 0, x_k = tau0 * sum of the first k values
    (mean removed first, as allantools does), length N + 1."""
    return _core.phase_from_rate(np.asarray(freqdata, dtype=float), 1.0 / float(rate))


def phase2frequency(phase, rate):
    """Fractional frequency from phase: rate * diff(phase)."""
    return float(rate) * np.diff(np.asarray(phase, dtype=float))


def _phase(data, rate, data_type):
    data = np.ascontiguousarray(data, dtype=float)
    if data_type == "phase":
        return data
    if data_type == "freq":
        return frequency2phase(data, rate)
    raise _core.InputError(f"data_type: expected 'phase' or 'freq', got '{data_type}'")


def tau_generator(data, rate, taus=None, even=False, maximum_m=-1):
    """allantools' tau_generator: (data, m, taus_used) for DATA sampled at RATE."""
    if rate == 0:
        raise _core.InputError("rate: must not be 0")
    n = len(data)
    if taus is None or (isinstance(taus, (list, tuple)) and len(taus) == 0):
        taus = "octave"
    if isinstance(taus, str):
        if taus == "all":
            factors = np.arange(1, n + 1, dtype=float)
        elif taus == "octave":
            k = int(np.floor(np.log2(n)))
            factors = np.logspace(0, k, k + 1, base=2.0)
        elif taus == "log10":
            top = np.log10(n)
            factors = np.logspace(0, top, int(10 * top), base=10.0)
        elif taus == "decade":
            k = int(np.floor(np.log10(n)))
            factors = np.array([f * 10.0**j for j in range(k + 1) for f in (1.0, 2.0, 4.0)])
        else:
            raise _core.InputError(
                f"taus: expected 'all', 'octave', 'decade', 'log10' or an array, got '{taus}'")
        taus = factors / float(rate)
    taus = np.asarray(taus, dtype=float)
    m = np.round(taus * float(rate))
    limit = n if maximum_m == -1 else maximum_m
    m = m[(m < n) & (m > 0) & (m <= limit)]
    m = np.unique(m)
    if even:
        m = m[m % 2 == 0]
    return data, m.astype(np.int64), m / float(rate)


def _counts(kind, n, m):
    """allantools' ns for KIND on N phase points at factors M."""
    m = m.astype(np.int64)
    return {
        "adev": (n - 1) // m - 1,
        "oadev": n - 2 * m,
        "mdev": n - 3 * m + 1,
        "tdev": n - 3 * m + 1,
        "hdev": (n - 1) // m - 2,
        "ohdev": n - 3 * m,
        "totdev": np.full_like(m, n - 2),
        "mtotdev": n - 3 * m + 1,
        "ttotdev": n - 3 * m + 1,
        "htotdev": np.where(m == 1, n - 3, (n - 1) - 3 * m + 1),
        "theo1": (n - m) * m // 2,
    }[kind]


def _compute(kind, data, rate, data_type, taus):
    rate = float(rate)
    phase = _phase(data, rate, data_type)
    n = len(phase)
    if kind in ("mtotdev", "ttotdev"):
        _, m, taus_used = tau_generator(phase, rate, taus, maximum_m=n / 3.0)
    elif kind == "htotdev":
        # allantools generates HTOTDEV's taus on the frequency data (N - 1 points).
        _, m, taus_used = tau_generator(np.empty(n - 1), rate, taus, maximum_m=(n - 1) / 3.0)
    else:
        _, m, taus_used = tau_generator(phase, rate, taus, even=(kind == "theo1"))
    ns = _counts(kind, n, m)
    keep = ns > 1
    m, taus_used, ns = m[keep], taus_used[keep], ns[keep]
    if len(m) == 0:
        raise _core.AnalysisError(f"{kind}: no tau left with more than one term "
                                  f"({n} phase points)")
    variance, _ = _core.variance_at(phase, kind, m, 1.0 / rate)
    devs = np.sqrt(variance)
    errs = devs / np.sqrt(n - m) if kind == "theo1" else devs / np.sqrt(ns)
    return taus_used, devs, errs, ns


def adev(data, rate=1.0, data_type="phase", taus=None):
    """Allan deviation (non-overlapping)."""
    return _compute("adev", data, rate, data_type, taus)


def oadev(data, rate=1.0, data_type="phase", taus=None):
    """Overlapping Allan deviation."""
    return _compute("oadev", data, rate, data_type, taus)


def mdev(data, rate=1.0, data_type="phase", taus=None):
    """Modified Allan deviation."""
    return _compute("mdev", data, rate, data_type, taus)


def tdev(data, rate=1.0, data_type="phase", taus=None):
    """Time deviation, tau * MDEV / sqrt(3) (phase units)."""
    return _compute("tdev", data, rate, data_type, taus)


def hdev(data, rate=1.0, data_type="phase", taus=None):
    """Hadamard deviation (non-overlapping)."""
    return _compute("hdev", data, rate, data_type, taus)


def ohdev(data, rate=1.0, data_type="phase", taus=None):
    """Overlapping Hadamard deviation."""
    return _compute("ohdev", data, rate, data_type, taus)


def totdev(data, rate=1.0, data_type="phase", taus=None):
    """Total deviation (SP 1065 doubly reflected)."""
    return _compute("totdev", data, rate, data_type, taus)


def mtotdev(data, rate=1.0, data_type="phase", taus=None):
    """Modified total deviation (no bias correction, as allantools)."""
    return _compute("mtotdev", data, rate, data_type, taus)


def ttotdev(data, rate=1.0, data_type="phase", taus=None):
    """Time total deviation, tau * MTOTDEV / sqrt(3) (phase units)."""
    return _compute("ttotdev", data, rate, data_type, taus)


def htotdev(data, rate=1.0, data_type="phase", taus=None):
    """Hadamard total deviation (OHDEV at m = 1)."""
    return _compute("htotdev", data, rate, data_type, taus)


def theo1(data, rate=1.0, data_type="phase", taus=None):
    """Thêo1 (even m; no bias correction, as allantools)."""
    return _compute("theo1", data, rate, data_type, taus)
