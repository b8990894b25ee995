#!/usr/bin/env python3
"""NEES of `imunoise drift` on the battery's independent recordings (issue 25, docs/validation.md).

Runs on the recordings and models a battery run kept (battery_runner --size long --keep --out DIR
writes DIR/work/CLASS_seedS.imnb and DIR/work/CLASS_seedS/model.yaml, the fit of the real CLI):

    drift_battery.py DIR [--imunoise PATH] [--segment 10min] [-- DRIFT_FLAGS...]

For each recording: `imunoise drift REC --model MODEL --heading 0 --holdout half --monte-carlo 0
--segment SEG` (the battery's IMU is level with x north at 45 deg N, the default location), then
from drift_summary.json: is the mean NEES inside its 95 % band at every report time, for the
same-file prediction and for the split-sample one (fit on the first half, judge the second)?
And inside the joint 95 % band at all report times together (each time's band at 0.95^(1/K),
pipeline::DriftConsistency)? Prints one row per recording ('!' outside the per-time band, '*'
also outside the joint one) and both fractions.
"""
import json
import pathlib
import subprocess
import sys


def main(argv):
    args = argv[1:]
    extra = []
    if "--" in args:
        extra = args[args.index("--") + 1:]
        args = args[: args.index("--")]
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(args[0])
    imunoise = "imunoise"
    segment = "10min"
    i = 1
    while i < len(args):
        if args[i] == "--imunoise":
            imunoise = args[i + 1]
            i += 2
        elif args[i] == "--segment":
            segment = args[i + 1]
            i += 2
        else:
            print(f"unknown argument {args[i]}", file=sys.stderr)
            return 2
    work = root / "work"
    rows = []
    for rec in sorted(work.glob("*_seed*.imnb")) + sorted(work.glob("*_seed*.csv")):
        tag = rec.stem
        model = work / tag / "model.yaml"
        if not model.exists():
            print(f"{tag}: no model.yaml, skipped", file=sys.stderr)
            continue
        out = work / tag / f"drift_{segment}"
        cmd = [imunoise, "drift", str(rec), "--model", str(model), "--heading", "0",
               "--holdout", "half", "--monte-carlo", "0", "--segment", segment, "-q",
               "-o", str(out)] + extra
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"{tag}: drift failed ({r.returncode}): {r.stderr.strip()}", file=sys.stderr)
            rows.append((tag, None, None, None, None))
            continue
        s = json.loads((out / "drift_summary.json").read_text())
        same = s["consistency"]
        held = s["holdout"]["consistency"]
        rows.append((tag, same, held, s["protocol"]["segments"], s["holdout"]["segments"]))

    def cells(cs):
        return " ".join(
            f"{c['mean_nees']:.2f}{'' if c['nees_inside_band'] else '!'}"
            f"{'' if c['nees_inside_joint_band'] else '*'}" for c in cs)

    print(f"segment {segment}; NEES per report time ('!' = outside its 95 % band, "
          "'*' = outside the joint band too)")
    print("| recording | segments (same / holdout) | same file | holdout half |")
    print("|---|---|---|---|")
    ok_same = ok_held = joint_same = joint_held = n = 0
    for tag, same, held, ns, nh in rows:
        if same is None:
            print(f"| {tag} | failed | | |")
            continue
        n += 1
        ok_same += all(c["nees_inside_band"] for c in same)
        ok_held += all(c["nees_inside_band"] for c in held)
        joint_same += all(c["nees_inside_joint_band"] for c in same)
        joint_held += all(c["nees_inside_joint_band"] for c in held)
        times = "/".join(f"{c['time_s']:g}" for c in same)
        print(f"| {tag} | {ns} / {nh} | {cells(same)} | {cells(held)} |")
    if n:
        print(f"\nreport times {times} s; in band at every time: same file {ok_same}/{n}, "
              f"holdout {ok_held}/{n}; in the joint band at all times: same file "
              f"{joint_same}/{n}, holdout {joint_held}/{n}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
