#!/usr/bin/python3
"""Compares the intervals of two battery runs of the same recordings (rows.csv of
battery_runner, e.g. the default interval draws and `-- --bootstrap 200`):

    compare_runs.py A/rows.csv B/rows.csv [--names A,B]

Per coefficient (rows with a truth and an interval in both runs): the coverage of each run
with its binomial standard error, the difference B − A with the standard error of a paired
difference (discordant pairs), and the median and 10–90 % range of the ratio of interval
widths A / B. Prints Markdown (docs/validation.md quotes it).
"""
import csv
import math
import statistics
import sys


def rows(path):
    out = {}
    for r in csv.DictReader(open(path)):
        if float(r["truth"]) <= 0 or r["has_interval"] != "1":
            continue
        # A channel has several GM terms or lines: the truth's T_c or frequency tells them apart.
        out[(r["class"], r["seed"], r["channel"], r["term"], r["truth_f_hz_or_tau_c_s"])] = r
    return out


def main(argv):
    names = ["A", "B"]
    args = [a for a in argv if not a.startswith("--names")]
    for a in argv:
        if a.startswith("--names"):
            names = a.split("=", 1)[1].split(",")
    a, b = rows(args[0]), rows(args[1])
    keys = sorted(set(a) & set(b))
    print(f"| coefficient | pairs | covered {names[0]} ± SE | covered {names[1]} ± SE | "
          f"{names[1]} − {names[0]} ± SE | width {names[0]}/{names[1]} median [10 %, 90 %] |")
    print("|---|---|---|---|---|---|")
    for term in ("quantization", "white_noise", "bias_instability", "random_walk", "ramp",
                 "gm_sigma", "gm_tau_c", "sinusoid_amplitude"):
        ks = [k for k in keys if k[3] == term]
        if not ks:
            continue
        n = len(ks)
        ca = [a[k]["covered"] == "1" for k in ks]
        cb = [b[k]["covered"] == "1" for k in ks]
        pa, pb = sum(ca) / n, sum(cb) / n
        se = lambda p: math.sqrt(p * (1 - p) / n)
        only_a = sum(x and not y for x, y in zip(ca, cb))
        only_b = sum(y and not x for x, y in zip(ca, cb))
        se_diff = math.sqrt(only_a + only_b) / n
        ratios = []
        for k in ks:
            wa = float(a[k]["ci_high"]) - float(a[k]["ci_low"])
            wb = float(b[k]["ci_high"]) - float(b[k]["ci_low"])
            if 0 < wa < math.inf and 0 < wb < math.inf:
                ratios.append(wa / wb)
        ratios.sort()
        q = lambda f: ratios[min(len(ratios) - 1, int(f * len(ratios)))]
        width = (f"{statistics.median(ratios):.2f} [{q(0.1):.2f}, {q(0.9):.2f}]"
                 if ratios else "—")
        print(f"| {term} | {n} | {sum(ca)}/{n} = {100 * pa:.1f} % ± {100 * se(pa):.1f} | "
              f"{sum(cb)}/{n} = {100 * pb:.1f} % ± {100 * se(pb):.1f} | "
              f"{100 * (pb - pa):+.1f} % ± {100 * se_diff:.1f} | {width} |")


if __name__ == "__main__":
    main(sys.argv[1:])
