#!/usr/bin/env python3
"""Both body-force estimators of one run (rows of build/bench/refmap_body_forces), as Turek &
Hron report forces: mean = (max + min) / 2, amplitude = (max - min) / 2 over a window, frequency
from the crossings of the mean (bench/fsi_summary.py's definitions, imported from there).

Estimators of the fluid's force on body 0 (with the soft solids clamped to it):
 * forcing     the direct forcing's force (docs/bodies.md), which in a steady state includes
               the clamped solids' pull;
 * forcing+dP  that plus d/dt of the clamped solids' momentum (centred differences): what
               bench/fsi_summary.py reports for Turek & Hron (results/README.md);
 * cv          the control-volume balance (output.body_force = "control_volume").
Usage: body_force_summary.py ROWS.csv T0 T1 [SMOOTH [SCALE]] -> CSV on stdout: for drag (x) and
lift (y) and each estimator, mean, amplitude, frequency, the rms of (raw - smoothed) (the
per-step noise SMOOTH removes), and the ratio of its amplitude to cv's. SCALE (default 1)
multiplies the forces (e.g. 1 / (rho U^2 D / 2) for coefficients).
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fsi_summary import moving_average, stats  # noqa: E402


def main():
    path, t0, t1 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    smooth = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0
    scale = float(sys.argv[5]) if len(sys.argv) > 5 else 1.0
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if all(v not in (None, "") for v in r.values())]  # a run still writing
    t = [float(r["time"]) for r in rows]
    col = {k: [float(r[k]) * scale for r in rows] for k in rows[0] if k != "time"}
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["quantity", "estimator", "mean", "amplitude", "frequency", "noise_rms", "amplitude_over_cv",
                  "t0", "t1", "smooth"])
    for q, a in (("drag", "x"), ("lift", "y")):
        series = {}
        tt = []
        for k in range(1, len(t) - 1):
            if t[k] < t0 - smooth or t[k] > t1 + smooth:
                continue
            h = t[k + 1] - t[k - 1]
            dp = (col["clamped_p" + a][k + 1] - col["clamped_p" + a][k - 1]) / h
            f = col["forcing_f" + a][k]
            series.setdefault("forcing", []).append(f)
            series.setdefault("forcing+dP", []).append(f + dp)
            series.setdefault("cv", []).append(col["cv_f" + a][k])
            tt.append(t[k])
        res = {}
        for name, s in series.items():
            sm = moving_average(tt, s, smooth) if smooth > 0 else s
            inside = [k for k, x in enumerate(tt) if t0 <= x <= t1]
            ti = [tt[k] for k in inside]
            si = [sm[k] for k in inside]
            noise = math.sqrt(sum((s[k] - sm[k]) ** 2 for k in inside) / len(inside))
            res[name] = stats(ti, si) + (noise,)
        for name, (mean, amp, freq, _, noise) in res.items():
            out.writerow([q, name, f"{mean:.5g}", f"{amp:.5g}", f"{freq:.4g}", f"{noise:.4g}",
                          f"{amp / res['cv'][1]:.4g}" if res["cv"][1] else "nan", t0, t1, smooth])


if __name__ == "__main__":
    main()
