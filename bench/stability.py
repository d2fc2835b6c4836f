#!/usr/bin/env python3
"""Where each method fails: stability and robustness maps (results/stability.md).

Runs build/refmap on coarse grids with --set overrides (one thread per run, --jobs runs at
once) and classifies every run from its own exit code, stderr and diagnostics.csv:

  stable      exit 0 and accurate: area drift <= 1 % (resolution sweep: the area error
              <= 1 %), total energy (kinetic + elastic) never more than 1 % above its
              start (every run here is viscous, so it may only fall; it oscillates by
              ~15 % between kinetic and elastic on these grids, so a rise above the running
              minimum would not separate stable from unstable)
  inaccurate  exit 0 but one of those measures over its bound (the measure is recorded)
  stopped     exit 3: a health check stopped the run (the cause is the message on stderr:
              folded reference map, kinetic-energy blow-up, solid vanished, ...), or exit 2
              (the scene was refused at the start, e.g. a solid too small for its band)
  crashed     any other exit code (must not occur)

Sweeps (scene scenes/disc_tgv.toml, a soft disc R = 0.2 in a decaying Taylor-Green
vortex, free-slip box):
  a  solid time-step factor P (solids.solid_cfl; dt <= P dx / sqrt(2 mu_s / rho_s)) against
     the stiffness mu_s / rho_s = 1e2 .. 1e5 (the solid limit then binds, not the
     advective one), 400 steps, for stress_discretisation x conservative x xi_advection;
     and the semi-implicit method (time.viscous = "implicit", time.solid_stress =
     "semi_implicit", docs/implicit.md; k = 0.5, 0.1 and 2), which has no solid limit: its P is
     imposed through time.dt_max = P dx / sqrt(2 mu_s / rho_s), up to P = 128, and where the
     advective limit binds first the P actually used is p_effective
  b  flow amplitude A / A0 (initial.amplitude, A0 = 0.05 * 2 pi as the scene) until the map
     folds, the area drifts or the run stops, 64 x 64 (R/dx = 12.8), to t = 2, for the extrapolations lsq (radius
     2.83 and 5.66) and pde, and lsq 2.83 with the non-conservative form; the strain reached
     is the largest principal stretch lambda from the largest normal stress
     sigma_max = mu_s (tr b - 2) assuming det b = 1: tr b = lambda^2 + lambda^-2, over the
     rows before the failing state; also the semi-implicit method (k = 0.5, lsq 2.83)
  c  density ratio rho_s / rho_f = 1e-3 .. 1e3 at mu_s / rho_s = 0.5 (the shear-wave speed
     and so the solid time step stay the scene's), 48 x 48, to t = 1, without gravity and
     with g = 1 downwards (then no energy bound: potential energy is released), for the
     multigrid and (full study) the plain CG pressure solve; a run whose pressure solve ends
     above solver.tol in any step is `inaccurate` ("Poisson not converged"); the iterations
     per step are recorded (poisson_iter_mean / _max)
  d  contact, scenes/wall_microgravity.toml (a disc launched at the bottom wall, no gravity),
     48 x 48, to t = 0.5: the impact speed V with the contact strength held at the scene's
     (velocity_scale 1.5), and the contact stiffness at V = 3; the same two for two such
     discs (the second added by --set) launched head-on at each other at V each, to t = 0.3;
     `inaccurate` also when a disc overlaps the wall or another solid (gap_wall / gap_solid
     < 0 in any row of any solid), and the energy bound includes the contact spring's energy
  e  resolution R / dx = 2 .. 16 (grid.nx = ny = 5 R/dx) at A0, to t = 2, for the same
     extrapolations; lost when the area error exceeds 10 % or the level set empties

For each method the limit is the largest swept value still `stable` below the first value
that is not (sweep e and the contact stiffness: the smallest value from which every larger
one is stable; sweep c: the range of stable ratios around 1, "lo..hi").

Then (--figure yes|only) stability_failures.png: one run just past each limit found
(SNAPSHOTS), the state a health check refused (frame_failed.vti) or the frame of the event.

The area drift is that of every solid. Usage: python3 bench/stability.py [--quick] [--bin build/refmap] [--out results] [--jobs 2]
                                  [--sweeps a,b,c,d,e] [--figure yes|no|only] [--charts-only]
(--charts-only: redraw the charts from <out>/stability.csv and stability_limits.csv, running
nothing; the solid time-step chart marks the binary's default solids.solid_cfl)
Writes <out>/stability.csv, <out>/stability_limits.csv, <out>/stability_<sweep>.png and
<out>/stability_failures.png; the raw
runs go to <raw> (default /tmp/refmap_stability, not kept).
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes"))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)
from coupling import with_coupling  # bench/coupling.py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "scenes")
A0 = 0.3141592653589793  # the scene's amplitude, U0 2 pi with U0 = 0.05
R = 0.2                  # the disc's radius in the scene
MU_S = 0.5               # the scene's mu_s (rho_s = 1)
POISSON_TOL = 1e-9       # the scenes' solver.tol (relative residual)

COLS = ["sweep", "scene", "method", "stress_discretisation", "conservative", "xi_advection",
        "extrapolation", "lsq_radius", "param", "value", "param2", "value2", "outcome",
        "t_event", "step_event", "measure", "measure_value", "cause", "max_stretch",
        "min_dt", "p_effective", "poisson_iter_mean", "poisson_iter_max", "steps", "wall_s",
        "energy_late_growth"]


# ------------------------------------------------------------------ one run
def run_one(job, binary, raw):
    out = os.path.join(raw, job["tag"])
    shutil.rmtree(out, ignore_errors=True)
    scene = os.path.join(SCENES, job.get("scene", "disc_tgv") + ".toml")
    cmd = [binary, "run", scene, "-o", out, "-j", "1", "-q"]
    for s in with_coupling(job["sets"]):
        cmd += ["--set", s]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    job = dict(job)
    job["rc"] = p.returncode
    job["stderr"] = p.stderr.strip()
    job["wall_s"] = time.time() - t0
    job["diag"] = read_diag(out)
    job["failed_frame"] = os.path.exists(os.path.join(out, "frame_failed.vti"))
    return job


def read_diag(run):
    """diagnostics.csv of RUN as columns, with the per-solid ones of solids.csv (solid<k>_<q>)."""
    path = os.path.join(run, "diagnostics.csv")
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    if len(rows) < 2:
        return {}
    head, data = rows[0], rows[1:]
    arr = np.array([[float(x) for x in r] for r in data if len(r) == len(head)])
    d = {h: arr[:, k] for k, h in enumerate(head)}
    d.update({k: np.array(v) for k, v in solids_csv.wide_columns(run, d["step"]).items()})
    return d


def stretch_from_sigma(sig, mu):
    """lambda_max from mu (tr b - 2) with det b = 1 (tr b = l^2 + l^-2)."""
    tr = 2.0 + abs(sig) / mu
    l2 = 0.5 * (tr + math.sqrt(max(tr * tr - 4.0, 0.0)))
    return math.sqrt(l2)


# ------------------------------------------------------------------ classification
def min_gap(d):
    """Per row, the smallest gap of any solid to a wall or another solid."""
    cols = [c for c in d if re.fullmatch(r"solid\d+_gap_(wall|solid)", c)]
    return np.min([d[c] for c in cols], axis=0)


def classify(job):
    """(outcome, t_event, step_event, measure, value, cause) from the run's own records."""
    rc, d = job["rc"], job["diag"]
    if rc == 3 or rc == 2:
        msg = job["stderr"].splitlines()
        msg = next((m for m in msg if "error" in m), msg[0] if msg else "")
        m = re.search(r"failed after (\d+) steps at t = ([0-9.eE+-]+): (.*)", msg)
        step, t, cause = (int(m.group(1)), float(m.group(2)), m.group(3)) if m else (0, 0.0, msg)
        cause = cause.replace("refmap: error: ", "")
        short = ("folded map" if "folded" in cause else
                 "energy blow-up" if "kinetic energy grew" in cause or "collapsed" in cause else
                 "non-finite" if "non-finite" in cause else
                 "projection failed" if "face divergence" in cause else
                 "velocity solve failed" if "not positive definite" in cause else
                 "solid vanished" if "vanish" in cause else
                 "reached side" if "side" in cause else
                 "rejected at start" if rc == 2 else "other")
        return "stopped", t, step, short, float("nan"), cause
    if rc != 0:
        return "crashed", float("nan"), 0, f"exit {rc}", float("nan"), job["stderr"][-300:]
    if not d:
        return "crashed", float("nan"), 0, "no diagnostics.csv", float("nan"), ""
    t, step = d["time"], d["step"]
    area = d["solid0_area"]
    a_exact = math.pi * R * R
    if job["sweep"] == "e":
        err = np.abs(area - a_exact) / a_exact
        k = int(np.argmax(err > 0.01)) if np.any(err > 0.01) else -1
        if k >= 0:
            lost = np.any(err > 0.10)
            return ("inaccurate", t[k], int(step[k]), "area error > 10 % (lost)" if lost else "area error",
                    float(err.max()), "")
        return "stable", float("nan"), 0, "area error", float(err.max()), ""
    # area drift of every solid (two in the solid-solid contact runs of sweep d)
    drift = np.max([np.abs(d[c] - d[c][0]) / d[c][0] for c in d if re.fullmatch(r"solid\d+_area", c)], axis=0)
    # the first row that breaks each bound: (row, measure, its largest value)
    bad = []
    if np.any(drift > 0.01):
        bad.append((int(np.argmax(drift > 0.01)), "area drift", float(drift.max())))
    if not job.get("gravity"):  # with gravity potential energy is released: no energy bound
        # contact stores energy in its spring (contact_energy) and gives it back
        e = d["total_energy"] + d.get("contact_energy", 0.0)
        rise = e / e[0] - 1.0  # a viscous run may never exceed its initial total energy
        if np.any(rise > 0.01):
            bad.append((int(np.argmax(rise > 0.01)), "energy rise", float(rise.max())))
    if job["sweep"] == "d":  # the zero level set crossed the wall (or another solid)
        gap = min_gap(d) / job["dx"]
        if np.any(gap < 0.0):
            bad.append((int(np.argmax(gap < 0.0)), "overlap (gap/dx < 0)", float(gap.min())))
    if job["sweep"] == "c":  # the pressure solve must reach its tolerance every step
        res = d["poisson_residual"][1:]
        if np.any(res > POISSON_TOL):
            k = int(np.argmax(res > POISSON_TOL)) + 1
            bad.append((k, "Poisson not converged", float(res.max())))
    if bad:
        k, meas, val = min(bad, key=lambda b: b[0])
        return "inaccurate", t[k], int(step[k]), meas, val, ""
    if job["sweep"] == "d":
        gap = min_gap(d) / job["dx"]
        return "stable", float("nan"), 0, "gap/dx", float(gap.min()), ""
    return "stable", float("nan"), 0, "area drift", float(drift.max()), ""


def result_row(job):
    outcome, tev, sev, meas, val, cause = classify(job)
    d = job["diag"]
    mu = job.get("mu_s", MU_S)
    row = {c: "" for c in COLS}
    row.update({k: job.get(k, "") for k in ["sweep", "method", "stress_discretisation", "conservative",
                                            "xi_advection", "extrapolation", "lsq_radius", "param",
                                            "value", "param2", "value2"]})
    row.update(scene=job.get("scene", "disc_tgv"), outcome=outcome, t_event=tev, step_event=sev, measure=meas,
               measure_value=val, cause=cause, wall_s=round(job["wall_s"], 3))
    if d:
        # the largest stretch of the healthy states: a stopped run's last row is the failing state
        sig = d["solid0_sigma_max"]
        if outcome == "stopped" and len(sig) > 2:
            sig = sig[:-1]
        row["max_stretch"] = stretch_from_sigma(float(np.max(sig)), mu)
        dts = d["dt"][1:] if len(d["dt"]) > 1 else d["dt"]
        row["min_dt"] = float(np.min(dts))
        nx = job.get("nx", 32)
        # P of the first step (the solid at rest): dt sqrt(2 mu_s / rho_s) / dx; below the
        # swept P where the advective or viscous limit binds instead
        row["p_effective"] = float(dts[0]) * math.sqrt(2.0 * mu / job.get("rho_s", 1.0)) * nx
        pit = d["poisson_iterations"][1:]
        if len(pit):
            row["poisson_iter_mean"] = float(np.mean(pit))
            row["poisson_iter_max"] = int(np.max(pit))
        row["steps"] = int(d["step"][-1])
        # growth over the run's second half (largest total energy there / its value at the
        # middle row): tells a start-up rise that then decays (<= 1) from a growing mode (> 1)
        e = d["total_energy"] + d.get("contact_energy", 0.0)
        if outcome != "stopped" and len(e) > 4 and e[len(e) // 2] > 0:
            row["energy_late_growth"] = float(np.max(e[len(e) // 2:]) / e[len(e) // 2])
    return row


# ------------------------------------------------------------------ the sweeps
def method_sets(stress, cons, xi):
    return [f'solids.stress_discretisation="{stress}"', f"solids.conservative={'true' if cons else 'false'}",
            f'solids.xi_advection="{xi}"']


EXTRAPS = [("lsq r=2.83", "lsq", 2.83, True), ("lsq r=5.66", "lsq", 5.66, True), ("pde", "pde", "", True),
           ("lsq r=2.83 non-conservative", "lsq", 2.83, False)]


def extrap_sets(ex, r, cons):
    s = [f'solids.extrapolation="{ex}"', f"solids.conservative={'true' if cons else 'false'}"]
    if ex == "lsq":
        s.append(f"solids.lsq_radius={r}")
    return s


def jobs_a(quick):
    if quick:
        methods = [("cell", True, "vanleer"), ("face", True, "vanleer"), ("cell", False, "vanleer"),
                   ("cell", True, "central")]
        stiff, ps = [1e2, 1e4], [0.5, 1, 2, 4, 8]
    else:
        methods = [(s, c, x) for s in ("cell", "face") for c in (True, False)
                   for x in ("central", "vanleer", "superbee")]
        stiff, ps = [1e2, 1e3, 1e4, 1e5], [0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4, 6, 8]
    out = []
    for (s, c, x) in methods:
        name = f"{s}/{'cons' if c else 'noncons'}/{x}"
        for mu in stiff:
            for p in ps:
                out.append(dict(sweep="a", method=name, stress_discretisation=s, conservative=c,
                                xi_advection=x, extrapolation="lsq", lsq_radius=2.83, param="solid_cfl",
                                value=p, param2="mu_s/rho_s", value2=mu, mu_s=mu,
                                tag=f"a/{s}_{int(c)}_{x}_mu{mu:g}_P{p:g}",
                                sets=method_sets(s, c, x) + ["grid.nx=32", "grid.ny=32", "time.end=100",
                                                             "time.max_steps=400", "output.vtk=false",
                                                             f"solid.0.mu_s={mu:g}", f"solids.solid_cfl={p:g}"]))
    # the velocity Verlet elastic coupling (time.elastic_coupling = "verlet", kernels/verlet.hpp):
    # the same explicit stress, second order in the energy; same P as the explicit rows
    for s_form in (("cell",) if quick else ("cell", "face")):
        for mu in stiff:
            for p in ps:
                out.append(dict(sweep="a", method=f"verlet ({s_form}/cons/vanleer)", stress_discretisation=s_form,
                                conservative=True, xi_advection="vanleer", extrapolation="lsq", lsq_radius=2.83,
                                param="solid_cfl", value=p, param2="mu_s/rho_s", value2=mu, mu_s=mu,
                                tag=f"a/verlet_{s_form}_mu{mu:g}_P{p:g}",
                                sets=method_sets(s_form, True, "vanleer") + [
                                    'time.elastic_coupling="verlet"', "grid.nx=32", "grid.ny=32", "time.end=100",
                                    "time.max_steps=400", "output.vtk=false", f"solid.0.mu_s={mu:g}",
                                    f"solids.solid_cfl={p:g}"]))
    # the semi-implicit solid stress (docs/implicit.md) has no solid time-step limit:
    # dt comes from advection and time.dt_max only, so P is imposed as dt_max = P dx /
    # sqrt(2 mu_s / rho_s) (where the advective limit binds first, p_effective records the P
    # actually used); k = 0.5 is the default, k = 0.1 is below the 1-D stability bound 1/4 and
    # k = 2 damps more
    ks, ps_si = ([0.5], [0.5, 1, 2, 4, 16, 64]) if quick else \
        ([0.5, 0.1, 2], [0.25, 0.5, 0.75, 1, 1.5, 2, 4, 8, 16, 32, 64, 128])
    for k in ks:
        out += implicit_p_jobs(semi_name(k), "cell", semi_sets(k), f"semi_k{k:g}", stiff, ps_si)
    # both implicit solid terms with their coefficient reaching 2 cells further into the fluid
    # than the stress (time.solid_implicit_reach = 2, docs/implicit.md)
    reach = ["time.solid_implicit_reach=2"]
    out += implicit_p_jobs(semi_name(0.5) + " reach 2", "cell", semi_sets(0.5) + reach, "reach2_semi", stiff, ps_si)
    out += implicit_p_jobs(uc_name("cell") + " reach 2", "cell", uc_sets("cell") + reach, "reach2_uc", stiff, ps_si)
    # the upper-convected solid stress (time.solid_stress = "upper_convected", docs/implicit.md),
    # P imposed the same way; with the cell and the face stress discretisation (the implicit
    # operator is the compact face one, the explicit cell form is not)
    for s_form in ("cell", "face"):
        out += implicit_p_jobs(uc_name(s_form), s_form, uc_sets(s_form), f"uc_{s_form}", stiff, ps_si)
    return out


def implicit_p_jobs(name, s_form, sets, tag, stiff, ps):
    """Sweep a for a method without a solid time-step limit of its own: P imposed as
    time.dt_max = P dx / sqrt(2 mu_s / rho_s) on 32^2."""
    out = []
    for mu in stiff:
        for p in ps:
            dt_max = p * (1.0 / 32) / math.sqrt(2.0 * mu)
            out.append(dict(sweep="a", method=name, stress_discretisation=s_form, conservative=True,
                            xi_advection="vanleer", extrapolation="lsq", lsq_radius=2.83,
                            param="solid_cfl", value=p, param2="mu_s/rho_s", value2=mu, mu_s=mu,
                            tag=f"a/{tag}_mu{mu:g}_P{p:g}",
                            sets=sets + ["grid.nx=32", "grid.ny=32", "time.end=100", "time.max_steps=400",
                                         "output.vtk=false", f"solid.0.mu_s={mu:g}", f"time.dt_max={dt_max!r}"]))
    return out


def uc_name(s_form):
    return f"upper-convected ({s_form}/cons/vanleer)"


def uc_sets(s_form):
    """The upper-convected method of docs/implicit.md (implicit viscosity too)."""
    return method_sets(s_form, True, "vanleer") + ['time.viscous="implicit"',
                                                   'time.solid_stress="upper_convected"']


def semi_name(k):
    return f"semi-implicit k={k:g} (cell/cons/vanleer)"


def semi_sets(k=0.5):
    """The semi-implicit method of docs/implicit.md: implicit viscosity and solid stress."""
    return ['time.viscous="implicit"', 'time.solid_stress="semi_implicit"', f"time.solid_implicit_k={k:g}"]


def jobs_b(quick):
    amps = [1, 2, 4, 8, 16] if quick else [1, 2, 3, 4, 6, 8, 10, 12, 16, 24, 32]
    out = []
    for (name, ex, r, cons) in EXTRAPS:
        for a in amps:
            out.append(dict(sweep="b", method=name, stress_discretisation="cell", conservative=cons,
                            xi_advection="vanleer", extrapolation=ex, lsq_radius=r, param="amplitude/A0",
                            value=a, tag=f"b/{name.replace(' ', '_').replace('=', '')}_A{a}",
                            sets=extrap_sets(ex, r, cons) + ["grid.nx=64", "grid.ny=64", "time.end=2.0",
                                                             "output.vtk=false", f"initial.amplitude={A0 * a!r}"]))
    # the semi-implicit method with lsq 2.83: the same flows at its own (advective) time step
    for a in amps:
        out.append(dict(sweep="b", method="semi-implicit k=0.5 (lsq r=2.83)", stress_discretisation="cell",
                        conservative=True, xi_advection="vanleer", extrapolation="lsq", lsq_radius=2.83,
                        param="amplitude/A0", value=a, tag=f"b/semi_A{a}",
                        sets=semi_sets() + ["grid.nx=64", "grid.ny=64", "time.end=2.0", "output.vtk=false",
                                            f"initial.amplitude={A0 * a!r}"]))
    return out


def jobs_e(quick):
    res = [2, 4, 8, 16] if quick else [2, 3, 4, 6, 8, 12, 16]
    out = []
    for (name, ex, r, cons) in EXTRAPS[:3]:
        for n in res:
            nx = int(round(n / R))
            out.append(dict(sweep="e", method=name, stress_discretisation="cell", conservative=cons,
                            xi_advection="vanleer", extrapolation=ex, lsq_radius=r, param="R/dx", value=n,
                            nx=nx, tag=f"e/{name.replace(' ', '_').replace('=', '')}_n{n}",
                            sets=extrap_sets(ex, r, cons) + [f"grid.nx={nx}", f"grid.ny={nx}", "time.end=2.0",
                                                             "output.vtk=false"]))
    return out


def jobs_c(quick):
    """Density ratio rho_s / rho_f (rho_f = 1) at a fixed shear-wave speed (mu_s / rho_s = 0.5,
    the scene's), so that only the density jump across the interface changes: 48 x 48, to
    t = 1, without gravity (the energy bound holds) and with g = 1 downwards (the disc sinks
    or rises; area drift only), for multigrid and CG pressure solves, and the multigrid with
    the specific stress blend (solids.stress_blend = "specific", docs/density_ratio.md)."""
    ratios = [1e-3, 1e-2, 1e-1, 1, 1e1, 1e2, 1e3] if quick else \
        [1e-3, 1e-2, 3e-2, 1e-1, 0.3, 1, 3, 1e1, 3e1, 1e2, 1e3]
    solvers = ["multigrid"] if quick else ["multigrid", "cg", "multigrid+specific"]
    out = []
    for variant in solvers:
        solver, _, blend = variant.partition("+")
        for grav in (False, True):
            name = f"{solver}{', specific stress blend' if blend else ''}{', g = 1' if grav else ''}"
            for r in ratios:
                sets = [f'solver.poisson="{solver}"', "grid.nx=48", "grid.ny=48", "time.end=1.0",
                        "output.vtk=false", f"solid.0.density={r:g}", f"solid.0.mu_s={0.5 * r:g}"]
                if blend:
                    sets.append(f'solids.stress_blend="{blend}"')
                if grav:
                    sets.append("gravity.g=[0.0, -1.0]")
                out.append(dict(sweep="c", method=name, stress_discretisation="cell", conservative=True,
                                xi_advection="vanleer", extrapolation="lsq", lsq_radius=2.83,
                                param="rho_s/rho_f", value=r, gravity=grav, rho_s=r, mu_s=0.5 * r, nx=48,
                                tag=f"c/{solver}{'_' + blend if blend else ''}_g{int(grav)}_r{r:g}", sets=sets))
    return out


def jobs_d(quick):
    """Contact (scenes/wall_microgravity.toml: a soft disc R = 0.15, rho_s = 2, mu_s = 100,
    launched at the bottom wall, no gravity), 48 x 48, to t = 0.5: the impact speed V raised
    with the contact strength held at the scene's (contact.velocity_scale = 1.5, the scene's
    speed; otherwise the strength scales with V^2), and the contact stiffness raised at
    V = 3 (at the scene's V = 1.5 the fluid film alone keeps the disc 0.4 dx off the wall
    down to stiffness 0.003: the contact force is not needed there)."""
    speeds = [0.75, 1.5, 3, 6, 12] if quick else [0.75, 1.5, 2, 3, 4, 6, 8, 12, 16]
    stiffs = [1, 20, 80, 2000] if quick else [0.1, 1, 5, 20, 40, 80, 200, 2000]
    base = ["grid.nx=48", "grid.ny=48", "time.end=0.5", "output.vtk=false"]
    out = []
    for v in speeds:
        out.append(dict(sweep="d", scene="wall_microgravity", method="impact speed (stiffness 20, U = 1.5)",
                        stress_discretisation="cell", conservative=True, xi_advection="vanleer",
                        extrapolation="lsq", lsq_radius=2.83, param="impact speed V", value=v, dx=1 / 48,
                        nx=48, mu_s=100.0, rho_s=2.0, tag=f"d/speed_{v:g}",
                        sets=base + ["contact.velocity_scale=1.5", f"solid.0.v={-v:g}"]))
    for k in stiffs:  # at V = 3, where the scene's stiffness 20 (strength for U = 1.5) lets it overlap
        out.append(dict(sweep="d", scene="wall_microgravity", method="contact stiffness (V = 3, U = 1.5)",
                        stress_discretisation="cell", conservative=True, xi_advection="vanleer",
                        extrapolation="lsq", lsq_radius=2.83, param="contact.stiffness", value=k, dx=1 / 48,
                        nx=48, mu_s=100.0, rho_s=2.0, tag=f"d/stiff_{k:g}",
                        sets=base + ["contact.velocity_scale=1.5", "solid.0.v=-3", f"contact.stiffness={k:g}"]))
    # solid-solid: the scene's disc and a copy of it (added by --set) side by side, gap 0.1,
    # launched head-on at each other at V each (closing speed 2 V) with the same contact
    # strength; to t = 0.3 (the contact is over before either disc can reach a side wall)
    speeds_ss = [0.75, 1.5, 3, 6] if quick else [0.75, 1.5, 2, 3, 4, 6, 8, 12]
    stiffs_ss = [1, 20, 2000] if quick else [0.1, 1, 5, 20, 80, 400, 2000]

    def pair(v):
        return ["grid.nx=48", "grid.ny=48", "time.end=0.3", "output.vtk=false", "contact.velocity_scale=1.5",
                "solid.0.center=[0.3, 0.5]", "solid.0.v=0.0", f"solid.0.u={v:g}",
                'solid.1.name="disc2"', 'solid.1.shape="circle"', "solid.1.center=[0.7, 0.5]",
                "solid.1.radius=0.15", "solid.1.mu_s=100.0", "solid.1.density=2.0", "solid.1.viscosity=0.0",
                f"solid.1.u={-v:g}", "solid.1.v=0.0"]
    for v in speeds_ss:
        out.append(dict(sweep="d", scene="wall_microgravity", method="solid-solid: speed V each (stiffness 20)",
                        stress_discretisation="cell", conservative=True, xi_advection="vanleer",
                        extrapolation="lsq", lsq_radius=2.83, param="impact speed V", value=v, dx=1 / 48,
                        nx=48, mu_s=100.0, rho_s=2.0, tag=f"d/pair_speed_{v:g}", sets=pair(v)))
    for k in stiffs_ss:
        out.append(dict(sweep="d", scene="wall_microgravity", method="solid-solid: contact stiffness (V = 3 each)",
                        stress_discretisation="cell", conservative=True, xi_advection="vanleer",
                        extrapolation="lsq", lsq_radius=2.83, param="contact.stiffness", value=k, dx=1 / 48,
                        nx=48, mu_s=100.0, rho_s=2.0, tag=f"d/pair_stiff_{k:g}",
                        sets=pair(3) + [f"contact.stiffness={k:g}"]))
    return out


# ------------------------------------------------------------------ limits and charts
def limits(rows):
    """Per sweep x method (x value2): the limit as documented in the module string."""
    out = []
    keys = sorted({(r["sweep"], r["method"], r["value2"]) for r in rows}, key=str)
    for (sw, m, v2) in keys:
        rs = sorted([r for r in rows if r["sweep"] == sw and r["method"] == m and r["value2"] == v2],
                    key=lambda r: float(r["value"]))
        if sw == "c":  # the stable range around rho_s / rho_f = 1: lo..hi
            k1 = next((k for k, r in enumerate(rs) if float(r["value"]) == 1.0), None)
            lo = hi = None
            bad_lo = bad_hi = None
            if k1 is not None and rs[k1]["outcome"] == "stable":
                lo = hi = k1
                while lo > 0 and rs[lo - 1]["outcome"] == "stable":
                    lo -= 1
                while hi + 1 < len(rs) and rs[hi + 1]["outcome"] == "stable":
                    hi += 1
                bad_lo = rs[lo - 1] if lo > 0 else None
                bad_hi = rs[hi + 1] if hi + 1 < len(rs) else None
            lim = f"{rs[lo]['value']:g}..{rs[hi]['value']:g}" if lo is not None else None
            fails = [b for b in (bad_lo, bad_hi) if b]
            out.append(dict(sweep=sw, method=m, param=rs[0]["param"], param2=rs[0]["param2"], value2=v2,
                            limit=lim if lim is not None else "none",
                            first_failure=" / ".join(f"{b['value']:g}" for b in fails),
                            failure_outcome=" / ".join(b["outcome"] for b in fails),
                            failure_measure=" / ".join(b["measure"] for b in fails),
                            stretch_at_failure="", p_effective_at_limit=""))
            continue
        if sw == "e" or (sw == "d" and rs[0]["param"] == "contact.stiffness"):
            # smallest value from which every larger one is stable (finer grid, stiffer contact)
            lim = None
            for r in reversed(rs):
                if r["outcome"] != "stable":
                    break
                lim = r["value"]
            first_bad = next((r for r in reversed(rs) if r["outcome"] != "stable"), None)
        else:
            lim, first_bad = None, None
            for r in rs:
                if r["outcome"] != "stable":
                    first_bad = r
                    break
                lim = r["value"]
        out.append(dict(sweep=sw, method=m, param=rs[0]["param"], param2=rs[0]["param2"], value2=v2,
                        limit=lim if lim is not None else "none",
                        first_failure=first_bad["value"] if first_bad else "",
                        failure_outcome=first_bad["outcome"] if first_bad else "",
                        failure_measure=first_bad["measure"] if first_bad else "",
                        stretch_at_failure=first_bad["max_stretch"] if first_bad else "",
                        # sweep a: the P of the first step actually taken at the limit (below the swept
                        # value where the advective limit binds first, the semi-implicit runs at large P)
                        p_effective_at_limit=next((r["p_effective"] for r in rs if lim is not None and
                                                   r["value"] == lim), "") if sw == "a" else ""))
    return out


COLOURS = {"stable": "tab:green", "inaccurate": "tab:orange", "stopped": "tab:red", "crashed": "black"}


def key_defaults(binary):
    """The defaults of solids.solid_cfl (a number) and time.elastic_coupling (a name), read
    from the binary's key table (one home: solver/model/config.hpp); None where the binary
    cannot say."""
    try:
        out = subprocess.run([binary, "keys"], capture_output=True, text=True, timeout=60).stdout
    except OSError:
        return None, None
    p = re.search(r"^solids\.solid_cfl\s+\(.*?default ([0-9.eE+-]+)\)", out, re.M)
    c = re.search(r'^time\.elastic_coupling\s+\(.*?default "(\w+)"\)', out, re.M)
    return (float(p.group(1)) if p else None), (c.group(1) if c else None)


def chart(rows, lims, sweep, path, title, xlabel, logx=False, by_value2=False, mark=None):
    """mark: (x, label) drawn as a vertical line in every panel (the default of the swept key)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rs = [r for r in rows if r["sweep"] == sweep]
    if not rs:
        return
    methods = list(dict.fromkeys(r["method"] for r in rs))
    if by_value2:
        v2s = sorted({r["value2"] for r in rs})
        fig, axes = plt.subplots(1, len(v2s), figsize=(3.2 * len(v2s) + 1.5, 0.45 * len(methods) + 1.8),
                                 sharey=True, squeeze=False)
        panels = [(axes[0][k], v2) for k, v2 in enumerate(v2s)]
    else:
        fig, ax = plt.subplots(figsize=(8, 0.5 * len(methods) + 1.8))
        panels = [(ax, "")]
    for ax, v2 in panels:
        for k, m in enumerate(methods):
            sel = [r for r in rs if r["method"] == m and r["value2"] == v2]
            for r in sel:
                ax.scatter(float(r["value"]), k, c=COLOURS[r["outcome"]], s=45, zorder=3)
                if sweep == "a" and r["p_effective"] != "" and float(r["p_effective"]) < 0.95 * float(r["value"]):
                    # the advective limit bound first: the P actually used
                    ax.annotate(f"{float(r['p_effective']):.2g}", (float(r["value"]), k), fontsize=5,
                                xytext=(0, 6), textcoords="offset points", ha="center")
                if sweep == "b" and r["outcome"] != "stable" and r["max_stretch"] != "":
                    ax.annotate(f"{float(r['max_stretch']):.1f}", (float(r["value"]), k), fontsize=6,
                                xytext=(0, 6), textcoords="offset points", ha="center")
            lim = next((l for l in lims if l["sweep"] == sweep and l["method"] == m and l["value2"] == v2), None)
            if lim and lim["limit"] != "none":
                for x in str(lim["limit"]).split(".."):
                    ax.scatter(float(x), k, marker="s", s=140, facecolors="none", edgecolors="k", zorder=4)
        if mark is not None:
            ax.axvline(mark[0], color="tab:blue", lw=1.2, ls="--", zorder=2)
        if logx:
            ax.set_xscale("log")
        ax.set_yticks(range(len(methods)))
        ax.set_yticklabels(methods, fontsize=7)
        ax.set_xlabel(xlabel)
        if by_value2:
            ax.set_title(f"mu_s/rho_s = {float(v2):g}", fontsize=9)
        ax.grid(alpha=0.3)
    for o, c in COLOURS.items():
        panels[0][0].scatter([], [], c=c, label=o)
    panels[0][0].scatter([], [], marker="s", facecolors="none", edgecolors="k", label="limit (largest stable)")
    if mark is not None:
        panels[0][0].plot([], [], color="tab:blue", lw=1.2, ls="--", label=mark[1])
    fig.legend(loc="lower center", ncol=5, fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 0.92))
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ------------------------------------------------------------------ snapshots of each failure
# One run just past each limit the study found (the values are from results/stability_limits.csv),
# with frames: the panel shows frame_failed.vti if a health check stopped the run (the state it
# refused, solver/app/run.cpp), else the frame nearest the event (contact: the smallest gap), else the
# last frame.
SNAPSHOTS = [
    ("solid time step: P = 3, mu_s/rho_s = 100,\ncentral xi fluxes (limit P = 1)", "disc_tgv", "a",
     method_sets("cell", True, "central") + ["grid.nx=32", "grid.ny=32", "time.end=100", "time.max_steps=400",
                                            "solid.0.mu_s=100", "solids.solid_cfl=3", "output.interval=0.1"]),
    ("large deformation: 6 A0, lsq r = 2.83\n(limit 1 A0)", "disc_tgv", "b",
     ["grid.nx=64", "grid.ny=64", "time.end=2.0", f"initial.amplitude={6 * A0!r}", "output.interval=0.05"]),
    ("non-conservative form: 1 A0\n(no stable amplitude)", "disc_tgv", "b",
     ["grid.nx=64", "grid.ny=64", "time.end=2.0", "solids.conservative=false", "output.interval=0.05"]),
    ("light solid: rho_s/rho_f = 1e-3\n(48^2)", "disc_tgv", "c",
     ["grid.nx=48", "grid.ny=48", "time.end=1.0", "solid.0.density=0.001", "solid.0.mu_s=0.0005",
      "output.interval=0.05"]),
    ("heavy solid: rho_s/rho_f = 100\n(48^2)", "disc_tgv", "c",
     ["grid.nx=48", "grid.ny=48", "time.end=1.0", "solid.0.density=100", "solid.0.mu_s=50", "output.interval=0.05"]),
    ("contact: V = 3 at the strength for 1.5\n(48^2, smallest gap)", "wall_microgravity", "d",
     ["grid.nx=48", "grid.ny=48", "time.end=0.3", "contact.velocity_scale=1.5", "solid.0.v=-3",
      "output.interval=0.005"]),
    ("resolution: R/dx = 2, PDE extrapolation\n(t = 2)", "disc_tgv", "e",
     ["grid.nx=10", "grid.ny=10", "time.end=2.0", 'solids.extrapolation="pde"', "output.interval=0.1"]),
    ("semi-implicit k = 0.5: P = 4,\nmu_s/rho_s = 100 (limit P = 1)", "disc_tgv", "a",
     semi_sets() + ["grid.nx=32", "grid.ny=32", "time.end=2.5", "solid.0.mu_s=100",
                    f"time.dt_max={4 / 32 / math.sqrt(200)!r}", "output.interval=0.1"]),
    ("solid-solid: V = 6 each at the strength for 1.5\n(48^2, smallest gap)", "wall_microgravity", "d",
     ["grid.nx=48", "grid.ny=48", "time.end=0.3", "contact.velocity_scale=1.5", "solid.0.center=[0.3, 0.5]",
      "solid.0.v=0.0", "solid.0.u=6", 'solid.1.name="disc2"', 'solid.1.shape="circle"', "solid.1.center=[0.7, 0.5]",
      "solid.1.radius=0.15", "solid.1.mu_s=100.0", "solid.1.density=2.0", "solid.1.viscosity=0.0",
      "solid.1.u=-6", "solid.1.v=0.0", "output.interval=0.005"]),
]


def det_grad_xi(xi, dx):
    """det grad xi by central differences (the stress kernel's, eq. 3.1), NaN on the border."""
    xx, xy = xi[..., 0], xi[..., 1]
    d = np.full(xx.shape, np.nan)
    dxx = (xx[1:-1, 2:] - xx[1:-1, :-2]) / (2 * dx)
    dxy = (xx[2:, 1:-1] - xx[:-2, 1:-1]) / (2 * dx)
    dyx = (xy[1:-1, 2:] - xy[1:-1, :-2]) / (2 * dx)
    dyy = (xy[2:, 1:-1] - xy[:-2, 1:-1]) / (2 * dx)
    d[1:-1, 1:-1] = dxx * dyy - dxy * dyx
    return d


def failure_figure(binary, raw, out_png, jobs):
    sys.path.insert(0, os.path.join(ROOT, "scenes"))
    from plot_run import Frame  # the project's .vti reader
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = [dict(sweep=sw, tag=f"snap/{k}", scene=sc, sets=sets, title=title)
            for k, (title, sc, sw, sets) in enumerate(SNAPSHOTS)]
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        done = list(ex.map(lambda j: run_one(j, binary, raw), runs))
    ncol = 4
    nrow = (len(done) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.0 * ncol + 1.2, 3.4 * nrow), squeeze=False)
    for ax in axes.flat:
        ax.set_visible(False)
    im = None
    for ax, job in zip(axes.flat, done):
        ax.set_visible(True)
        out = os.path.join(raw, job["tag"])
        failed = os.path.join(out, "frame_failed.vti")
        if os.path.exists(failed):
            path, what = failed, "frame_failed.vti"
        else:
            frames = sorted(f for f in os.listdir(out) if re.match(r"frame_\d+\.vti$", f))
            d = job["diag"]
            path = os.path.join(out, frames[-1])
            what = "last frame"
            if job["scene"] == "wall_microgravity" and d:
                gap = min_gap(d)
                t_min = d["time"][int(np.argmin(gap))]
                times = [Frame(os.path.join(out, f)).time for f in frames]
                path = os.path.join(out, frames[int(np.argmin([abs(t - t_min) for t in times]))])
                what = f"smallest gap {np.min(gap) / Frame(path).dx:.2f} dx"
        fr = Frame(path)
        phi = fr.get("phi")
        det = det_grad_xi(fr.get("xi"), fr.dx)
        inside = np.ma.masked_where(~(phi < 0) | np.isnan(det), det)
        speed = np.hypot(fr.get("u"), fr.get("v"))
        ax.imshow(speed, origin="lower", extent=fr.extent, cmap="Greys", alpha=0.6,
                  vmax=np.nanpercentile(speed, 98))  # a blow-up's few huge cells would hide the rest
        im = ax.imshow(inside, origin="lower", extent=fr.extent, cmap="RdBu", vmin=-1, vmax=3)
        X, Y = fr.cell_centres()
        ax.contour(X, Y, phi, levels=[0.0], colors="k", linewidths=0.8)
        fold = (phi < 0) & (det <= 0)
        if np.any(fold):
            ax.plot(X[fold], Y[fold], "x", color="magenta", ms=4, mew=1.2)
        outcome, _, _, measure, _, _ = classify(dict(job, dx=fr.dx)) if job["diag"] else ("crashed", 0, 0, "", 0, "")
        ax.set_title(job["title"], fontsize=8)
        ax.set_xlabel(f"{outcome}: {measure}\n{what}, t = {fr.time:.4g}", fontsize=7)
        ax.set_xticks([])
        ax.set_yticks([])
    if im is not None:
        fig.colorbar(im, ax=axes.ravel().tolist(), shrink=0.6, label="det grad xi inside the solid (x: <= 0, folded)")
    fig.suptitle("Where methods fail: one run just past each limit (grey: speed; line: phi = 0)", fontsize=10)
    fig.savefig(out_png, dpi=110)
    plt.close(fig)
    for job in done:
        print(f"  snapshot {job['tag']}: exit {job['rc']} {job['stderr'].splitlines()[0][:120] if job['stderr'] else ''}")


def write_charts(rows, lims, args):
    """The charts stability_<sweep>.png from the rows and limits; the solid time-step map marks
    the default solids.solid_cfl and names the default elastic coupling of args.bin (the
    rows "verlet (...)" are that coupling, the other explicit rows Algorithm 1's)."""
    p_default, coupling = key_defaults(args.bin)
    chart(rows, lims, "a", os.path.join(args.out, "stability_solid_cfl.png"),
          "solid time-step factor P (dt = P dx / sqrt(2 mu_s/rho_s)), disc_tgv 32^2, 400 steps; semi-implicit: "
          "dt_max from P\n(small labels: the P actually used where the advective limit binds first)",
          "P (solids.solid_cfl)", logx=True, by_value2=True,
          mark=(p_default, f"default solid_cfl = {p_default:g}" + (f", coupling {coupling}" if coupling else ""))
          if p_default else None)
    chart(rows, lims, "b", os.path.join(args.out, "stability_deformation.png"),
          "large deformation: disc_tgv 64^2 to t = 2, flow amplitude raised (labels: largest stretch before failure)",
          "amplitude / A0 (A0 = 0.1 pi)", logx=True)
    chart(rows, lims, "c", os.path.join(args.out, "stability_density.png"),
          "density ratio: disc_tgv 48^2 to t = 1, mu_s/rho_s = 0.5 fixed (stable range boxed at its ends)",
          "rho_s / rho_f", logx=True)
    chart(rows, lims, "d", os.path.join(args.out, "stability_contact.png"),
          "contact: wall_microgravity 48^2 to t = 0.5, solid-solid pair to t = 0.3\n"
          "(impact speed: largest stable; stiffness: smallest from which all are)",
          "impact speed V  /  contact.stiffness", logx=True)
    chart(rows, lims, "e", os.path.join(args.out, "stability_resolution.png"),
          "resolution: disc_tgv to t = 2, cells across the disc's radius", "R / dx", logx=True)


def read_rows(out):
    """results/stability.csv and stability_limits.csv back as the rows and limits the charts take
    (numbers where the study wrote numbers)."""
    def load(name):
        with open(os.path.join(out, name)) as f:
            return list(csv.DictReader(l for l in f if not l.startswith("#")))
    num = lambda v: float(v) if v not in ("", None) else ""
    rows = load("stability.csv")
    for r in rows:
        r["value"], r["value2"] = float(r["value"]), num(r["value2"])
    lims = load("stability_limits.csv")
    for l in lims:
        l["value2"] = num(l["value2"])
    return rows, lims


# ------------------------------------------------------------------ main
def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "refmap"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results"))
    ap.add_argument("--raw", default="/tmp/refmap_stability")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--sweeps", default="a,b,c,d,e")
    ap.add_argument("--figure", choices=["yes", "no", "only"], default="yes",
                    help="results/stability_failures.png (one run past each limit): with the sweeps, not, or alone")
    ap.add_argument("--methods", default="",
                    help="comma-separated substrings: run only the methods whose name contains one "
                         "(e.g. 'upper-convected'; merge the rows into results/ by hand)")
    ap.add_argument("--charts-only", action="store_true",
                    help="redraw the charts stability_<sweep>.png from <out>/stability.csv and "
                         "stability_limits.csv, running nothing")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.charts_only:
        write_charts(*read_rows(args.out), args)
        return
    if args.figure != "no":
        t0 = time.time()
        failure_figure(args.bin, args.raw, os.path.join(args.out, "stability_failures.png"), args.jobs)
        print(f"stability_failures.png: {len(SNAPSHOTS)} runs in {time.time() - t0:.0f} s")
        if args.figure == "only":
            return
    sweeps = args.sweeps.split(",")
    jobs = []
    for sw, fn in [("a", jobs_a), ("b", jobs_b), ("c", jobs_c), ("d", jobs_d), ("e", jobs_e)]:
        if sw in sweeps:
            jobs += fn(args.quick)
    if args.methods:
        keep = args.methods.split(",")
        jobs = [j for j in jobs if any(k in j["method"] for k in keep)]
    t0 = time.time()
    rows = []
    with cf.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        futs = [ex.submit(run_one, j, args.bin, args.raw) for j in jobs]
        for k, f in enumerate(cf.as_completed(futs)):
            rows.append(result_row(f.result()))
            if (k + 1) % 20 == 0:
                print(f"  {k + 1}/{len(jobs)} runs, {time.time() - t0:.0f} s", flush=True)
    order = {id(j): k for k, j in enumerate(jobs)}
    rows.sort(key=lambda r: (r["sweep"], r["method"], float(r["value2"] or 0), float(r["value"])))
    os.makedirs(args.out, exist_ok=True)
    mode = "quick" if args.quick else "full"
    header = [f"# refmap stability study ({mode}), bench/stability.py; {len(rows)} runs in "
              f"{time.time() - t0:.0f} s with {args.jobs} parallel single-thread runs; "
              f"date {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}"]
    with open(os.path.join(args.out, "stability.csv"), "w", newline="") as f:
        for h in header:
            f.write(h + "\n")
        w = csv.DictWriter(f, COLS)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    lims = limits(rows)
    with open(os.path.join(args.out, "stability_limits.csv"), "w", newline="") as f:
        for h in header:
            f.write(h + "\n")
        w = csv.DictWriter(f, list(lims[0].keys()))
        w.writeheader()
        for l in lims:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in l.items()})
    write_charts(rows, lims, args)
    counts = {o: sum(r["outcome"] == o for r in rows) for o in COLOURS}
    print(f"{len(rows)} runs in {time.time() - t0:.0f} s: {counts}")
    for l in lims:
        print(f"  {l['sweep']} {l['method']:<32} {l['param2']} {l['value2']!s:<8} limit {l['param']} = {l['limit']}"
              f"  (first failure {l['first_failure']} {l['failure_outcome']} {l['failure_measure']})")
    if counts["crashed"]:
        print("CRASHED runs:")
        for r in rows:
            if r["outcome"] == "crashed":
                print("  ", r["sweep"], r["method"], r["value"], r["value2"], r["cause"])


if __name__ == "__main__":
    main()
