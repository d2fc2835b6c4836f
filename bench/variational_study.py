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
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
import disc_study  # noqa: E402  (bench/disc_study.py)

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
    return disc_study.run_disc_tgv(binary, raw, tag, sets)[0]


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
    old = disc_study.read_rows(path)  # rows of other (method, grid, mu, P) are kept
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
    disc_study.write_merged(path, cols, old, new)


if __name__ == "__main__":
    main()
