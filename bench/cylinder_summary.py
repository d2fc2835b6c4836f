#!/usr/bin/env python3
"""Summarise runs of scenes/cylinder_re20.toml (bench/run_cylinder.sh) into one CSV row each.

For each run directory: the last row of diagnostics.csv and its rows of solids.csv give the
force on the cylinder (solid0_fx, solid0_fy per unit depth), hence c_D = 2 F_x / (rho U^2 D), c_L = 2 F_y / (rho U^2 D)
with rho = 1, U = 0.2 (the mean inflow), D = 0.1; probe_p_front_back.csv gives
Delta p = p(0.15, 0.2) - p(0.25, 0.2); probe_u_wake.csv (u on y = 0.2 from the back of the
cylinder, x = 0.25, to x = 0.45) the recirculation length L_a = x_r - 0.25, x_r the last zero
of u (linear between samples) after which u stays positive. The reference bounds of
Schafer & Turek (1996), docs/references.md#cylinder-in-a-channel-at-re--20, are written as two more rows.
The cost of each run sits beside its accuracy: steps, wall time, threads and ms per step.

Usage: cylinder_summary.py [--keep CSV] [--convergence CSV] [--plot PNG] RUN_DIR... > results/cylinder_re20.csv
  --keep: the rows of an earlier summary (its runs' directories gone) are kept unless a RUN_DIR of
    the same name replaces them (bench/run_cylinder.sh KEEP=1: add variants without re-running
    the others).
  dp_fluid: Delta p from the fluid's pressure extrapolated to the surface points; L_a_centre:
    L_a from u on y = 0.2 itself, not the mean of the two rows beside it (probes that
    bench/run_cylinder.sh adds; both empty for runs without them).
  --convergence: per forcing and quantity, the error against the centre of the bounds on each
    grid (runs named <forcing>_dx_<dx>), the observed order between successive grids,
    log2(|e(dx)| / |e(dx/2)|), and from three successive grids the order of the differences,
    log2(|v(4h) - v(2h)| / |v(2h) - v(h)|) (Richardson: no reference value needed) with the
    limit v(h) + (v(h) - v(2h)) / (2^p - 1); standard library only.
  --plot: accuracy against cost (|error| of c_D, c_L, Delta p, L_a against wall time), one line
    per forcing over its grids, the dt studies as open markers (needs Debian's matplotlib).
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes"))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)

RHO, U_MEAN, D = 1.0, 0.2, 0.1
X_BACK = 0.25
BOUNDS = {"c_D": (5.57, 5.59), "c_L": (0.0104, 0.0110), "dp": (0.1172, 0.1176), "L_a": (0.0842, 0.0852),
          "dp_fluid": (0.1172, 0.1176), "L_a_centre": (0.0842, 0.0852)}


def read_csv(path):
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    return rows[0], rows[1:]


def header_value(path, key):
    with open(path) as f:
        for line in f:
            if line.startswith("# " + key + ":"):
                return line.split(":", 1)[1].strip()
    return ""


def recirculation(xs, us):
    last_neg = max((k for k, u in enumerate(us) if u < 0.0), default=None)
    if last_neg is None or last_neg + 1 >= len(us):
        return float("nan")
    x0, x1, u0, u1 = xs[last_neg], xs[last_neg + 1], us[last_neg], us[last_neg + 1]
    return x0 + (x1 - x0) * (-u0) / (u1 - u0) - X_BACK


def summarise(run):
    head, rows = read_csv(run + "/diagnostics.csv")
    # the last FULL step: a step cut short to land on the end time has a different slip in the
    # partly forced cells, so its force is off (results/validation.md, "Flow past a cylinder")
    k_dt = head.index("dt")
    dt_full = max(float(r[k_dt]) for r in rows)
    last = dict(zip(head, [r for r in rows if float(r[k_dt]) > 0.99 * dt_full][-1]))
    last.update({k: v[0] for k, v in solids_csv.wide_columns(run, [last["step"]]).items()})
    q = 0.5 * RHO * U_MEAN**2 * D
    _, pp = read_csv(run + "/probe_p_front_back.csv")
    _, uw = read_csv(run + "/probe_u_wake.csv")
    xs, us = [float(r[0]) for r in uw], [float(r[2]) for r in uw]
    timings = run + "/timings.csv"
    with open(run + "/scene.toml") as f:
        first = f.readline() + f.readline()  # the --set overrides are on the second line
    radius = "0.05"
    if "radius=" in first:
        radius = first.split("radius=")[1].split()[0].strip("'\"")
    name = run.rstrip("/").split("/")[-1]
    forcing = "diffuse"  # the scene's default
    if "forcing=" in first:
        forcing = first.split("forcing=")[1].split()[0].strip("'\"")
    if "_dx_" in name:  # bench/run_cylinder.sh's variant: <forcing>[+hold][+inc]_dx_...
        forcing = name.split("_dx_")[0]
    load = ""  # the 1-minute load average at the run's start and end (bench/run_cylinder.sh)
    if os.path.exists(run + "/load.txt"):
        with open(run + "/load.txt") as f:
            load = "-".join(f.read().split())
    # dp_fluid: the fluid's pressure extrapolated to the two surface points, the quadratic through
    # the samples 1, 2 and 3 dx from each along y = 0.2 (probes p_front_fluid, p_back_fluid that
    # bench/run_cylinder.sh adds; p(0) = 3 p(1) - 3 p(2) + p(3)): the probes of dp sit on the
    # surface, where the bilinear stencil mixes a fluid cell with a cell inside the body (the
    # sharp forcing fills those with the fluid's pressure at an image point sqrt(2) dx out), so dp
    # reads the pressure about one dx outside the surface
    dp_fluid = ""
    if os.path.exists(run + "/probe_p_front_fluid.csv") and os.path.exists(run + "/probe_p_back_fluid.csv"):
        _, pf = read_csv(run + "/probe_p_front_fluid.csv")  # from 3 dx to 1 dx in front of x = 0.15
        _, pb = read_csv(run + "/probe_p_back_fluid.csv")  # from 1 dx to 3 dx behind x = 0.25
        front = 3 * float(pf[2][2]) - 3 * float(pf[1][2]) + float(pf[0][2])
        back = 3 * float(pb[0][2]) - 3 * float(pb[1][2]) + float(pb[2][2])
        dp_fluid = f"{front - back:.5f}"
    # L_a_centre: the same from u on y = 0.2 itself. y = 0.2 is a face row on every grid, so the
    # probe's bilinear value there is the mean of the rows y = 0.2 -+ dx/2, which exceeds u on the
    # line by (dx/2)^2 u_yy / 2 where the wake's deficit makes u_yy > 0 (the zero moves upstream);
    # with the rows -+ 3 dx/2 (probes u_wake_below, u_wake_above that bench/run_cylinder.sh adds)
    # the cubic midpoint value (9 (u_1 + u_2) - (u_0 + u_3)) / 16 removes that bias
    la_centre = ""
    if os.path.exists(run + "/probe_u_wake_below.csv") and os.path.exists(run + "/probe_u_wake_above.csv"):
        _, lo = read_csv(run + "/probe_u_wake_below.csv")
        _, hi = read_csv(run + "/probe_u_wake_above.csv")
        uc = [(18 * m - float(a[2]) - float(b[2])) / 16 for m, a, b in zip(us, lo, hi)]
        la_centre = f"{recirculation(xs, uc):.5f}"
    return {
        "run": name,
        "forcing": forcing,
        "dx": round(2.2 / int(header_value(timings, "nx")), 6),
        "nx": header_value(timings, "nx"),
        "ny": header_value(timings, "ny"),
        "radius": radius,
        "threads": header_value(timings, "threads"),
        "dt": f"{float(last['dt']):.6g}",
        "steps": last["step"],
        "t_end": f"{float(last['time']):.4g}",
        "wall_s": f"{float(header_value(timings, 'wall_s')):.1f}",
        "ms_per_step": f"{1000 * float(header_value(timings, 'wall_s')) / max(1, int(last['step'])):.2f}",
        "load": load,
        "c_D": f"{float(last['solid0_fx']) / q:.5f}",
        "c_L": f"{float(last['solid0_fy']) / q:.5f}",
        "dp": f"{float(pp[0][2]) - float(pp[1][2]):.5f}",
        "L_a": f"{recirculation(xs, us):.5f}",
        "dp_fluid": dp_fluid,
        "L_a_centre": la_centre,
    }


QUANTITIES = ("c_D", "c_L", "dp", "L_a", "dp_fluid", "L_a_centre")


def centre(q):
    return 0.5 * (BOUNDS[q][0] + BOUNDS[q][1])


def grid_runs(out):
    """{forcing: [row, ...]} of the runs <forcing>_dx_<dx> (the grid study), coarse to fine."""
    by = {}
    for r in out:
        tail = r["run"].split("_dx_")[-1]
        if "_dx_" in r["run"] and all(c in "0123456789." for c in tail):
            by.setdefault(r["forcing"], []).append(r)
    for rows in by.values():
        rows.sort(key=lambda r: -float(r["dx"]))
    return by


def write_convergence(out, path):
    import math
    with open(path, "w") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["forcing", "quantity", "dx", "cells_per_D", "value", "error", "rel_error", "inside_bounds",
                    "order", "order_richardson", "limit_richardson", "steps", "wall_s", "threads"])
        for forcing, rows in grid_runs(out).items():
            for q in QUANTITIES:
                prev = None
                vals = []
                for r in rows:
                    if not r.get(q):  # a kept row from before the column existed
                        continue
                    v = float(r[q])
                    e = v - centre(q)
                    order = ""
                    if prev is not None and e != 0 and prev != 0:
                        order = f"{math.log2(abs(prev) / abs(e)):.2f}"
                    inside = BOUNDS[q][0] <= v <= BOUNDS[q][1]
                    vals.append(v)
                    rich = lim = ""
                    if len(vals) >= 3:
                        d1, d2 = vals[-3] - vals[-2], vals[-2] - vals[-1]
                        if d1 * d2 > 0 and abs(d1) > abs(d2):  # monotone and converging
                            pr = math.log2(abs(d1) / abs(d2))
                            rich, lim = f"{pr:.2f}", f"{v + (vals[-1] - vals[-2]) / (2**pr - 1):.5f}"
                    w.writerow([forcing, q, r["dx"], round(0.1 / float(r["dx"])), r[q], f"{e:.5f}",
                                f"{e / centre(q):.4f}", int(inside), order, rich, lim, r["steps"], r["wall_s"],
                                r["threads"]])
                    prev = e


def plot(out, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 4, figsize=(16, 4))  # c_D, c_L, dp, L_a (not dp_fluid)
    colours = {"diffuse": "tab:blue", "interpolated": "tab:orange", "sharp": "tab:green", "sharp+hold": "tab:purple",
               "sharp+inc": "tab:brown", "sharp+hold+inc": "tab:red", "sharp+hold+inc+rc": "tab:pink",
               "sharp+inc+rc": "tab:olive", "sharp+hold+inc+rc+quad": "tab:cyan"}
    by = grid_runs(out)
    for ax, q in zip(axes, QUANTITIES[:4]):
        for forcing, rows in by.items():
            xs = [float(r["wall_s"]) for r in rows]
            ys = [abs(float(r[q]) - centre(q)) / centre(q) for r in rows]
            ax.loglog(xs, ys, "o-", color=colours.get(forcing), label=forcing)
            for r, x, y in zip(rows, xs, ys):
                ax.annotate(f"{round(0.1 / float(r['dx']))}", (x, y), fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        grid = {id(r) for rows in by.values() for r in rows}
        for r in out:  # the dt study (and any other run): open markers
            if id(r) in grid:
                continue
            ax.loglog(float(r["wall_s"]), abs(float(r[q]) - centre(q)) / centre(q), "o", mfc="none",
                      color=colours.get(r["forcing"]))
        half = 0.5 * (BOUNDS[q][1] - BOUNDS[q][0]) / centre(q)
        ax.axhline(half, color="grey", ls=":", lw=1)
        ax.set_title(f"{q}: |error| / reference")
        ax.set_xlabel("wall time of the run (s)")
    axes[0].legend(fontsize=8)
    axes[0].set_ylabel("relative error against the centre of the bounds")
    fig.suptitle("Cylinder Re 20 (Schafer & Turek 2D-1): accuracy against cost; labels: cells per diameter; "
                 "open: the dt studies (dt/2, dt/4); dotted: half-width of the bounds", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    args = sys.argv[1:]
    conv = png = keep = None
    while args and args[0].startswith("--"):
        if args[0] == "--keep":
            keep = args[1]
        elif args[0] == "--convergence":
            conv = args[1]
        elif args[0] == "--plot":
            png = args[1]
        else:
            sys.exit(f"unknown option {args[0]}")
        args = args[2:]
    out = [summarise(r) for r in args]
    if keep and os.path.exists(keep):
        names = {r["run"] for r in out}
        with open(keep) as f:
            kept = [r for r in csv.DictReader(f) if r["run"] not in names and not r["run"].startswith("reference_")]
        for r in kept:
            for c in ("load", "dp_fluid", "L_a_centre"):
                r[c] = r.get(c) or ""
        out = sorted(kept + out, key=lambda r: r["run"])
    if conv:
        write_convergence(out, conv)
    if png:
        plot(out, png)
    cols = ["run", "forcing", "dx", "nx", "ny", "radius", "threads", "dt", "steps", "t_end", "wall_s", "ms_per_step",
            "load", "c_D", "c_L", "dp", "L_a", "dp_fluid", "L_a_centre"]
    w = csv.DictWriter(sys.stdout, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in out:
        w.writerow(r)
    for k, name in ((0, "reference_low"), (1, "reference_high")):
        w.writerow({c: (BOUNDS[c][k] if c in BOUNDS else (name if c == "run" else "")) for c in cols})


if __name__ == "__main__":
    main()
