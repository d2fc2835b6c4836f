#!/usr/bin/env python3
"""Summary of the sheared-suspension study (bench/run_suspension.sh; results/suspension.md).

    /usr/bin/python3 bench/suspension.py --runs RUNS.txt --t0 1 --stiff 0.01 --nx 128 --out results/suspension
    /usr/bin/python3 bench/suspension.py --stiff 0.01 --nx 128 --out results/suspension \
        --extra results/suspension/dense/suspension.csv --dilute results/suspension/dilute.csv
                                       # redraws eta_vs_phi.png alone, from suspension.csv

RUNS.txt: one line per run, "DIR PHI CA" (DIR.rc holds the exit code, DIR.err the messages).
For every run: eta_r (diagnostics.csv, output.wall_stress: the mean of the two walls' shear
stress over mu_f gamma) averaged in time over t in [T0, t_end] -- time-weighted (the steps
are not equal) -- and its standard error from NB = 5 equal blocks of that window (the
standard deviation of the block means over sqrt(NB)). The area fraction is the one placed
(solids.csv: the particles' areas at the first row, over the domain's area 2 x 1).

Writes OUT/suspension.csv, OUT/eta_vs_phi.png, OUT/eta_time_series.png and
OUT/snapshot_stress.png (the largest phi with VTK frames, its last frame, stiff and the
softest side by side). Only numpy and matplotlib.
"""
import argparse
import csv
import glob
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scenes"))
import solids_csv  # noqa: E402

NB = 5
AREA = 2.0  # the cell's area, lx x ly of bench/scenes/shear_suspension.toml
# the confined dilute coefficient of one disc at the centre of this cell at a/H = 0.1,
# from results/shear_cell.csv (bench/run_shear_cell.sh): 1.889 + 18.17 (a/H)^2
CONFINED = 1.889 + 18.17 * 0.1 ** 2


def read_diag(run):
    header, rows = solids_csv.read_rows(os.path.join(run, "diagnostics.csv"))
    col = {n: i for i, n in enumerate(header)}
    a = np.array(rows)
    return {n: a[:, i] for n, i in col.items()}


def placed(run):
    """(N, phi) of the particles at the first row of solids.csv."""
    header, rows = solids_csv.read_rows(os.path.join(run, "solids.csv"))
    col = {n: i for i, n in enumerate(header)}
    first = rows[0][col["step"]]
    areas = [r[col["area"]] for r in rows if r[col["step"]] == first]
    return len(areas), sum(areas) / AREA


def window_mean(t, y, t0, t1):
    """Time-weighted mean of y over [t0, t1] (trapezoids between the rows)."""
    m = (t >= t0) & (t <= t1)
    tt, yy = t[m], y[m]
    if len(tt) < 2:
        return float("nan")
    return float(np.trapz(yy, tt) / (tt[-1] - tt[0]))


def average(t, eta, t0):
    t1 = t[-1]
    mean = window_mean(t, eta, t0, t1)
    edges = np.linspace(t0, t1, NB + 1)
    blocks = [window_mean(t, eta, edges[k], edges[k + 1]) for k in range(NB)]
    err = float(np.std(blocks, ddof=1) / math.sqrt(NB))
    return mean, err, blocks


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", default="", help="the runs list; without it, only eta_vs_phi.png is redrawn "
                    "from OUT/suspension.csv (and --extra, --dilute)")
    ap.add_argument("--t0", type=float, default=1.0)
    ap.add_argument("--stiff", type=float, required=True)
    ap.add_argument("--nx", type=int, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--extra", default="", help="a suspension.csv of runs made apart (the dense point), "
                    "added to the chart when it exists and is not OUT's own")
    ap.add_argument("--dilute", default="", help="dilute.csv of bench/run_suspension_dilute.sh: the free "
                    "disc's coefficient at this grid, drawn when it exists")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if not a.runs:
        rows = list(csv.DictReader(open(os.path.join(a.out, "suspension.csv"))))
        plots(a, rows, {})
        return
    runs = [l.split() for l in open(a.runs) if l.strip()]
    rows, series = [], {}
    for d, phi, ca in runs:
        rc = int(open(d + ".rc").read().strip()) if os.path.exists(d + ".rc") else -1
        kind = "stiff" if float(ca) == a.stiff else "soft"
        base = dict(phi_requested=phi, kind=kind, capillary=ca, grid=f"{a.nx}x{a.nx // 2}",
                    cells_per_radius=f"{0.1 * a.nx / 2.0:.1f}", threads=1, exit=rc)
        if rc != 0:
            err = open(d + ".err").read().strip().splitlines() if os.path.exists(d + ".err") else []
            print(f"phi {phi} Ca {ca}: exit {rc}: {err[-1] if err else ''}", file=sys.stderr)
            rows.append(dict(base, phi="", N="", eta_r="", eta_err="", steps="", wall_s="",
                             note=(err[-1][:160].replace(",", ";") if err else "")))
            continue
        dg = read_diag(d)
        n, phi_m = placed(d)
        mean, err, _ = average(dg["time"], dg["eta_r"], a.t0)
        series[(float(phi), float(ca))] = (dg["time"], dg["eta_r"])
        rows.append(dict(base, phi=f"{phi_m:.4f}", N=n, eta_r=f"{mean:.4f}", eta_err=f"{err:.4f}",
                         steps=int(dg["step"][-1]), wall_s=f"{dg['wall_time'][-1]:.1f}", note=""))
    cols = ["phi_requested", "phi", "kind", "capillary", "N", "grid", "cells_per_radius", "eta_r", "eta_err",
            "steps", "wall_s", "threads", "exit", "note"]
    with open(os.path.join(a.out, "suspension.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    for r in rows:
        print(",".join(str(r[c]) for c in cols))
    plots(a, rows, series)


def plots(a, rows, series):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # ---- eta_r against phi
    fig, ax = plt.subplots(figsize=(6, 4.2))
    cas = sorted({float(r["capillary"]) for r in rows})
    marks = ["o", "s", "^", "D", "v"]
    extra = []
    if a.extra and os.path.exists(a.extra) and \
            os.path.abspath(os.path.dirname(a.extra)) != os.path.abspath(a.out):
        extra = [r for r in csv.DictReader(open(a.extra)) if r["eta_r"] != ""]
        cas = sorted(set(cas) | {float(r["capillary"]) for r in extra})
    for k, ca in enumerate(cas):
        rr = [r for r in rows + extra if float(r["capillary"]) == ca and r["eta_r"] != ""]
        rr.sort(key=lambda r: float(r["phi"]))
        if not rr:
            continue
        x = [float(r["phi"]) for r in rr]
        y = [float(r["eta_r"]) for r in rr]
        e = [float(r["eta_err"]) for r in rr]
        lab = ("stiff" if ca == a.stiff else "soft") + f", Ca = {ca:g}"
        ax.errorbar(x, y, yerr=e, marker=marks[k % len(marks)], capsize=3, label=lab)
    xs = np.linspace(0, 0.45, 50)
    ax.plot(xs, 1 + 2 * xs, "k--", lw=1, label=r"2-D Einstein $1 + 2\phi$ (Brady 1984)")
    ax.plot(xs, 1 + CONFINED * xs, "k:", lw=1,
            label=rf"one pinned disc, this cell: $1 + {CONFINED:.2f}\phi$ (shear_cell.csv)")
    if a.dilute and os.path.exists(a.dilute):
        # the free stiff disc on the centre line at this grid: the dilute slope these runs
        # would show if the particles did not interact (walls and blend width included)
        free = [r for r in csv.DictReader(open(a.dilute)) if r["series"] == "res" and int(r["nx"]) == a.nx
                and abs(float(r["H"]) - 1) < 1e-12]
        if free:
            c = float(free[0]["coefficient"])
            ax.plot(xs, 1 + c * xs, "-.", color="0.4", lw=1,
                    label=rf"one free stiff disc, this cell and grid: $1 + {c:.2f}\phi$ (dilute.csv)")
    ax.set_xlabel(r"area fraction $\phi$ (placed)")
    ax.set_ylabel(r"relative viscosity $\eta_r = \tau_w / (\mu \dot\gamma)$")
    ax.set_title(f"sheared suspension of discs, a/H = 0.1, grid {a.nx}x{a.nx // 2} "
                 f"({0.1 * a.nx / 2:.1f} cells per radius)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "eta_vs_phi.png"), dpi=110)
    plt.close(fig)

    # ---- eta_r time series of the largest phi run, every Ca, with the averaging window
    if series:
        phis = sorted({p for p, _ in series})
        pick = [p for p in phis if p <= 0.3] or phis
        phi = pick[-1]
        fig, ax = plt.subplots(figsize=(6.5, 3.8))
        t_end = 0.0
        for ca in cas:
            if (phi, ca) not in series:
                continue
            t, eta = series[(phi, ca)]
            t_end = max(t_end, t[-1])
            mean, err, blocks = average(t, eta, a.t0)
            line, = ax.plot(t, eta, lw=0.8, label=("stiff" if ca == a.stiff else "soft") + f", Ca = {ca:g}: "
                            rf"$\bar\eta_r$ = {mean:.3f} $\pm$ {err:.3f}")
            ax.hlines(mean, a.t0, t[-1], colors=line.get_color(), linestyles="--", lw=1)
        ax.axvspan(a.t0, t_end, color="0.9", zorder=0, label=f"averaging window t in [{a.t0:g}, {t_end:g}]")
        ax.set_xlabel(r"$\dot\gamma t$")
        ax.set_ylabel(r"$\eta_r$")
        ax.set_title(rf"$\phi$ = {phi:g}: relative viscosity from the wall stress", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, "eta_time_series.png"), dpi=110)
        plt.close(fig)

    # ---- snapshot: the solids' shear stress at the last frame
    if not a.runs:
        return
    from plot_run import Frame
    runs = [l.split() for l in open(a.runs) if l.strip()]
    framed = [(float(p), float(c), d) for d, p, c in runs if glob.glob(os.path.join(d, "frame_*.vti"))]
    if not framed:
        return
    phi = max(p for p, _, _ in framed)
    panels = sorted([(c, d) for p, c, d in framed if p == phi])
    panels = [panels[0], panels[-1]] if len(panels) > 1 else panels
    fig, axes = plt.subplots(len(panels), 1, figsize=(7, 3.3 * len(panels)), squeeze=False)
    frames = [Frame(sorted(glob.glob(os.path.join(d, "frame_*.vti")))[-1]) for _, d in panels]
    vals = [f.get("stress_xy")[f.get("phi") < 0] for f in frames if "stress_xy" in f.fields]
    lim = float(np.percentile(np.abs(np.concatenate(vals)), 99)) if vals else 1.0
    for ax, (ca, _), f in zip(axes[:, 0], panels, frames):
        phi_f = f.get("phi")
        s = np.ma.masked_where(phi_f >= 0, f.get("stress_xy"))
        ax.imshow(np.ones_like(phi_f), extent=f.extent, origin="lower", cmap="Greys", vmin=0, vmax=4)
        im = ax.imshow(s, extent=f.extent, origin="lower", cmap="RdBu_r", vmin=-lim, vmax=lim)
        x, y = f.cell_centres()
        ax.contour(x, y, phi_f, levels=[0], colors="k", linewidths=0.6)
        ax.set_aspect("equal")
        ax.set_title(("stiff" if ca == a.stiff else "soft") + rf", Ca = {ca:g}, $\phi$ = {phi:g}, "
                     rf"$\dot\gamma t$ = {f.time:g}", fontsize=9)
        fig.colorbar(im, ax=ax, fraction=0.025, pad=0.01,
                     label=r"solid shear stress $\sigma_{xy} / (\mu\dot\gamma)$")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "snapshot_stress.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
