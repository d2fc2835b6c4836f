#!/usr/bin/env python3
"""No include runs back up the layers (docs/layout.md, "Layers").

Every source file of core/, kernels/ and solver/ belongs to one layer; a file may include
files of its own layer or of a lower one, never of a higher one. The layers, lowest first:

  core      the grid and the field storage
  kernels   stateless stencil kernels
  io        generic tools that know no physics: enum names, the TOML reader and its key
            catalogue, expressions, CSV, checkpoint records, the state registry, timers
  pressure  the Poisson solvers (they name their own options: no scene, no Config)
  config    the plain data a scene becomes (Config, the shapes' parameters): no code
  model     the configuration, the shapes, the solids, the Simulation and its components
  scene     the scene schema: the loader, the key table, the option names of Config
  app       the command line and the run loop

A file's layer is the first folder under solver/ when that folder is named after a layer
(solver/pressure/<file>), else core/ or kernels/, else the table FLAT below for
the files still directly in solver/ (unlisted ones are `model`).

Usage: check_includes.py [REPO]   (exit 1 and one line per include that runs up)
"""
import pathlib
import re
import sys

LAYERS = ["core", "kernels", "io", "pressure", "config", "model", "scene", "app"]

# the files directly in solver/, by name (without extension)
FLAT = {
    "io": ["enum_names", "input_error", "key_def", "toml_reader", "expression", "csv", "checkpoint_io",
           "state_registry", "timers", "stop_signal", "progress", "step_landing", "schedule", "vtk",
           "periodic_window", "contact_pairs"],
    "pressure": ["poisson", "poisson_cg", "poisson_multigrid", "poisson_factory", "multigrid_coarse",
                 "multigrid_galerkin"],
    "config": ["config", "shape_params"],
    "scene": ["scene", "scene_keys", "option_names"],
    "app": ["main", "run"],
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def layer_of(rel: pathlib.PurePosixPath) -> str:
    parts = rel.parts
    if parts[0] in ("core", "kernels"):
        return parts[0]
    if parts[0] == "solver" and len(parts) > 2 and parts[1] in LAYERS:
        return parts[1]
    for layer, stems in FLAT.items():
        if rel.stem in stems:
            return layer
    return "model"


def main() -> int:
    repo = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    bad = []
    files = [p for d in ("core", "kernels", "solver") for p in sorted((repo / d).rglob("*"))
             if p.suffix in (".hpp", ".cpp")]
    for f in files:
        rel = pathlib.PurePosixPath(f.relative_to(repo).as_posix())
        mine = LAYERS.index(layer_of(rel))
        for inc in INCLUDE.findall(f.read_text()):
            target = pathlib.PurePosixPath(inc)
            if target.parts[0] not in ("core", "kernels", "solver"):
                continue  # tests/, third-party
            theirs = LAYERS.index(layer_of(target))
            if theirs > mine:
                bad.append(f"{rel}: ({LAYERS[mine]}) includes {inc} ({LAYERS[theirs]})")
    for b in bad:
        print(b)
    if not bad:
        print(f"{len(files)} files: no include runs up the layers")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
