#!/usr/bin/env python3
"""Turn one refmap run directory into PNG figures.

    python3 scenes/plot_run.py RUN_DIR [--out DIR] [--times 0.5,1,2 | --count N]
                               [--field vorticity|speed|p|u|v|density|normal_stress|phi|...]
                               [--reference-path FILE[:LABEL] ...] [--dpi 110]

RUN_DIR is what `refmap run` wrote: frame_NNNNN.vti (+ <name>.pvd), diagnostics.csv, and
optionally probe_*.csv, events.csv, tracers.csv and markers.csv. Figures go to RUN_DIR/figures/ unless --out is given:

* snapshots_<field>.png  colour field at the chosen times (nearest output frame; the panel
                         title gives the frame's actual time). In the fluid the chosen field;
                         inside every solid (phi < 0) the normal stress (s11 + s22)/2 of the
                         solid stress, on its own colour scale; the zero level set of the
                         solids drawn as a black contour. The .vti files carry one merged
                         phi (the level set of the nearest solid), so the contour is that of
                         the union of the solids.
* energy.png             kinetic, elastic and total energy against time (those that exist)
* solids.png             per solid: centroid path (with --reference-path overlays), area
                         change, and, when the columns exist, sigma_max, gap_solid, gap_wall;
                         restitution values from events.csv when present
* tracers.png            (with tracers.csv / markers.csv) the paths of the fluid tracers and
                         of the solids' material points over the frames, start and end
                         marked; the snapshots also show them as dots at each frame's time
* probes.png             the probe_*.csv profiles (value along the probe), with reference
                         points from --probe-reference (e.g. Ghia's centreline tables)
* path_distance.txt      with --reference-path: distances between our centroid path and
                         each reference polyline (also printed)

Only python3, numpy and matplotlib (Debian: python3-numpy, python3-matplotlib).
Missing columns or files are skipped with a note; a directory that is not a run is an error.
"""
import argparse
import base64
import csv
import glob
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import solids_csv  # noqa: E402  (solids.csv pivoted to solid<k>_<quantity> columns)

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:  # pragma: no cover
    sys.exit(f"plot_run.py: error: {e}; install Debian's python3-numpy and python3-matplotlib "
             "(and run them with /usr/bin/python3 if another python3 comes first in PATH)")


def fail(msg):
    sys.exit(f"plot_run.py: error: {msg}")


def note(msg):
    print(f"plot_run.py: {msg}", file=sys.stderr)


# ----------------------------------------------------------------------------- VTK reading

_NP_TYPES = {"Float64": "f8", "Float32": "f4", "Int32": "i4", "Int64": "i8", "UInt8": "u1",
             "UInt32": "u4", "UInt64": "u8", "Int8": "i1", "Int16": "i2", "UInt16": "u2"}


class Frame:
    """One .vti image: cell fields as (ny, nx) arrays, vectors as (ny, nx, 3)."""

    def __init__(self, path):
        self.path = path
        with open(path, "rb") as f:
            raw = f.read()
        marker = raw.find(b"<AppendedData")
        if marker >= 0:
            start = raw.index(b"_", raw.index(b">", marker)) + 1  # data starts after '_'
            head = raw[:marker].decode("utf-8", "replace") + "</VTKFile>"
            appended = raw[start:]
            enc = re.search(rb'encoding="(\w+)"', raw[marker:start])
            encoding = enc.group(1).decode() if enc else "raw"
        else:
            head, appended, encoding = raw.decode("utf-8", "replace"), b"", None
        root = ET.fromstring(head)
        if root.get("type") != "ImageData":
            raise ValueError(f"{path}: not a VTK ImageData file")
        endian = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
        hdr = endian + ("u8" if root.get("header_type", "UInt32") == "UInt64" else "u4")
        hdr_size = np.dtype(hdr).itemsize
        img = root.find("ImageData")
        ext = [int(v) for v in img.get("WholeExtent").split()]
        self.nx, self.ny = ext[1] - ext[0], ext[3] - ext[2]
        ox, oy, _ = (float(v) for v in img.get("Origin").split())
        sx, sy, _ = (float(v) for v in img.get("Spacing").split())
        self.x0, self.y0, self.dx, self.dy = ox, oy, sx, sy
        self.extent = (ox, ox + self.nx * sx, oy, oy + self.ny * sy)
        self.time = None
        for da in img.iter("DataArray"):
            if da.get("Name") == "TIME" and da.get("format") == "ascii":
                self.time = float(da.text.split()[0])
        self.fields = {}
        cd = img.find("Piece/CellData")
        ncell = self.nx * self.ny
        for da in (cd if cd is not None else []):
            name = da.get("Name")
            dt = np.dtype(endian + _NP_TYPES[da.get("type")])
            ncomp = int(da.get("NumberOfComponents", "1"))
            fmt = da.get("format")
            if fmt == "appended":
                off = int(da.get("offset"))
                if encoding == "raw":
                    nbytes = int(np.frombuffer(appended, hdr, 1, off)[0])
                    data = np.frombuffer(appended, dt, nbytes // dt.itemsize, off + hdr_size)
                else:  # base64 appended: header and data encoded together (uncompressed)
                    blob = appended[off:].split(b"_")[0]
                    dec = base64.b64decode(blob.strip() + b"=" * (-len(blob.strip()) % 4))
                    data = np.frombuffer(dec, dt, ncell * ncomp, hdr_size)
            elif fmt == "binary":
                dec = base64.b64decode("".join(da.text.split()))
                data = np.frombuffer(dec, dt, ncell * ncomp, hdr_size)
            else:
                data = np.array(da.text.split(), dtype=dt)
            if data.size != ncell * ncomp:
                raise ValueError(f"{path}: array {name} has {data.size} values, expected {ncell * ncomp}")
            self.fields[name] = data.reshape(self.ny, self.nx, ncomp) if ncomp > 1 else data.reshape(self.ny, self.nx)

    def cell_centres(self):
        x = self.x0 + (np.arange(self.nx) + 0.5) * self.dx
        y = self.y0 + (np.arange(self.ny) + 0.5) * self.dy
        return np.meshgrid(x, y)

    def get(self, name):
        f = self.fields
        if name in f:
            return f[name]
        vel = f.get("velocity")
        if vel is not None:
            if name == "speed":
                return np.hypot(vel[..., 0], vel[..., 1])
            if name in ("u", "v"):
                return vel[..., 0 if name == "u" else 1]
        raise KeyError(name)

    def names(self):
        n = [k for k, a in self.fields.items() if a.ndim == 2]
        if "velocity" in self.fields:
            n += ["speed", "u", "v"]
        return n


def read_series(run):
    """(time, path) of every frame: from the .pvd when there is one, else the frames' TIME."""
    pvds = sorted(glob.glob(os.path.join(run, "*.pvd")))
    out = []
    if pvds:
        root = ET.parse(pvds[0]).getroot()
        for ds in root.iter("DataSet"):
            p = os.path.join(os.path.dirname(pvds[0]), ds.get("file"))
            if os.path.exists(p):
                out.append((float(ds.get("timestep")), p))
    if not out:
        for p in sorted(glob.glob(os.path.join(run, "frame_*.vti"))):
            out.append((Frame(p).time or 0.0, p))
    return sorted(out)


# ----------------------------------------------------------------------------- CSV reading

def read_table(path):
    """CSV with '#' comment lines and one header line -> dict of column -> array (or str list)."""
    with open(path) as f:
        lines = [l for l in f if l.strip() and not l.lstrip().startswith("#")]
    if not lines:
        return {}
    rows = list(csv.reader(lines))
    header = [h.strip() for h in rows[0]]
    cols = {h: [] for h in header}
    for r in rows[1:]:
        if len(r) != len(header):
            continue  # a partly written last line
        for h, v in zip(header, r):
            cols[h].append(v.strip())
    out = {}
    for h, vals in cols.items():
        try:
            out[h] = np.array([float(v) for v in vals])
        except ValueError:
            out[h] = vals
    return out


def read_path(spec):
    """FILE[:LABEL] of a reference path: the first two numeric columns are x, y."""
    path, label = spec, None
    if ":" in spec and not os.path.exists(spec):
        path, label = spec.rsplit(":", 1)
    if not os.path.exists(path):
        fail(f"--reference-path: no such file: {path}")
    t = read_table(path)
    num = [k for k, v in t.items() if isinstance(v, np.ndarray)]
    if len(num) < 2:
        fail(f"--reference-path: {path}: need two numeric columns (x, y)")
    if label is None:
        label = os.path.basename(path).split("_")[0]
    return label, np.column_stack([t[num[0]], t[num[1]]])


def dist_to_polyline(pts, poly):
    """Distance from each point of pts (n, 2) to the polyline poly (m, 2)."""
    a, b = poly[:-1], poly[1:]
    ab = b - a
    L2 = np.maximum((ab ** 2).sum(1), 1e-300)
    d = np.full(len(pts), np.inf)
    for k in range(0, len(pts), 2048):
        p = pts[k:k + 2048, None, :]
        s = np.clip(((p - a) * ab).sum(2) / L2, 0.0, 1.0)
        q = a + s[..., None] * ab
        d[k:k + 2048] = np.sqrt(((p - q) ** 2).sum(2)).min(1)
    return d


# ----------------------------------------------------------------------------- figures

FLUID_LABELS = {"vorticity": r"vorticity $\omega$", "speed": r"speed $|u|$", "p": "pressure $p$",
                "u": "$u$", "v": "$v$", "density": r"density $\rho$", "phi": r"level set $\phi$"}


# fields with wall-corner singularities (lid corners): colour range clipped at the 99th percentile
CLIPPED = ("vorticity", "p")


def read_points(run):
    """tracers.csv and markers.csv -> {"tracers": table, "markers": table} (those present)."""
    out = {}
    for name in ("tracers", "markers"):
        path = os.path.join(run, name + ".csv")
        if os.path.exists(path):
            t = read_table(path)
            if all(k in t for k in ("frame", "id", "x", "y")):
                out[name] = t
            else:
                note(f"{path}: expected columns frame,...,id,x,y; ignored")
    return out


def frame_index(path):
    m = re.search(r"frame_(\d+)\.vti$", path)
    return int(m.group(1)) if m else None


def draw_points(ax, points, frame):
    """Dots of the tracers (white) and markers (black) of one frame."""
    for name, style in (("tracers", dict(c="w", edgecolors="k", s=9, linewidths=0.4)),
                        ("markers", dict(c="k", s=7))):
        t = points.get(name)
        if t is None or frame is None:
            continue
        sel = t["frame"] == frame
        if np.any(sel):
            ax.scatter(t["x"][sel], t["y"][sel], zorder=5, **style)


def plot_points(points, outdir, title, dpi, domain):
    """Paths of every tracer and marker over the frames."""
    if not points:
        return None
    lx, ly = domain[1] - domain[0], domain[3] - domain[2]
    w = 5.0
    fig, ax = plt.subplots(figsize=(w + 0.6, max(w * ly / lx, 1.5) + 0.6), layout="constrained")
    for name, colour in (("tracers", "tab:blue"), ("markers", "tab:red")):
        t = points.get(name)
        if t is None:
            continue
        keys = list(zip(t["solid"], t["id"])) if "solid" in t else list(t["id"])
        for k in sorted(set(keys)):
            sel = np.array([kk == k for kk in keys])
            order = np.argsort(t["frame"][sel])
            x, y = t["x"][sel][order], t["y"][sel][order]
            ax.plot(x, y, "-", color=colour, lw=0.7)
            ax.plot(x[:1], y[:1], "o", color=colour, ms=2.5)
            ax.plot(x[-1:], y[-1:], "s", color=colour, ms=2.5)
        ax.plot([], [], "-", color=colour, label=f"{name} (o start, \u25a0 end)")
    ax.set_xlim(domain[0], domain[1])
    ax.set_ylim(domain[2], domain[3])
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(f"{title}: tracer and marker paths", fontsize=11)
    out = os.path.join(outdir, "tracers.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def pick_frames(series, args):
    times = np.array([t for t, _ in series])
    if args.times:
        want = [float(s) for s in args.times.split(",") if s.strip()]
    else:
        n = max(1, min(args.count, len(series)))
        want = list(np.linspace(times[0], times[-1], n)) if n > 1 else [times[-1]]
    idx = []
    for w in want:
        k = int(np.argmin(np.abs(times - w)))
        if args.times and not getattr(args, "quiet_pick", False) and abs(times[k] - w) > 1e-9 * max(1.0, abs(w)):
            note(f"t = {w:g}: nearest frame is at t = {times[k]:.6g}")
        if k not in idx:
            idx.append(k)
    return [series[k] for k in idx]


def robust_range(arrays, symmetric, pct=99.0):
    vals = np.concatenate([a[np.isfinite(a)].ravel() for a in arrays if a.size]) if arrays else np.array([])
    if vals.size == 0:
        return -1.0, 1.0
    if symmetric:
        m = float(np.percentile(np.abs(vals), pct)) or float(np.abs(vals).max()) or 1.0
        return -m, m
    lo, hi = float(np.percentile(vals, 100 - pct)), float(np.percentile(vals, pct))
    if hi <= lo:
        lo, hi = float(vals.min()), float(vals.max()) + 1e-30
    return lo, hi


def plot_snapshots(series, args, outdir, title):
    picked = pick_frames(series, args)
    frames = [(t, Frame(p)) for t, p in picked]
    fr_paths = [p for _, p in picked]
    field = args.field
    f0 = frames[0][1]
    if field not in f0.names():
        fail(f"--field {field}: not in the frames (available: {', '.join(f0.names())})")
    has_solid = "phi" in f0.fields and field not in ("phi", "normal_stress")
    solid_key = "normal_stress" if "normal_stress" in f0.fields else None
    symmetric = field in ("vorticity", "u", "v", "p", "normal_stress") or field.startswith("stress_")
    fluid_data, solid_data = [], []
    for _, fr in frames:
        a = np.array(fr.get(field), dtype=float)
        if field == "p":
            a = a - np.mean(a)  # pressure is defined up to a constant
        if has_solid:
            inside = fr.fields["phi"] < 0
            fluid_data.append(np.where(inside, np.nan, a))
            s = fr.fields[solid_key] if solid_key else np.zeros_like(a)
            solid_data.append(np.where(inside, s, np.nan))
        else:
            fluid_data.append(a)
    if args.vmax is not None:
        fl = (-args.vmax, args.vmax) if symmetric else (0.0, args.vmax)
    else:
        fl = robust_range(fluid_data, symmetric, 99.0 if field in CLIPPED else 100.0)
        if field == "speed":
            fl = (0.0, fl[1])
    # solid stress: symmetric range clipped at the 99th percentile of |s| over the frames (a
    # wall contact can make a few cells 10x larger than the rest); mu_s (tr b - 2) >= 0 only
    # when det b = 1 exactly, so small negative values occur and a diverging map shows them
    sl = robust_range([s[np.isfinite(s)] for s in solid_data], True, 99.0) if has_solid else None
    if has_solid and args.solid_vmax:
        sl = (-args.solid_vmax, args.solid_vmax)
    cmap_s = "PuOr_r"

    n = len(frames)
    ncol = min(n, args.columns)
    nrow = math.ceil(n / ncol)
    lx = f0.extent[1] - f0.extent[0]
    ly = f0.extent[3] - f0.extent[2]
    aspect = ly / lx
    if aspect > 2.0:  # tall strip (e.g. the Couette layer): narrow panels
        ph = 5.0
        pw = max(ph / aspect, 0.5) + 0.9
    else:
        pw = 3.2 if aspect >= 0.6 else 4.5
        ph = min(max(pw * aspect, 1.2), 6.0)
    extra = 1.1 if has_solid else 0.6
    fig, axes = plt.subplots(nrow, ncol, figsize=(pw * ncol + extra + 0.4, ph * nrow + 0.9), squeeze=False,
                             layout="constrained")
    cmap_f = "RdBu_r" if symmetric else "viridis"
    im_f = im_s = None
    for k, (t, fr) in enumerate(frames):
        ax = axes[k // ncol][k % ncol]
        im_f = ax.imshow(fluid_data[k], origin="lower", extent=fr.extent, cmap=cmap_f,
                         vmin=fl[0], vmax=fl[1], interpolation="nearest")
        if has_solid:
            im_s = ax.imshow(solid_data[k], origin="lower", extent=fr.extent, cmap=cmap_s,
                             vmin=sl[0], vmax=sl[1], interpolation="nearest")
            X, Y = fr.cell_centres()
            phi = fr.fields["phi"]
            if phi.min() < 0 < phi.max():
                ax.contour(X, Y, phi, levels=[0.0], colors="k", linewidths=0.9)
        draw_points(ax, args.points, frame_index(fr_paths[k]))
        ax.set_aspect("equal")
        ax.set_xlim(fr.extent[0], fr.extent[1])
        ax.set_ylim(fr.extent[2], fr.extent[3])
        ax.set_title(f"t = {fr.time if fr.time is not None else t:.4g}", fontsize=10)
        if k % ncol == 0:
            ax.set_ylabel("y")
        if k // ncol == nrow - 1:
            ax.set_xlabel("x")
    for k in range(n, nrow * ncol):
        axes[k // ncol][k % ncol].set_visible(False)
    lab = FLUID_LABELS.get(field, field)
    if has_solid:
        lab += " (fluid)"
    if field in CLIPPED and args.vmax is None:
        lab += ", clipped at 99th pct"
    cb = fig.colorbar(im_f, ax=axes, shrink=0.9 if nrow > 1 else 0.95, pad=0.01, aspect=30)
    cb.set_label(lab)
    if has_solid:
        cb2 = fig.colorbar(im_s, ax=axes, shrink=0.9 if nrow > 1 else 0.95, pad=0.02, aspect=30)
        cb2.set_label(r"normal stress $(\sigma_{11}+\sigma_{22})/2$ (solid)" + ("" if args.solid_vmax else ", clipped at 99th pct"))
    fig.suptitle(f"{title}: {f0.nx}x{f0.ny}", fontsize=11)
    out = os.path.join(outdir, f"snapshots_{field}.png")
    fig.savefig(out, dpi=args.dpi)
    plt.close(fig)
    return out


def plot_energy(d, outdir, title, dpi):
    t = d["time"]
    fig, ax = plt.subplots(figsize=(6, 3.6), layout="constrained")
    drawn = False
    for key, lab in (("kinetic_energy", "kinetic"), ("elastic_energy", "elastic"), ("total_energy", "total")):
        if key in d and isinstance(d[key], np.ndarray):
            ax.plot(t, d[key], label=lab, lw=1.3, ls="--" if key == "total_energy" else "-")
            drawn = True
    if not drawn:
        plt.close(fig)
        return None
    ax.set_xlabel("t")
    ax.set_ylabel("energy")
    ax.set_title(title, fontsize=10)
    ax.legend()
    ax.grid(alpha=0.3)
    out = os.path.join(outdir, "energy.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def solid_indices(d):
    return sorted({int(m.group(1)) for k in d for m in [re.match(r"solid(\d+)_cx$", k)] if m})


def plot_solids(d, events, refs, outdir, title, dpi, domain):
    sids = solid_indices(d)
    if not sids:
        return None, []
    t = d["time"]
    extra_cols = [c for c in ("sigma_max", "gap_solid", "gap_wall") if f"solid{sids[0]}_{c}" in d
                  or any(f"solid{i}_{c}" in d for i in sids)]
    restitution = None
    if events is not None and "event" in events:
        ev = events["event"]
        mask = np.array(["restitution" in str(e) for e in ev])
        if mask.any():
            restitution = mask
    panels = ["path", "area"] + extra_cols + (["restitution"] if restitution is not None else [])
    ncol = 2 if len(panels) > 1 else 1
    nrow = math.ceil(len(panels) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.2 * ncol, 4.0 * nrow), squeeze=False, layout="constrained")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    distances = []
    for p, name in enumerate(panels):
        ax = axes[p // ncol][p % ncol]
        if name == "path":
            for r, (lab, xy) in enumerate(refs):
                ax.plot(xy[:, 0], xy[:, 1], "o-", ms=2.5, lw=0.8, color="0.35" if r == 0 else "0.65",
                        label=lab)
            for i in sids:
                cx, cy = d[f"solid{i}_cx"], d[f"solid{i}_cy"]
                c = colours[i % len(colours)]
                ax.plot(cx, cy, color=c, lw=1.4, label=f"solid{i} (refmap)")
                ax.plot(cx[0], cy[0], "o", color=c, ms=5)
                ax.plot(cx[-1], cy[-1], "s", color=c, ms=5)
                ours = np.column_stack([cx, cy])
                for lab, xy in refs:
                    d1 = dist_to_polyline(ours, xy)
                    d2 = dist_to_polyline(xy, ours)
                    distances.append((i, lab, d1.max(), d1.mean(), d2.max(), d2.mean()))
            ax.set_xlim(domain[0], domain[1])
            ax.set_ylim(domain[2], domain[3])
            ax.set_aspect("equal")
            ax.set_xlabel("x")
            ax.set_ylabel("y")
            ax.set_title("centroid path (o start, s end)", fontsize=10)
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
        elif name == "area":
            for i in sids:
                a = d[f"solid{i}_area"]
                ax.plot(t, (a - a[0]) / a[0], color=colours[i % len(colours)], label=f"solid{i}")
            ax.set_xlabel("t")
            ax.set_ylabel(r"$(A - A_0)/A_0$")
            ax.set_title("area change", fontsize=10)
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
        elif name == "restitution":
            sol = np.asarray(events["solid"], dtype=float) if isinstance(events["solid"], np.ndarray) else \
                np.array([float(s) for s in events["solid"]])
            et = events["time"]
            val = events["value"]
            # restitution_unfinished (the run ended before the rebound was over): a lower
            # bound, drawn hollow and annotated with ">="
            unfinished = np.array(["unfinished" in str(e) for e in events["event"]])
            for i in sorted(set(sol[restitution].astype(int))):
                c = colours[i % len(colours)]
                m = restitution & (sol.astype(int) == i) & ~unfinished
                mu = restitution & (sol.astype(int) == i) & unfinished
                ax.plot(et[m], val[m], "o", color=c, label=f"solid{i}")
                if mu.any():
                    ax.plot(et[mu], val[mu], "o", mfc="none", color=c, label=f"solid{i} (unfinished)")
                for tt, vv, u in zip(et[restitution & (sol.astype(int) == i)],
                                     val[restitution & (sol.astype(int) == i)],
                                     unfinished[restitution & (sol.astype(int) == i)]):
                    ax.annotate(f"{'>= ' if u else ''}{vv:.3f}", (tt, vv), textcoords="offset points",
                                xytext=(4, 4), fontsize=7)
            ax.set_xlabel("t")
            ax.set_ylabel("restitution coefficient")
            ax.set_title("restitution (events.csv)", fontsize=10)
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
        else:
            for i in sids:
                k = f"solid{i}_{name}"
                if k in d and isinstance(d[k], np.ndarray):
                    y = np.where(np.isfinite(d[k]), d[k], np.nan)
                    ax.plot(t, y, color=colours[i % len(colours)], label=f"solid{i}")
            if events is not None and "event" in events and name.startswith("gap"):
                for tt, e in zip(events["time"], events["event"]):
                    if "restitution" not in str(e):
                        ax.axvline(tt, color="0.7", lw=0.6, ls=":")
            ax.set_xlabel("t")
            ax.set_ylabel(name)
            ax.set_title({"sigma_max": r"max $|(\sigma_{11}+\sigma_{22})/2|$ in the solid",
                          "gap_solid": "gap to the nearest other solid",
                          "gap_wall": "gap to the nearest wall"}[name], fontsize=10)
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
    for p in range(len(panels), nrow * ncol):
        axes[p // ncol][p % ncol].set_visible(False)
    fig.suptitle(title, fontsize=11)
    out = os.path.join(outdir, "solids.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out, distances


def parse_probe_refs(specs):
    refs = {}
    for spec in specs:
        m = re.match(r"^(\w+)=(.+?):([^:]+):([^:]+)(?::([^:]+))?$", spec)
        if not m:
            fail(f"--probe-reference {spec}: expected PROBE=FILE:COORD:VALUE[:LABEL]")
        probe, path, ccol, vcol, label = m.groups()
        if not os.path.exists(path):
            fail(f"--probe-reference: no such file: {path}")
        t = read_table(path)
        for c in (ccol, vcol):
            if c not in t or not isinstance(t[c], np.ndarray):
                fail(f"--probe-reference: {path} has no numeric column {c}")
        refs.setdefault(probe, []).append((label or os.path.basename(path), t[ccol], t[vcol]))
    return refs


def plot_probes(run, outdir, title, dpi, refs=None):
    refs = refs or {}
    files = sorted(glob.glob(os.path.join(run, "probe_*.csv")))
    if not files:
        return None
    fig, axes = plt.subplots(1, len(files), figsize=(4.2 * len(files), 3.6), squeeze=False, layout="constrained")
    for ax, fpath in zip(axes[0], files):
        p = read_table(fpath)
        name = os.path.basename(fpath)[6:-4]
        if not all(k in p for k in ("x", "y", "value")):
            ax.set_visible(False)
            continue
        x, y, v = p["x"], p["y"], p["value"]
        # plot against the coordinate that varies; a vertical probe as value(y) upright
        vertical = np.ptp(y) > np.ptp(x)
        if vertical:
            ax.plot(v, y, label="refmap")
            ax.set_xlabel(name.split("_")[0] if "_" in name else "value")
            ax.set_ylabel("y")
        else:
            ax.plot(x, v, label="refmap")
            ax.set_xlabel("x")
            ax.set_ylabel(name.split("_")[0] if "_" in name else "value")
        for lab, c, rv in refs.get(name, []):
            if vertical:
                ax.plot(rv, c, "o", mfc="none", ms=5, label=lab)
            else:
                ax.plot(c, rv, "o", mfc="none", ms=5, label=lab)
        if name in refs:
            ax.legend(fontsize=8)
        ax.set_title(name, fontsize=10)
        ax.grid(alpha=0.3)
    fig.suptitle(f"{title}: probes at the end of the run", fontsize=11)
    out = os.path.join(outdir, "probes.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("run", help="output directory of one refmap run")
    ap.add_argument("--out", help="directory for the PNGs (default RUN/figures)")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--times", help="comma-separated times of the snapshots (nearest frame)")
    g.add_argument("--count", type=int, default=4, help="number of evenly spaced snapshots (default 4)")
    ap.add_argument("--field", default="vorticity",
                    help="fluid colour field: vorticity (default), speed, p, u, v, density, or any cell array; "
                         "several separated by commas give one PNG each")
    ap.add_argument("--vmax", type=float, help="fix the fluid colour range to [-vmax, vmax] (or [0, vmax])")
    ap.add_argument("--solid-vmax", type=float, help="fix the solid stress colour range to [-v, v]")
    ap.add_argument("--columns", type=int, default=4, help="snapshot panels per row (default 4)")
    ap.add_argument("--reference-path", action="append", default=[], metavar="FILE[:LABEL]",
                    help="centroid path (CSV, first two columns x, y) to overlay; repeatable")
    ap.add_argument("--probe-reference", action="append", default=[], metavar="PROBE=FILE:COORD:VALUE[:LABEL]",
                    help="overlay reference points on probe PROBE: columns COORD (position along x or y) and "
                         "VALUE of the CSV FILE, e.g. u_vertical=tests/data/ghia1982_u_vertical.csv:y_exact:u_Re1000:Ghia")
    ap.add_argument("--title", help="figure title (default: the scene name)")
    ap.add_argument("--dpi", type=int, default=110)
    ap.add_argument("--no-snapshots", action="store_true", help="time series only")
    args = ap.parse_args(argv)

    run = args.run
    if not os.path.isdir(run):
        fail(f"{run}: no such directory")
    diag_path = os.path.join(run, "diagnostics.csv")
    series = read_series(run)
    if not os.path.exists(diag_path) and not series:
        fail(f"{run}: not a refmap run directory (no diagnostics.csv and no frame_*.vti)")
    if args.count is not None and args.count < 1:
        fail("--count must be >= 1")
    refs = [read_path(s) for s in args.reference_path]
    outdir = args.out or os.path.join(run, "figures")
    os.makedirs(outdir, exist_ok=True)
    title = args.title
    if not title:
        pvds = glob.glob(os.path.join(run, "*.pvd"))
        title = os.path.splitext(os.path.basename(pvds[0]))[0] if pvds else os.path.basename(os.path.abspath(run))

    written = []
    domain = None
    args.points = read_points(run)
    if series and not args.no_snapshots:
        for field in [f.strip() for f in args.field.split(",") if f.strip()]:
            args_f = argparse.Namespace(**vars(args))
            args_f.field = field
            args.quiet_pick = True  # report the nearest-frame substitutions once
            written.append(plot_snapshots(series, args_f, outdir, title))
    elif not series:
        note("no frames (frame_*.vti): no snapshots")
    if series:
        domain = Frame(series[0][1]).extent
    d = read_table(diag_path) if os.path.exists(diag_path) else {}
    if d and "step" in d:  # the per-solid series (solids.csv), one value per row of d
        d.update({k: np.array(v) for k, v in solids_csv.wide_columns(run, d["step"]).items()})
    if not d:
        note("no diagnostics.csv (or it is empty): no time series")
    else:
        if "time" not in d:
            fail(f"{diag_path}: no 'time' column")
        if domain is None:
            domain = (0.0, 1.0, 0.0, 1.0)
        written.append(plot_energy(d, outdir, title, args.dpi))
        ev_path = os.path.join(run, "events.csv")
        events = read_table(ev_path) if os.path.exists(ev_path) else None
        if events is not None and not all(k in events for k in ("time", "solid", "event", "value")):
            note(f"{ev_path}: expected columns time,solid,event,value; ignored")
            events = None
        out, distances = plot_solids(d, events, refs, outdir, title, args.dpi, domain)
        written.append(out)
        if refs and not solid_indices(d):
            note("--reference-path given but the run has no solids")
        if distances:
            lines = ["# distances between the centroid path and reference polylines (unit: domain length)",
                     "# ours->ref: from each of our points to the nearest point of the reference polyline",
                     "# ref->ours: from each reference point to the nearest point of our path",
                     "solid,reference,ours_to_ref_max,ours_to_ref_mean,ref_to_ours_max,ref_to_ours_mean"]
            for i, lab, a, b, c, e in distances:
                lines.append(f"{i},{lab},{a:.4f},{b:.4f},{c:.4f},{e:.4f}")
            txt = os.path.join(outdir, "path_distance.txt")
            with open(txt, "w") as f:
                f.write("\n".join(lines) + "\n")
            print("\n".join(lines[3:]))
            written.append(txt)
    if args.points:
        written.append(plot_points(args.points, outdir, title, args.dpi, domain or (0.0, 1.0, 0.0, 1.0)))
    written.append(plot_probes(run, outdir, title, args.dpi, parse_probe_refs(args.probe_reference)))
    for w in written:
        if w:
            print(w)


if __name__ == "__main__":
    main()
