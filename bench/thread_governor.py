#!/usr/bin/env python3
"""Medians of bench/run_thread_governor.sh runs: a markdown table of the 1- and 2-thread
times and their ratio (speed-up of 2 threads over 1) per scene, variant and machine state.
    python3 bench/thread_governor.py runs_idle.csv runs_busy.csv > table.md"""
import collections
import csv
import statistics
import sys

runs = collections.defaultdict(list)
switched = collections.Counter()
for path in sys.argv[1:]:
    for r in csv.DictReader(open(path)):
        key = (r["scene"], r["grid"], "beside a busy process" if r["busy"] == "1" else "idle", r["variant"])
        runs[key + (r["threads"],)].append(float(r["total_s"]))
        if r["threads"] == "2" and r["switches"] not in ("", "0", "nan"):
            switched[key] += 1
print("| machine | scene | grid | variant | 1 thread (s) | 2 threads (s) | 2 thr / 1 thr speed-up | runs that changed team |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for key in sorted({k[:4] for k in runs}, key=lambda k: (k[2], k[0], int(k[1]), k[3])):
    one, two = runs[key + ("1",)], runs[key + ("2",)]
    if not one or not two:
        continue
    t1, t2 = statistics.median(one), statistics.median(two)
    scene, grid, state, variant = key
    print(f"| {state} | {scene} | {grid if grid != '0' else 'own'} | {variant} | {t1:.3f} | {t2:.3f} | "
          f"{t1 / t2:.2f} | {switched[key]}/{len(two)} |")
