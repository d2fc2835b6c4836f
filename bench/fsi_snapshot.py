#!/usr/bin/env python3
"""Snapshot of a Turek & Hron run (bench/run_fsi.sh): the vorticity near the cylinder and the
flag, with the solids' outline (phi = 0), from one VTK frame.
Usage (Debian's matplotlib and numpy): /usr/bin/python3 bench/fsi_snapshot.py FRAME.vti OUT.png"""
import sys

import matplotlib
import numpy as np

from studies import read_vti_fields

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    frame, out = sys.argv[1], sys.argv[2]
    t, (x0, y0, dx), f = read_vti_fields(frame, ("vorticity", "phi"))
    ny, nx = f["phi"].shape
    x = x0 + dx * (np.arange(nx) + 0.5)
    y = y0 + dx * (np.arange(ny) + 0.5)
    keep = x <= 1.2
    w = f["vorticity"][:, keep]
    lim = np.percentile(np.abs(w), 99)
    fig, ax = plt.subplots(figsize=(12, 4.4))
    im = ax.pcolormesh(x[keep], y, w, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
    ax.contour(x[keep], y, f["phi"][:, keep], levels=[0.0], colors="k", linewidths=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title(f"vorticity and the solids' outline (phi = 0), t = {t:.3f}")
    fig.colorbar(im, ax=ax, shrink=0.8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
