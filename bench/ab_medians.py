"""Medians of an A/B benchmark's rows "old|new SECONDS [CHECK]" and the new/old ratio; with CHECK values (a final
energy, a checksum), whether every run of both binaries gave the same one.
Usage: python3 bench/ab_medians.py RESULTS LABEL [CHECK_NAME]"""
import statistics
import sys

rows = [line.split() for line in open(sys.argv[1]) if line.strip()]
label = sys.argv[2]
wall = {w: [float(r[1]) for r in rows if r[0] == w] for w in ("old", "new")}
mo, mn = statistics.median(wall["old"]), statistics.median(wall["new"])
print(f"median {label}: old {mo:.2f} s, new {mn:.2f} s, new/old {mn / mo:.3f}")
if len(sys.argv) > 3:
    check = {w: {r[2] for r in rows if r[0] == w} for w in ("old", "new")}
    same = check["old"] == check["new"] and len(check["old"]) == 1
    print(f"{sys.argv[3]}:", "identical" if same else f"differs: old {sorted(check['old'])}, new {sorted(check['new'])}")
