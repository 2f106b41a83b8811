#!/usr/bin/env python3
"""Two ensembles of the same packings (the same seeds, `fluidbed ensemble`), run with two settings of the code:
is the difference of Table 2 and the detachment time within the spread of the packings?

    python3 post/ensemble_compare.py BASE_DIR NEW_DIR [--times 0.2 0.3 0.4 0.5] [--markdown]

For each quantity (Table 2's four at each instant, as `fluidbed report` takes them, and the detachment time) it
prints the base and new means with their sample standard deviations over the members, the mean paired difference
(new - base, seed by seed), and z = mean difference / standard error of the two means, sqrt((s_b^2 + s_n^2) / n):
|z| < 2 is a difference the 8 packings cannot tell from none. The ratio s_new / s_base says whether the new
setting adds spread of its own. Members missing from either ensemble, or without a bubble at an instant, are left
out of that row (n counts the pairs)."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report  # noqa: E402  (the report's own readers and Table 2 definitions)

QUANTITIES = [
    ("nose gas velocity (m/s)", "nose_gas_velocity_m_s"),
    ("U_b, centroid (m/s)", "centroid_rise_velocity_m_s"),
    ("U_th/U_mf", None),
    ("nose rise velocity (m/s)", "rise_velocity_m_s"),
]


def members(folder):
    out = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "bubble.csv")
        if name.startswith("seed-") and os.path.isfile(path):
            out[name] = report.read_csv(path)
    return out


def value(cols, column, t, u_mf):
    k = report.nearest_row(cols, t)
    if k is None:
        return None
    get = lambda c: cols.get(c, [""] * (k + 1))[k]  # noqa: E731
    token = (report.centroid_throughflow(get("nose_gas_velocity_m_s"), get("centroid_rise_velocity_m_s"), u_mf)
             if column is None else get(column))
    return None if token in (None, "") else float(token)


def stats(xs):
    n = len(xs)
    m = sum(xs) / n
    s = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1)) if n > 1 else 0.0
    return m, s


def compare(pairs):
    """pairs: [(base, new)] -> (n, base mean, base sd, new mean, new sd, mean difference, z)."""
    b = [p[0] for p in pairs]
    w = [p[1] for p in pairs]
    mb, sb = stats(b)
    mn, sn = stats(w)
    d = mn - mb
    se = math.sqrt((sb ** 2 + sn ** 2) / len(pairs))
    return len(pairs), mb, sb, mn, sn, d, (d / se if se > 0 else (0.0 if d == 0 else math.inf))


def table(base_dir, new_dir, times, u_mf):
    """The seeds in both folders, and per quantity (label, t or None for the detachment, n, base mean, base sd,
    new mean, new sd, mean difference, z); rows with fewer than 2 pairs have n only."""
    base, new = members(base_dir), members(new_dir)
    seeds = [s for s in base if s in new]
    rows = []
    for t in times:
        for label, column in QUANTITIES:
            pairs = [(value(base[s], column, t, u_mf), value(new[s], column, t, u_mf)) for s in seeds]
            pairs = [p for p in pairs if p[0] is not None and p[1] is not None]
            rows.append((label, t) + (compare(pairs) if len(pairs) >= 2 else (len(pairs),)))
    pairs = [(report.detachment_time(base[s]), report.detachment_time(new[s])) for s in seeds]
    pairs = [(float(a), float(b)) for a, b in pairs if a is not None and b is not None]
    rows.append(("detachment time (s)", None) + (compare(pairs) if len(pairs) >= 2 else (len(pairs),)))
    return seeds, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("base")
    ap.add_argument("new")
    ap.add_argument("--times", type=float, nargs="+", default=list(report.TABLE2_TIMES))
    ap.add_argument("--u-mf", type=float, default=1.8, help="U_mf of the throughflow ratio (m/s)")
    args = ap.parse_args()
    seeds, rows = table(args.base, args.new, args.times, args.u_mf)
    if len(seeds) < 2:
        sys.exit(f"ensemble_compare: {len(seeds)} seed(s) in both folders; need at least 2")
    print(f"{len(seeds)} packings in both ({', '.join(seeds)})")
    print()
    print("| quantity | t (s) | n | base: mean ± sd | new: mean ± sd | new - base | z | sd new / sd base |")
    print("|---|---|---|---|---|---|---|---|")
    worst = 0.0
    for row in rows:
        label, t = row[0], ("–" if row[1] is None else f"{row[1]:g}")
        if len(row) == 3:
            print(f"| {label} | {t} | {row[2]} | – | – | – | – | – |")
            continue
        n, mb, sb, mn, sn, d, z = row[2:]
        worst = max(worst, abs(z))
        ratio = f"{sn / sb:.2f}" if sb > 0 else "–"
        print(f"| {label} | {t} | {n} | {mb:.3f} ± {sb:.3f} | {mn:.3f} ± {sn:.3f} | {d:+.3f} | {z:+.2f} | {ratio} |")
    print()
    print(f"largest |z|: {worst:.2f}")


if __name__ == "__main__":
    main()
