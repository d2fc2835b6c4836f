#!/usr/bin/env python3
"""Analyse the runs of bench/run_studies.sh (results/performance.md, "Whole-run studies").

Reads <raw>/cost/<scene>/<t>t/rep<k>/timings.csv, <raw>/many/<scene>/<t>t/rep<k>/timings.csv
and <raw>/acc/<case>/<scheme>/<n>/ (timings.csv, probes, the last VTK frame), and writes
(a part not run this time -- no raw runs -- keeps its rows of the existing CSV)

  <out>/scene_costs.csv          one row per study x scene x threads x phase: seconds over the
                                 timed steps, calls, us per cell per step, ms per step, the
                                 2-thread speed-up of that phase, and for the solids the
                                 window cells and storage bytes
  <out>/scene_costs.png          stacked bars of us/cell/step by phase, 1 and 2 threads per
                                 scene; the many-small-solids study beside it
  <out>/accuracy_vs_cost.csv     case, scheme, n, steps, wall_s, error columns
  <out>/accuracy_vs_cost_{taylor_green,cavity,couette}.png   error vs wall time

Every CSV begins with the '#' header lines of bench/summarise.py (header_lines: lscpu model,
cores, compiler, date, source, command) plus the load before and after the run.

Errors:
  taylor_green  RMS over the cells of |u - u_exact| at the final time (the last VTK frame),
                u_exact = (sin x cos y, -cos x sin y) e^{-2 nu t}, as tests/test_taylor_green.cpp
  cavity        RMS difference of the centreline probes to Ghia et al. (1982) Re 100 at the 15
                interior stations (tests/data/ghia1982_*.csv), u on x = 0.5 and v on y = 0.5,
                as tests/test_cavity.cpp (the probes' 129 points are Ghia's stations k/128)
  couette       L-infinity difference of the u_profile probe (41 points, y = 0..1) to
                tests/data/couette_elastic_startup.csv column u_t4.8, as
                tests/test_couette_elastic.cpp
Cost = wall time of the run minus its "output" phase (VTK frames and probe files), from
timings.csv: the solver's time including the per-step diagnostics rows.

Usage: python3 bench/studies.py --raw results/raw/studies --info results/raw/studies_info.txt --out results
"""
from __future__ import annotations

import argparse
import csv
import glob
import math
import os
import re
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from summarise import header_lines, read_info  # noqa: E402  (the shared CSV header)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")

# phase order of the plots (the table order of `refmap run`); unknown phases go last
PHASES = ["xi advection", "extrapolation", "level set", "prescribed flow", "advection", "viscous",
          "solid stress", "poisson setup", "face velocities", "poisson", "projection",
          "diagnostics", "output", "other"]
SOLID_PHASES = ["xi advection", "extrapolation", "level set", "solid stress", "poisson setup"]


# ------------------------------------------------------------------ timings.csv
def read_timings(path):
    meta, phases = {}, {}
    with open(path) as f:
        lines = f.read().splitlines()
    body = []
    for ln in lines:
        if ln.startswith("#"):
            if ":" in ln:
                k, v = ln[1:].split(":", 1)
                meta[k.strip()] = v.strip()
        elif ln.strip():
            body.append(ln)
    for row in csv.DictReader(body):
        phases[row["phase"]] = (float(row["seconds"]), int(row["calls"]))
    return meta, phases


def median_run(dirs):
    """the repetition whose total timed wall time is the median (lower median)"""
    runs = []
    for d in dirs:
        p = os.path.join(d, "timings.csv")
        if os.path.exists(p):
            runs.append(read_timings(p))
    if not runs:
        return None
    runs.sort(key=lambda r: r[1]["total"][0])
    return runs[(len(runs) - 1) // 2], len(runs)


def cost_rows(raw, study):
    rows = []
    base = os.path.join(raw, study)
    for scene_dir in sorted(glob.glob(os.path.join(base, "*"))):
        scene = os.path.basename(scene_dir)
        per_t = {}
        for tdir in sorted(glob.glob(os.path.join(scene_dir, "*t"))):
            t = int(re.search(r"(\d+)t$", tdir).group(1))
            m = median_run(sorted(glob.glob(os.path.join(tdir, "rep*"))))
            if m:
                per_t[t] = m
        for t, ((meta, ph), nrep) in sorted(per_t.items()):
            nx, ny, steps = int(meta["nx"]), int(meta["ny"]), int(meta["timed_steps"])
            cells = nx * ny
            for name in sorted(ph, key=lambda n: PHASES.index(n) if n in PHASES else len(PHASES)):
                sec, calls = ph[name]
                sp = ""
                if t != 1 and 1 in per_t and name in per_t[1][0][1] and sec > 0:
                    sp = per_t[1][0][1][name][0] / sec
                rows.append({
                    "study": study, "scene": scene, "nx": nx, "ny": ny, "threads": t,
                    "repetitions": nrep, "timed_steps": steps, "phase": name, "seconds": sec,
                    "calls": calls, "us_per_cell_step": 1e6 * sec / (cells * steps),
                    "ms_per_step": 1e3 * sec / steps, "speedup_vs_1t": sp,
                    "solids": int(meta.get("solids", 0)),
                    "solid_window_cells": int(meta.get("solid_window_cells", 0)),
                    "solid_storage_bytes": int(meta.get("solid_storage_bytes", 0)),
                })
    return rows


def write_costs_csv(rows, path, header):
    cols = ["study", "scene", "nx", "ny", "threads", "repetitions", "timed_steps", "phase", "seconds",
            "calls", "us_per_cell_step", "ms_per_step", "speedup_vs_1t", "solids",
            "solid_window_cells", "solid_storage_bytes"]
    with open(path, "w", newline="") as f:
        for h in header:
            f.write(f"# {h}\n")
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            out = []
            for c in cols:
                v = r[c]
                out.append(f"{v:.6g}" if isinstance(v, float) else v)
            w.writerow(out)


def read_costs_csv(path, study):
    """the rows of one study from an existing scene_costs.csv (typed as cost_rows makes them)"""
    if not os.path.exists(path):
        return []
    ints = {"nx", "ny", "threads", "repetitions", "timed_steps", "calls", "solids", "solid_window_cells",
            "solid_storage_bytes"}
    out = []
    with open(path) as f:
        for r in csv.DictReader(ln for ln in f if not ln.startswith("#")):
            if r["study"] != study:
                continue
            for k, v in r.items():
                if k in ints:
                    r[k] = int(v)
                elif k in ("seconds", "us_per_cell_step", "ms_per_step") or (k == "speedup_vs_1t" and v):
                    r[k] = float(v)
            out.append(r)
    return out


def total(rows, study, scene, t, key="us_per_cell_step"):
    for r in rows:
        if r["study"] == study and r["scene"] == scene and r["threads"] == t and r["phase"] == "total":
            return r[key]
    return None


def print_costs(rows):
    scenes = sorted({(r["study"], r["scene"]) for r in rows}, key=lambda s: (s[0] != "cost", s[1]))
    print("scene costs (us per cell per step, whole step incl. diagnostics):")
    for st, sc in scenes:
        t1, t2 = total(rows, st, sc, 1), total(rows, st, sc, 2)
        r0 = next(r for r in rows if r["study"] == st and r["scene"] == sc)
        line = f"  {st:5s} {sc:28s} {r0['nx']}x{r0['ny']}: 1t {t1:.4g}" if t1 else f"  {sc}"
        if t1 and t2:
            line += f"  2t {t2:.4g}  speed-up {t1 / t2:.2f}"
        if r0["solids"]:
            solid_ms = sum(r["ms_per_step"] for r in rows if r["study"] == st and r["scene"] == sc
                           and r["threads"] == 1 and r["phase"] in SOLID_PHASES)
            line += (f"  solid phases {solid_ms:.3g} ms/step, windows {r0['solid_window_cells']} cells, "
                     f"storage {r0['solid_storage_bytes'] / 2**20:.2f} MiB")
        print(line)


def plot_costs(rows, path, plt):
    cost_scenes = sorted({r["scene"] for r in rows if r["study"] == "cost"})
    many = sorted({r["scene"] for r in rows if r["study"] == "many"},
                  key=lambda s: next((r["nx"], r["solids"]) for r in rows if r["study"] == "many" and r["scene"] == s))
    phases = [p for p in PHASES if any(r["phase"] == p for r in rows)]
    phases += sorted({r["phase"] for r in rows} - set(phases) - {"total"})
    cmap = plt.get_cmap("tab20")
    colour = {p: cmap(i % 20) for i, p in enumerate(phases)}
    ncol = 2 if many else 1
    fig, axes = plt.subplots(1, ncol, figsize=(12 if many else 8, 5.5),
                             gridspec_kw={"width_ratios": [max(len(cost_scenes), 1), max(2, 0.6 * len(many))]} if many else None)
    axes = np.atleast_1d(axes)

    def bars(ax, study, scenes, threads, ylabel, key):
        x, labels = 0.0, []
        ticks = []
        for sc in scenes:
            for t in threads:
                sel = {r["phase"]: r for r in rows if r["study"] == study and r["scene"] == sc and r["threads"] == t}
                if not sel:
                    continue
                bottom = 0.0
                for p in phases:
                    if p in sel:
                        v = sel[p][key]
                        ax.bar(x, v, 0.8, bottom=bottom, color=colour[p],
                               label=p if p not in ax.get_legend_handles_labels()[1] else None)
                        bottom += v
                ticks.append(x)
                labels.append(f"{sc}\n{t} thr" if len(threads) > 1 else sc)
                x += 1.0
            x += 0.5
        ax.set_xticks(ticks)
        ax.set_xticklabels(labels, rotation=60, ha="right", fontsize=7)
        ax.set_ylabel(ylabel)
        ax.grid(axis="y", alpha=0.3)

    bars(axes[0], "cost", cost_scenes, [1, 2], "µs per cell per step", "us_per_cell_step")
    axes[0].set_title("Paper scenes: whole step by phase, 1 and 2 threads", fontsize=10)
    if many:
        bars(axes[1], "many", many, [1], "µs per cell per step", "us_per_cell_step")
        for k, sc in enumerate(many):
            r0 = next(r for r in rows if r["study"] == "many" and r["scene"] == sc)
            tot = total(rows, "many", sc, 1) or 0
            axes[1].text(k * 1.5, tot, f"{r0['nx']}²\n{r0['solid_storage_bytes'] / 2**20:.1f} MiB", ha="center",
                         va="bottom", fontsize=7)
        axes[1].set_title("1 disc vs N small discs (same area),\n1 thread; label: grid, solids' storage", fontsize=10)
    handles, labels = [], []
    for ax in axes:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    order = sorted(range(len(labels)), key=lambda i: phases.index(labels[i]))
    fig.legend([handles[i] for i in order], [labels[i] for i in order], loc="upper right", fontsize=7,
               ncol=1, bbox_to_anchor=(1.0, 0.93))
    fig.tight_layout(rect=(0, 0, 0.87, 1))
    fig.savefig(path, dpi=120)
    plt.close(fig)


# ------------------------------------------------------------------ accuracy
def read_probe(path):
    a = np.loadtxt(path, delimiter=",", skiprows=1, comments="#")
    return a[:, 0], a[:, 1], a[:, 2]


def read_ref(path):
    with open(path) as f:
        rows = [r for r in csv.DictReader(ln for ln in f if not ln.startswith("#"))]
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def read_vti_fields(path, names):
    """time, (x0, y0, dx) and the named cell fields of a refmap .vti (raw appended, UInt64
    headers): each an array (ny, nx) or (ny, nx, components)"""
    with open(path, "rb") as f:
        data = f.read()
    head_end = data.index(b"<AppendedData")
    head = data[:head_end].decode()
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    nx, ny = ext[1] - ext[0], ext[3] - ext[2]
    x0, y0, _ = [float(v) for v in re.search(r'Origin="([^"]+)"', head).group(1).split()]
    dx = float(re.search(r'Spacing="([^"]+)"', head).group(1).split()[0])
    time = float(re.search(r'Name="TIME"[^>]*>([^<]+)<', head).group(1))
    base = data.index(b"_", head_end) + 1
    out = {}
    for name in names:
        off = int(re.search(r'Name="%s"[^>]*offset="(\d+)"' % name, head).group(1))
        n = int(np.frombuffer(data, dtype="<u8", count=1, offset=base + off)[0]) // 8
        a = np.frombuffer(data, dtype="<f8", count=n, offset=base + off + 8)
        out[name] = a.reshape(ny, nx) if n == nx * ny else a.reshape(ny, nx, n // (nx * ny))
    return time, (x0, y0, dx), out


def read_vti_velocity(path):
    """(nx, ny, x0, y0, dx, time, u, v) from a refmap .vti"""
    time, (x0, y0, dx), f = read_vti_fields(path, ("velocity",))
    vel = f["velocity"]
    ny, nx = vel.shape[:2]
    return nx, ny, x0, y0, dx, time, vel[:, :, 0], vel[:, :, 1]


def solver_wall(run_dir):
    meta, ph = read_timings(os.path.join(run_dir, "timings.csv"))
    out = ph.get("output", (0.0, 0))[0]
    return float(meta["wall_s"]) - out, int(meta["steps"])


def err_taylor_green(run_dir):
    frames = sorted(glob.glob(os.path.join(run_dir, "frame_*.vti")))
    nx, ny, x0, y0, dx, t, u, v = read_vti_velocity(frames[-1])
    with open(os.path.join(run_dir, "scene.toml"), "rb") as f:
        sc = tomllib.load(f)
    nu = sc["fluid"]["viscosity"] / sc["fluid"].get("density", 1.0)
    x = x0 + (np.arange(nx) + 0.5) * dx
    y = y0 + (np.arange(ny) + 0.5) * dx
    X, Y = np.meshgrid(x, y)
    d = math.exp(-2.0 * nu * t)
    e = (u - np.sin(X) * np.cos(Y) * d) ** 2 + (v + np.cos(X) * np.sin(Y) * d) ** 2
    return {"error": math.sqrt(e.mean()), "error_u": "", "error_v": "", "t_end": t,
            "metric": "RMS |u - u_exact| over cells"}


def err_cavity(run_dir):
    gu = read_ref(os.path.join(DATA, "ghia1982_u_vertical.csv"))
    gv = read_ref(os.path.join(DATA, "ghia1982_v_horizontal.csv"))
    _, py, pu = read_probe(os.path.join(run_dir, "probe_u_vertical.csv"))
    px, _, pv = read_probe(os.path.join(run_dir, "probe_v_horizontal.csv"))
    ky = (gu["y_exact"] > 0) & (gu["y_exact"] < 1)
    kx = (gv["x_exact"] > 0) & (gv["x_exact"] < 1)
    du = np.interp(gu["y_exact"][ky], py, pu) - gu["u_Re100"][ky]
    dv = np.interp(gv["x_exact"][kx], px, pv) - gv["v_Re100"][kx]
    ru, rv = math.sqrt(np.mean(du ** 2)), math.sqrt(np.mean(dv ** 2))
    with open(os.path.join(run_dir, "diagnostics.csv")) as f:
        last = [ln for ln in f if ln.strip() and not ln.startswith("#")][-1]
    t_end = float(last.split(",")[1])
    return {"error": math.sqrt(0.5 * (ru * ru + rv * rv)), "error_u": ru, "error_v": rv, "t_end": t_end,
            "metric": "RMS vs Ghia Re 100 (15 + 15 interior stations; error = sqrt((u^2 + v^2)/2))"}


def err_couette(run_dir):
    ref = read_ref(os.path.join(DATA, "couette_elastic_startup.csv"))
    _, py, pu = read_probe(os.path.join(run_dir, "probe_u_profile.csv"))
    e = np.max(np.abs(np.interp(ref["y"], py, pu) - ref["u_t4.8"]))
    with open(os.path.join(run_dir, "diagnostics.csv")) as f:
        last = [ln for ln in f if ln.strip() and not ln.startswith("#")][-1]
    return {"error": float(e), "error_u": "", "error_v": "", "t_end": float(last.split(",")[1]),
            "metric": "L-inf vs couette_elastic_startup.csv u_t4.8"}


ERR = {"taylor_green": err_taylor_green, "cavity": err_cavity, "couette": err_couette}
NLABEL = {"taylor_green": "n (n x n cells)", "cavity": "n (n x n cells)", "couette": "cells per unit length"}


def accuracy_rows(raw):
    rows = []
    for case, fn in ERR.items():
        for d in sorted(glob.glob(os.path.join(raw, "acc", case, "*", "*"))):
            scheme, n = d.split(os.sep)[-2], int(d.split(os.sep)[-1])
            if not os.path.exists(os.path.join(d, "timings.csv")):
                print(f"studies.py: {d}: no timings.csv (run failed?), skipped", file=sys.stderr)
                continue
            wall, steps = solver_wall(d)
            e = fn(d)
            rows.append({"case": case, "scheme": scheme, "n": n, "steps": steps, "wall_s": wall, **e})
    rows.sort(key=lambda r: (list(ERR).index(r["case"]), r["scheme"], r["n"]))
    return rows


def write_acc_csv(rows, path, header):
    cols = ["case", "scheme", "n", "steps", "t_end", "wall_s", "error", "error_u", "error_v", "metric"]
    with open(path, "w", newline="") as f:
        for h in header:
            f.write(f"# {h}\n")
        f.write("# n: cells per side (taylor_green, cavity) or per unit length (couette); wall_s: run wall "
                "time minus its output phase, 1 thread\n")
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([f"{r[c]:.6g}" if isinstance(r[c], float) else r[c] for c in cols])


def plot_accuracy(rows, outdir, plt):
    titles = {"taylor_green": "Taylor–Green vortex, t = 1: RMS error vs exact",
              "cavity": "Lid-driven cavity Re 100 (steady): RMS vs Ghia et al. (1982)",
              "couette": "Elastic-layer Couette flow, t = 4.8: L∞ vs start-up reference"}
    for case in ERR:
        sel = [r for r in rows if r["case"] == case]
        if not sel:
            continue
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for scheme, mk, c in (("central", "o", "C0"), ("superbee", "s", "C3")):
            rs = sorted([r for r in sel if r["scheme"] == scheme], key=lambda r: r["n"])
            if not rs:
                continue
            w = [r["wall_s"] for r in rs]
            if case == "cavity":
                ax.loglog(w, [r["error_u"] for r in rs], mk + "-", color=c, label=f"{scheme}: u on x = 0.5")
                ax.loglog(w, [r["error_v"] for r in rs], mk + "--", color=c, mfc="none",
                          label=f"{scheme}: v on y = 0.5")
            else:
                ax.loglog(w, [r["error"] for r in rs], mk + "-", color=c, label=scheme)
            for r in rs:
                yv = r["error_u"] if case == "cavity" else r["error"]
                ax.annotate(str(r["n"]), (r["wall_s"], yv), textcoords="offset points", xytext=(4, 4),
                            fontsize=7, color=c)
        ax.set_xlabel("wall time of the run [s] (1 thread, output excluded)")
        ax.set_ylabel("error")
        ax.set_title(titles[case] + f"\nlabels: {NLABEL[case]}", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, f"accuracy_vs_cost_{case}.png"), dpi=120)
        plt.close(fig)


def print_accuracy(rows):
    print("accuracy vs cost (1 thread):")
    for r in rows:
        extra = f" (u {r['error_u']:.3e}, v {r['error_v']:.3e})" if r["case"] == "cavity" else ""
        print(f"  {r['case']:12s} {r['scheme']:8s} n={r['n']:4d} steps={r['steps']:7d} t={r['t_end']:.4g} "
              f"wall={r['wall_s']:8.3f} s  error={r['error']:.3e}{extra}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--raw", default="results/raw/studies")
    ap.add_argument("--info", default="results/raw/studies_info.txt")
    ap.add_argument("--out", default="results")
    ap.add_argument("--no-plots", action="store_true")
    a = ap.parse_args()

    info = read_info(a.info)
    header = header_lines(info, {})
    for k in ("uptime_before", "uptime_after"):
        if k in info:
            header.append(f"{k.replace('_', ' ')} (this invocation): {info[k]}")
    for part in ("costs", "many", "accuracy"):  # each part's own date, load and wall time
        if f"date_{part}" in info:
            header.append(f"part {part}: run {info[f'date_{part}']}, wall {info.get(f'wall_{part}_s', '?')} s, "
                          f"uptime before: {info.get(f'uptime_before_{part}', '?')}; "
                          f"after: {info.get(f'uptime_after_{part}', '?')}")
    plt = None
    if not a.no_plots:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt  # noqa: F811
        except ImportError:
            print("studies.py: no matplotlib, tables only", file=sys.stderr)

    crow = []
    for study in ("cost", "many"):
        rows = cost_rows(a.raw, study)
        if not rows:  # a part not run this time: its rows of the previous CSV stay
            rows = read_costs_csv(os.path.join(a.out, "scene_costs.csv"), study)
            if rows:
                header.append(f"rows of study {study}: kept from the previous scene_costs.csv (their run is the "
                              f"part's record above; the machine may differ from this header's)")
        crow += rows
    if crow:
        write_costs_csv(crow, os.path.join(a.out, "scene_costs.csv"), header)
        print_costs(crow)
        if plt:
            plot_costs(crow, os.path.join(a.out, "scene_costs.png"), plt)
    arow = accuracy_rows(a.raw)
    if arow:
        write_acc_csv(arow, os.path.join(a.out, "accuracy_vs_cost.csv"), header)
        print_accuracy(arow)
        if plt:
            plot_accuracy(arow, a.out, plt)
    if not crow and not arow:
        sys.exit(f"studies.py: nothing to analyse in {a.raw}")


if __name__ == "__main__":
    main()
