#!/usr/bin/env python3
"""post/bubble_stats.py on a synthetic bubbles.csv whose statistics are known exactly: three 2D bubbles of
equivalent diameter 0.04 m born at y = 0.05 m at t = 0, 0.5, 1.0 s, rising at 0.3 m/s, sampled every 0.1 s; the
bed fraction is 0.1 at every sample. Exact: every diameter bin holds 0.04, every velocity bin 0.3 m/s (the centroid
speed), each bubble crosses y = 0.2 m once, so the frequency over [0, 2] s is 3 / 2 = 1.5 per second; the fraction
is 0.1 with no spread. Tolerances are rounding (1e-9). The 3D Darton diameter is checked at one point against the
formula evaluated by hand, and its h^0.8 scaling; the 2D form of Shen et al. (2004) likewise with its h^(2/3)
scaling. The report's entry point (run_statistics, table_runs) on a run folder with a case.toml without a jet: the
case's [averages] window is the statistics window, U and U_mf come from the case, the frequency heights are the
quarters of the mean bed height; its table carries the exact numbers above. A 3D file (volume_m3) gets Darton's
correlation and 0.711. Usage (CTest): test_bubble_stats.py FLUIDBED_BINARY SOURCE_DIR"""
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(sys.argv[2], "post"))
import bubble_stats as bs  # noqa: E402

failures = 0


def check(name, exact, computed, tol=1e-9):
    global failures
    err = abs(computed - exact)
    ok = bool(err <= tol)
    failures += not ok
    print(f"{name}: exact {exact:.6g} computed {computed:.6g} error {err:.3g} {'ok' if ok else 'FAIL'}")


with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, "bubbles.csv"), "w") as fh:
        fh.write("time_s,id,event,parents,area_m2,equivalent_diameter_m,centroid_x_m,centroid_y_m,nose_m,tail_m,"
                 "aspect_ratio,u_centroid_m_s,u_nose_m_s\n")
        area = np.pi * 0.04**2 / 4
        for k in range(21):
            t = 0.1 * k
            for i, born in enumerate((0.0, 0.5, 1.0)):
                if t < born - 1e-12:
                    continue
                y = 0.05 + 0.3 * (t - born)
                if y > 0.5:
                    continue
                first = abs(t - born) < 1e-12
                u = "" if first else "0.3"
                fh.write(f"{t},{i},{'birth' if first else ''},,{area},0.04,0.1,{y},{y + 0.02},{y - 0.02},1,{u},{u}\n")
    with open(os.path.join(tmp, "bubble_frames.csv"), "w") as fh:
        fh.write("time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction\n")
        for k in range(21):
            fh.write(f"{0.1 * k},0.6,0.12,0.012,1,0.1\n")
    s = bs.bubble_statistics(bs.read_csv(os.path.join(tmp, "bubbles.csv")),
                             bs.read_csv(os.path.join(tmp, "bubble_frames.csv")), t0=0.0, t1=2.0,
                             heights=[0.2], bins=5)
    check("dimension from header", 2, s["dimension"], 0)
    d = s["d_mean"][s["d_count"] > 0]
    check("diameter in every height bin, max error", 0.0, float(np.max(np.abs(d - 0.04))))
    u = s["u_mean"][s["u_count"] > 0]
    check("centroid rise velocity, max error", 0.0, float(np.max(np.abs(u - 0.3))))
    check("frequency at 0.2 m (1/s)", 1.5, s["frequency"][0])
    check("bubble fraction", 0.1, s["fraction_mean"])
    check("bubble fraction spread", 0.0, s["fraction_std"])
    check("2D rise constant", 0.5, bs.rise_constant(2), 0)
    check("3D rise constant", 0.711, bs.rise_constant(3), 0)
    bs.write_table(s, os.path.join(tmp, "t.csv"))
    bs.figure(s, os.path.join(tmp, "f.png"))
    check("figure written", 1, int(os.path.getsize(os.path.join(tmp, "f.png")) > 1000), 0)

# Darton et al. (1977) at U - U_mf = 0.5 m/s, h = 0.3 m, A0 = 1e-4 m^2.
hand = 0.54 * 0.5**0.4 * (0.3 + 4 * 0.01) ** 0.8 / 9.81**0.2
check("Darton d_b (m)", hand, float(bs.darton_diameter(0.3, 1.0, 0.5, 1e-4)))
check("Darton h^0.8 scaling", 2**0.8, float(bs.darton_diameter(0.6, 1.0, 0.5) / bs.darton_diameter(0.3, 1.0, 0.5)))
# Shen et al. (2004), 2D, at U - U_mf = 0.5 m/s, h = 0.3 m, h0 = 0.02 m.
hand2 = 0.89 * (0.5 * 0.32) ** (2 / 3) / 9.81 ** (1 / 3)
check("Shen 2D D_b (m)", hand2, float(bs.shen_diameter_2d(0.3, 1.0, 0.5, 0.02)))
check("Shen 2D h^(2/3) scaling", 2 ** (2 / 3), float(bs.shen_diameter_2d(0.6, 1.0, 0.5) / bs.shen_diameter_2d(0.3, 1.0, 0.5)))
check("correlation of the dimension, 3D", float(bs.darton_diameter(0.3, 1.0, 0.5)),
      float(bs.diameter_correlation(3, 0.3, 1.0, 0.5)), 0)
check("correlation of the dimension, 2D", float(bs.shen_diameter_2d(0.3, 1.0, 0.5)),
      float(bs.diameter_correlation(2, 0.3, 1.0, 0.5)), 0)

# The report's entry point on a run folder: the synthetic bubbles above in a bed 0.84 m high, so the first
# frequency height is 0.21 m; window [0.5, 1.5] from the case's [averages]. The bubbles reach 0.21 m at 0.533,
# 1.033 and 1.533 s, so the samples after those (0.6 and 1.1 s) hold two crossings in the window: 2 per second.
with tempfile.TemporaryDirectory() as run:
    with open(os.path.join(run, "bubbles.csv"), "w") as fh:
        fh.write("time_s,id,event,parents,area_m2,equivalent_diameter_m,centroid_x_m,centroid_y_m,nose_m,tail_m,"
                 "aspect_ratio,u_centroid_m_s,u_nose_m_s\n")
        area = np.pi * 0.04**2 / 4
        for k in range(21):
            t = 0.1 * k
            for i, born in enumerate((0.0, 0.5, 1.0)):
                y = 0.05 + 0.3 * (t - born)
                if t < born - 1e-12 or y > 0.5:
                    continue
                u = "" if abs(t - born) < 1e-12 else "0.3"
                fh.write(f"{t},{i},,,{area},0.04,0.1,{y},{y + 0.02},{y - 0.02},1,{u},{u}\n")
    with open(os.path.join(run, "bubble_frames.csv"), "w") as fh:
        fh.write("time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction\n")
        for k in range(21):
            fh.write(f"{0.1 * k},0.84,0.12,0.012,1,0.1\n")
    case = {"inlet": {"velocity": 3.6}, "bubble": {"u_mf": 1.8}, "averages": {"t_start": 0.5, "t_end": 1.5}}
    s, why = bs.run_statistics(run, case, 2)
    check("run_statistics: a result", 1, int(s is not None), 0)
    check("run_statistics: window from [averages], t0", 0.5, s["t0"], 0)
    check("run_statistics: window from [averages], t1", 1.5, s["t1"], 0)
    check("run_statistics: frequency heights = quarters of the bed (0.21 m)", 0.21, s["frequency_height"][0], 1e-12)
    check("run_statistics: frequency at 0.21 m (1/s)", 2.0, s["frequency"][0])
    check("run_statistics: mean diameter", 0.04, s["d_all_mean"])
    check("run_statistics: mean centroid velocity", 0.3, s["u_all_mean"])
    check("run_statistics: 2D correlation from U - U_mf = 1.8 m/s",
          float(bs.shen_diameter_2d(0.3, 3.6, 1.8)), float(bs.shen_diameter_2d(0.3, s["u"], s["u_mf"])))
    table = "\n".join(bs.table_runs([("synthetic", s)]))
    check("table_runs: window and fraction", 1, int("0.5-1.5 (the case's [averages] window)" in table
                                                    and "0.100 ± 0.000" in table), 0)
    s2, why2 = bs.run_statistics(run, {"inlet": {"velocity": 3.6}}, 2)
    check("no [averages]: the second half of the samples, t0 (s)", 1.0, s2["t0"])
    empty, why3 = bs.run_statistics(os.path.join(run, "missing"), case, 2)
    check("a folder without bubbles.csv is left out with a reason", 1, int(empty is None and "no bubbles.csv" in why3), 0)
# 3D: the same bubbles as spheres (volume_m3, centroid_z_m): the dimension comes from the header, the correlation
# is Darton's at every bin centre, the rise constant 0.711.
with tempfile.TemporaryDirectory() as run:
    with open(os.path.join(run, "bubbles.csv"), "w") as fh:
        fh.write("time_s,id,event,parents,volume_m3,equivalent_diameter_m,centroid_x_m,centroid_y_m,centroid_z_m,"
                 "nose_m,tail_m,aspect_ratio,u_centroid_m_s,u_nose_m_s\n")
        vol = np.pi * 0.04**3 / 6
        for k in range(21):
            t = 0.1 * k
            y = 0.05 + 0.3 * t
            if y <= 0.5:
                u = "" if k == 0 else "0.3"
                fh.write(f"{t},0,,,{vol},0.04,0.1,{y},0.05,{y + 0.02},{y - 0.02},1,{u},{u}\n")
    with open(os.path.join(run, "bubble_frames.csv"), "w") as fh:
        fh.write("time_s,bed_height_m,bed_measure,bubble_measure,bubbles,bubble_fraction\n")
        for k in range(21):
            fh.write(f"{0.1 * k},0.84,0.012,0.0012,1,0.1\n")
    s3, _ = bs.run_statistics(run, {"inlet": {"velocity": 1.0}, "bubble": {"u_mf": 0.5}}, 3)
    check("3D from the header", 3, bs.bubble_statistics(bs.read_csv(os.path.join(run, "bubbles.csv")),
                                                       bs.read_csv(os.path.join(run, "bubble_frames.csv")))["dimension"], 0)
    check("3D: Darton at the bin centres, max error", 0.0,
          float(np.max(np.abs(s3["d_corr"] - bs.darton_diameter(s3["h"], 1.0, 0.5)))), 0)
    check("3D: 0.711 sqrt(g D), max error", 0.0,
          float(np.max(np.abs(s3["u_theory"] - 0.711 * np.sqrt(9.81 * s3["D"])))), 1e-15)
    check("3D: mean centroid velocity", 0.3, s3["u_all_mean"])
sys.exit(1 if failures else 0)
