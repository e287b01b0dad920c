#!/usr/bin/env python3
"""Layer means of both programs' fluid in a `tools/crosscheck --keep DIR` folder.

    tools/crosscheck_layers.py DIR [--window T0 T1] [--layers N]

For each program (DIR/dpmfoam, DIR/fsim) and each cell layer normal to z (the lowest N), the
mean over the layer's cells and over the written times in the window of the fluid's cell
velocity `w`, its fluid fraction `ε` and `ε w`. Where the fluid enters through the floor,
continuity makes every layer's `ε w` the inlet's superficial velocity in the mean (up to the
bed's own motion); a cell velocity that departs from it is the discretisation's. This is how
DPMFoam's inlet-cell error was seen in liquidFluidizedBed (docs/crosscheck.md).

Both meshes are the case's one blockMesh block, cells x fastest: DPMFoam's `U.<phase>` and
`alpha.<phase>` (ascii), fsim's `fluid.vtk` (`U`, `alpha`).
"""
import argparse
import pathlib
import sys

import numpy as np

TOOLS = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(TOOLS / "figures"))
import crosscheck  # noqa: E402
import foam_dict  # noqa: E402
from figure import block_cells  # noqa: E402


def dpmfoam_fields(path, cells):
    """(U, alpha) of one DPMFoam time directory: the continuous phase's `U.*` and `alpha.*`."""
    def one(prefix):
        found = sorted(path.glob(prefix + ".*"))
        if not found:
            raise ValueError(f"{path}: no {prefix}.<phase> field")
        return foam_dict.read_internal_field(found[0].read_text(), cells)
    return one("U"), one("alpha")


def fsim_fields(path):
    import meshio
    data = meshio.read(path / "fluid.vtk").cell_data
    return (np.asarray(data["U"][0]).reshape(-1, 3), np.asarray(data["alpha"][0]).ravel())


def layer_means(run, program, window, shape):
    """Per z layer: mean w, mean ε and mean ε w over the window's written times (and the
    number of times)."""
    nx, ny, nz = shape
    cells = nx * ny * nz
    w_sum, a_sum, aw_sum, count = np.zeros(nz), np.zeros(nz), np.zeros(nz), 0
    for t, path in crosscheck.time_dirs(run):
        if not window[0] - 1e-9 <= t <= window[1] + 1e-9 or t == 0:
            continue
        if program == "dpmfoam":
            if not list(path.glob("U.*")):
                continue
            u, alpha = dpmfoam_fields(path, cells)
        else:
            if not (path / "fluid.vtk").is_file():
                continue
            u, alpha = fsim_fields(path)
        if len(u) != cells:
            raise ValueError(f"{path}: {len(u)} cells, the block has {cells}")
        w = u[:, 2].reshape(nz, nx * ny)
        a = alpha.reshape(nz, nx * ny)
        w_sum += w.mean(axis=1)
        a_sum += a.mean(axis=1)
        aw_sum += (a * w).mean(axis=1)
        count += 1
    if count == 0:
        raise ValueError(f"{run}: no written time in {window}")
    return w_sum / count, a_sum / count, aw_sum / count, count


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", type=pathlib.Path)
    ap.add_argument("--window", nargs=2, type=float, default=(0.0, float("inf")))
    ap.add_argument("--layers", type=int, default=8)
    args = ap.parse_args(argv)
    shape = block_cells((args.dir / "fsim" / "system" / "blockMeshDict").read_text())
    for program in ("dpmfoam", "fsim"):
        w, a, aw, count = layer_means(args.dir / program, program, args.window, shape)
        n = min(args.layers, len(w))
        print(f"{program} ({count} times), layers 1-{n} from the floor")
        for name, v, fmt in (("w", w, "{:8.4f}"), ("eps", a, "{:8.3f}"), ("eps w", aw, "{:8.4f}")):
            print(f"  {name:6s}" + "".join(fmt.format(x) for x in v[:n]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
