#!/usr/bin/env python3
"""Checks that solids.csv (long format) carries exactly the per-solid numbers that
diagnostics.csv carried as solid<k>_<quantity> columns before it.

    python3 scripts/check_solids_pivot.py OLD NEW

OLD and NEW are output directories of `scripts/compare_scenes.sh run` for the binary before
and after the change (NAME.diag.csv, and in NEW also NAME.solids.csv). For every scene of
OLD: every column of the old NAME.diag.csv is found, as the same text in every row, either
in the new NAME.diag.csv (the global columns, in the same order) or in the new
NAME.solids.csv at the row of that step and solid (solid<k>_<q>: column q, solid k).
Prints one line per scene; exit 1 if any differs.
"""
import csv
import glob
import os
import re
import sys


def table(path):
    with open(path) as f:
        rows = [r for r in csv.reader(l for l in f if l.strip() and not l.startswith("#"))]
    return rows[0], rows[1:]


def check(old_diag, new_diag, new_solids):
    oh, orows = table(old_diag)
    nh, nrows = table(new_diag)
    if len(orows) != len(nrows):
        return f"{len(orows)} rows before, {len(nrows)} after"
    globals_old = [c for c in oh if not re.match(r"solid\d+_", c)]
    if globals_old != nh:
        return f"global columns differ: {globals_old} vs {nh}"
    cell = {}
    if os.path.exists(new_solids):
        sh, srows = table(new_solids)
        si, ki = sh.index("step"), sh.index("solid")
        for r in srows:
            for q, v in zip(sh, r):
                cell[(r[si], r[ki], q)] = v
    ns = 0
    for j, c in enumerate(oh):
        m = re.match(r"solid(\d+)_(.+)$", c)
        for i, r in enumerate(orows):
            if m:
                got = cell.get((r[0], m.group(1), m.group(2)))
                ns += 1
            else:
                got = nrows[i][nh.index(c)]
            if got != r[j]:
                return f"row {i} column {c}: {r[j]!r} before, {got!r} after"
    # nothing extra in solids.csv: one row per solid and old row
    solids = {m.group(1) for c in oh for m in [re.match(r"solid(\d+)_cx$", c)] if m}
    extra = len({(k[0], k[1]) for k in cell}) - len(orows) * len(solids)
    if extra:
        return f"{extra} more (step, solid) rows in solids.csv than before"
    return f"same ({ns} per-solid values)" if ns else "same (no solids)"


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    old, new = argv[1], argv[2]
    bad = 0
    for f in sorted(glob.glob(os.path.join(old, "*.diag.csv"))):
        name = os.path.basename(f)[: -len(".diag.csv")]
        msg = check(f, os.path.join(new, name + ".diag.csv"), os.path.join(new, name + ".solids.csv"))
        bad |= not msg.startswith("same")
        print(f"{name}: {msg}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
