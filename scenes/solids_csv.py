"""Reading solids.csv, the per-solid diagnostics of a refmap run (docs/output.md).

solids.csv is in long format: one row per solid and output step (columns step, time,
solid, area, cx, ...), so its width does not grow with the number of solids. Scripts that
want one time series per solid and quantity aligned with the rows of diagnostics.csv use
wide_columns(), which pivots it back to columns named solid<k>_<quantity> (the names
diagnostics.csv itself carried before the long format).

    import solids_csv                      # scenes/ on sys.path
    cols = solids_csv.wide_columns(run_dir, steps)   # steps: diagnostics.csv's step column
    cols["solid0_cx"]                      # one float per given step
"""
import csv
import math
import os


def read_rows(path):
    """The header and the data rows (lists of floats) of a refmap CSV ('#' lines skipped);
    a partly written last line is dropped."""
    header, rows = None, []
    with open(path) as f:
        for line in f:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            r = next(csv.reader([line]))
            if header is None:
                header = [h.strip() for h in r]
            elif len(r) == len(header) and line.endswith("\n"):
                rows.append([float(v) for v in r])
    return header or [], rows


def wide_columns(run_dir, steps=None):
    """{"solid<k>_<quantity>": [float, ...]} from RUN_DIR/solids.csv ({} without the file).

    With `steps` (e.g. diagnostics.csv's step column) one value per given step, nan where
    solids.csv has no row for it (a run killed between the flushes of the two files);
    without, one per step of solids.csv, in file order (then also "step" and "time")."""
    path = run_dir if run_dir.endswith(".csv") else os.path.join(run_dir, "solids.csv")
    if not os.path.exists(path):
        return {}
    header, rows = read_rows(path)
    if not rows:
        return {}
    ci, si = header.index("step"), header.index("solid")
    quantities = [h for h in header if h not in ("step", "time", "solid")]
    by_step = {}   # step -> {solid: row}
    order = []     # the steps in file order
    for r in rows:
        s = int(r[ci])
        if s not in by_step:
            by_step[s] = {}
            order.append(s)
        by_step[s][int(r[si])] = r
    solids = sorted({k for per in by_step.values() for k in per})
    want = [int(s) for s in steps] if steps is not None else order
    out = {}
    if steps is None:
        out["step"] = [float(s) for s in order]
        out["time"] = [next(iter(by_step[s].values()))[header.index("time")] for s in order]
    for k in solids:
        for q in quantities:
            j = header.index(q)
            # a quantity a solid does not have (the rigid-body columns of a free solid: nan
            # on all its rows) is left out, as diagnostics.csv had no column for it
            if all(math.isnan(per[k][j]) for per in by_step.values() if k in per):
                continue
            out[f"solid{k}_{q}"] = [by_step[s][k][j] if k in by_step.get(s, {}) else math.nan for s in want]
    return out
