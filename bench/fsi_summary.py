#!/usr/bin/env python3
"""Summarise a Turek & Hron FSI2 / FSI3 run (scenes/turek_hron_fsi*.toml, bench/run_fsi.sh).

Inputs of RUN_DIR: markers.csv (the material point at the reference tip A = (0.6, 0.2), one row
per VTK frame) and diagnostics.csv. Outputs, over the window [t_end - WINDOW, t_end]:
 * tip displacement u_x = x_A - 0.6, u_y = y_A - 0.2;
 * drag and lift on cylinder + flag (per unit depth):
       F = solid0_f + d/dt (rho_s A_flag U_flag),
   solid0_f the force on the fixed cylinder from its direct forcing, which includes the
   clamped flag's pull on it (docs/bodies.md), plus the rate of change of the flag's own
   momentum (solid1_area times the mean velocity solid1_u, solid1_v, times rho_s; centred
   differences): the fluid's force on the flag is its momentum change minus the clamp's
   force on it.
Each signal is reported as Turek & Hron do: mean = (max + min) / 2, amplitude = (max - min) / 2
over the window, frequency = 1 / (mean spacing of its upward crossings of the mean).
Usage: fsi_summary.py RUN_DIR CASE RHO_S [WINDOW] -> CSV rows on stdout (quantity, ours, reference).
"""
import csv
import sys

REF = {  # BENCHMARKS.md 7d: mean, amplitude, frequency
    "FSI2": {"ux": (-14.58e-3, 12.44e-3, 3.8), "uy": (1.23e-3, 80.6e-3, 2.0),
             "drag": (208.83, 73.75, 3.8), "lift": (0.88, 234.2, 2.0)},
    "FSI3": {"ux": (-2.69e-3, 2.53e-3, 10.9), "uy": (1.48e-3, 34.38e-3, 5.3),
             "drag": (457.3, 22.66, 10.9), "lift": (2.22, 149.78, 5.3)},
}


def read(path):
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    head = rows[0]
    return {h: [float(r[k]) for r in rows[1:]] for k, h in enumerate(head)}


def stats(t, s):
    hi, lo = max(s), min(s)
    mean, amp = 0.5 * (hi + lo), 0.5 * (hi - lo)
    ups = [t[k] + (t[k + 1] - t[k]) * (mean - s[k]) / (s[k + 1] - s[k])
           for k in range(len(s) - 1) if s[k] < mean <= s[k + 1]]
    freq = (len(ups) - 1) / (ups[-1] - ups[0]) if len(ups) >= 3 else float("nan")
    return mean, amp, freq, len(ups)


def main():
    run, case, rho_s = sys.argv[1], sys.argv[2], float(sys.argv[3])
    window = float(sys.argv[4]) if len(sys.argv) > 4 else 2.0
    m = read(run + "/markers.csv")
    d = read(run + "/diagnostics.csv")
    t_end = d["time"][-1]
    t0 = t_end - window
    tm = [t for t in m["t"] if t >= t0]
    ux = [x - 0.6 for t, x in zip(m["t"], m["x"]) if t >= t0]
    uy = [y - 0.2 for t, y in zip(m["t"], m["y"]) if t >= t0]
    td = d["time"]
    px = [rho_s * a * u for a, u in zip(d["solid1_area"], d["solid1_u"])]
    py = [rho_s * a * v for a, v in zip(d["solid1_area"], d["solid1_v"])]
    drag, lift, tf = [], [], []
    for k in range(1, len(td) - 1):
        if td[k] < t0:
            continue
        h = td[k + 1] - td[k - 1]
        drag.append(d["solid0_fx"][k] + (px[k + 1] - px[k - 1]) / h)
        lift.append(d["solid0_fy"][k] + (py[k + 1] - py[k - 1]) / h)
        tf.append(td[k])
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["case", "quantity", "mean", "amplitude", "frequency", "crossings", "ref_mean", "ref_amplitude",
                "ref_frequency", "window_start", "t_end"])
    for name, t, s in (("ux", tm, ux), ("uy", tm, uy), ("drag", tf, drag), ("lift", tf, lift)):
        mean, amp, freq, n = stats(t, s)
        r = REF[case][name]
        w.writerow([case, name, f"{mean:.5g}", f"{amp:.5g}", f"{freq:.4g}", n, r[0], r[1], r[2], f"{t0:.4g}",
                    f"{t_end:.4g}"])


if __name__ == "__main__":
    main()
