#!/usr/bin/env python3
"""The Turek & Hron flag's area and its reference map's Jacobian over a run (results/fsi.md,
"The flag loses area once it swings").

For each VTK frame of a run of scenes/turek_hron_fsi{2,3}.toml: the area of the cells with
phi < 0 behind the cylinder (x > 0.26, so the flag alone), and J = det grad xi (central
differences) over the cells deeper than 3/4 dx inside it: mean, min and max. An incompressible
solid keeps J = 1 (det F = 1 / J); J > 1 means the map itself has compressed the flag. Also
the range of the reference coordinates xi_x, xi_y found in the flag: if the material at its
tip or edges were lost, the range would shrink.

    /usr/bin/python3 bench/flag_jacobian.py RUN_DIR [every-n-th frame, default 50] > out.csv
"""
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from studies import read_vti_fields  # noqa: E402


def main():
    run = sys.argv[1]
    every = int(sys.argv[2]) if len(sys.argv) > 2 else 50
    frames = sorted(glob.glob(os.path.join(run, "frame_[0-9]*.vti")))
    print("t,area,inner_cells,J_mean,J_min,J_max,xi_x_min,xi_x_max,xi_y_min,xi_y_max")
    for path in frames:
        n = int(os.path.basename(path)[6:11])
        if n % every:
            continue
        t, (x0, _, dx), f = read_vti_fields(path, ("phi", "xi"))
        phi, xi = f["phi"], f["xi"]
        ny, nx = phi.shape
        x = np.broadcast_to(x0 + (np.arange(nx) + 0.5) * dx, (ny, nx))
        flag = (phi < 0) & (x > 0.26)
        inner = (phi < -0.75 * dx) & (x > 0.26)
        a, b = xi[:, :, 0], xi[:, :, 1]

        def d(q, axis):
            return (np.roll(q, -1, axis) - np.roll(q, 1, axis)) / (2 * dx)

        jac = d(a, 1) * d(b, 0) - d(a, 0) * d(b, 1)
        j = jac[inner]
        print(f"{t:.4f},{flag.sum() * dx * dx:.6g},{inner.sum()},{j.mean():.4f},{j.min():.4f},{j.max():.4f},"
              f"{a[flag].min():.4f},{a[flag].max():.4f},{b[flag].min():.4f},{b[flag].max():.4f}")


if __name__ == "__main__":
    main()
