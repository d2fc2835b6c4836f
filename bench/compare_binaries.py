#!/usr/bin/env python3
"""Two refmap_bench binaries, interleaved: for each round, A then B, one benchmark filter.

Prints a markdown table of the medians over the rounds (ns per unknown where the benchmark
reports it, else the real time in the benchmark's unit) and the ratio B / A, and keeps every
row in --raw (CSV). The machine is shared and noisy: interleaving puts A and B under the same
load, and the median of several rounds is what results/multigrid.md quotes.

    python3 bench/compare_binaries.py OLD/refmap_bench NEW/refmap_bench \
        --filter '^PoissonContrast/V/average/(256|1024|2048)/1/' --rounds 5 --threads 1
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys


def run(binary, flt, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = subprocess.run([binary, f"--benchmark_filter={flt}", "--benchmark_format=json"],
                         env=env, check=True, capture_output=True, text=True).stdout
    rows = {}
    for b in json.loads(out)["benchmarks"]:
        name = b["name"].removesuffix("/real_time")
        if "ns_per_unknown" in b:
            rows[name] = (b["ns_per_unknown"], "ns/unknown")
        else:
            rows[name] = (b["real_time"], b["time_unit"])
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--filter", required=True)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--raw", help="CSV of every measurement")
    args = ap.parse_args()
    vals = {}
    raw = []
    for r in range(args.rounds):
        for tag, binary in (("A", args.a), ("B", args.b)):
            for name, (v, unit) in run(binary, args.filter, args.threads).items():
                vals.setdefault(name, {"A": [], "B": [], "unit": unit})[tag].append(v)
                raw.append((r, tag, name, v, unit))
            print(f"round {r + 1}/{args.rounds} {tag} done", file=sys.stderr)
    print(f"A = {args.a}, B = {args.b}; {args.rounds} interleaved rounds, {args.threads} thread(s)")
    print()
    print("| benchmark | unit | median A | median B | B / A |")
    print("|---|---|---|---|---|")
    for name, v in vals.items():
        a, b = statistics.median(v["A"]), statistics.median(v["B"])
        print(f"| {name} | {v['unit']} | {a:.4g} | {b:.4g} | {b / a:.3f} |")
    if args.raw:
        with open(args.raw, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["round", "binary", "benchmark", "value", "unit"])
            w.writerows(raw)


if __name__ == "__main__":
    main()
