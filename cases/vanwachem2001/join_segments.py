#!/usr/bin/env python3
"""The probes of a run as one file on the simulated clock, the columns of the comparison at 7 significant digits
(results/README.md): time_s, then COLUMNS.

One run (the validation run at the source's stiffness): join_segments.py RUN/probes.csv --out results/probes.csv

Two segments (the softened run, results/softened-1e6/): that run stepped 2e-5 s to t = 1.19888 s (segment 1,
RUN1/probes-start.csv) and was continued from there at 2.4e-5 s (segment 2, RUN2/probes.csv). A restart with
another dem.time_step then labelled the clock as the DEM step count times the new step (a bug fixed since), so
segment 2's labels run OFFSET s ahead of the simulated time (0.239768 s: ../README.md, "The softened run").
Segment 1 is written up to its end and segment 2 after it; bed_bed_height_m is empty in segment 1 (the probe was
added at the restart).

Usage: join_segments.py RUN1/probes-start.csv RUN2/probes.csv --offset 0.239768 --out results/softened-1e6/probes.csv
"""
import argparse
import csv

COLUMNS = ("rel45_dp_Pa", "tap45_p_Pa", "tap45_eps", "plane45_p_Pa", "plane45_eps", "bed_bed_height_m")


def rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("first")
    ap.add_argument("second", nargs="?", help="the second segment's probes.csv, if the run was made in two")
    ap.add_argument("--offset", type=float, default=0.0, help="segment 2's label minus the simulated time, s")
    ap.add_argument("--out", required=True)
    ap.add_argument("--extra", nargs="*", default=[], help="more columns to keep after COLUMNS (a study's probes)")
    a = ap.parse_args()
    one, two = rows(a.first), rows(a.second) if a.second else []
    cols = COLUMNS + tuple(a.extra)
    t_end = max(float(r["time_s"]) for r in one)
    with open(a.out, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(("time_s",) + cols)
        for r in one:
            w.writerow([f"{float(r['time_s']):.6f}"] + [f"{float(r[c]):.7g}" if r.get(c) else "" for c in cols])
        for r in two:
            t = float(r["time_s"]) - a.offset
            if t > t_end + 1e-9:
                w.writerow([f"{t:.6f}"] + [f"{float(r[c]):.7g}" if r.get(c) else "" for c in cols])


if __name__ == "__main__":
    main()
