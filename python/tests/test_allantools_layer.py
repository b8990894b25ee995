"""imunoise.allantools keeps allantools' documented semantics: the tau lists of taus=None,
'octave', 'decade', 'all' and arrays (allantools' own test expectations for 128 points), the
(taus, devs, errs, ns) tuple with errs = devs / sqrt(ns), and values equal to the SP 1065
formulas written out here in numpy, and to the Stable32 tables."""
import csv

import numpy as np
import pytest

import imunoise.allantools as at

RNG = np.random.default_rng(11)
D128 = RNG.random(128)


def test_tau_lists_as_allantools():
    assert list(at.adev(D128)[0]) == [1, 2, 4, 8, 16, 32]
    assert list(at.adev(D128, taus=[])[0]) == [1, 2, 4, 8, 16, 32]
    assert list(at.adev(D128, rate=1.0, taus="octave")[0]) == [1, 2, 4, 8, 16, 32]
    assert list(at.adev(D128, rate=1.0, taus="decade")[0]) == [1, 2, 4, 10, 20, 40]
    assert list(at.adev(D128, rate=1.0, taus="all")[0]) == list(range(1, 43))
    taus, *_ = at.oadev(D128, rate=10.0, taus=np.array([0.1, 0.14, 0.2, 0.21, 5.0]))
    assert list(taus) == [0.1, 0.2, 5.0]  # m = 1, 1 (duplicate), 2, 2, 50 → 1, 2, 50
    taus, *_ = at.theo1(D128, rate=1.0, taus="all")
    assert all(t % 2 == 0 for t in taus)


def oadev_formula(x, m, tau0):
    d = x[2 * m:] - 2 * x[m:-m] + x[:-2 * m]
    return np.sqrt(np.mean(d * d) / 2.0) / (m * tau0), len(d)


def mdev_formula(x, m, tau0):
    n = len(x)
    c = np.concatenate(([0.0], np.cumsum(x)))
    s = [(c[j + 3 * m] - c[j + 2 * m]) - 2 * (c[j + 2 * m] - c[j + m]) + (c[j + m] - c[j])
         for j in range(n - 3 * m + 1)]
    s = np.array(s) / m
    return np.sqrt(np.mean(s * s) / 2.0) / (m * tau0), len(s)


@pytest.mark.parametrize("data_type", ["phase", "freq"])
def test_values_errs_and_ns_follow_the_formulas(data_type):
    y = RNG.standard_normal(5000)
    rate = 4.0
    x = y if data_type == "phase" else np.concatenate(([0.0], np.cumsum(y - y.mean()) / rate))
    taus, devs, errs, ns = at.oadev(y, rate=rate, data_type=data_type, taus="octave")
    for t, dev, err, n in zip(taus, devs, errs, ns):
        m = int(round(t * rate))
        want, count = oadev_formula(x, m, 1.0 / rate)
        assert dev == pytest.approx(want, rel=1e-9)
        assert n == count
        assert err == pytest.approx(dev / np.sqrt(n), rel=1e-15)
    taus, devs, _, ns = at.mdev(y, rate=rate, data_type=data_type, taus=[1 / rate, 8 / rate])
    for t, dev, n in zip(taus, devs, ns):
        want, count = mdev_formula(x, int(round(t * rate)), 1.0 / rate)
        assert dev == pytest.approx(want, rel=1e-9)
        assert n == count
    # TDEV = tau·MDEV/√3 with MDEV's ns.
    tt, td, _, tn = at.tdev(y, rate=rate, data_type=data_type, taus=taus)
    np.testing.assert_allclose(td, tt * devs / np.sqrt(3), rtol=1e-13)
    np.testing.assert_array_equal(tn, ns)


def test_points_with_one_term_are_dropped():
    # OADEV of 101 phase points: m = 50 has N − 2m = 1 term, allantools drops it.
    taus, _, _, ns = at.oadev(RNG.random(101), taus="all")
    assert taus[-1] == 49 and ns[-1] == 3


STABLE32 = {"Overlapping Allan": at.oadev, "Modified Allan": at.mdev, "Time": at.tdev,
            "Overlapping Hadamard": at.ohdev, "Allan": at.adev, "Hadamard": at.hdev,
            "Total": at.totdev}


def test_stable32_tables_through_the_allantools_calls(reference_data):
    d = reference_data / "allantools-stable32" / "phasedat"
    phase = np.array([float(l) for l in open(d / "PHASE.DAT") if l.strip() and l[0] != "#"])
    rows = [r for r in csv.DictReader(open(d / "expected_stable32.csv"))
            if r["sigma_type"] in STABLE32 and r["source_file"].endswith("_octave.txt")]
    assert len(rows) > 30
    for r in rows:
        fn = STABLE32[r["sigma_type"]]
        m = int(r["af"])
        taus, devs, _, _ = fn(phase, rate=1.0, data_type="phase", taus=[float(m)])
        assert list(taus) == [m]
        assert devs[0] / float(r["sigma"]) == pytest.approx(1.0, abs=1e-4), (r["source_file"], m)
