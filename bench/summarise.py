#!/usr/bin/env python3
"""Summarise the Google Benchmark JSON files written by bench/run_benchmarks.sh.

Reads <raw>/bench_<threads>t.json (run with --benchmark_repetitions=k
--benchmark_report_aggregates_only=true) and <raw>/run_info.txt, keeps the *median*
aggregate of every benchmark, and writes

  <out>/benchmarks.csv   benchmark, grid, param, threads, median_time_us, cells_per_s,
                         GB_per_s (header comment: CPU model, cores, compiler, date, load)
  <out>/benchmarks.md    markdown tables of the medians with the 2-thread/1-thread speed-up
  <out>/speedup.png      2-thread/1-thread speed-up of every benchmark at its largest grid
  <out>/bandwidth.png    GB/s of the stencil kernels (1 and 2 threads, 256^2 and 1024^2)

Benchmark names "Kernel[/variant]/<N>/<param...>[/real_time|/manual_time]" are split into
benchmark (the non-numeric leading parts), grid (the first number, N for an N x N grid)
and param (the remaining numbers joined by '/').  The time is the median wall-clock time
per iteration (manual time for the extrapolation benchmarks) in microseconds.

Usage: python3 bench/summarise.py --raw results/raw --out results
"""
from __future__ import annotations

import argparse
import csv
import glob
import json
import os
import re
import sys

UNIT_TO_US = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
# benchmarks whose first argument is not a grid size
NO_GRID = {"FastMarchingSolidWindow"}  # argument: disc radius in cells
PARAM_LABELS = {"AdvectionStage": {"0": "central", "1": "superbee"}}


def parse_name(run_name: str):
    parts = [p for p in run_name.split("/") if p not in ("real_time", "manual_time")]
    head = []
    while parts and not re.fullmatch(r"-?\d+", parts[0]):
        head.append(parts.pop(0))
    bench = "/".join(head)
    if bench in NO_GRID:
        return bench, "", "/".join(parts)
    grid = parts[0] if parts else ""
    return bench, grid, "/".join(parts[1:])


def read_info(path: str) -> dict:
    info = {}
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                if ":" in line:
                    k, v = line.split(":", 1)
                    info[k.strip()] = v.strip()
    return info


def load_runs(raw: str):
    """-> rows (dicts), contexts {threads: context}"""
    rows, contexts = [], {}
    for path in sorted(glob.glob(os.path.join(raw, "bench_*t.json"))):
        m = re.search(r"bench_(\d+)t\.json$", path)
        if not m:
            continue
        threads = int(m.group(1))
        with open(path) as f:
            data = json.load(f)
        contexts[threads] = data.get("context", {})
        benches = data.get("benchmarks", [])
        medians = [b for b in benches if b.get("aggregate_name") == "median"]
        if not medians:  # a run without repetitions: take the plain iterations
            medians = [b for b in benches if b.get("run_type", "iteration") == "iteration"]
        for b in medians:
            if b.get("error_occurred"):
                continue
            name = b.get("run_name", b["name"])
            bench, grid, param = parse_name(name)
            scale = UNIT_TO_US[b.get("time_unit", "ns")]
            cps = b.get("cells_per_s", b.get("cells/s"))
            rows.append(
                {
                    "name": name,
                    "benchmark": bench,
                    "grid": grid,
                    "param": param,
                    "threads": threads,
                    "median_time_us": b["real_time"] * scale,
                    "cells_per_s": cps,
                    "GB_per_s": b.get("GB/s"),
                    "us_per_cell_step": b.get("us_per_cell_step"),
                    "poisson_iters": b.get("poisson_iters"),
                    "repetitions": b.get("repetitions"),
                }
            )
    return rows, contexts


def fmt(x, digits=4):
    if x is None or x == "":
        return ""
    x = float(x)
    if x == 0:
        return "0"
    if abs(x) >= 10 ** digits:
        return f"{x:.0f}"
    return f"{x:.{digits}g}"


def fmt_rate(x):
    if x is None:
        return ""
    x = float(x)
    for s, f in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if x >= f:
            return f"{x / f:.3g} {s}"
    return f"{x:.3g}"


def header_lines(info: dict, contexts: dict) -> list[str]:
    lines = [
        f"machine: Model name: {info.get('host_model', '?')}",
        f"cores: {info.get('cores', '?')}",
        f"compiler: {info.get('compiler', '?')}",
        f"date: {info.get('date', '?')}",
    ]
    if "git" in info:
        lines.append(f"source: git {info['git']}")
    for t in sorted(contexts):
        c = contexts[t]
        la = c.get("load_avg")
        la = ", ".join(f"{v:.2f}" for v in la) if la else "?"
        line = f"{t} thread(s): run {info.get(f'date_{t}t', '?')}, {info.get(f'reps_{t}t', '?')}, load average at start {la}"
        extra = [f"{w} {info[f'load_{w}_{t}t']}" for w in ("before", "after") if f"load_{w}_{t}t" in info]
        if extra:
            line += " (uptime " + "; ".join(extra) + ")"
        if f"wall_s_{t}t" in info:
            line += f", wall {info[f'wall_s_{t}t']} s"
        lines.append(line)
    if contexts:
        c = next(iter(contexts.values()))
        lines.append(
            f"google benchmark: {c.get('num_cpus', '?')} CPUs at {c.get('mhz_per_cpu', '?')} MHz, "
            f"library build {c.get('library_build_type', '?')}; times are the median of the "
            f"repetitions (wall clock; manual time for Extrapolate*)"
        )
    if "command" in info:
        lines.append(f"command: {info['command']}")
    return lines


def sort_key(r):
    g = int(r["grid"]) if r["grid"] else 0
    return (r["order"], g, r["param"], r["threads"])


def write_csv(rows, path, header):
    with open(path, "w", newline="") as f:
        for h in header:
            f.write(f"# {h}\n")
        w = csv.writer(f)
        w.writerow(["benchmark", "grid", "param", "threads", "median_time_us", "cells_per_s", "GB_per_s"])
        for r in rows:
            w.writerow(
                [
                    r["benchmark"],
                    r["grid"],
                    r["param"],
                    r["threads"],
                    f"{r['median_time_us']:.6g}",
                    "" if r["cells_per_s"] is None else f"{r['cells_per_s']:.6g}",
                    "" if r["GB_per_s"] is None else f"{r['GB_per_s']:.4g}",
                ]
            )


def grouped(rows):
    """{(benchmark, grid, param): {threads: row}} in first-seen order"""
    out = {}
    for r in rows:
        out.setdefault((r["benchmark"], r["grid"], r["param"]), {})[r["threads"]] = r
    return out


def param_label(bench, param):
    lab = PARAM_LABELS.get(bench, {}).get(param)
    return f"{param} ({lab})" if lab else param


def write_md(rows, path, header, threads):
    g = grouped(rows)
    t1, t2 = (threads[0], threads[-1]) if threads else (1, 2)
    out = ["# refmap benchmarks", ""]
    out += [f"- {h}" for h in header]
    out += [
        "",
        "Median wall time per call (µs); speed-up = time with "
        f"{t1} thread / time with {t2} threads. GB/s uses the bytes-per-cell estimate stated "
        "in each bench/*.cpp (compulsory traffic, neighbouring rows assumed cached). "
        "Regenerate with `bash bench/run_benchmarks.sh`.",
        "",
    ]
    cols = ["benchmark", "grid", "param"]
    cols += [f"{t} thr (µs)" for t in threads]
    if len(threads) >= 2:
        cols.append(f"speed-up {t2}/{t1}")
    cols += [f"cells/s {t} thr" for t in threads]
    cols += [f"GB/s {t} thr" for t in threads]
    out.append("| " + " | ".join(cols) + " |")
    out.append("|" + "|".join(["---"] * 3 + ["---:"] * (len(cols) - 3)) + "|")
    for (bench, grid, param), by_t in g.items():
        cells = [bench, f"{grid}²" if grid else "", param_label(bench, param)]
        cells += [fmt(by_t[t]["median_time_us"]) if t in by_t else "" for t in threads]
        if len(threads) >= 2:
            if t1 in by_t and t2 in by_t:
                cells.append(f"{by_t[t1]['median_time_us'] / by_t[t2]['median_time_us']:.2f}")
            else:
                cells.append("")
        cells += [fmt_rate(by_t[t]["cells_per_s"]) if t in by_t else "" for t in threads]
        cells += [fmt(by_t[t]["GB_per_s"], 3) if t in by_t and by_t[t]["GB_per_s"] else "" for t in threads]
        out.append("| " + " | ".join(cells) + " |")

    steps = [(k, v) for k, v in g.items() if k[0].startswith("Whole")]
    if steps:
        out += ["", "## Whole time steps", "",
                "| benchmark | grid | threads | ms/step | µs/cell/step | Poisson cycles (last step) |",
                "|---|---|---:|---:|---:|---:|"]
        for (bench, grid, param), by_t in steps:
            for t in threads:
                if t in by_t:
                    r = by_t[t]
                    out.append(
                        f"| {bench} | {grid}² | {t} | {fmt(r['median_time_us'] / 1e3)} | "
                        f"{fmt(r['us_per_cell_step'], 3)} | {fmt(r['poisson_iters'], 3)} |"
                    )
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def plots(rows, outdir, threads):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception as e:  # plots are optional
        print(f"summarise.py: no plots ({e})", file=sys.stderr)
        return
    g = grouped(rows)
    if len(threads) >= 2:
        t1, t2 = threads[0], threads[-1]
        # one bar per (benchmark, param) at its largest grid
        best = {}
        for (bench, grid, param), by_t in g.items():
            if t1 in by_t and t2 in by_t:
                n = int(grid) if grid else 0
                key = (bench, param)
                if key not in best or n > best[key][0]:
                    best[key] = (n, by_t[t1]["median_time_us"] / by_t[t2]["median_time_us"])
        labels = [f"{b}/{p}" if p else b for (b, p) in best]
        labels = [f"{l} @{best[k][0]}²" if best[k][0] else l for l, k in zip(labels, best)]
        vals = [v[1] for v in best.values()]
        fig, ax = plt.subplots(figsize=(8, 0.24 * len(vals) + 1.2))
        ax.barh(range(len(vals)), vals, color="tab:blue")
        ax.axvline(1.0, color="k", lw=0.8)
        ax.axvline(float(t2) / t1, color="tab:red", lw=0.8, ls="--", label="ideal")
        ax.set_yticks(range(len(vals)))
        ax.set_yticklabels(labels, fontsize=7)
        ax.invert_yaxis()
        ax.set_xlabel(f"speed-up {t2} threads / {t1} thread (median times)")
        ax.legend(loc="lower right", fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "speedup.png"), dpi=120)
        plt.close(fig)

    bw = [(k, v) for k, v in g.items() if any(r["GB_per_s"] for r in v.values())]
    if bw:
        labels = [f"{b}/{gr}" + (f"/{p}" if p else "") for (b, gr, p), _ in bw]
        fig, ax = plt.subplots(figsize=(8, 0.26 * len(bw) + 1.2))
        h = 0.8 / max(1, len(threads))
        for k, t in enumerate(threads):
            vals = [v[t]["GB_per_s"] if t in v and v[t]["GB_per_s"] else 0.0 for _, v in bw]
            ax.barh([y + k * h for y in range(len(bw))], vals, height=h, label=f"{t} thread(s)")
        ax.set_yticks([y + 0.4 - h / 2 for y in range(len(bw))])
        ax.set_yticklabels(labels, fontsize=7)
        ax.invert_yaxis()
        ax.set_xlabel("GB/s (bytes-per-cell estimate x cells/s, median)")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "bandwidth.png"), dpi=120)
        plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--raw", default="results/raw", help="directory with bench_<t>t.json")
    ap.add_argument("--out", default="results", help="output directory")
    ap.add_argument("--no-plots", action="store_true")
    a = ap.parse_args()

    rows, contexts = load_runs(a.raw)
    if not rows:
        sys.exit(f"summarise.py: no benchmark results in {a.raw}/bench_*t.json")
    order = {}
    for r in rows:
        order.setdefault(r["benchmark"], len(order))
        r["order"] = order[r["benchmark"]]
    rows.sort(key=sort_key)
    threads = sorted({r["threads"] for r in rows})
    info = read_info(os.path.join(a.raw, "run_info.txt"))
    for t in threads:
        info.update(read_info(os.path.join(a.raw, f"run_{t}t.txt")))
    header = header_lines(info, contexts)
    os.makedirs(a.out, exist_ok=True)
    write_csv(rows, os.path.join(a.out, "benchmarks.csv"), header)
    write_md(rows, os.path.join(a.out, "benchmarks.md"), header, threads)
    if not a.no_plots:
        plots(rows, a.out, threads)
    print(f"summarise.py: {len(rows)} medians ({len(grouped(rows))} benchmarks, threads {threads}) "
          f"-> {a.out}/benchmarks.csv, {a.out}/benchmarks.md")


if __name__ == "__main__":
    main()
