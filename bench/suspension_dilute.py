#!/usr/bin/env python3
"""Summary of the dilute-coefficient study (bench/run_suspension_dilute.sh; results/suspension.md).

    /usr/bin/python3 bench/suspension_dilute.py --runs RUNS.txt --win 0.4 --out results/suspension

RUNS.txt: one line per (run, series): "DIR SERIES L H NX NY TRANSITION CA T_END" (DIR.rc holds
the exit code, DIR.err the messages); a run may belong to several series. For each run:
eta_r (diagnostics.csv, output.wall_stress) averaged in time over the last WIN of the run
(time-weighted), its drift (the mean of the window's second half minus the first half's),
phi = pi a^2 / (L H) (a = 0.1) and the coefficient c = (eta_r - 1) / phi.

Fits (written to OUT/dilute_fits.csv, one number per row):
  wall    c = c_w + k_w (a/H)^2 over the wall series (dx, a fixed): the walls' correction at
          the test's a/H = 0.1 is k_w / 100;
  period  c(L = 2) - c(L = 4) at H = 1: the periodic images' correction of the L = 2 cell;
  width   c = c_t + s_t (w dx / a) over the blend's half-width w (cells) at dx = 1/64;
  wallfine  the same slope at 12.8 cells per radius, from H = 1 and 1.5;
  res     c against h = dx / a: the linear fit of the finest two (Richardson's first-order
          extrapolation), and every grid's c minus the walls' and images' corrections, to
          compare with 2; the area the blend adds to the disc (analytic, eq. 3.5).
Writes OUT/dilute.csv, OUT/dilute_fits.csv and OUT/dilute_coefficient.png. numpy, matplotlib.
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scenes"))
import solids_csv  # noqa: E402
from suspension import window_mean  # noqa: E402  (bench/suspension.py: the study's own average)

A = 0.1  # the disc's radius


def read_diag(run):
    header, rows = solids_csv.read_rows(os.path.join(run, "diagnostics.csv"))
    a = np.array(rows)
    return {n: a[:, i] for i, n in enumerate(header)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", required=True)
    ap.add_argument("--win", type=float, default=0.4)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    lines = [l.split() for l in open(a.runs) if l.strip()]
    rows, series = [], {}
    for d, s, L, H, nx, ny, wt, ca, t_end in lines:
        L, H, nx, ny, wt, ca, t_end = float(L), float(H), int(nx), int(ny), float(wt), float(ca), float(t_end)
        dx = L / nx
        rc = int(open(d + ".rc").read().strip()) if os.path.exists(d + ".rc") else -1
        r = dict(series=s, L=L, H=H, a_over_H=A / H, nx=nx, ny=ny, cells_per_radius=A / dx, transition=wt,
                 capillary=ca, t_end=t_end, phi=math.pi * A * A / (L * H), exit=rc)
        if rc != 0 or not os.path.exists(os.path.join(d, "diagnostics.csv")):
            print(f"{d}: exit {rc}", file=sys.stderr)
            continue
        dg = read_diag(d)
        t, eta = dg["time"], dg["eta_r"]
        t1 = t[-1]
        t0 = t1 * (1 - a.win)
        mean = window_mean(t, eta, t0, t1)
        drift = window_mean(t, eta, 0.5 * (t0 + t1), t1) - window_mean(t, eta, t0, 0.5 * (t0 + t1))
        r.update(t_end=float(t1), eta_r=mean, drift=drift, coefficient=(mean - 1) / r["phi"],
                 drift_coefficient=drift / r["phi"], steps=int(dg["step"][-1]), wall_s=float(dg["wall_time"][-1]))
        rows.append(r)
        series.setdefault(s, []).append((r, t, eta))
    cols = ["series", "L", "H", "a_over_H", "nx", "ny", "cells_per_radius", "transition", "capillary", "t_end", "phi",
            "eta_r", "drift", "coefficient", "drift_coefficient", "steps", "wall_s", "exit"]
    fmt = {"a_over_H": "{:.4f}", "cells_per_radius": "{:.1f}", "phi": "{:.6f}", "eta_r": "{:.6f}", "drift": "{:.2e}",
           "coefficient": "{:.4f}", "drift_coefficient": "{:.4f}", "wall_s": "{:.1f}", "t_end": "{:.3f}"}
    with open(os.path.join(a.out, "dilute.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([fmt.get(c, "{}").format(r[c]) for c in cols])
    fits = fit(series)
    with open(os.path.join(a.out, "dilute_fits.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["name", "value", "meaning"])
        for name, value, meaning in fits:
            w.writerow([name, f"{value:.4f}", meaning])
    for r in rows:
        print(f"{r['series']:6s} L {r['L']:g} H {r['H']:g} nx {r['nx']} w {r['transition']:g} Ca {r['capillary']:g}: "
              f"eta_r {r['eta_r']:.5f} c {r['coefficient']:.4f} (drift {r['drift_coefficient']:+.4f})")
    for name, value, meaning in fits:
        print(f"{name} = {value:.4f}  ({meaning})")
    plot(a, series, dict((n, v) for n, v, _ in fits))


def fit(series):
    out = []
    get = lambda s: sorted([r for r, _, _ in series.get(s, [])], key=lambda r: r["a_over_H"])  # noqa: E731
    wall = period = 0.0
    if len(get("wall")) >= 2:
        rr = get("wall")
        x = np.array([r["a_over_H"] ** 2 for r in rr])
        y = np.array([r["coefficient"] for r in rr])
        k, c = np.polyfit(x, y, 1)
        wall = k * 0.01
        out += [("wall_c0", c, "wall series: the fit's unconfined coefficient at 6.4 cells per radius"),
                ("wall_k", k, "wall series: the slope k_w of c against (a/H)^2"),
                ("wall_correction", wall, "k_w (a/H)^2 at a/H = 0.1: the walls' share of c in the test's cell"),
                ("wall_fit_rms", float(np.sqrt(np.mean((np.polyval([k, c], x) - y) ** 2))),
                 "rms residual of the wall fit")]
    pr = {r["L"]: r["coefficient"] for r, _, _ in series.get("period", [])}
    if 2.0 in pr and 4.0 in pr:
        period = pr[2.0] - pr[4.0]
        out.append(("period_correction", period, "c(L = 2) - c(L = 4) at H = 1: the periodic images' share"))
    if 1.0 in pr and 2.0 in pr:
        out.append(("period_L1_minus_L2", pr[1.0] - pr[2.0], "c(L = 1) - c(L = 2) at H = 1"))
    wr = sorted([r for r, _, _ in series.get("width", [])], key=lambda r: r["transition"])
    if len(wr) >= 2:
        x = np.array([r["transition"] / r["cells_per_radius"] for r in wr])  # w dx / a
        y = np.array([r["coefficient"] for r in wr])
        s, c = np.polyfit(x, y, 1)
        out += [("width_c0", c, "width series: c extrapolated to a zero blend width at 6.4 cells per radius"),
                ("width_slope", s, "width series: dc / d(w dx / a)"),
                ("width_beta", s / (2 * c), "the effective radius's excess over the half-width, "
                                            "(a_eff - a) / (w dx), if c scales as (a_eff / a)^2")]
    # the walls again at the finer grid (two heights): k from the difference
    wf = {r["H"]: r["coefficient"] for r, _, _ in series.get("wallfine", [])}
    wall_fine = wall
    if 1.0 in wf and 1.5 in wf:
        kf = (wf[1.0] - wf[1.5]) / (0.1 ** 2 - (0.1 / 1.5) ** 2)
        wall_fine = kf * 0.01
        out += [("wallfine_k", kf, "the slope k_w at 12.8 cells per radius, from H = 1 and 1.5"),
                ("wallfine_correction", wall_fine, "k_w (a/H)^2 at a/H = 0.1 and 12.8 cells per radius")]
    rs = sorted([r for r, _, _ in series.get("res", [])], key=lambda r: -r["cells_per_radius"])
    for r in rs:
        # the area the smoothed interface adds: the blend 1 - H(phi) of eq. (3.5), half-width
        # w, integrated over a disc: pi a^2 + 2 pi w^2 (1/6 - 1/pi^2) (its odd part against r)
        w = r["transition"] / r["cells_per_radius"]
        out.append((f"area_excess_at_{r['cells_per_radius']:.1f}", 2 * (1 / 6 - 1 / math.pi ** 2) * w * w,
                    f"the blend's area over pi a^2, minus 1, at {r['cells_per_radius']:.1f} cells per radius"))
    if len(rs) >= 2:
        h = np.array([1 / r["cells_per_radius"] for r in rs])
        y = np.array([r["coefficient"] for r in rs])
        c1, c0 = np.polyfit(h[:2], y[:2], 1)
        out += [("res_c0_linear_finest_two", c0, "res series: first-order (Richardson) extrapolation of the finest two"),
                ("res_slope_finest_two", c1, "res series: dc / d(dx / a) of the finest two"),
                ("corrected_linear", c0 - wall_fine - period,
                 "that extrapolation minus the walls (at 12.8 cells per radius) and the images: compare with 2")]
        for r in rs:
            wc = wall if r["cells_per_radius"] < 10 else wall_fine
            out.append((f"corrected_at_{r['cells_per_radius']:.1f}", r["coefficient"] - wc - period,
                        f"c at {r['cells_per_radius']:.1f} cells per radius minus the walls' correction "
                        f"({'6.4' if r['cells_per_radius'] < 10 else '12.8'} cells per radius) and the images'"))
    return out


def plot(a, series, fits):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    ax = axes[0, 0]
    rs = sorted([r for r, _, _ in series.get("res", [])], key=lambda r: r["cells_per_radius"])
    if rs:
        h = np.array([1 / r["cells_per_radius"] for r in rs])
        y = np.array([r["coefficient"] for r in rs])
        ax.plot(h, y, "o", label="measured (H = 1, L = 2)")
        hh = np.linspace(0, h.max() * 1.05, 50)
        cor = [fits.get(f"corrected_at_{r['cells_per_radius']:.1f}") for r in rs]
        if all(c is not None for c in cor):
            ax.plot(h, cor, "D", mfc="none", label="minus the walls' and images' corrections")
        if "res_c0_linear_finest_two" in fits:
            ax.plot(hh, fits["res_c0_linear_finest_two"] + fits["res_slope_finest_two"] * hh, "--", lw=1,
                    label=f"linear, finest two: $c_0$ = {fits['res_c0_linear_finest_two']:.3f}")
        if "corrected_linear" in fits:
            ax.plot([0], [fits["corrected_linear"]], "k*", ms=10,
                    label=f"$c_0$ − walls − images = {fits['corrected_linear']:.3f}")
        ax.axhline(2, color="k", ls=":", lw=1, label="2-D Einstein: 2 (Brady 1984)")
        ax.axhspan(1.8, 2.2, color="0.9", zorder=0, label="±10 %")
        ax.set_xlabel(r"$\Delta x / a$")
        ax.set_ylabel(r"$(\eta_r - 1)/\phi$")
        ax.set_title("grid (blend half-width 3 cells)", fontsize=9)
        ax.set_xlim(left=0)
        ax.legend(fontsize=7, loc="upper left")
        ax.grid(alpha=0.3)
    ax = axes[0, 1]
    rr = sorted([r for r, _, _ in series.get("wall", [])], key=lambda r: r["a_over_H"])
    if rr:
        x = np.array([r["a_over_H"] ** 2 for r in rr])
        ax.plot(x, [r["coefficient"] for r in rr], "s", label=r"measured ($\Delta x$ = a/6.4, L = 2H)")
        xx = np.linspace(0, x.max() * 1.05, 20)
        ax.plot(xx, fits.get("wall_c0", 0) + fits.get("wall_k", 0) * xx, "-", lw=1,
                label=rf"{fits.get('wall_c0', 0):.3f} + {fits.get('wall_k', 0):.1f} $(a/H)^2$")
        ax.axvline(0.01, color="0.5", ls=":", lw=1, label="the test's cell, a/H = 0.1")
        ax.set_xlabel(r"$(a/H)^2$")
        ax.set_ylabel(r"$(\eta_r - 1)/\phi$")
        ax.set_title("walls (H varied at fixed a and grid)", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    ax = axes[1, 0]
    wr = sorted([r for r, _, _ in series.get("width", [])], key=lambda r: r["transition"])
    if wr:
        x = np.array([r["transition"] / r["cells_per_radius"] for r in wr])
        ax.plot(x, [r["coefficient"] for r in wr], "^", label=r"measured ($\Delta x$ = a/6.4, H = 1)")
        xx = np.linspace(0, x.max() * 1.05, 20)
        ax.plot(xx, fits.get("width_c0", 0) + fits.get("width_slope", 0) * xx, "-", lw=1,
                label=f"linear: {fits.get('width_c0', 0):.3f} at zero width")
        ax.set_xlabel(r"blend half-width $w_T \Delta x / a$ (solids.transition)")
        ax.set_ylabel(r"$(\eta_r - 1)/\phi$")
        ax.set_title("the smoothed interface's width", fontsize=9)
        ax.set_xlim(left=0)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    ax = axes[1, 1]
    for r, t, eta in sorted(series.get("res", []), key=lambda e: e[0]["cells_per_radius"]):
        line, = ax.plot(t, (eta - 1) / r["phi"], lw=0.8, label=f"{r['cells_per_radius']:.1f} cells per radius")
        t1 = t[-1]
        ax.axvspan(t1 * (1 - a.win), t1, color=line.get_color(), alpha=0.08)
        ax.hlines(r["coefficient"], t1 * (1 - a.win), t1, colors=line.get_color(), linestyles="--", lw=1)
    ax.set_ylim(1.5, 3.2)
    ax.set_xlabel(r"$\dot\gamma t$")
    ax.set_ylabel(r"$(\eta_r - 1)/\phi$")
    ax.set_title("time series (shaded: the averaging windows)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.suptitle("one free stiff disc (Ca = 0.01) in a wall-bounded periodic shear cell: the dilute coefficient",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "dilute_coefficient.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
