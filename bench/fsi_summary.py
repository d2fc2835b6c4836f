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
SMOOTH (seconds, default 0: none): the forces are first averaged over a centred window of that
length, to take out the per-step noise of the cylinder's forcing force (oscillations far faster
than the benchmark's 2-11 Hz) that would otherwise set max - min.
T_END (default: the run's last time): end of the window, for a run whose last stretch is not
periodic (e.g. one that went unstable).
Usage: fsi_summary.py RUN_DIR CASE RHO_S [WINDOW [SMOOTH [T_END]]] -> CSV rows on stdout
(quantity, ours, reference).
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes"))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)

REF = {  # docs/references.md#turek-and-hron-fsi-benchmark: mean, amplitude, frequency
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


def moving_average(t, s, width):
    """centred running mean of s over |t' - t| <= width / 2 (shorter at the window's ends)"""
    out, lo, hi, acc = [], 0, 0, 0.0
    for k in range(len(t)):
        while hi < len(t) and t[hi] <= t[k] + 0.5 * width:
            acc += s[hi]
            hi += 1
        while t[lo] < t[k] - 0.5 * width:
            acc -= s[lo]
            lo += 1
        out.append(acc / (hi - lo))
    return out


def main():
    run, case, rho_s = sys.argv[1], sys.argv[2], float(sys.argv[3])
    window = float(sys.argv[4]) if len(sys.argv) > 4 else 2.0
    smooth = float(sys.argv[5]) if len(sys.argv) > 5 else 0.0
    m = read(run + "/markers.csv")
    d = read(run + "/diagnostics.csv")
    d.update(solids_csv.wide_columns(run, d["step"]))
    t_end = float(sys.argv[6]) if len(sys.argv) > 6 else d["time"][-1]
    t0 = t_end - window
    tm = [t for t in m["t"] if t0 <= t <= t_end]
    ux = [x - 0.6 for t, x in zip(m["t"], m["x"]) if t0 <= t <= t_end]
    uy = [y - 0.2 for t, y in zip(m["t"], m["y"]) if t0 <= t <= t_end]
    td = d["time"]
    px = [rho_s * a * u for a, u in zip(d["solid1_area"], d["solid1_u"])]
    py = [rho_s * a * v for a, v in zip(d["solid1_area"], d["solid1_v"])]
    drag, lift, tf = [], [], []
    for k in range(1, len(td) - 1):
        if td[k] < t0 - smooth or td[k] > t_end + smooth:
            continue
        h = td[k + 1] - td[k - 1]
        drag.append(d["solid0_fx"][k] + (px[k + 1] - px[k - 1]) / h)
        lift.append(d["solid0_fy"][k] + (py[k + 1] - py[k - 1]) / h)
        tf.append(td[k])
    if smooth > 0:
        drag, lift = moving_average(tf, drag, smooth), moving_average(tf, lift, smooth)
    inside = [k for k, t in enumerate(tf) if t0 <= t <= t_end]  # the padding only fed the means
    tf, drag, lift = [tf[k] for k in inside], [drag[k] for k in inside], [lift[k] for k in inside]
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["case", "quantity", "mean", "amplitude", "frequency", "crossings", "ref_mean", "ref_amplitude",
                "ref_frequency", "window_start", "t_end", "force_smoothing"])
    for name, t, s in (("ux", tm, ux), ("uy", tm, uy), ("drag", tf, drag), ("lift", tf, lift)):
        mean, amp, freq, n = stats(t, s)
        r = REF[case][name]
        w.writerow([case, name, f"{mean:.5g}", f"{amp:.5g}", f"{freq:.4g}", n, r[0], r[1], r[2], f"{t0:.4g}",
                    f"{t_end:.4g}", smooth])


if __name__ == "__main__":
    main()
