#!/usr/bin/env python3
"""Summarise the Google Benchmark JSON files written by bench/run_benchmarks.sh.

Reads <raw>/bench_<threads>t.json (run with --benchmark_repetitions=k
--benchmark_report_aggregates_only=true) and <raw>/run_info.txt, keeps the *median*
aggregate of every benchmark, and writes

  <out>/benchmarks.csv   benchmark, grid, param, threads, median_time_us, cells_per_s,
                         GB_per_s, GFlop_per_s, bytes_per_cell, flops_per_cell (header
                         comment: CPU model, cores, compiler, date, load)
  <out>/benchmarks.md    markdown tables of the medians with the 2-thread/1-thread speed-up
  <out>/speedup.png      2-thread/1-thread speed-up of every benchmark at its largest grid
  <out>/bandwidth.png    GB/s of the stencil kernels (1 and 2 threads, every grid)
  <out>/roofline.png     every stencil kernel at (flop/byte, GFlop/s) under the roof made of
                         the measured STREAM Triad bandwidth and FMA peak (MachineStream*,
                         MachineFmaPeak), 1 and 2 threads
  <out>/poisson_study.csv           PoissonSolve/*: time, iterations, residuals,
                                    convergence factor, ns per unknown
  <out>/poisson_time_per_unknown.png  ns per unknown vs N, one line per solver x ratio
  <out>/extrapolation_sweep.csv     ExtrapolateLSQ/PDE over grids and bands: time, error
  <out>/extrapolation_accuracy_vs_cost.png  error vs time per call, one marker per
                                    method x band (100^2 highlighted)
benchmarks.md also gets the machine limits, each kernel's fraction of the measured
bandwidth and peak, the solver study table (with the hypre reference quoted in docs/references.md)
and the PDE/LSQ extrapolation ratios (with the paper's figures). Every CSV starts with
'#' header lines: CPU model (lscpu), cores, compiler, date, load.

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
import math
import os
import re
import sys

UNIT_TO_US = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
# benchmarks whose first argument is not a grid size
NO_GRID = {"FastMarchingSolidWindow",  # argument: disc radius in cells
           "MachineStreamCopy", "MachineStreamTriad", "MachineFmaPeak",  # MiB per array
           "ContactPairs/cells", "ContactPairs/all"}  # number of solids' boxes
PARAM_LABELS = {"AdvectionStage": {"0": "central", "1": "superbee"}}
# whole-step benchmarks of scenes with many solids (bench/bench_step.cpp), listed with the
# Whole* ones in "Whole time steps" (ManyDiscsStep/<grid>/<discs>)
STEP_BENCHES = {"ManyDiscsStep", "Discs1000Step", "IncrmtCircles42"}


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
                    "GFlop_per_s": b.get("GFlop/s"),
                    "bytes_per_cell": b.get("bytes_per_cell"),
                    "flops_per_cell": b.get("flops_per_cell"),
                    "raw": b,  # every counter of the median aggregate
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
        w.writerow(["benchmark", "grid", "param", "threads", "median_time_us", "cells_per_s", "GB_per_s",
                    "GFlop_per_s", "bytes_per_cell", "flops_per_cell"])
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
                    "" if r["GFlop_per_s"] is None else f"{r['GFlop_per_s']:.4g}",
                    "" if r["bytes_per_cell"] is None else f"{r['bytes_per_cell']:g}",
                    "" if r["flops_per_cell"] is None else f"{r['flops_per_cell']:g}",
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

    steps = [(k, v) for k, v in g.items() if k[0].startswith("Whole") or k[0] in STEP_BENCHES]
    if steps:
        out += ["", "## Whole time steps", "",
                "| benchmark | grid | threads | ms/step | µs/cell/step | Poisson cycles (last step) |",
                "|---|---|---:|---:|---:|---:|"]
        for (bench, grid, param), by_t in steps:
            for t in threads:
                if t in by_t:
                    r = by_t[t]
                    out.append(
                        f"| {bench}{'/' + param if param else ''} | {grid}² | {t} | {fmt(r['median_time_us'] / 1e3)} | "
                        f"{fmt(r['us_per_cell_step'], 3)} | {fmt(r['poisson_iters'], 3)} |"
                    )
    out += extra_md(rows, threads)
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

    study_plots(rows, outdir, threads, plt)

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


# ---- machine limits, roofline, solver study, extrapolation sweep -------------------------
HYPRE_REF_S = {1: 0.37, 1000: 0.64}  # hypre PFMG-CG, 1024^2, one core: quoted in docs/references.md
PAPER_EXTRAP_MS = {"LSQ": 100.0, "PDE": 1550.0}  # Jain & Mani, 100^2, band 5 (paper)
SOLVER_LABEL = {"V": "multigrid V(2,2)", "F": "multigrid F(2,2)", "cg": "CG (Jacobi)",
                "mgpcg": "CG + V-cycle preconditioner"}


def counter(r, name):
    v = r["raw"].get(name)
    return None if v is None else float(v)


def machine_limits(rows):
    """{threads: {"copy", "copy_wa", "triad", "triad_wa", "peak"}} from Machine* rows"""
    out = {}
    for r in rows:
        m = out.setdefault(r["threads"], {})
        if r["benchmark"] == "MachineStreamCopy":
            m["copy"], m["copy_wa"] = r["GB_per_s"], counter(r, "GB/s_with_wa")
        elif r["benchmark"] == "MachineStreamTriad":
            m["triad"], m["triad_wa"] = r["GB_per_s"], counter(r, "GB/s_with_wa")
        elif r["benchmark"] == "MachineFmaPeak":
            m["peak"] = r["GFlop_per_s"]
    return {t: m for t, m in out.items() if m}


def roofline_rows(rows):
    return [r for r in rows if not r["benchmark"].startswith("Machine") and r["bytes_per_cell"]
            and r["flops_per_cell"] and r["GFlop_per_s"]]


def solver_rows(rows):
    return [r for r in rows if r["benchmark"].startswith("PoissonSolve/")]


def extrap_rows(rows):
    return [r for r in rows if r["benchmark"] in ("ExtrapolateLSQ", "ExtrapolatePDE")]


def pct(a, b):
    return f"{100.0 * a / b:.0f} %" if a is not None and b else ""


def extra_md(rows, threads):
    out = []
    lim = machine_limits(rows)
    if lim:
        out += ["", "## Machine limits (measured by `MachineStream*` and `MachineFmaPeak`)", "",
                "STREAM-like loops over arrays far larger than the last-level cache (size in MiB "
                "per array in the benchmark name: 2 arrays for Copy, 3 for Triad). GB/s counts each array once per element (16 B Copy, 24 B Triad), "
                "write-allocate NOT counted (the convention of the kernel figures); the "
                "write-allocate column adds the read of the destination line (24 / 32 B), "
                "which ordinary stores really cause. FMA peak: independent FMA chains in "
                "vector registers on every thread.", "",
                "| threads | Copy GB/s | Copy GB/s incl. write-allocate | Triad GB/s | "
                "Triad GB/s incl. write-allocate | FMA peak GFlop/s |",
                "|---:|---:|---:|---:|---:|---:|"]
        for t in sorted(lim):
            m = lim[t]
            out.append(f"| {t} | {fmt(m.get('copy'), 3)} | {fmt(m.get('copy_wa'), 3)} | "
                       f"{fmt(m.get('triad'), 3)} | {fmt(m.get('triad_wa'), 3)} | {fmt(m.get('peak'), 3)} |")
    rr = roofline_rows(rows)
    if rr and lim:
        out += ["", "## Kernels against the measured limits (roofline.png)", "",
                "Fraction of the STREAM Triad bandwidth (without write-allocate, as the kernel "
                "figures) and of the FMA peak measured with the same thread count. "
                "flop/byte = flops_per_cell / bytes_per_cell of the model stated in each "
                "bench/*.cpp; roof = min(peak, Triad x flop/byte). Grids whose arrays stay in "
                "cache can exceed 100 % of the DRAM bandwidth.", "",
                "| benchmark | grid | param | threads | flop/byte | GB/s | % of Triad | "
                "GFlop/s | % of FMA peak | % of roof |",
                "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"]
        for r in rr:
            m = lim.get(r["threads"], {})
            ai = r["flops_per_cell"] / r["bytes_per_cell"]
            roof = min(m["peak"], m["triad"] * ai) if m.get("peak") and m.get("triad") else None
            out.append(
                f"| {r['benchmark']} | {r['grid']}² | {param_label(r['benchmark'], r['param'])} | "
                f"{r['threads']} | {ai:.3g} | {fmt(r['GB_per_s'], 3)} | "
                f"{pct(r['GB_per_s'], m.get('triad'))} | {fmt(r['GFlop_per_s'], 3)} | "
                f"{pct(r['GFlop_per_s'], m.get('peak'))} | {pct(r['GFlop_per_s'], roof)} |")
    sr = solver_rows(rows)
    if sr:
        g = {}
        for r in sr:
            g.setdefault((int(r["grid"]), int(r["param"]), r["benchmark"].split("/", 1)[1]), {})[r["threads"]] = r
        out += ["", "## Pressure solver study (PoissonSolve, poisson_time_per_unknown.png)", "",
                "Standard problem `standard_problem(N, R)` (tests/fixtures/poisson_problem.hpp) from "
                "x = 0 to ||r||_2/||rhs||_2 <= 1e-8. Iterations = cycles (multigrid) or CG "
                "steps; conv. factor = final residual^(1/iterations); ref. residual = the "
                "final residual recomputed independently of the solver. Time = median wall "
                "time of one solve (hierarchy setup excluded).", "",
                "| N | R | solver | iterations | conv. factor | final residual | ref. residual | "
                + " | ".join(f"ms {t} thr" for t in threads) + " | "
                + " | ".join(f"ns/unknown {t} thr" for t in threads) + " |",
                "|---:|---:|---|---:|---:|---:|---:|" + "---:|" * (2 * len(threads))]
        order = {"V": 0, "F": 1, "mgpcg": 2, "cg": 3}
        for (n, ratio, m) in sorted(g, key=lambda k: (k[0], k[1], order.get(k[2], 9))):
            by_t = g[(n, ratio, m)]
            r0 = by_t[min(by_t)]
            cells = [str(n), str(ratio), SOLVER_LABEL.get(m, m), fmt(counter(r0, "iterations"), 5),
                     fmt(counter(r0, "conv_factor"), 3), fmt(counter(r0, "rel_residual"), 2),
                     fmt(counter(r0, "ref_residual"), 2)]
            cells += [fmt(by_t[t]["median_time_us"] / 1e3) if t in by_t else "" for t in threads]
            cells += [fmt(counter(by_t[t], "ns_per_unknown"), 3) if t in by_t else "" for t in threads]
            out.append("| " + " | ".join(cells) + " |")
        t1 = threads[0]
        out += ["", f"### 1024², one core: ours beside the hypre reference", "",
                "The hypre PFMG-CG times are the figures quoted in docs/references.md (Performance reference points) "
                "(0.37 s for R = 1, 0.64 s for R = 1000, 1024², one core). They were **not "
                "measured here**; their machine and stopping criterion are not known, so "
                "the comparison is indicative only.", "",
                "| R | hypre PFMG-CG (quoted, not measured) | "
                + " | ".join(SOLVER_LABEL[m] for m in ("V", "F", "mgpcg")) + " |",
                "|---:|---:|---:|---:|---:|"]
        for ratio, ref in HYPRE_REF_S.items():
            cells = [str(ratio), f"{ref:.2f} s"]
            for m in ("V", "F", "mgpcg"):
                r = g.get((1024, ratio, m), {}).get(t1)
                cells.append(f"{r['median_time_us'] / 1e6:.3g} s ({fmt(counter(r, 'iterations'), 3)} it.)"
                             if r else "not run")
            out.append("| " + " | ".join(cells) + " |")
    er = extrap_rows(rows)
    if er:
        t1 = min(r["threads"] for r in er)
        g = {}
        for r in er:
            if r["threads"] == t1:
                g.setdefault((int(r["grid"]), int(r["param"])), {})[r["benchmark"][len("Extrapolate"):]] = r
        out += ["", f"## Extrapolation band sweep ({t1} thread; extrapolation_accuracy_vs_cost.png)", "",
                "Disc of radius 0.15 N cells in the whole N x N window; smooth field "
                "xi = (x + 0.1 sin 2 pi y, y + 0.1 x^2); errors over the cells each call fills "
                "(err_l2 = RMS). PDE/LSQ = ratio of the median times at equal band.", "",
                "| N | band | LSQ µs | PDE µs | PDE/LSQ | LSQ cells | PDE cells | LSQ err_linf | "
                "PDE err_linf | LSQ err_l2 | PDE err_l2 |",
                "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for (n, band) in sorted(g):
            d = g[(n, band)]
            L, P = d.get("LSQ"), d.get("PDE")
            ratio = f"{P['median_time_us'] / L['median_time_us']:.2f}" if L and P else ""
            cells = [str(n), str(band),
                     fmt(L["median_time_us"]) if L else "", fmt(P["median_time_us"]) if P else "", ratio,
                     fmt(counter(L, "cells_filled"), 6) if L else "", fmt(counter(P, "cells_filled"), 6) if P else "",
                     fmt(counter(L, "err_linf"), 3) if L else "", fmt(counter(P, "err_linf"), 3) if P else "",
                     fmt(counter(L, "err_l2"), 3) if L else "", fmt(counter(P, "err_l2"), 3) if P else ""]
            out.append("| " + " | ".join(cells) + " |")
        L, P = g.get((100, 5), {}).get("LSQ"), g.get((100, 5), {}).get("PDE")
        paper = PAPER_EXTRAP_MS["PDE"] / PAPER_EXTRAP_MS["LSQ"]
        out += ["", "100², band 5, beside the paper (Jain & Mani; hardware and PDE iteration "
                "count not stated there):", "",
                "| | LSQ | PDE | PDE/LSQ |", "|---|---:|---:|---:|",
                f"| paper | {PAPER_EXTRAP_MS['LSQ']:.0f} ms | {PAPER_EXTRAP_MS['PDE']:.0f} ms | {paper:.1f} |"]
        if L and P:
            out.append(f"| this run ({t1} thread) | {fmt(L['median_time_us'])} µs | "
                       f"{fmt(P['median_time_us'])} µs | {P['median_time_us'] / L['median_time_us']:.2f} |")
    return out


def print_extrap_ratio(rows):
    er = extrap_rows(rows)
    if not er:
        return
    t1 = min(r["threads"] for r in er)
    d = {(r["benchmark"], int(r["grid"]), int(r["param"])): r["median_time_us"] for r in er if r["threads"] == t1}
    paper = PAPER_EXTRAP_MS["PDE"] / PAPER_EXTRAP_MS["LSQ"]
    print(f"summarise.py: extrapolation PDE/LSQ time ratio at equal band ({t1} thread); "
          f"paper (100^2, band 5): {PAPER_EXTRAP_MS['PDE']:.0f} ms / {PAPER_EXTRAP_MS['LSQ']:.0f} ms = {paper:.1f}")
    for (b, n, band), t in sorted(d.items(), key=lambda kv: (kv[0][1], kv[0][2])):
        if b == "ExtrapolateLSQ" and ("ExtrapolatePDE", n, band) in d:
            p = d[("ExtrapolatePDE", n, band)]
            mark = "   <- the paper's setting" if (n, band) == (100, 5) else ""
            print(f"   {n:5d}^2 band {band}: LSQ {t:9.1f} us  PDE {p:9.1f} us  PDE/LSQ {p / t:6.2f}{mark}")


def write_study_csvs(rows, outdir, header):
    sr = solver_rows(rows)
    if sr:
        with open(os.path.join(outdir, "poisson_study.csv"), "w", newline="") as f:
            for h in header:
                f.write(f"# {h}\n")
            w = csv.writer(f)
            w.writerow(["solver", "N", "ratio", "threads", "median_time_s", "iterations",
                        "rel_residual", "ref_residual", "conv_factor", "ns_per_unknown"])
            for r in sr:
                w.writerow([r["benchmark"].split("/", 1)[1], r["grid"], r["param"], r["threads"],
                            f"{r['median_time_us'] / 1e6:.6g}"]
                           + ["" if counter(r, k) is None else f"{counter(r, k):.6g}"
                              for k in ("iterations", "rel_residual", "ref_residual", "conv_factor",
                                        "ns_per_unknown")])
    er = extrap_rows(rows)
    if er:
        with open(os.path.join(outdir, "extrapolation_sweep.csv"), "w", newline="") as f:
            for h in header:
                f.write(f"# {h}\n")
            w = csv.writer(f)
            w.writerow(["method", "N", "band", "threads", "median_time_us", "best_us", "cells_filled",
                        "iters", "err_linf", "err_l2"])
            for r in er:
                w.writerow([r["benchmark"][len("Extrapolate"):], r["grid"], r["param"], r["threads"],
                            f"{r['median_time_us']:.6g}"]
                           + ["" if counter(r, k) is None else f"{counter(r, k):.6g}"
                              for k in ("best_us", "cells_filled", "iters", "err_linf", "err_l2")])


def study_plots(rows, outdir, threads, plt):
    lim = machine_limits(rows)
    rr = roofline_rows(rows)
    if rr:
        fig, ax = plt.subplots(figsize=(9, 6))
        kernels = list(dict.fromkeys(f"{r['benchmark']}" + (f"/{param_label(r['benchmark'], r['param'])}"
                                                            if r["param"] else "") for r in rr))
        cmap = plt.get_cmap("tab20")
        colour = {k: cmap(i % 20) for i, k in enumerate(kernels)}
        markers = {t: m for t, m in zip(threads, ("o", "^", "s", "D"))}
        ais = [r["flops_per_cell"] / r["bytes_per_cell"] for r in rr]
        xs = [min(ais) / 2, max(ais) * 4]
        for t, m in sorted(lim.items()):
            if m.get("triad") and m.get("peak"):
                knee = m["peak"] / m["triad"]
                x = [xs[0], min(max(knee, xs[0]), max(xs[1], knee * 2)), max(xs[1], knee * 2)]
                y = [min(m["peak"], m["triad"] * v) for v in x]
                ls = "-" if t == threads[0] else "--"
                ax.plot(x, y, "k" + ls, lw=1.2,
                        label=f"roof {t} thr: Triad {m['triad']:.3g} GB/s, FMA {m['peak']:.3g} GFlop/s")
        for r in rr:
            k = f"{r['benchmark']}" + (f"/{param_label(r['benchmark'], r['param'])}" if r["param"] else "")
            n = int(r["grid"]) if r["grid"] else 256
            ax.scatter(r["flops_per_cell"] / r["bytes_per_cell"], r["GFlop_per_s"], color=colour[k],
                       marker=markers.get(r["threads"], "o"), s=12 + 10 * max(0.0, math.log2(n / 64)),
                       edgecolors="k" if n >= 1024 else "none", linewidths=0.5)
        for k in kernels:
            ax.scatter([], [], color=colour[k], marker="o", s=25, label=k)
        for t in threads:
            ax.scatter([], [], color="grey", marker=markers.get(t, "o"), s=25, label=f"{t} thread(s)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("arithmetic intensity (flop / byte, model of bench/*.cpp)")
        ax.set_ylabel("GFlop/s (median)")
        ax.set_title("Roofline: marker size grows with N (128²..2048²), black edge = N ≥ 1024", fontsize=9)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.01, 0.5))
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "roofline.png"), dpi=120)
        plt.close(fig)
    sr = solver_rows(rows)
    if sr:
        fig, axes = plt.subplots(1, len(threads), figsize=(5.5 * len(threads), 4.5), squeeze=False, sharey=True)
        styles = {"V": ("tab:blue", "o"), "F": ("tab:green", "s"), "mgpcg": ("tab:red", "^"), "cg": ("tab:grey", "x")}
        dash = {1: "-", 10: "--", 1000: ":"}
        for ax, t in zip(axes[0], threads):
            lines = {}
            for r in sr:
                if r["threads"] == t and counter(r, "ns_per_unknown"):
                    lines.setdefault((r["benchmark"].split("/", 1)[1], int(r["param"])), []).append(
                        (int(r["grid"]), counter(r, "ns_per_unknown")))
            for (m, ratio), pts in sorted(lines.items()):
                pts.sort()
                c, mk = styles.get(m, ("k", "o"))
                ax.plot([p[0] for p in pts], [p[1] for p in pts], color=c, marker=mk, ls=dash.get(ratio, "-"),
                        lw=1, ms=4, label=f"{SOLVER_LABEL.get(m, m)}, R={ratio}")
            ax.set_xscale("log", base=2)
            ax.set_yscale("log")
            ax.set_xlabel("N (N × N cells)")
            ax.set_title(f"{t} thread(s)", fontsize=9)
            ax.grid(True, which="both", lw=0.3)
        axes[0][0].set_ylabel("ns per unknown to 1e-8 (median)")
        axes[0][-1].legend(fontsize=6)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "poisson_time_per_unknown.png"), dpi=120)
        plt.close(fig)
    er = extrap_rows(rows)
    if er:
        t1 = min(r["threads"] for r in er)
        bands = sorted({int(r["param"]) for r in er})
        cmap = plt.get_cmap("viridis")
        col = {b: cmap(i / max(1, len(bands) - 1)) for i, b in enumerate(bands)}
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
        for ax, key in zip(axes, ("err_linf", "err_l2")):
            for r in er:
                if r["threads"] != t1 or counter(r, key) is None:
                    continue
                b, n = int(r["param"]), int(r["grid"])
                mk = "o" if r["benchmark"].endswith("LSQ") else "s"
                hl = n == 100
                ax.scatter(r["median_time_us"], counter(r, key), color=col[b], marker=mk,
                           s=60 if hl else 18, edgecolors="r" if hl else "none", linewidths=1.2,
                           alpha=1.0 if hl else 0.6)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(f"time per call (µs, median, {t1} thread)")
            ax.set_ylabel(key + (" (RMS over filled cells)" if key == "err_l2" else " (max over filled cells)"))
            ax.grid(True, which="both", lw=0.3)
        for b in bands:
            axes[1].scatter([], [], color=col[b], marker="o", label=f"band {b}")
        axes[1].scatter([], [], color="w", edgecolors="k", marker="o", label="LSQ")
        axes[1].scatter([], [], color="w", edgecolors="k", marker="s", label="PDE")
        axes[1].scatter([], [], color="w", edgecolors="r", marker="o", s=60, label="100² (larger, red edge)")
        axes[1].legend(fontsize=7)
        fig.suptitle("Extrapolation of a smooth xi: error vs cost (grids 100²..1600²)", fontsize=10)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "extrapolation_accuracy_vs_cost.png"), dpi=120)
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
    write_study_csvs(rows, a.out, header)
    if not a.no_plots:
        plots(rows, a.out, threads)
    print_extrap_ratio(rows)
    print(f"summarise.py: {len(rows)} medians ({len(grouped(rows))} benchmarks, threads {threads}) "
          f"-> {a.out}/benchmarks.csv, {a.out}/benchmarks.md")


if __name__ == "__main__":
    main()
