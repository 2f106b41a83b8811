#!/usr/bin/env python3
"""Largest differences between two sets of TFM outputs (bubble.csv, monitor.csv), column by column.

Used to show that a change of arithmetic moves the paper's TFM cases only at the level intended before the
regression oracle is regenerated (docs/performance.md section 17).
Usage: python3 bench/tfm_oracle_diff.py OLD.csv NEW.csv [...pairs]
For every numeric column: the largest absolute difference, the largest relative one (to the column's largest
magnitude, so that values crossing zero do not inflate it) and the time where the absolute one occurs; columns
that are equal say so. wall_s is skipped.
"""
import csv
import sys


def load(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def compare(old_path, new_path):
    head, old = load(old_path)
    head_new, new = load(new_path)
    print(f"{old_path} vs {new_path}: {len(old)} / {len(new)} rows")
    if head != head_new[: len(head)] and head_new != head[: len(head_new)]:
        print("  headers differ")
    for j, name in enumerate(head):
        if name == "wall_s" or j >= len(head_new):
            continue
        worst, worst_t, scale, text_diff = 0.0, None, 0.0, 0
        for a, b in zip(old, new):
            try:
                x, y = float(a[j]), float(b[j])
            except (ValueError, IndexError):
                text_diff += (a[j] if j < len(a) else "") != (b[j] if j < len(b) else "")
                continue
            scale = max(scale, abs(x))
            if abs(x - y) > worst:
                worst, worst_t = abs(x - y), a[0]
        if worst == 0.0 and text_diff == 0:
            print(f"  {name}: equal")
        else:
            rel = worst / scale if scale > 0 else float("inf")
            print(f"  {name}: max |diff| {worst:.3g} (relative {rel:.2g}) at t = {worst_t}"
                  + (f", {text_diff} empty/non-numeric cells differ" if text_diff else ""))


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) < 2 or len(args) % 2:
        sys.exit(__doc__)
    for i in range(0, len(args), 2):
        compare(args[i], args[i + 1])
