"""tools/crosscheck_layers.py: the layer means of both programs' fluid in a --keep folder, on
a 2 x 2 x 3 block whose values are known per cell."""
import numpy as np

import crosscheck_layers

SHAPE = (2, 2, 3)
CELLS = 12


def foam_field(path, kind, values):
    rows = "\n".join(f"({' '.join(str(x) for x in v)})" if kind == "vector" else str(v)
                     for v in values)
    path.write_text(
        "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class vol%sField;\n}\n"
        "dimensions [0 0 0 0 0 0 0];\n"
        "internalField nonuniform List<%s>\n%d\n(\n%s\n)\n;\n"
        "boundaryField\n{\n    bottom { type zeroGradient; }\n}\n"
        % ("Vector" if kind == "vector" else "Scalar", kind, len(values), rows))


def fsim_field(path, u, alpha):
    import meshio
    points, cells = [], []
    for k in range(3):
        for j in range(2):
            for i in range(2):
                base = len(points)
                corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                           (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
                points += [(i + a, j + b, k + c) for a, b, c in corners]
                cells.append(list(range(base, base + 8)))
    mesh = meshio.Mesh(np.array(points, float), [("hexahedron", np.array(cells))],
                       cell_data={"U": [np.asarray(u)], "alpha": [np.asarray(alpha)]})
    meshio.write(path, mesh, file_format="vtk")


def keep_folder(tmp_path, u, alpha):
    for program in ("dpmfoam", "fsim"):
        (tmp_path / program / "system").mkdir(parents=True)
        (tmp_path / program / "system" / "blockMeshDict").write_text(
            "blocks\n(\n    hex (0 1 2 3 4 5 6 7) (2 2 3) simpleGrading (1 1 1)\n);\n")
    for t, scale in (("0.1", 1.0), ("0.2", 3.0), ("0.5", 100.0)):
        d = tmp_path / "dpmfoam" / t
        d.mkdir()
        foam_field(d / "U.water", "vector", u * scale)
        foam_field(d / "alpha.water", "scalar", alpha)
        f = tmp_path / "fsim" / t
        f.mkdir()
        fsim_field(f / "fluid.vtk", u * scale, alpha)


def test_layer_means_of_both_programs(tmp_path):
    # cells x fastest: layer k holds cells 4k..4k+3; w = layer + the cell's index in it
    w = np.array([k + 0.1 * c for k in range(3) for c in range(4)])
    u = np.column_stack([np.ones(CELLS), np.zeros(CELLS), w])
    alpha = np.array([0.5 if c % 2 else 1.0 for k in range(3) for c in range(4)])
    keep_folder(tmp_path, u, alpha)
    for program in ("dpmfoam", "fsim"):
        mw, ma, maw, count = crosscheck_layers.layer_means(
            tmp_path / program, program, (0.05, 0.25), SHAPE)
        assert count == 2  # 0.5 is outside the window
        # times scale w by 1 and 3: the mean over both is 2 w
        assert np.allclose(mw, [2 * (k + 0.15) for k in range(3)])
        assert np.allclose(ma, 0.75)
        # eps w per layer: (1 (k) + 0.5 (k + .1) + 1 (k + .2) + 0.5 (k + .3))/4, doubled
        assert np.allclose(maw, [2 * (3 * k + 0.4) / 4 for k in range(3)])
