#!/usr/bin/env python3
"""Snapshot of a Turek & Hron run (bench/run_fsi.sh): the vorticity near the cylinder and the
flag, with the solids' outline (phi = 0), from one VTK frame.
Usage (Debian's matplotlib and numpy): /usr/bin/python3 bench/fsi_snapshot.py FRAME.vti OUT.png"""
import re
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_vti(path, names):
    """time, (x0, y0, dx) and the named cell fields (ny, nx) of a refmap .vti (raw appended)"""
    with open(path, "rb") as f:
        data = f.read()
    head_end = data.index(b"<AppendedData")
    head = data[:head_end].decode()
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    nx, ny = ext[1] - ext[0], ext[3] - ext[2]
    x0, y0, _ = [float(v) for v in re.search(r'Origin="([^"]+)"', head).group(1).split()]
    dx = float(re.search(r'Spacing="([^"]+)"', head).group(1).split()[0])
    time = float(re.search(r'Name="TIME"[^>]*>([^<]+)<', head).group(1))
    base = data.index(b"_", head_end) + 1
    out = {}
    for name in names:
        off = int(re.search(r'Name="%s"[^>]*offset="(\d+)"' % name, head).group(1))
        n = int(np.frombuffer(data, dtype="<u8", count=1, offset=base + off)[0]) // 8
        out[name] = np.frombuffer(data, dtype="<f8", count=n, offset=base + off + 8).reshape(ny, nx)
    return time, (x0, y0, dx), out


def main():
    frame, out = sys.argv[1], sys.argv[2]
    t, (x0, y0, dx), f = read_vti(frame, ("vorticity", "phi"))
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
