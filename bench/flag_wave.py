#!/usr/bin/env python3
"""Grid-scale wave along the Turek & Hron flag (results/fsi.md, "The grid-scale wave along the
flag"): for every VTK frame of a run, the amplitude of the velocity's short-wave content inside
the flag and its dominant wavelength along it; then the growth rate of that amplitude.

  amplitude A(t): rms over the flag's cells (phi < -dx, x in [X0, X1]) of the second difference
                  along x of the velocity, |u_{i+1} - 2 u_i + u_{i-1}| / 4 (both components): a
                  high-pass filter with gain 1 at the odd-even mode, 0.56 at 3 cells, 0.25 at
                  4 cells and ~ (pi / n)^2 for a wave of n cells;
  wavelength:     the peak (in cells) of the power spectrum along x of the velocity (both
                  components, each row of the flag's inside, the row's linear trend removed)
                  over wavelengths of 2-12 cells.
  growth rate:    the least-squares slope of ln A over the frames with 1e-6 <= A <= 1e-2 m/s up
                  to A's first reaching 1e-2 (the exponential stretch, before saturation or failure).

Usage (Debian's numpy): /usr/bin/python3 bench/flag_wave.py RUN_DIR [X0 X1]
prints one line per frame (t, A, wavelength) and a last line `growth RATE /s` (or `no growth`).
"""
import glob
import math
import os
import sys

import numpy as np

from studies import read_vti_fields


def frame_measure(path, x0f, x1f):
    t, (x0, y0, dx), f = read_vti_fields(path, ("velocity", "phi"))
    vel, phi = f["velocity"], f["phi"]
    ny, nx = phi.shape
    x = x0 + dx * (np.arange(nx) + 0.5)
    cols = np.where((x >= x0f) & (x <= x1f))[0]
    i0, i1 = cols[0], cols[-1] + 1
    u, v = vel[:, :, 0], vel[:, :, 1]
    inside = phi[:, i0:i1] < -dx
    inner = inside.copy()
    inner[:, 0] = inner[:, -1] = False  # the second difference needs both neighbours
    d2u = (u[:, i0 + 1:i1 + 1] - 2 * u[:, i0:i1] + u[:, i0 - 1:i1 - 1]) / 4
    d2v = (v[:, i0 + 1:i1 + 1] - 2 * v[:, i0:i1] + v[:, i0 - 1:i1 - 1]) / 4
    n = inner.sum()
    amp = math.sqrt(((d2u[inner] ** 2 + d2v[inner] ** 2).sum()) / n) if n else float("nan")
    # spectrum along x of each row that is inside the flag over its whole length
    power = None
    for j in range(ny):
        if not inside[j].all():
            continue
        for q in (u[j, i0:i1], v[j, i0:i1]):
            s = np.arange(len(q))
            q = q - np.polyval(np.polyfit(s, q, 1), s)
            p = np.abs(np.fft.rfft(q * np.hanning(len(q)))) ** 2
            power = p if power is None else power + p
    wl = float("nan")
    if power is not None:
        m = i1 - i0
        k = np.arange(len(power))
        with np.errstate(divide="ignore"):
            lam = np.where(k > 0, m / np.maximum(k, 1), np.inf)
        keep = (lam >= 2) & (lam <= 12)
        if keep.any():
            wl = float(lam[keep][np.argmax(power[keep])])
    return t, amp, wl


def main():
    run = sys.argv[1]
    x0f = float(sys.argv[2]) if len(sys.argv) > 2 else 0.27
    x1f = float(sys.argv[3]) if len(sys.argv) > 3 else 0.57
    rows = []
    for path in sorted(glob.glob(os.path.join(run, "frame_[0-9]*.vti"))):
        try:
            rows.append(frame_measure(path, x0f, x1f))
        except (ValueError, IndexError):
            continue  # a frame being written
    for t, a, wl in rows:
        print(f"{t:.4f} {a:.4e} {wl:.2f}")
    ts = np.array([r[0] for r in rows])
    amps = np.array([r[1] for r in rows])
    # the exponential stretch: from A = 1e-6 m/s (above the start-up transient) to its first
    # reaching 1e-2 m/s (before the run saturates or fails)
    top = np.where(amps >= 1e-2)[0]
    last = top[0] if len(top) else len(rows) - 1
    sel = [i for i in range(last + 1) if 1e-6 <= amps[i] <= 1e-2]
    if len(sel) < 3:
        print("no growth (A stays below 1e-6 m/s or jumps past 1e-2 within two frames)")
        return
    rate = np.polyfit(ts[sel], np.log(amps[sel]), 1)[0]
    print(f"growth {rate:.1f} /s over t in [{ts[sel[0]]:.3f}, {ts[sel[-1]]:.3f}]")

if __name__ == "__main__":
    main()
