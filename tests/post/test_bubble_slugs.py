#!/usr/bin/env python3
"""Slugs and plugs in post/bubble_stats.py and the report: bubbles.csv's last column `slug` (1: a void across the
whole cross-section) and bubble_frames.csv's last column `slugs` (their number per frame). The synthetic bubbles of
tests/post/test_bubble_stats.py (three 2D bubbles of D = 0.04 m rising at 0.3 m/s from y = 0.05 m, born at 0, 0.5 and
1.0 s, sampled every 0.1 s) plus one slug (D = 0.3 m, rising at 0.1 m/s from y = 0.1 m over 0.5-1.5 s, so it also
crosses y = 0.2 m), in a file with the columns and, without the slug, in one without them (as written before them).
Exact: the statistics of both files are those of the three bubbles (every diameter bin 0.04 m, every velocity bin
0.3 m/s, 1.5 crossings of 0.2 m per second over [0, 2] s); the slug's 11 rows are counted as set aside (the frames'
`slugs` sum to 11 too), drawn apart with the label "slug / plug" in both figures, named in the table and in the
report's summary.md; the file without the columns reads as no slug. Before the columns were read, the slug's rows
entered the bins (D up to 0.3 m) and its crossing the frequency (2.0 per second).
Usage (CTest): test_bubble_slugs.py FLUIDBED_BINARY SOURCE_DIR"""
import csv
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
import bubble_stats as bs  # noqa: E402

failures = 0


def check(name, ok, detail=""):
    global failures
    failures += not ok
    print(f"{name}: {'ok' if ok else 'FAIL'} {detail}")


SLUG_ROWS = 11


def write_run(folder, with_slug_columns):
    os.makedirs(folder)
    area = np.pi * 0.04**2 / 4
    slug_area = np.pi * 0.3**2 / 4
    with open(os.path.join(folder, "bubbles.csv"), "w") as fh:
        fh.write("time_s,id,event,parents,area_m2,equivalent_diameter_m,centroid_x_m,centroid_y_m,nose_m,tail_m,"
                 "aspect_ratio,u_centroid_m_s,u_nose_m_s" + (",slug" if with_slug_columns else "") + "\n")
        end = ",0" if with_slug_columns else ""
        for k in range(21):
            t = 0.1 * k
            for i, born in enumerate((0.0, 0.5, 1.0)):
                y = 0.05 + 0.3 * (t - born)
                if t < born - 1e-12 or y > 0.5:
                    continue
                first = abs(t - born) < 1e-12
                u = "" if first else "0.3"
                fh.write(f"{t},{i},{'birth' if first else ''},,{area},0.04,0.1,{y},{y + 0.02},{y - 0.02},1,{u},{u}"
                         f"{end}\n")
            if with_slug_columns and 5 <= k <= 15:
                y = 0.1 + 0.1 * (t - 0.5)
                u = "" if k == 5 else "0.1"
                fh.write(f"{t},7,{'birth' if k == 5 else ''},,{slug_area},0.3,0.3,{y},{y + 0.1},{y - 0.1},0.7,{u},"
                         f"{u},1\n")
    with open(os.path.join(folder, "bubble_frames.csv"), "w") as fh:
        fh.write("time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction"
                 + (",slugs" if with_slug_columns else "") + "\n")
        for k in range(21):
            slugs = f",{int(5 <= k <= 15)}" if with_slug_columns else ""
            fh.write(f"{0.1 * k},0.84,0.12,0.012,1,0.1{slugs}\n")
    with open(os.path.join(folder, "case.toml"), "w") as fh:
        fh.write('[case]\nname = "slugging"\nmodel = "tfm"\n[inlet]\nvelocity = 3.6\n[bubble]\nu_mf = 1.8\n'
                 '[averages]\nt_start = 0.0\nt_end = 2.0\n')


def legend_capture():
    """Replace Figure.savefig by one that records every axes' lines (label, marker) per file, then saves."""
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    seen = {}
    original = Figure.savefig

    def savefig(self, fname, *a, **k):
        seen[os.path.basename(str(fname))] = [[(ln.get_label(), ln.get_marker()) for ln in ax.lines]
                                              for ax in self.axes]
        return original(self, fname, *a, **k)

    Figure.savefig = savefig
    return seen


seen = legend_capture()
with tempfile.TemporaryDirectory() as tmp:
    stats = {}
    for name, cols in (("new", True), ("old", False)):
        folder = os.path.join(tmp, name)
        write_run(folder, cols)
        bub = bs.read_csv(os.path.join(folder, "bubbles.csv"))
        frm = bs.read_csv(os.path.join(folder, "bubble_frames.csv"))
        n_slug = int(bs.slug_mask(bub).sum()) if hasattr(bs, "slug_mask") else -1
        check(f"{name}: slug rows read", n_slug == (SLUG_ROWS if cols else 0), f"{n_slug}")
        s = bs.bubble_statistics(bub, frm, t0=0.0, t1=2.0, u=3.6, u_mf=1.8, heights=[0.2], bins=5)
        stats[name] = s
        d = s["d_mean"][s["d_count"] > 0]
        check(f"{name}: diameter in every height bin is the bubbles' 0.04 m", bool(np.max(np.abs(d - 0.04)) < 1e-9),
              f"{d}")
        u = s["u_mean"][s["u_count"] > 0]
        check(f"{name}: centroid velocity in every bin is 0.3 m/s", bool(np.max(np.abs(u - 0.3)) < 1e-9), f"{u}")
        check(f"{name}: frequency at 0.2 m is 1.5 per second", abs(s["frequency"][0] - 1.5) < 1e-9,
              f"{s['frequency'][0]}")
        check(f"{name}: mean diameter 0.04 m", abs(s["d_all_mean"] - 0.04) < 1e-9, f"{s['d_all_mean']}")
        check(f"{name}: slug samples set aside", s.get("slug_samples") == (SLUG_ROWS if cols else 0),
              f"{s.get('slug_samples')}")
        check(f"{name}: slugs of bubble_frames.csv", s.get("frame_slugs") == (SLUG_ROWS if cols else 0),
              f"{s.get('frame_slugs')}")
        bs.figure(s, os.path.join(tmp, f"{name}.png"))
        slug_lines = [ln for ax in seen[f"{name}.png"] for ln in ax if ln[0] == "slug / plug"]
        # Diameter against height and velocity against diameter, open squares, only when there are slugs.
        check(f"{name}: slugs drawn as 'slug / plug'", [m for _, m in slug_lines] == (["s", "s"] if cols else []),
              f"{slug_lines}")
        bs.write_table(s, os.path.join(tmp, f"{name}.csv"))
        with open(os.path.join(tmp, f"{name}.csv"), newline="") as fh:
            rows = {r["quantity"]: r for r in csv.DictReader(fh)}
        check(f"{name}: bubble_stats.csv counts the slugs set aside",
              rows["slug_samples_set_aside"]["count"] == str(SLUG_ROWS if cols else 0)
              and rows["bubble_samples"]["count"] == str(s["samples"]))
    check("the slug column changes no bubble statistic", stats["new"]["samples"] == stats["old"]["samples"]
          and np.array_equal(stats["new"]["d_count"], stats["old"]["d_count"])
          and np.allclose(stats["new"]["d_corr"], stats["old"]["d_corr"], rtol=0, atol=0),
          f"{stats['new']['samples']} vs {stats['old']['samples']}")
    # The correlation is compared at the bins of the bubbles only: the top bin edge is the bubbles' highest centroid.
    check("correlation bins from the bubbles only", abs(stats["new"]["h"][-1] - stats["old"]["h"][-1]) < 1e-12)

    # The report's entry point, its table and figure; then fluidbed report's summary.md of the folder.
    entries = []
    for name in ("new", "old"):
        s, why = bs.run_statistics(os.path.join(tmp, name), {"inlet": {"velocity": 3.6}, "bubble": {"u_mf": 1.8},
                                                             "averages": {"t_start": 0.0, "t_end": 2.0}}, 2)
        entries.append((name, s))
    table = "\n".join(bs.table_runs(entries))
    check("table_runs: the slugs set aside", f"| {stats['new']['samples']} ({SLUG_ROWS} slug / plug samples set "
          "aside) | 0.040 |" in table and f"| {stats['old']['samples']} (0 slug / plug samples set aside) | 0.040 |"
          in table, "\n" + table)
    bs.figure_runs(entries, os.path.join(tmp, "runs.png"))
    labels = [ln[0] for ax in seen["runs.png"] for ln in ax]
    check("figure_runs: the slugs of the run that has them", labels.count("new: slug / plug") == 2
          and not any("old: slug" in lab for lab in labels), f"{labels}")
    bs.figure_runs(entries[:1], os.path.join(tmp, "one.png"))
    check("figure_runs of one run: 'slug / plug'",
          [ln[0] for ax in seen["one.png"] for ln in ax].count("slug / plug") == 2)

    import report  # noqa: E402
    out = os.path.join(tmp, "report")
    report.write_report([os.path.join(tmp, "new")], out)
    summary = open(os.path.join(out, "summary.md")).read()
    part = summary.split("## Freely bubbling statistics")[1] if "## Freely bubbling statistics" in summary else ""
    check("summary.md: the slugs set aside", f"({SLUG_ROWS} slug / plug samples set aside)" in part, "\n" + part)
    labels = [ln[0] for ax in seen.get("bubbling_statistics.png", []) for ln in ax]
    check("bubbling_statistics.png: 'slug / plug'", "slug / plug" in labels, f"{labels}")
sys.exit(1 if failures else 0)
