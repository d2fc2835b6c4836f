"""The disc_tgv runs of the stiff-solid studies (bench/variational_study.py,
bench/picard_study.py): one run of scenes/disc_tgv.toml with --set overrides and the energy
and area measures of its diagnostics; and the merge of a study's rows into its CSV, keeping
the rows of the (method, grid, mu_s / rho_s, P) it did not rerun."""
import csv
import math
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scenes"))
import solids_csv  # noqa: E402
from coupling import with_coupling  # noqa: E402  (bench/coupling.py)

KEY = ("method", "grid", "mu_s_over_rho_s", "P")


def run_disc_tgv(binary, raw, tag, sets):
    """(result, diagnostics columns by name or None): rc, the last error line of a failed run,
    steps, t_end, the largest and last total energy over its start (e_max, e_end), the growth
    over the second half (late_growth) and the largest area drift of solid 0."""
    out = os.path.join(raw, tag)
    shutil.rmtree(out, ignore_errors=True)
    cmd = [binary, "run", os.path.join(ROOT, "scenes", "disc_tgv.toml"), "-o", out, "-j", "1", "-q"]
    for s in with_coupling(sets):
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    res = dict(rc=p.returncode, failure=p.stderr.strip().splitlines()[-1] if p.returncode and p.stderr.strip() else "")
    path = os.path.join(out, "diagnostics.csv")
    if not os.path.exists(path):
        return res, None
    head, rows = solids_csv.read_rows(path)
    if not rows:
        return res, None
    col = {h: [r[k] for r in rows] for k, h in enumerate(head)}
    e = col["total_energy"]
    area = solids_csv.wide_columns(out, col["step"]).get("solid0_area", [])
    mid = len(e) // 2
    res.update(steps=int(col["step"][-1]), t_end=col["time"][-1], e_max=max(e) / e[0],
               late_growth=max(e[mid:]) / e[mid] if e[mid] > 0 else float("nan"), e_end=e[-1] / e[0],
               area_drift=max(abs(a - area[0]) / area[0] for a in area if not math.isnan(a)) if area else float("nan"))
    return res, col


def read_rows(path):
    """The rows already in a study's CSV (none if it does not exist)."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def write_merged(path, cols, old, new):
    """Writes old's rows whose KEY no new row has, then new's; floats to 4 digits."""
    keys = {tuple(str(r[k]) for k in KEY) for r in new}
    rows = [r for r in old if tuple(str(r[k]) for k in KEY) not in keys] + new
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items() if k in cols})
