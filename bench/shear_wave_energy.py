"""Runs of bench/run_shear_wave_energy.sh: the shear wave's energy error against the solid
step P (solids.solid_cfl), for both stress forms and both elastic couplings
(time.elastic_coupling; docs/method.md, "Time step"). One row per run."""
import argparse, csv, os, subprocess, sys


def rows(path):
    return [r for r in csv.reader(open(path)) if r and not r[0].startswith("#")]


def run(args, form, coupling, p):
    name = "%s_%s_P%g" % (form, coupling, p)
    d = os.path.join(args.raw, name)
    sets = ["grid.nx=%d" % args.n, "grid.ny=%d" % args.n, "time.end=%g" % args.periods,
            "output.interval=0", "solids.stress_discretisation=%s" % form,
            "time.elastic_coupling=%s" % coupling, "solids.solid_cfl=%g" % p]
    cmd = [args.bin, "run", "scenes/shear_wave.toml", "-o", d, "-q", "-j", "1"] + sum((["--set", s] for s in sets), [])
    proc = subprocess.run(cmd, capture_output=True, text=True)
    r = rows(os.path.join(d, "diagnostics.csv"))
    h = r[0]
    ke, ee, t = h.index("kinetic_energy"), h.index("elastic_energy"), h.index("time")
    e = [float(x[ke]) + float(x[ee]) for x in r[1:]]
    dev = [x / e[0] - 1.0 for x in e]
    # the largest |E / E0 - 1| over the steps (the ShearWaveEnergy tests' measure), the final
    # value (the accumulated loss) and the largest rise
    out = {"stress": form, "coupling": coupling, "solid_cfl": "%g" % p, "ok": int(proc.returncode == 0),
           "steps": len(r) - 2, "t_end": "%.6g" % float(r[-1][t]),
           "max_abs_dev_pct": "%.4f" % (100 * max(abs(x) for x in dev)),
           "final_dev_pct": "%.4f" % (100 * dev[-1]), "max_rise_pct": "%.4f" % (100 * max(dev))}
    print(out, flush=True)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="build/refmap")
    ap.add_argument("--out", default="results")
    ap.add_argument("--raw", default="/tmp/refmap_shear_wave_energy")
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--periods", type=float, default=4.0)
    ap.add_argument("--cfl", type=float, nargs="+", default=[1.0, 0.75, 0.5, 0.25, 0.1])
    ap.add_argument("--couplings", nargs="+", default=["symplectic_euler", "verlet"])
    a = ap.parse_args()
    os.makedirs(a.raw, exist_ok=True)
    out = [run(a, form, c, p) for c in a.couplings for form in ("cell", "face") for p in a.cfl]
    path = os.path.join(a.out, "shear_wave_energy.csv")
    with open(path, "w", newline="") as f:
        f.write("# bash bench/run_shear_wave_energy.sh: scenes/shear_wave.toml on %d^2, t in [0, %g] (%g periods); "
                "max_abs_dev_pct = max over the steps of |E / E0 - 1| in %%, E = kinetic + elastic energy "
                "(exactly constant)\n" % (a.n, a.periods, a.periods))
        w = csv.DictWriter(f, fieldnames=list(out[0].keys()))
        w.writeheader()
        w.writerows(out)
    print("wrote", path)


if __name__ == "__main__":
    sys.exit(main())
