#!/usr/bin/python3
"""post/report.py shows at a requested instant only a frame or a row within half its series' interval of it, else
'–' (an instant after the run ended, or in a gap of its output):

- Table 2: a jet run whose bubble.csv ends at 0.25 s (rows every 0.01 s, the same 9.55 m/s gas velocity at the
  nose in every row) has its 0.2 s values and '–' in all four cells at 0.3, 0.4 and 0.5 s, and summary.md names
  those instants; a run that reaches 0.5 s keeps its values there. nearest_row() at the end of the rows (half an
  interval past the last row: kept; beyond: none) and in a gap.
- Bed figures of a mixed report (columns = the paper's instants that some run reaches): a run that ends at 0.06 s
  (frames 0 ... 0.06 s) keeps its row in voidage.png, but with '–' panels: none of its frames (the t = 0 frame
  included) is shown under an instant, and summary.md says why. nearest_frame() and choose_panels() directly.

Usage (ctest): test_report_instants.py FLUIDBED_BINARY REPO_ROOT. Exits non-zero on failure.
"""

import csv
import os
import sys
import tempfile
from types import SimpleNamespace

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import test_report as tr  # noqa: E402  (the synthetic run folders of tests/post/test_report.py)


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def write_bubble(folder, times, gas):
    """bubble.csv with one bubble row per time, the gas velocity at the nose `gas` everywhere."""
    with open(os.path.join(folder, "bubble.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "nose_height_m", "rise_velocity_m_s", "nose_gas_velocity_m_s", "throughflow_ratio",
                    "bubble_area_m2", "attached", "equivalent_diameter_m", "bed_height_m", "erupted", "bubble_id",
                    "nose_x_m", "centroid_y_m", "centroid_rise_velocity_m_s"])
        for t in times:
            w.writerow([repr(t), repr(0.1 + t), "0.9", repr(gas), "4.8", "0.004", "1", "0.07", "0.54", "0", "0",
                        "0.31", repr(0.05 + t), "0.45"])


def table2_cells(summary, t):
    line = next((ln for ln in summary.splitlines() if ln.startswith(f"| {t} |")), None)
    if line is None:
        fail(f"Table 2 has no row for t = {t}")
    return [c.strip() for c in line.strip().strip("|").split("|")][1:]


def main():
    repo = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "..")
    sys.path.insert(0, os.path.join(repo, "post"))
    import report

    rng = np.random.default_rng(3)
    with tempfile.TemporaryDirectory() as tmp:
        # ---- A: Table 2 of a run that ended at 0.25 s, beside one that reaches 0.5 s.
        ended, _ = tr.make_run(tmp, "ended", "tfm", 0.25, False, True, rng)
        full, _ = tr.make_run(tmp, "full", "tfm", 0.5, False, True, rng)
        write_bubble(ended, [round(0.01 * k, 10) for k in range(26)], 9.55)
        write_bubble(full, [round(0.01 * k, 10) for k in range(51)], 3.25)
        out = os.path.join(tmp, "report-a")
        report.write_report([ended, full], out)
        summary = open(os.path.join(out, "summary.md")).read()
        table2 = summary.split("## Table 2")[1].split("## Bubble events")[0]
        cells = table2_cells(table2, 0.2)
        if cells[:4] != ["9.55 [0.200]", "0.45", f"{(9.55 - 0.45) / 1.8:.2f}", "0.90"]:
            fail(f"Table 2 at 0.2 s, run 'ended': {cells[:4]}")
        for t in (0.3, 0.4, 0.5):
            cells = table2_cells(table2, t)
            if cells[:4] != ["–"] * 4:
                fail(f"Table 2 at {t} s shows values of a run that ended at 0.25 s: {cells[:4]}")
            if cells[4] != f"3.25 [{t:.3f}]":
                fail(f"Table 2 at {t} s, run 'full' (reaches 0.5 s): {cells[4:]}")
        if "ended at t = 0.3, 0.4, 0.5 s" not in table2:
            fail(f"Table 2 does not name the instants 'ended' did not reach:\n{table2}")
        if "full at t" in table2:
            fail(f"Table 2 names instants of 'full', which reaches them all:\n{table2}")

        # nearest_row: half an interval past the last row still counts, more does not; nor a gap in the rows.
        cols = {"time_s": [repr(round(0.01 * k, 10)) for k in range(26)]}
        if report.nearest_row(cols, 0.25) != 25 or report.nearest_row(cols, 0.254) != 25:
            fail("nearest_row at the last row")
        if report.nearest_row(cols, 0.256) is not None or report.nearest_row(cols, 0.3) is not None:
            fail("nearest_row gives a row for an instant beyond the last row + half an interval")
        gap = {"time_s": [repr(t) for t in (0.0, 0.01, 0.02, 0.03, 0.2, 0.21, 0.22)]}
        if report.nearest_row(gap, 0.1) is not None or report.nearest_row(gap, 0.205) not in (4, 5):
            fail("nearest_row in a gap of the rows")

        # ---- B: a mixed report; a run shorter than 0.1 s next to one that reaches 0.1 ... 0.5 s.
        figs = tr.capture_figures(report)
        long_run, _ = tr.make_run(tmp, "long", "tfm", 0.5, False, True, rng)
        short, _ = tr.make_run(tmp, "short", "tfm", 0.06, False, True, rng,
                               frame_times=[0.0, 0.02, 0.04, 0.06])
        out = os.path.join(tmp, "report-b")
        report.write_report([long_run, short], out)
        summary = open(os.path.join(out, "summary.md")).read()
        v = figs["voidage.png"]
        if tr.rows_of(v) != ["long", "short"]:
            fail(f"voidage.png rows {tr.rows_of(v)}")
        titles = [a["title"] for a in v["axes"] if a["images"]]
        if titles != [f"t = {t:.2f} s" for t in (0.1, 0.2, 0.3, 0.4, 0.5)]:
            fail(f"voidage.png panels {titles}: only long's frames at the paper's instants are shown")
        dashes = [a["title"] for a in v["axes"] if not a["images"] and a["title"].endswith(": –")]
        if dashes != [f"{t:g} s: –" for t in (0.1, 0.2, 0.3, 0.4, 0.5)]:
            fail(f"short's row is not '–' at every instant: {dashes}")
        if "short: no field frames within half its frame interval of the paper's instants" not in summary:
            fail(f"summary.md does not say why short has no panel:\n{summary}")

        # nearest_frame: within half the frame interval only.
        frames = [(round(0.01 * k, 10), f"{k}") for k in range(26)]
        if report.nearest_frame(frames, 0.1) != (0.1, "10"):
            fail("nearest_frame at a frame's instant")
        if report.nearest_frame(frames, 0.259) is not None or report.nearest_frame([(0.0, "0")], 0.1) is not None:
            fail("nearest_frame gives a frame for an instant beyond the last frame + half an interval")
        # choose_panels: the short run's t = 0 frame is not put under 0.1 s.
        runs = [SimpleNamespace(label="long", f=[(round(0.05 * k, 10), f"l{k}") for k in range(11)]),
                SimpleNamespace(label="short", f=[(0.0, "s0"), (0.02, "s1"), (0.04, "s2"), (0.06, "s3")])]
        rows, n_cols, notes, columns = report.choose_panels(runs, lambda r: r.f, "frames")
        if columns != [0.1, 0.2, 0.3, 0.4, 0.5] or n_cols != 5:
            fail(f"choose_panels columns {columns}")
        if [fr[1] for fr in rows[0][1]] != ["l2", "l4", "l6", "l8", "l10"] or rows[1][1] != [None] * 5:
            fail(f"choose_panels rows {rows}")
        # Alone, the short run shows its own frames.
        rows, n_cols, notes, columns = report.choose_panels(runs[1:], lambda r: r.f, "frames")
        if columns or [fr[1] for fr in rows[0][1]] != ["s0", "s1", "s2", "s3"]:
            fail(f"choose_panels of the short run alone: {rows}, {columns}")
    print("post report instants: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
