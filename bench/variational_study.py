#!/usr/bin/env python3
"""Issue 26: the variational (energy-consistent) solid force on disc_tgv past the explicit step.

Runs disc_tgv (grid N^2, 400 steps) for mu_s / rho_s in MUS and the solid step factor P in PS
(dt = P dx / sqrt(2 mu_s / rho_s), imposed as time.dt_max for the implicit methods and as
solids.solid_cfl for the explicit ones) with each METHOD below, one thread each, and writes
one row per run to results/implicit_variational.csv: exit code, steps, the largest total
energy (kinetic + elastic) over its start, its growth over the second half (largest energy
there over the value at the middle row), the largest area drift, the final energy.

    python3 bench/variational_study.py     # the whole PLAN below, ~3 min on a shared 2-core machine
    python3 bench/variational_study.py [--bin build/refmap] [--out results] [--grid 64]
                                       [--methods a,b --mus 100,1e5 --ps 1,2,4,8,16]   # a subset

docs/implicit.md ("The variational force") and results/implicit.md read this CSV.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scenes"))
import solids_csv  # noqa: E402
from coupling import with_coupling  # bench/coupling.py

SEMI = ['time.viscous="implicit"', 'time.solid_stress="semi_implicit"']
METHODS = {
    # the paper's cell stress, explicit (P through solids.solid_cfl)
    "explicit_cell": (False, []),
    # the variational force, explicit
    "explicit_variational": (False, ['solids.stress_discretisation="variational"']),
    # today's semi-implicit splitting with the cell stress (docs/implicit.md), k = 0.5
    "semi_cell_k0.5": (True, SEMI + ["time.solid_implicit_k=0.5"]),
    # the same splitting on the variational force, k = 0.5 and 0.25
    "semi_variational_k0.5": (True, SEMI + ["time.solid_implicit_k=0.5",
                                            'solids.stress_discretisation="variational"']),
    "semi_variational_k0.25": (True, SEMI + ["time.solid_implicit_k=0.25",
                                             'solids.stress_discretisation="variational"']),
    # the variational force with the narrower energy weight w_V = 0.5 (1.5 cells inset)
    "explicit_variational_w0.5": (False, ['solids.stress_discretisation="variational"',
                                          "solids.variational_width=0.5"]),
    # the variational force with xi moved by the cell velocity through the same central
    # gradient (solids.xi_velocity = "cell" with xi_advection = "central", the transport it pairs with exactly)
    "explicit_variational_cell": (False, ['solids.stress_discretisation="variational"',
                                          'solids.xi_velocity="cell"', 'solids.xi_advection="central"']),
    "semi_variational_k0.5_cell": (True, SEMI + ["time.solid_implicit_k=0.5", 'solids.xi_velocity="cell"', 'solids.xi_advection="central"',
                                                 'solids.stress_discretisation="variational"']),
    "semi_variational_k0.5_w0.5": (True, SEMI + ["time.solid_implicit_k=0.5", "solids.variational_width=0.5",
                                                 'solids.stress_discretisation="variational"']),
}

# what results/implicit_variational.csv holds (the default run): every method at 1e2 and 1e5,
# the two semi-implicit variational ones also at 1e3 and 1e4 past the cell limit
PLAN = [(list(METHODS), "100,1e5", "0.5,1,4,8,16"),
        (["semi_variational_k0.25", "semi_variational_k0.5"], "1e3,1e4", "4,8"),
        (["semi_variational_k0.5_cell"], "1e3,1e4", "1,4,8")]


def run(binary, raw, tag, sets):
    out = os.path.join(raw, tag)
    shutil.rmtree(out, ignore_errors=True)
    cmd = [binary, "run", os.path.join(ROOT, "scenes", "disc_tgv.toml"), "-o", out, "-j", "1", "-q"]
    for s in with_coupling(sets):
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    if not os.path.exists(os.path.join(out, "diagnostics.csv")):
        return dict(rc=p.returncode, failure=p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "")
    head, rows = solids_csv.read_rows(os.path.join(out, "diagnostics.csv"))
    res = dict(rc=p.returncode, failure=p.stderr.strip().splitlines()[-1] if p.returncode else "")
    if not rows:
        return res
    col = {h: [r[k] for r in rows] for k, h in enumerate(head)}
    e = col["total_energy"]
    area = solids_csv.wide_columns(out, col["step"]).get("solid0_area", [])
    mid = len(e) // 2
    res.update(steps=int(col["step"][-1]), t_end=col["time"][-1], e_max=max(e) / e[0],
               late_growth=max(e[mid:]) / e[mid] if e[mid] > 0 else float("nan"), e_end=e[-1] / e[0],
               area_drift=max(abs(a - area[0]) / area[0] for a in area if not math.isnan(a)) if area else float("nan"))
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "refmap"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results"))
    ap.add_argument("--raw", default="/tmp/refmap_variational_study")
    ap.add_argument("--grid", type=int, default=64)
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--mus", default="100,1e5")
    ap.add_argument("--ps", default="0.5,1,2,4,8,16")
    ap.add_argument("--steps", type=int, default=400)
    a = ap.parse_args()
    path = os.path.join(a.out, "implicit_variational.csv")
    cols = ["method", "grid", "mu_s_over_rho_s", "P", "rc", "steps", "t_end", "e_max", "late_growth", "e_end",
            "area_drift", "failure"]
    old = []
    if os.path.exists(path):  # rows of other (method, grid, mu, P) are kept
        with open(path) as f:
            old = list(csv.DictReader(f))
    new = []
    n = a.grid
    plan = [(a.methods.split(","), a.mus, a.ps)] if a.methods else PLAN
    for m, mus, ps in [(m, mus, ps) for (ms, mus, ps) in plan for m in ms]:
        implicit, sets0 = METHODS[m]
        for mu in [float(x) for x in mus.split(",")]:
            for p in [float(x) for x in ps.split(",")]:
                if not implicit and p >= 8:  # solids.solid_cfl must stay below 8 (scene_keys)
                    continue
                sets = sets0 + [f"grid.nx={n}", f"grid.ny={n}", "time.end=100", f"time.max_steps={a.steps}",
                                "output.vtk=false", f"solid.0.mu_s={mu:g}"]
                if implicit:
                    sets.append(f"time.dt_max={p / n / math.sqrt(2.0 * mu)!r}")
                else:
                    sets.append(f"solids.solid_cfl={p:g}")
                r = run(a.bin, a.raw, f"{m}_n{n}_mu{mu:g}_P{p:g}", sets)
                row = dict(method=m, grid=n, mu_s_over_rho_s=f"{mu:g}", P=f"{p:g}", **r)
                print(", ".join(f"{k}={row.get(k, '')}" for k in cols if k != "failure"), row.get("failure", ""),
                      flush=True)
                new.append(row)
    keys = {(r["method"], str(r["grid"]), r["mu_s_over_rho_s"], r["P"]) for r in new}
    rows = [r for r in old if (r["method"], r["grid"], r["mu_s_over_rho_s"], r["P"]) not in keys] + new
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items() if k in cols})


if __name__ == "__main__":
    main()
