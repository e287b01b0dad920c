#!/usr/bin/env python3
"""Writes tutorials/fluidizedBed and tutorials/packedBed: DPMFoam case directories (valid for
OpenFOAM v1912's DPMFoam and for fsimFoam) for the drag-law model.

    tools/make_drag_tutorials.py [REPO_ROOT]

fluidizedBed: a small Goldschmidt-like bed, 1,080 glass beads (d = 2.5 mm, rho_p = 2526 kg/m3)
in air fluidized at 1.875 m/s (about 1.5 U_mf) in a 10 x 50 x 150 mm column, cells of 5 mm
(h = 2d), soft Hertzian contacts (E = 1e6 Pa: DPMFoam's collision sub-steps grow as E^0.4,
and with Goldschmidt's 1e8 DPMFoam needs about 5 min of CPU for the 0.2 s here). The beads
start on a loose lattice off every cell face (DPMFoam decides a bead on a face by round-off).

packedBed: 160 glass beads (d = 1 mm) stacked on a simple cubic lattice (one per 1 mm cell,
solid fraction pi/6) in water flowing up at 1 mm/s, far below minimum fluidization: the bed
stays put and its pressure drop per length is Ergun's, 389 Pa/m.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dpmfoam_case import (CYCLIC, NO_SLIP, SYMMETRY, block_mesh, cloud_properties,  # noqa: E402
                          constant, control, fields, inlet, local_interaction,
                          manual_injection, outlet, positions, spring_slider_dashpot, system)
from foam_case import write  # noqa: E402


def cloud(phase, rho0, youngs, d, interpolation, patches):
    """Beads under Ergun-Wen-Yu drag and gravity, rebounding from `patches`, with soft Hertzian
    contacts (alpha 0.02 between beads, 0.01 with the walls)."""
    return cloud_properties(
        phase, rho0, youngs, interpolation,
        f"ErgunWenYuDrag\n{{\n    alphac alpha.{phase};\n}}\ngravity;",
        manual_injection("model1", d), local_interaction(patches),
        spring_slider_dashpot(d, youngs, phase, ("0.02", "0.10"), ("0.01", "0.09")))


def fluid(root, phase, rho, nu):
    """The fluid's constant/ files (gravity along -z) and system/fvSchemes, fvSolution."""
    constant(root, phase, rho, nu)
    system(root)


def fluidized_bed(root):
    root = os.path.join(root, "tutorials", "fluidizedBed")
    fluid(root, "air", 1.2, 1e-5)
    write(root, "system/controlDict", "dictionary", control(
        0.2, 2e-4, 0.005,
        "A small Goldschmidt-like bed: 1,080 glass beads (d = 2.5 mm) fluidized by air at 1.875 "
        "m/s\n// (about 1.5 U_mf), 10 x 50 x 150 mm, cells of 5 mm. Runs under DPMFoam and "
        "fsimFoam alike\n// (tools/crosscheck compares them, every 5 ms); fsim's monitor "
        "postProcessing/dragLaw/0/dragLaw.dat\n// logs the bed's pressure drop (the buoyant "
        "weight per area, 438 Pa, once fluidized)."))
    write(root, "system/blockMeshDict", "dictionary", block_mesh(
        (10, 50, 150), (2, 10, 30),
        [("top", "wall", ["z+"], ""), ("bottom", "wall", ["z-"], ""),
         ("walls", "wall", ["y-", "y+"], ""), ("frontAndBack", "symmetry", ["x-", "x+"], "")]))
    fields(root, "air", [("bottom", inlet("air", 1.875)), ("top", outlet("air")),
                         ("walls", NO_SLIP), ("frontAndBack", SYMMETRY)])
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud(
        "air", 2526, "1e6", 0.0025, "cellPoint", ["top", "bottom", "walls", "frontAndBack"]))
    pts = []
    for k in range(20):
        for j in range(18):
            for i in range(3):
                # 0.1 mm or more off every 5 mm cell face
                pts.append((0.0019 + 0.0033 * i + 0.0001 * (k % 2),
                            0.0017 + 0.0027 * j, 0.0017 + 0.0027 * k))
    write(root, "constant/kinematicCloudPositions", "vectorField", positions(pts))


def packed_bed(root):
    root = os.path.join(root, "tutorials", "packedBed")
    fluid(root, "water", 1000, 1e-6)
    write(root, "system/controlDict", "dictionary", control(
        0.05, 5e-5, 0.001,
        "A packed bed: 160 glass beads (d = 1 mm) on a simple cubic lattice (solid fraction "
        "pi/6),\n// water flowing up at 1 mm/s (minimum fluidization is about 8 mm/s). The bed "
        "stays put; its\n// pressure drop is Ergun's, 150 mu phi^2 U/(eps^3 d^2) + 1.75 rho phi "
        "U^2/(eps^3 d) = 389 Pa/m,\n// 3.9 Pa over its 10 mm (postProcessing/dragLaw/0/"
        "dragLaw.dat, column pressureDrop).\n// deltaT is small for the bed's sake: DPMFoam's collision sub-step follows the particles'\n// speed and grows without bound for a bed at rest, so the fluid step must itself resolve\n// the Hertzian contacts of the resting stack."))
    write(root, "system/blockMeshDict", "dictionary", block_mesh(
        (4, 4, 20), (4, 4, 20),
        [("top", "wall", ["z+"], ""), ("bottom", "wall", ["z-"], ""),
         ("sidesX1", "cyclic", ["x-"], "        neighbourPatch sidesX2;\n"),
         ("sidesX2", "cyclic", ["x+"], "        neighbourPatch sidesX1;\n"),
         ("sidesY1", "cyclic", ["y-"], "        neighbourPatch sidesY2;\n"),
         ("sidesY2", "cyclic", ["y+"], "        neighbourPatch sidesY1;\n")]))
    fields(root, "water", [("bottom", inlet("water", 0.001)), ("top", outlet("water"))]
           + [(name, CYCLIC) for name in ["sidesX1", "sidesX2", "sidesY1", "sidesY2"]])
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud(
        "water", 2500, "1e7", 0.001, "cell", ["top", "bottom"]))
    pts = [(0.0005 + 0.001 * i, 0.0005 + 0.001 * j, 0.0005 + 0.001 * k)
           for k in range(10) for j in range(4) for i in range(4)]
    write(root, "constant/kinematicCloudPositions", "vectorField", positions(pts))
    # fsim's own settings: the paper's trilinear stencils would smear the bed's edge; DPMFoam's
    # cell rule keeps each bead's volume in its own cell (the bed's ε is uniform).


if __name__ == "__main__":
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    fluidized_bed(repo)
    packed_bed(repo)
    print("wrote tutorials/fluidizedBed and tutorials/packedBed; phi packed bed =",
          math.pi / 6)
