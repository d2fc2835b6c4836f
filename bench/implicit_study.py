"""Runs of bench/run_implicit_study.sh: explicit vs semi-implicit stepping (results/implicit.md)."""
import argparse, csv, math, os, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes"))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)
from coupling import with_coupling  # bench/coupling.py

SEMI = ["time.viscous=implicit", "time.solid_stress=semi_implicit"]
UC = ["time.viscous=implicit", "time.solid_stress=upper_convected"]


def rows(path):
    return [r for r in csv.reader(open(path)) if r and not r[0].startswith("#")]


def diag(d):
    """diagnostics.csv of run d as one dict per row, with the per-solid values of solids.csv
    (solid<k>_<q>) of that row's step."""
    r = rows(os.path.join(d, "diagnostics.csv"))
    h = r[0]
    out = [dict(zip(h, x)) for x in r[1:]]
    wide = solids_csv.wide_columns(d, [x["step"] for x in out])
    for k, row in enumerate(out):
        row.update({c: v[k] for c, v in wide.items()})
    return out


def timing(d):
    t = {r[0]: float(r[1]) for r in rows(os.path.join(d, "timings.csv"))[1:]}
    return t


def run(args, scene, name, sets):
    d = os.path.join(args.raw, name)
    cmd = [args.bin, "run", scene, "-o", d, "-q", "-j", "1"] + sum((["--set", s] for s in with_coupling(sets)), [])
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    return collect(d, p.returncode == 0, time.time() - t0)


def collect(d, ok, wall):
    """The numbers of a finished run in directory d (also for a run made by hand)."""
    info = {"dir": d, "ok": ok, "wall_s": wall}
    if os.path.exists(os.path.join(d, "diagnostics.csv")):
        dg = diag(d)
        info["steps"] = int(dg[-1]["step"])
        info["t"] = float(dg[-1]["time"])
        info["diag"] = dg
    if os.path.exists(os.path.join(d, "timings.csv")):
        t = timing(d)
        info["wall_s"] = t.get("total", wall)
        info["implicit_share"] = t.get("implicit velocity", 0.0) / max(t.get("total", 1.0), 1e-12)
        info["poisson_share"] = t.get("poisson", 0.0) / max(t.get("total", 1.0), 1e-12)
        info["implicit_per_poisson"] = t.get("implicit velocity", 0.0) / max(t.get("poisson", 0.0), 1e-12)
    dg = info.get("diag", [])[1:]  # the rows of the steps (row 0: the initial state)
    if dg and "implicit_iterations" in dg[0]:
        info["implicit_iters"] = sum(float(r["implicit_iterations"]) for r in dg) / len(dg)
    if dg:
        info["poisson_iters"] = sum(float(r["poisson_iterations"]) for r in dg) / len(dg)
    return info


def out_row(w, case, variant, info, **extra):
    r = {"case": case, "variant": variant, "ok": int(info["ok"]), "steps": info.get("steps", ""),
         "wall_s": "%.3f" % info["wall_s"], "implicit_share": "%.3f" % info.get("implicit_share", 0.0),
         "poisson_share": "%.3f" % info.get("poisson_share", 0.0),
         # per step: cycles of the velocity solve (u + v) and of the pressure solve, and
         # the velocity solve's time over the pressure solve's (timings.csv)
         "implicit_iters": "%.2f" % info["implicit_iters"] if "implicit_iters" in info else "",
         "poisson_iters": "%.2f" % info.get("poisson_iters", float("nan")),
         "implicit_per_poisson": "%.2f" % info["implicit_per_poisson"] if info.get("implicit_share") else ""}
    for k, v in extra.items():
        r[k] = v if isinstance(v, str) else "%.5g" % v
    w.append(r)
    print(r, flush=True)


def couette(args, w, variants=(("explicit", []), ("semi_implicit", SEMI))):
    ref = list(csv.DictReader(open("tests/data/couette_elastic_startup.csv")))
    sets = ["grid.ny=128", "domain.lx=0.125", "domain.ly=2.0", "output.interval=0"]
    for variant, extra in variants:
        info = run(args, "scenes/couette_elastic.toml", "couette_" + variant, sets + extra)
        err = float("nan")
        if info["ok"]:
            pr = [r for r in rows(os.path.join(info["dir"], "probe_u_profile.csv")) if r[0] != "x"][-41:]
            err = max(abs(float(a[2]) - float(b["u_t4.8"])) for a, b in zip(pr, ref))
        out_row(w, "couette_elastic_64", variant, info, linf_error=err)


def shear(args, w, variants=("explicit", "semi_implicit")):
    lim = 0.5 / 32  # solid_cfl dx / c on 32 x 32, c = 1
    E0 = 0.25 ** 2 / 4
    for variant, m in tuple(("explicit", m) for m in (1, 2, 4) if "explicit" in variants) + tuple(
            (v, m) for v in variants if v != "explicit" for m in (1, 2, 4, 8, 10)):
        sets = ["time.dt=%.10g" % (m * lim), "output.interval=0"]
        if variant != "explicit":
            sets += ["time.solid_stress=" + variant]
        info = run(args, "scenes/shear_wave.toml", "shear_%s_%g" % (variant, m), sets)
        err = drift = float("nan")
        if info["ok"]:
            t = info["t"]
            pr = [r for r in rows(os.path.join(info["dir"], "probe_u_profile.csv")) if r[0] != "x"][-32:]
            err = max(abs(float(r[2]) - 0.25 * math.sin(2 * math.pi * float(r[1])) * math.cos(2 * math.pi * t))
                      for r in pr) / 0.25
            drift = max(abs(float(r["total_energy"]) / E0 - 1) for r in info["diag"][1:])
        out_row(w, "shear_wave_32", "%s dt=%gx" % (variant, m), info, linf_error=err, energy_dev_max=drift)


def soft_disc(args, w):
    res = {}
    for variant, extra in (("explicit", []), ("semi_implicit", SEMI)):
        # to t = 1 of the scene's 8: the automatic contact velocity scale is lx / t_end
        # without an initial flow (solver/model/contact.cpp), so keep the full run's 1/8, or the
        # shorter run's contact limit (8e-4) would set dt for both variants
        info = run(args, "scenes/soft_disc_cavity.toml", "soft_disc_" + variant,
                   ["time.end=1.0", "output.interval=0", "contact.velocity_scale=0.125"] + extra)
        res[variant] = info
        c = info["diag"][-1] if info.get("diag") else {}
        out_row(w, "soft_disc_cavity_t1", variant, info, cx=float(c.get("solid0_cx", "nan")), cy=float(c.get("solid0_cy", "nan")))


def implicit_tol(args, w):
    """time.implicit_tol against the old setting (the pressure's solver.tol = 1e-10 of both
    scenes): couette_elastic at 64 cells per unit and the shear wave at 4 and 10 times the
    explicit step (the rows of couette() and shear() above, at each tolerance)."""
    ref = list(csv.DictReader(open("tests/data/couette_elastic_startup.csv")))
    for tol in ("1e-10", "1e-8", "1e-6", "1e-5", "1e-4", "1e-3"):
        sets = ["grid.ny=128", "domain.lx=0.125", "domain.ly=2.0", "output.interval=0",
                "time.implicit_tol=" + tol] + SEMI
        info = run(args, "scenes/couette_elastic.toml", "couette_tol" + tol, sets)
        err = float("nan")
        if info["ok"]:
            pr = [r for r in rows(os.path.join(info["dir"], "probe_u_profile.csv")) if r[0] != "x"][-41:]
            err = max(abs(float(a[2]) - float(b["u_t4.8"])) for a, b in zip(pr, ref))
        out_row(w, "tol_couette_elastic_64", "implicit_tol=" + tol, info, linf_error=err)
        lim = 0.5 / 32
        for m in (4, 10):
            sets = ["time.dt=%.10g" % (m * lim), "output.interval=0", "time.solid_stress=semi_implicit",
                    "time.implicit_tol=" + tol]
            info = run(args, "scenes/shear_wave.toml", "shear_tol%s_%g" % (tol, m), sets)
            err = float("nan")
            if info["ok"]:
                t = info["t"]
                pr = [r for r in rows(os.path.join(info["dir"], "probe_u_profile.csv")) if r[0] != "x"][-32:]
                err = max(abs(float(r[2]) - 0.25 * math.sin(2 * math.pi * float(r[1])) * math.cos(2 * math.pi * t))
                          for r in pr) / 0.25
            out_row(w, "tol_shear_wave_32", "dt=%gx implicit_tol=%s" % (m, tol), info, linf_error=err)


def dist_to_polyline(p, poly):
    best = float("inf")
    for (ax, ay), (bx, by) in zip(poly, poly[1:]):
        dx, dy = bx - ax, by - ay
        l2 = dx * dx + dy * dy
        s = min(max(((p[0] - ax) * dx + (p[1] - ay) * dy) / l2, 0.0), 1.0) if l2 > 0 else 0.0
        best = min(best, math.hypot(p[0] - ax - s * dx, p[1] - ay - s * dy))
    return best


def soft_disc_full(args, w):
    """The shipped scene (128^2, t = 8) explicit and with both implicit keys, back to back:
    wall time, and the largest distance of the centroid (every step) to Sugiyama et al.'s
    path (tests/test_soft_disc_cavity.cpp's criterion)."""
    sug = [(float(r["x_centroid"]), float(r["y_centroid"]))
           for r in csv.DictReader(open("tests/data/sugiyama2011_disc_centroid_path.csv"))]
    explicit_path = []
    for variant, extra in (("explicit", []), ("semi_implicit", SEMI)):
        info = run(args, "scenes/soft_disc_cavity.toml", "soft_disc_full_" + variant,
                   ["output.interval=0", "output.vtk=false"] + extra)
        dg = info.get("diag", [])
        path = [(float(r["time"]), float(r["solid0_cx"]), float(r["solid0_cy"])) for r in dg]
        d = max((dist_to_polyline((x, y), sug) for _, x, y in path), default=float("nan"))
        # the largest distance is at the start (the disc's centre against the digitised
        # path's first point, 0.013); after t = 0.5 it is the path's own
        d05 = max((dist_to_polyline((x, y), sug) for t, x, y in path if t >= 0.5), default=float("nan"))
        if variant == "explicit":
            explicit_path = [(x, y) for _, x, y in path]
        dex = max((dist_to_polyline((x, y), explicit_path) for _, x, y in path), default=float("nan"))
        out_row(w, "soft_disc_cavity_t8", variant, info, max_dist_sugiyama=d, max_dist_sugiyama_t05=d05,
                max_dist_explicit_path=dex,
                cx=float(dg[-1]["solid0_cx"]) if dg else float("nan"),
                cy=float(dg[-1]["solid0_cy"]) if dg else float("nan"))


def first_restitution(d):
    p = os.path.join(d, "events.csv")
    if not os.path.exists(p):
        return float("nan")
    for r in csv.DictReader(open(p)):
        if "restitution" in r["event"]:
            return float(r["value"])
    return float("nan")


def variant_sets(variant):
    """--set arguments of a variant "stress[+reachR][+cflP][+kK][+specific][+dtmaxD]":
    time.solid_stress (with the implicit viscous term unless explicit),
    time.solid_implicit_reach = R, time.solid_implicit_cfl = P, time.solid_implicit_k = K,
    solids.stress_blend = "specific", time.dt_max = D (docs/implicit.md)."""
    stress, *opts = variant.split("+")
    sets = [] if stress == "explicit" else ["time.viscous=implicit", "time.solid_stress=" + stress]
    keys = (("reach", "time.solid_implicit_reach="), ("cfl", "time.solid_implicit_cfl="),
            ("dtmax", "time.dt_max="), ("k", "time.solid_implicit_k="))
    for o in opts:
        if o == "specific":
            sets.append("solids.stress_blend=specific")
            continue
        key = next(k for k in keys if o.startswith(k[0]))
        sets.append(key[1] + o[len(key[0]):])
    return sets


RC = "semi_implicit+reach2+cfl8"  # the reach with the implicit stress's own step cap P = 8


def bounce(args, w, cases=((1e3, ("explicit", "semi_implicit", "semi_implicit+reach2", RC)),
                          (1e4, ("explicit", "semi_implicit", "semi_implicit+reach2", RC, RC + "+specific")),
                          (1e5, ("explicit", "semi_implicit", "semi_implicit+reach2", RC, RC + "+specific")))):
    # variants as variant_sets reads them, e.g. "semi_implicit+reach2+cfl8+specific"
    for mu_s, variants in cases:
        for variant in variants:
            sets = ["time.end=0.5", "output.interval=0", "solid[0].mu_s=%g" % mu_s] + variant_sets(variant)
            info = run(args, "scenes/bounce_stiff.toml", "bounce_%g_%s" % (mu_s, variant), sets)
            dg = info.get("diag", [])
            a0 = float(dg[0]["solid0_area"]) if dg else float("nan")
            area_dev = max(abs(float(r["solid0_area"]) / a0 - 1) for r in dg) if dg else float("nan")
            gap = min(float(r["solid0_gap_wall"]) for r in dg) if dg else float("nan")
            # kinetic + elastic energy: at most what the fall released (the impact's) if stable
            ke_el = max((float(r["kinetic_energy"]) + float(r["elastic_energy"]) for r in dg), default=float("nan"))
            out_row(w, "bounce_stiff_mu%g" % mu_s, variant, info, area_dev_max=area_dev, min_gap_wall=gap,
                    restitution=first_restitution(info["dir"]), max_ke_elastic=ke_el)


# disc_tgv's explicit step is the solid limit 0.5 dx / c (c = 1); "explicit+dtmax0.0019" is a
# quarter of it, the reference the explicit run's own time error is read against
TGV_FINE = "explicit+dtmax0.0019"
TGV = ("explicit", TGV_FINE, "semi_implicit", "semi_implicit+cfl0.5", "semi_implicit+cfl1",
       "semi_implicit+cfl0.5+k0.25", "semi_implicit+cfl1+k0.25", "semi_implicit+k0.25",
       "upper_convected", "upper_convected+cfl0.5", "upper_convected+cfl1")


def disc_tgv(args, w, variants=TGV):
    """Energy exchange of a disc in a Taylor-Green flow: the elastic energy's peak, the kinetic
    energy at t = 1, 2, 4 (interpolated in time), and the largest difference of the kinetic
    energy over t in [0, 4] from the explicit run and from the explicit run at a quarter of its
    step, in % of the initial kinetic energy (ke_dev_explicit, ke_dev_fine)."""
    series = {}
    for variant in dict.fromkeys(("explicit", TGV_FINE) + tuple(variants)):
        series[variant] = run(args, "scenes/disc_tgv.toml", "disc_tgv_" + variant.replace("+", "_"),
                              ["output.interval=0"] + variant_sets(variant))

    def ke(info):
        dg = info.get("diag", [])
        return [float(r["time"]) for r in dg], [float(r["kinetic_energy"]) for r in dg]

    def at(info, t):
        ts, ks = ke(info)
        if not ts or ts[-1] < t:
            return float("nan")
        j = next(j for j, x in enumerate(ts) if x >= t)
        if j == 0:
            return ks[0]
        a = (t - ts[j - 1]) / (ts[j] - ts[j - 1])
        return ks[j - 1] + a * (ks[j] - ks[j - 1])

    def dev(info, ref):
        k0 = at(ref, 0.0)
        return max(abs(at(info, 0.01 * i) - at(ref, 0.01 * i)) for i in range(401)) / k0 * 100

    for variant in variants:
        info = series[variant]
        dg = info.get("diag", [])
        peak = max(dg, key=lambda r: float(r["elastic_energy"])) if dg else {}
        out_row(w, "disc_tgv", variant, info, elastic_peak=float(peak.get("elastic_energy", "nan")),
                elastic_peak_t=float(peak.get("time", "nan")), ke_t1=at(info, 1), ke_t2=at(info, 2),
                ke_t4=at(info, 4), ke_dev_explicit=dev(info, series["explicit"]),
                ke_dev_fine=dev(info, series[TGV_FINE]))


def upper_convected(args, w):
    """time.solid_stress = "upper_convected" (docs/implicit.md) on the cases above, beside the
    explicit and semi-implicit rows already in results/implicit.csv (not re-run); its
    disc_tgv rows are made by disc_tgv with the others."""
    couette(args, w, (("upper_convected", UC),))
    shear(args, w, ("upper_convected",))
    bounce(args, w, ((1e3, ("upper_convected", "upper_convected+reach2")), (1e4, ("upper_convected", "upper_convected+reach2")),
                     (1e5, ("upper_convected", "upper_convected+reach2"))))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin")
    ap.add_argument("--out")
    ap.add_argument("--raw")
    ap.add_argument("--cases", nargs="+")
    args = ap.parse_args()
    os.makedirs(args.raw, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    # rows of the cases not run now are kept from the last results/implicit.csv
    prefix = {"couette": "couette_elastic", "shear": "shear_wave", "soft_disc": "soft_disc_cavity_t1",
              "bounce": "bounce_stiff", "disc_tgv": "disc_tgv", "tol": "tol_",
              "soft_disc_full": "soft_disc_cavity_t8", "uc": None}
    path = os.path.join(args.out, "implicit.csv")
    w = []
    if os.path.exists(path):
        w = [r for r in csv.DictReader(open(path))
             if not any(r["case"].startswith(prefix[c]) if prefix[c] else
                        r["variant"].startswith("upper_convected") and r["case"] != "disc_tgv"
                        for c in args.cases)]
    for c in args.cases:
        {"couette": couette, "shear": shear, "soft_disc": soft_disc, "bounce": bounce, "disc_tgv": disc_tgv,
         "tol": implicit_tol, "soft_disc_full": soft_disc_full, "uc": upper_convected}[c](args, w)
        keys = []
        for r in w:
            keys += [k for k in r if k not in keys]
        with open(os.path.join(args.out, "implicit.csv"), "w", newline="") as f:
            cw = csv.DictWriter(f, fieldnames=keys)
            cw.writeheader()
            cw.writerows(w)


if __name__ == "__main__":
    main()
