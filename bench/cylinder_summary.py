#!/usr/bin/env python3
"""Summarise runs of scenes/cylinder_re20.toml (bench/run_cylinder.sh) into one CSV row each.

For each run directory: the last row of diagnostics.csv and its rows of solids.csv give the
force on the cylinder (solid0_fx, solid0_fy per unit depth), hence c_D = 2 F_x / (rho U^2 D), c_L = 2 F_y / (rho U^2 D)
with rho = 1, U = 0.2 (the mean inflow), D = 0.1; probe_p_front_back.csv gives
Delta p = p(0.15, 0.2) - p(0.25, 0.2); probe_u_wake.csv (u on y = 0.2 from the back of the
cylinder, x = 0.25, to x = 0.45) the recirculation length L_a = x_r - 0.25, x_r the last zero
of u (linear between samples) after which u stays positive. The reference bounds of
Schafer & Turek (1996), docs/references.md#cylinder-in-a-channel-at-re--20, are written as two more rows.
Standard library only. Usage: cylinder_summary.py RUN_DIR... > results/cylinder_re20.csv
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes"))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)

RHO, U_MEAN, D = 1.0, 0.2, 0.1
X_BACK = 0.25
BOUNDS = {"c_D": (5.57, 5.59), "c_L": (0.0104, 0.0110), "dp": (0.1172, 0.1176), "L_a": (0.0842, 0.0852)}


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
    return {
        "run": run.rstrip("/").split("/")[-1],
        "dx": round(2.2 / int(header_value(timings, "nx")), 6),
        "nx": header_value(timings, "nx"),
        "ny": header_value(timings, "ny"),
        "radius": radius,
        "threads": header_value(timings, "threads"),
        "dt": f"{float(last['dt']):.6g}",
        "steps": last["step"],
        "t_end": f"{float(last['time']):.4g}",
        "wall_s": f"{float(header_value(timings, 'wall_s')):.1f}",
        "c_D": f"{float(last['solid0_fx']) / q:.5f}",
        "c_L": f"{float(last['solid0_fy']) / q:.5f}",
        "dp": f"{float(pp[0][2]) - float(pp[1][2]):.5f}",
        "L_a": f"{recirculation(xs, us):.5f}",
    }


def main():
    out = [summarise(r) for r in sys.argv[1:]]
    cols = list(out[0].keys())
    w = csv.DictWriter(sys.stdout, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in out:
        w.writerow(r)
    for k, name in ((0, "reference_low"), (1, "reference_high")):
        w.writerow({c: (BOUNDS[c][k] if c in BOUNDS else (name if c == "run" else "")) for c in cols})


if __name__ == "__main__":
    main()
