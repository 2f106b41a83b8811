#!/usr/bin/env python3
"""What the main thread of a 2-thread run does alone (docs/performance.md section 34). A parallel loop's body shows
in both threads' samples, so per symbol the main thread's samples less the worker's estimate its serial work (a
symbol run on the main thread only counts whole: the pressure's LDLT, the list's binning; template arguments are
dropped, so the momentum components, one a thread, cancel). The categories are
profile_split.py's. Usage:
  perf record -F 1000 -e cpu-clock -o perf.data BINARY run ... --threads 2
  perf report -i perf.data --no-children --sort pid,sym --stdio -g none -F sample,pid,sym \\
    | python3 bench/serial_split.py [SIMULATED_SECONDS GAS_STEP]   (then also ms a gas step)"""
import collections
import re
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from profile_split import category, without_templates  # noqa: E402

per = collections.defaultdict(lambda: collections.Counter())
for line in sys.stdin:
    m = re.match(r"\s*(\d+)\s+(\d+):\S+\s+\[(.)\]\s+(.*)", line)
    if m:
        samples, tid, where, sym = int(m.group(1)), m.group(2), m.group(3), m.group(4)
        # template arguments dropped: the two momentum components, solved one a thread, are one function here
        sym = without_templates(sym).replace("fluidbed::", "").replace("(anonymous namespace)::", "")
        per[("[k] " if where == "k" else "") + sym][tid] += samples
threads = collections.Counter()
for counts in per.values():
    threads.update(counts)
if len(threads) < 2:
    sys.exit("serial_split.py: the profile has fewer than two threads")
main, worker = [t for t, _ in threads.most_common(2)]
scale = 1.0
unit = "samples"
if len(sys.argv) == 3:  # 1 kHz samples over the gas steps of the run: ms a gas step
    scale = 1.0 / (float(sys.argv[1]) / float(sys.argv[2]))
    unit = "ms a gas step"
alone = collections.Counter()
items = collections.defaultdict(list)
for sym, counts in per.items():
    extra = counts[main] - counts[worker]
    if extra <= 0:
        continue
    cat = category(sym)
    alone[cat] += extra
    items[cat].append((extra, sym))
print(f"main thread {threads[main]} samples, worker {threads[worker]}; main less worker, by symbol ({unit}):")
for cat, n in alone.most_common():
    top = sorted(items[cat], reverse=True)[:4]
    names = "; ".join(f"{s[:48]} {e * scale:.2g}" for e, s in top)
    print(f"  {cat:22s} {n * scale:8.3g}   {names}")
print(f"  {'all':22s} {sum(alone.values()) * scale:8.3g}")
