#!/usr/bin/env python3
"""Energy budget of the split stress step at a disc's surface (docs/implicit.md).

Runs build/bench/refmap_energy_budget (bench/energy_budget/energy_budget.cpp: the terms and
their definitions) on scenes/disc_tgv.toml at 32^2, 400 steps, with the time step imposed
as in sweep a of bench/stability.py: dt = P dx / sqrt(2 mu_s / rho_s) through time.dt_max
(the advective limit does not bind at these stiffnesses), for the explicit stress and
time.solid_stress = "semi_implicit" (implicit viscosity) at k = 0.25 and 1, reach 0 and 2,
and "upper_convected".

The raw output (one row per step and ring of phi/dx, <raw>/<case>.csv) stays in --raw; into
--out (results/energy_budget) go, every energy divided by the initial energy E0 (kinetic; the
disc starts unstrained):
  summary.csv  per case: E_max, E_end, the step of the first 1 % rise, and the terms
               (bench/energy_budget/energy_budget.cpp) summed over the growth window: the 50
               steps before the total energy first exceeds 10 E0, or the last 100 steps of a
               run that never does; created = W_s + dE_xi + dE_band + dE_blend, the energy
               the stress coupling makes (kinetic energy the stress gives minus the elastic
               energy that pays for it)
  rings.csv    the same window per ring of phi/dx, with each ring's share of W_s and Pi
  steps.csv    per case at mu_s / rho_s = 1e3 and step: E / E0, the elastic energy, and W_s, Pi, W_i, W_v,
               W_proj summed over the solid side (phi < 0) and the fluid side (phi >= 0)

Usage: python3 bench/energy_budget.py [--bin build/bench/refmap_energy_budget] [--jobs 2]
                                      [--cases name,...] [--mu 1e2,1e3,1e4,1e5] [--steps 400]
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import csv
import math
import os
import subprocess
from collections import defaultdict
from coupling import with_coupling  # bench/coupling.py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes", "disc_tgv.toml")
SEMI = ['time.viscous="implicit"', 'time.solid_stress="semi_implicit"']
UC = ['time.viscous="implicit"', 'time.solid_stress="upper_convected"']


def cases(mus):
    out = []
    for mu in mus:
        out.append((f"explicit_mu{mu:g}_P0.5", mu, 0.5, []))
        for p in (2, 4):
            for k in (0.25, 1):
                for r in (0, 2):
                    out.append((f"semi_k{k:g}_r{r}_mu{mu:g}_P{p:g}", mu, p,
                                SEMI + [f"time.solid_implicit_k={k:g}", f"time.solid_implicit_reach={r}"]))
            out.append((f"uc_mu{mu:g}_P{p:g}", mu, p, UC))
            out.append((f"semi_k0.25_r0_viscexpl_mu{mu:g}_P{p:g}", mu, p,
                        ['time.solid_stress="semi_implicit"', "time.solid_implicit_k=0.25"]))
    return out


def run(case, binary, outdir, steps):
    name, mu, p, sets = case
    dt = p * (1.0 / 32) / math.sqrt(2.0 * mu)
    sets = sets + ["grid.nx=32", "grid.ny=32", f"solid.0.mu_s={mu:g}", f"time.dt_max={dt!r}",
                   "output.vtk=false"]
    cmd = [binary, SCENE, "--steps", str(steps), "--out", os.path.join(outdir, name + ".csv")]
    for s in with_coupling(sets):
        cmd += ["--set", s]
    r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    return name, r.returncode, r.stderr.strip(), " ".join(cmd[1:])


TERMS = ["W_s_step", "W_s", "Pi", "W_v", "W_i", "W_adv", "W_proj", "dE_xi", "dE_band", "dE_blend"]
KE_TERMS = ["W_adv", "W_s", "W_v", "W_i", "W_proj"]
EE_TERMS = ["dE_xi", "dE_band", "dE_blend"]


def load(path):
    """Per step: ke, ee and per ring (lo, hi) the terms."""
    steps = defaultdict(lambda: {"rings": {}})
    for r in csv.DictReader(open(path)):
        s = steps[int(r["step"])]
        s["ke"], s["ee"], s["dt"] = float(r["ke"]), float(r["ee"]), float(r["dt"])
        s["rings"][(float(r["ring_lo"]), float(r["ring_hi"]))] = {t: float(r[t]) for t in TERMS}
    return dict(sorted(steps.items()))


def summarise(name, path):
    """The growth window: the 50 steps before the total energy first exceeds 10 E0 (a run
    that blows up), else the last 100 steps; E0 the initial (kinetic) energy."""
    st = load(path)
    if not st:
        return None, []
    n0 = next(iter(st))
    first = st[n0]
    e0 = first["ke"] + first["ee"] - sum(v[t] for v in first["rings"].values() for t in KE_TERMS + EE_TERMS)
    e = {n: (s["ke"] + s["ee"]) / e0 for n, s in st.items()}
    over = [n for n in st if e[n] > 10.0]
    w1 = over[0] if over else list(st)[-1]
    w0 = max(n0, w1 - (49 if over else 99))
    rings = defaultdict(lambda: defaultdict(float))
    for n, s in st.items():
        if w0 <= n <= w1:
            for k, v in s["rings"].items():
                for t in TERMS:
                    rings[k][t] += v[t] / e0
    tot = {t: sum(r[t] for r in rings.values()) for t in TERMS}
    rise = next((n for n in st if e[n] > 1.01), "")
    info = dict(case=name, e0=f"{e0:.6g}", steps=list(st)[-1], rise_1pct_step=rise,
                e_max=f"{max(e.values()):.4g}", e_end=f"{e[list(st)[-1]]:.4g}", window=f"{w0}-{w1}",
                created=f"{tot['W_s'] + sum(tot[t] for t in EE_TERMS):.4g}",
                **{t: f"{tot[t]:.4g}" for t in TERMS})
    # shares of the stress work by ring (of the window's total W_s), and of -Pi
    ws, pi = tot["W_s"] or 1e-300, tot["Pi"] or 1e-300
    ring_rows = [dict(case=name, window=f"{w0}-{w1}", ring_lo=k[0], ring_hi=k[1],
                      **{t: f"{v[t]:.4g}" for t in TERMS},
                      W_s_share=f"{v['W_s'] / ws:.3f}", Pi_share=f"{v['Pi'] / pi:.3f}")
                 for k, v in sorted(rings.items())]
    return info, ring_rows


def step_rows(name, path, e0):
    """Per step: the total energy / E0 and the terms / E0 summed over the solid side
    (phi < 0) and the fluid side (phi >= 0) of the blend."""
    out = []
    for n, s in load(path).items():
        row = dict(case=name, step=n, E=f"{(s['ke'] + s['ee']) / e0:.5g}", ee=f"{s['ee'] / e0:.4g}")
        for side, pick in (("solid", lambda k: k[0] < 0), ("fluid", lambda k: k[0] >= 0)):
            for t in ("W_s", "Pi", "W_i", "W_v", "W_proj"):
                row[f"{t}_{side}"] = f"{sum(v[t] for k, v in s['rings'].items() if pick(k)) / e0:.4g}"
        row["dE"] = f"{sum(v[t] for v in s['rings'].values() for t in EE_TERMS) / e0:.4g}"
        out.append(row)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bench", "refmap_energy_budget"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "energy_budget"))
    ap.add_argument("--raw", default="/tmp/refmap_energy_budget")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--cases", default="")
    ap.add_argument("--mu", default="1e2,1e3,1e4,1e5")
    ap.add_argument("--steps", type=int, default=400)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.raw, exist_ok=True)
    todo = cases([float(m) for m in args.mu.split(",")])
    if args.cases:
        keep = args.cases.split(",")
        todo = [c for c in todo if c[0] in keep]
    with cf.ThreadPoolExecutor(args.jobs) as ex:
        for name, rc, err, cmd in ex.map(lambda c: run(c, args.bin, args.raw, args.steps), todo):
            print(f"{name}: exit {rc} {err}", flush=True)
    infos, rings, steps = [], [], []
    for name, *_ in todo:
        path = os.path.join(args.raw, name + ".csv")
        info, rr = summarise(name, path)
        if info:
            infos.append(info)
            rings += rr
            if name.endswith(("mu1000_P0.5", "mu1000_P2", "mu1000_P4")):  # the size of results/
                steps += step_rows(name, path, float(info["e0"]))
    for fname, rows in (("summary.csv", infos), ("rings.csv", rings), ("steps.csv", steps)):
        if rows:
            with open(os.path.join(args.out, fname), "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=list(rows[0]))
                w.writeheader()
                w.writerows(rows)


if __name__ == "__main__":
    main()
