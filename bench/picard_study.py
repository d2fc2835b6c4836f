#!/usr/bin/env python3
"""Issue 26, items 2-3: the fixed-point iteration of the whole step with xi moved by the new
velocity (time.solid_picard_iterations; solver/model/solid_picard.cpp, docs/implicit.md "The
implicit step in xi") on disc_tgv past the explicit solid step.

disc_tgv at grid N^2 (default 64), mu_s / rho_s in MUS, the solid step factor P in PS
(dt = P dx / sqrt(2 mu_s / rho_s) through time.dt_max), every run to the same end time
T = 128 * 8 dx / sqrt(2 mu_s / rho_s) (128 steps at P = 8, --steps8), one thread each; the reference is
the explicit cell-stress run at P = 0.5 (solids.solid_cfl = 0.5) to the same T. One row per
run to results/implicit_picard.csv: exit code, steps, the largest total energy (kinetic +
elastic) over its start, its growth over the second half, the largest area drift, the
failure (a fold or a blow-up: the health check's message), ke_dev_explicit (the largest
|KE(t) - KE_ref(t)| over the run, in % of KE(0), KE_ref interpolated in t), ke_dev_verlet (the
same against a second reference, the default explicit coupling, velocity Verlet, at the default
P = 0.5: row explicit_verlet, whose ke_dev_explicit is the gap of the two references),
e_dev_explicit (the same of the total energy KE + elastic, which the exchange between the two
leaves alone, so a phase error of the oscillation does not enter it), the last
iteration's relative velocity change (picard_change: median and largest over the steps),
passes per step, multigrid cycles per step of all passes (pressure and velocity) and the
same over the reference run's pressure cycles per step ("cost": pressure-solve units), and the
velocity solves' cycles alone in the same units (velocity_cost_pressure_units).

    python3 bench/picard_study.py            # the PLAN below (~15 min on a 2-core machine at load 10)
    python3 bench/picard_study.py --plan trapezoidal   # PLAN_TRAP: time.solid_picard_force = "trapezoidal"
    python3 bench/picard_study.py --plan anderson      # PLAN_AA: time.solid_picard_anderson
    python3 bench/picard_study.py [--bin build/refmap] [--grid 64] [--methods a,b --mus 100,1e4 --ps 2,4,8]
"""
import argparse
import bisect
import math
import os
import statistics

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
import disc_study  # noqa: E402  (bench/disc_study.py)

SEMI = ['time.viscous="implicit"', 'time.solid_stress="semi_implicit"']


def picard(n, theta, defect=True, k=None, force="new"):
    s = SEMI + [f"time.solid_picard_iterations={n}", f"time.solid_picard_theta={theta}",
                f"time.solid_picard_defect={'true' if defect else 'false'}"]
    if force != "new":
        s.append(f'time.solid_picard_force="{force}"')
    return s + [f"time.solid_implicit_k={k if k is not None else 0.5}"]


def trap(n, k=0.25, reach=2):
    """The trapezoidal force (mean of F(xi^n) and the pass's), theta = 1/2, defect form;
    k = theta / 2 makes one pass exact in the 1-D model (solver/model/solid_picard.cpp)."""
    return picard(n, 0.5, k=k, force="trapezoidal") + ([f"time.solid_implicit_reach={reach}"] if reach else [])


METHODS = {
    # today's semi-implicit splitting (one pass, xi moved by u^n), k = 0.5
    "semi_k0.5": SEMI + ["time.solid_implicit_k=0.5"],
    # defect correction through the eta operator, xi by the midpoint velocity, k = theta = 1/2
    "picard_defect_th0.5_n2": picard(2, 0.5),
    "picard_defect_th0.5_n4": picard(4, 0.5),
    # the same with plain repetitions of the semi-implicit step (the eta term kept)
    "picard_plain_th0.5_n2": picard(2, 0.5, defect=False),
    # backward Euler in the transport, k = theta = 1
    "picard_defect_th1_n2": picard(2, 1.0, k=1.0),
    # the defect form with the preconditioner's eta reaching 2 cells further into the fluid
    # (time.solid_implicit_reach: in the defect form it changes the iteration, not its fixed point)
    "picard_defect_th0.5_n2_r2": picard(2, 0.5) + ["time.solid_implicit_reach=2"],
    # time.solid_picard_force = "trapezoidal": the kick with (F^n + F^{n+1,(k)}) / 2, theta = 1/2,
    # k = 1/4 (= theta / 2), reach 2 unless named otherwise
    "picard_trap_n1_r2": trap(1),
    "picard_trap_n2_r2": trap(2),
    "picard_trap_n3_r2": trap(3),
    "picard_trap_n6_r2": trap(6),
    # the force of xi^{n+1} with as many passes, for the damping against N
    "picard_defect_th0.5_n6_r2": picard(6, 0.5) + ["time.solid_implicit_reach=2"],
    "picard_trap_n2_r0": trap(2, reach=0),
    "picard_trap_n2_r2_k0.5": trap(2, k=0.5),
    # time.solid_picard_anderson = m: Anderson acceleration of the passes (depth m)
    "picard_trap_n4_r2": trap(4),
    "picard_trap_n2_r2_aa1": trap(2) + ["time.solid_picard_anderson=1"],
    "picard_trap_n4_r2_aa2": trap(4) + ["time.solid_picard_anderson=2"],
    "picard_trap_n8_r2_aa4": trap(8) + ["time.solid_picard_anderson=4"],
    "picard_defect_th0.5_n2_r2_aa1": picard(2, 0.5) + ["time.solid_implicit_reach=2", "time.solid_picard_anderson=1"],
    "picard_defect_th0.5_n4_r2_aa2": picard(4, 0.5) + ["time.solid_implicit_reach=2", "time.solid_picard_anderson=2"],
}
PLAN = [(["semi_k0.5", "picard_defect_th0.5_n2"], "100,1e4", "2,4,8"),
        (["picard_plain_th0.5_n2", "picard_defect_th1_n2"], "100,1e4", "8"),
        (["picard_defect_th0.5_n4", "picard_defect_th0.5_n2_r2"], "100,1e4", "4,8"),
        (["picard_defect_th0.5_n2_r2"], "1e5,100", "8,16")]
# the trapezoidal force (--plan trapezoidal)
PLAN_TRAP = [(["picard_trap_n2_r2"], "100,1e4,1e5", "4,8"),
             (["picard_trap_n1_r2", "picard_trap_n3_r2", "picard_trap_n2_r0", "picard_trap_n2_r2_k0.5"], "100,1e4", "4,8"),
             (["picard_trap_n6_r2", "picard_defect_th0.5_n6_r2"], "100", "4")]
# Anderson acceleration of the passes (--plan anderson): the trapezoidal force at N = 4 without
# and with it, N = 8 with depth 4, and the force of xi^{n+1} with it
PLAN_AA = [(["picard_trap_n4_r2", "picard_trap_n2_r2_aa1", "picard_trap_n4_r2_aa2", "picard_trap_n8_r2_aa4",
             "picard_defect_th0.5_n2_r2_aa1", "picard_defect_th0.5_n4_r2_aa2"], "100,1e4", "4,8")]


def run(binary, raw, tag, sets):
    res, col = disc_study.run_disc_tgv(binary, raw, tag, sets)
    if col is None:
        return res, None
    res.update(poisson_per_step=statistics.mean(col["poisson_iterations"][1:] or [0]),
               wall_per_step=col["wall_time"][-1] / max(1, len(col["step"]) - 1))
    if "picard_change" in col:
        ch = col["picard_change"][1:]
        res.update(change_median=statistics.median(ch), change_max=max(ch),
                   cycles_per_step=statistics.mean(col["picard_cycles"][1:]))
        if "picard_velocity_cycles" in col:
            res.update(velocity_cycles_per_step=statistics.mean(col["picard_velocity_cycles"][1:]))
    elif "implicit_iterations" in col:
        res.update(cycles_per_step=statistics.mean(
            [a + b for a, b in zip(col["poisson_iterations"][1:], col["implicit_iterations"][1:])]),
                   velocity_cycles_per_step=statistics.mean(col["implicit_iterations"][1:]))
    else:
        res.update(cycles_per_step=res["poisson_per_step"])
    return res, (col["time"], col["kinetic_energy"], col["total_energy"])


def ke_dev(series, ref, k=1):
    """Largest |KE(t) - KE_ref(t)| over the run's rows, in % of KE(0) (KE_ref linear in t);
    k = 2: the same of the total energy E = KE + elastic (e_dev_explicit)."""
    t, ke = series[0], series[k]
    tr, kr = ref[0], ref[k]
    dev = 0.0
    for ti, ki in zip(t, ke):
        j = min(max(bisect.bisect_left(tr, ti), 1), len(tr) - 1)
        w = (ti - tr[j - 1]) / (tr[j] - tr[j - 1]) if tr[j] > tr[j - 1] else 0.0
        dev = max(dev, abs(ki - ((1 - w) * kr[j - 1] + w * kr[j])))
    return 100.0 * dev / ke[0]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "refmap"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results"))
    ap.add_argument("--raw", default="/tmp/refmap_picard_study")
    ap.add_argument("--grid", type=int, default=64)
    ap.add_argument("--methods", default="")
    ap.add_argument("--mus", default="100,1e4")
    ap.add_argument("--ps", default="2,4,8")
    ap.add_argument("--steps8", type=int, default=128, help="steps at P = 8 (sets the end time T)")
    ap.add_argument("--plan", choices=["new", "trapezoidal", "anderson"], default="new",
                    help="without --methods: PLAN (the force of xi^{n+1}), PLAN_TRAP (the trapezoidal force) "
                         "or PLAN_AA (Anderson acceleration of the passes)")
    a = ap.parse_args()
    path = os.path.join(a.out, "implicit_picard.csv")
    cols = ["method", "grid", "mu_s_over_rho_s", "P", "rc", "steps", "t_end", "e_max", "late_growth", "e_end",
            "area_drift", "ke_dev_explicit", "e_dev_explicit", "ke_dev_verlet", "change_median", "change_max", "passes", "cycles_per_step",
            "cost_pressure_units", "velocity_cost_pressure_units", "wall_per_step", "failure"]
    old = disc_study.read_rows(path)  # rows of other (method, grid, mu, P) are kept
    n = a.grid
    plans = {"new": PLAN, "trapezoidal": PLAN_TRAP, "anderson": PLAN_AA}
    plan = [(a.methods.split(","), a.mus, a.ps)] if a.methods else plans[a.plan]
    refs = {}
    new = []
    for ms, mus, ps in plan:
        for mu in [float(x) for x in mus.split(",")]:
            c = math.sqrt(2.0 * mu)
            t_end = a.steps8 * 8.0 / n / c
            base = [f"grid.nx={n}", f"grid.ny={n}", f"time.end={t_end!r}", "output.vtk=false", f"solid.0.mu_s={mu:g}"]
            if mu not in refs:
                r, series = run(a.bin, a.raw, f"explicit_n{n}_mu{mu:g}_P0.5", base + ["solids.solid_cfl=0.5"])
                refs[mu] = (series, r.get("poisson_per_step", float("nan")))
                row = dict(method="explicit_cell", grid=n, mu_s_over_rho_s=f"{mu:g}", P="0.5", passes=1,
                           cost_pressure_units=1.0, **r)
                print(", ".join(f"{k}={row.get(k, '')}" for k in cols), flush=True)
                new.append(row)
                # the default explicit coupling (velocity Verlet) at the default P: the second
                # reference (ke_dev_verlet); its row's ke_dev_explicit is the two references' gap
                r, vseries = run(a.bin, a.raw, f"explicit_verlet_n{n}_mu{mu:g}_P0.5",
                                 base + ["solids.solid_cfl=0.5", 'time.elastic_coupling="verlet"'])
                refs[mu] += (vseries,)
                row = dict(method="explicit_verlet", grid=n, mu_s_over_rho_s=f"{mu:g}", P="0.5", passes=1,
                           cost_pressure_units=r.get("poisson_per_step", float("nan")) / refs[mu][1], **r)
                if vseries and series:
                    row["ke_dev_explicit"] = ke_dev(vseries, series)
                    row["e_dev_explicit"] = ke_dev(vseries, series, k=2)
                print(", ".join(f"{k}={row.get(k, '')}" for k in cols), flush=True)
                new.append(row)
            for m in ms:
                for p in [float(x) for x in ps.split(",")]:
                    sets = METHODS[m] + base + [f"time.dt_max={p / n / c!r}"]
                    r, series = run(a.bin, a.raw, f"{m}_n{n}_mu{mu:g}_P{p:g}", sets)
                    passes = 1
                    for s in METHODS[m]:
                        if s.startswith("time.solid_picard_iterations="):
                            passes += int(s.split("=")[1])
                    row = dict(method=m, grid=n, mu_s_over_rho_s=f"{mu:g}", P=f"{p:g}", passes=passes, **r)
                    if series and refs[mu][0]:
                        row["ke_dev_explicit"] = ke_dev(series, refs[mu][0])
                        row["e_dev_explicit"] = ke_dev(series, refs[mu][0], k=2)
                    if series and refs[mu][2]:
                        row["ke_dev_verlet"] = ke_dev(series, refs[mu][2])
                    if "cycles_per_step" in r:
                        row["cost_pressure_units"] = r["cycles_per_step"] / refs[mu][1]
                    if "velocity_cycles_per_step" in r:  # the velocity solves alone (issue 26's cost goal)
                        row["velocity_cost_pressure_units"] = r["velocity_cycles_per_step"] / refs[mu][1]
                    print(", ".join(f"{k}={row.get(k, '')}" for k in cols), flush=True)
                    new.append(row)
    disc_study.write_merged(path, cols, old, new)


if __name__ == "__main__":
    main()
