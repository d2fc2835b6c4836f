#!/usr/bin/env python3
"""Figure of a Turek & Hron run (bench/run_fsi.sh): the tip displacement u_x, u_y of A against
time, the tip trajectory (u_y against u_x), and the force on the cylinder (solid0_fx, _fy of solids.csv).
Usage (Debian's matplotlib): /usr/bin/python3 bench/fsi_plot.py RUN_DIR OUT.png [T_MAX]
(T_MAX: leave out later rows, e.g. the last steps of a run that failed)"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scenes"))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    return {h: [float(r[k]) for r in rows[1:]] for k, h in enumerate(rows[0])}


def main():
    run, out = sys.argv[1], sys.argv[2]
    m, d = read(run + "/markers.csv"), read(run + "/diagnostics.csv")
    d.update(solids_csv.wide_columns(run, d["step"]))
    t_max = float(sys.argv[3]) if len(sys.argv) > 3 else float("inf")
    for tab, key in ((m, "t"), (d, "time")):
        keep = [k for k, t in enumerate(tab[key]) if t <= t_max]
        for h in tab:
            tab[h] = [tab[h][k] for k in keep]
    ux = [x - 0.6 for x in m["x"]]
    uy = [y - 0.2 for y in m["y"]]
    fig, ax = plt.subplots(1, 3, figsize=(14, 3.8))
    ax[0].plot(m["t"], ux, label="u_x(A)")
    ax[0].plot(m["t"], uy, label="u_y(A)")
    ax[0].set_xlabel("t")
    ax[0].set_ylabel("tip displacement")
    ax[0].legend()
    ax[1].plot(ux, uy, lw=0.7)
    ax[1].set_xlabel("u_x(A)")
    ax[1].set_ylabel("u_y(A)")
    ax[1].set_title("tip trajectory")
    ax[2].plot(d["time"], d["solid0_fx"], lw=0.7, label="F_x on cylinder (forcing)")
    ax[2].plot(d["time"], d["solid0_fy"], lw=0.7, label="F_y on cylinder (forcing)")
    ax[2].set_xlabel("t")
    ax[2].legend()
    fig.suptitle(run.rstrip("/").split("/")[-1])
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
