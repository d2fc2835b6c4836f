#!/usr/bin/env python3
"""Medians of bench/run_threads_study.sh output: one row per (policy, busy, scene) with the
median microseconds per cell-step of binary A and B on 1 and 2 threads and the 2-thread
speed-up of each (t1 / t2; below 1: the second thread makes the run slower).

Usage: python3 bench/threads_study.py RUNS.csv [RUNS.csv ...]   (Markdown table on stdout)
"""
import csv
import statistics
import sys
from collections import defaultdict


def main():
    t = defaultdict(list)
    load = defaultdict(list)
    bins = []
    for path in sys.argv[1:]:
        with open(path) as f:
            for r in csv.DictReader(f):
                if r["us_per_cell_step"] in ("", "nan"):
                    continue
                if r["binary"] not in bins:
                    bins.append(r["binary"])
                key = (r["policy"], r["busy"], r["scene"])
                t[key + (r["binary"], r["threads"])].append(float(r["us_per_cell_step"]))
                load[(r["policy"], r["busy"])].append(float(r["load1"]))
    a, b = bins[0], bins[1]
    print("| wait policy | busy process | scene | A 1 thr | A 2 thr | A speed-up | B 1 thr | B 2 thr | B speed-up | load (1-min, median) |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    seen = []
    for k in t:
        if k[:3] not in seen:
            seen.append(k[:3])
    for pol, busy, scene in seen:
        def med(binary, th):
            v = t.get((pol, busy, scene, binary, th), [])
            return statistics.median(v) if v else float("nan")
        a1, a2, b1, b2 = med(a, "1"), med(a, "2"), med(b, "1"), med(b, "2")
        print(f"| {pol} | {'yes' if busy == '1' else 'no'} | {scene} | {a1:.3f} | {a2:.3f} | {a1 / a2:.2f} | "
              f"{b1:.3f} | {b2:.3f} | {b1 / b2:.2f} | {statistics.median(load[(pol, busy)]):.1f} |")
    print(f"\nA = {a}, B = {b}; microseconds per cell-step (timings.csv total / steps / cells), median of the repeats")


if __name__ == "__main__":
    main()
