"""The NIST SP 1065 and Stable32 tables of ../shared/data through Python, within the
tolerances of the C++ tests (tests/analysis/nist_sp1065_test.cpp, stable32_reference_test.cpp):
NIST values at 5e-7 relative; Stable32 values at 1e-4 (5 printed digits), term counts exactly,
68.3 % bounds at 1e-3 with the table's alpha."""
import csv

import numpy as np
import pytest

import imunoise
from imunoise import _core

NIST_KINDS = {"ADEV": "adev", "OADEV": "oadev", "MDEV": "mdev", "TDEV": "tdev", "HDEV": "hdev",
              "OHDEV": "ohdev", "TOTDEV": "totdev"}
STABLE32_KINDS = {"Allan": "adev", "Overlapping Allan": "oadev", "Modified Allan": "mdev",
                  "Time": "tdev", "Hadamard": "hdev", "Overlapping Hadamard": "ohdev",
                  "Total": "totdev"}


def read_numbers(path):
    values = []
    for line in open(path, encoding="latin-1"):
        line = line.split("#")[0].strip()
        if line:
            values.append(float(line.split()[0].replace(",", ".")))
    return np.array(values)


def read_column(path, column):
    return np.array([float(r[column]) for r in csv.DictReader(open(path))])


def test_nist_sp1065_table(reference_data):
    d = reference_data / "nist-sp1065-nbs"
    rows = list(csv.DictReader(open(d / "expected_values.csv")))
    checked = 0
    for r in rows:
        kind = NIST_KINDS.get(r["statistic"])
        if kind is None:
            continue
        freq = read_column(d / f"{r['dataset']}_freq.csv", "y")
        phase = _core.phase_from_rate(freq, 1.0)
        m = int(r["m"])
        variance, _ = _core.variance_at(phase, kind, np.array([m]), 1.0)
        published = float(r["published_value"])
        assert np.sqrt(variance[0]) / published == pytest.approx(1.0, abs=5e-7), \
            (r["dataset"], kind, m)
        checked += 1
    assert checked == 21 + 14
    # Within the stop ratio, imunoise.deviation (the allan command's path) gives the same.
    freq = read_column(d / "nbs14_1000_freq.csv", "y")
    dev = imunoise.deviation(freq, "oadev", rate=1.0, taus=[1, 10, 100])
    assert dev.value == pytest.approx([2.922319e-01, 9.159953e-02, 3.241343e-02], rel=5e-7)


def test_stable32_phase_dat(reference_data):
    d = reference_data / "allantools-stable32" / "phasedat"
    phase = read_numbers(d / "PHASE.DAT")
    rows = [r for r in csv.DictReader(open(d / "expected_stable32.csv"))
            if r["sigma_type"] in STABLE32_KINDS]
    assert len(rows) > 50
    for r in rows:
        kind = STABLE32_KINDS[r["sigma_type"]]
        m = int(r["af"])
        tau0 = float(r["tau_s"]) / m
        variance, n_terms = _core.variance_at(phase, kind, np.array([m]), tau0)
        assert np.sqrt(variance[0]) / float(r["sigma"]) == pytest.approx(1.0, abs=1e-4), \
            (r["source_file"], m)
        assert n_terms[0] == int(r["n"]), (r["source_file"], m)
        if r["ci_given"] == "yes":
            try:
                dev = imunoise.deviation(phase, kind, rate=1.0 / tau0, data="phase", taus=[m],
                                         alpha=int(r["alpha"]), confidence=0.683)
            except imunoise.AnalysisError:
                continue  # beyond the stop ratio: no interval here, as in the C++ test
            assert dev.ci_low[0] / float(r["sigma_min"]) == pytest.approx(1.0, abs=1e-3)
            assert dev.ci_high[0] / float(r["sigma_max"]) == pytest.approx(1.0, abs=1e-3)
