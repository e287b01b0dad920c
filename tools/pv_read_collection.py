"""Opens an fsim collection file with ParaView and prints what it sees, as JSON.

Run with ParaView's own interpreter (not the venv):  pvpython tools/pv_read_collection.py CASE/CASE.pvd
Output: {"times": [...], "steps": [{"time": t, "blocks": [{"class", "cells", "points",
"cell_arrays": {name: [first, middle, last] of component 0}, "point_arrays": {...}}]}]}
It only reads; tools/vtk_checks.py compares the result with meshio and pyvista.
"""

import json
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile, UpdatePipeline


def leaves(data):
    """The datasets of a (nested) multiblock, in order."""
    if data is None:
        return []
    if data.IsA("vtkMultiBlockDataSet"):
        out = []
        for i in range(data.GetNumberOfBlocks()):
            out += leaves(data.GetBlock(i))
        return out
    return [data]


def samples(field_data):
    """Component 0 of the first, middle and last tuple of every array."""
    out = {}
    for i in range(field_data.GetNumberOfArrays()):
        array = field_data.GetArray(i)
        n = array.GetNumberOfTuples()
        picks = [0, n // 2, n - 1] if n else []
        out[array.GetName()] = [array.GetComponent(k, 0) for k in picks]
    return out


def main(path):
    reader = OpenDataFile(path)
    if reader is None:
        raise SystemExit(f"ParaView could not open {path}")
    times = list(reader.TimestepValues)
    steps = []
    for t in times:
        UpdatePipeline(time=t, proxy=reader)
        blocks = []
        for block in leaves(servermanager.Fetch(reader)):
            blocks.append(
                {
                    "class": block.GetClassName(),
                    "cells": block.GetNumberOfCells(),
                    "points": block.GetNumberOfPoints(),
                    "cell_arrays": samples(block.GetCellData()),
                    "point_arrays": samples(block.GetPointData()),
                }
            )
        steps.append({"time": t, "blocks": blocks})
    print("FSIM-JSON " + json.dumps({"times": times, "steps": steps}))


if __name__ == "__main__":
    main(sys.argv[1])
