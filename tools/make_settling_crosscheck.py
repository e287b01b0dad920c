#!/usr/bin/env python3
"""Writes tutorials/settlingInLiquid and tutorials/settlingColumn: two cross-check cases
against DPMFoam (issue 38) that run unchanged under OpenFOAM v1912's `blockMesh && DPMFoam`
and under `fsimFoam`. tools/crosscheck compares them by their crosscheck.toml.

    tools/make_settling_crosscheck.py [REPO_ROOT]

settlingInLiquid: one glass bead (d = 1 mm, rho_p = 2500 kg/m3) settling from rest in water
(rho = 1000 kg/m3, nu = 1e-6 m2/s) in a closed 20 x 20 x 60 mm box of 4 mm cells (h = 4d);
sphereDrag (Schiller-Naumann) and gravity only; terminal velocity 0.1459 m/s (Re = 146).

settlingColumn: 1,000 glass beads (d = 2 mm, rho_p = 2500) on a jittered loose lattice (10
layers of 10 x 10, solid fraction 0.24) fall through air onto the floor of a closed 30 x 30 x
40 mm box of 5 mm cells (h = 2.5d) and settle into a bed about 9 mm high; sphereDrag, gravity,
Hertzian spring-slider-dashpot contacts (youngsModulus 5e5: DPMFoam's collision sub-steps, and
so its run time, grow as E^0.4).
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dpmfoam_case import (NO_COLLISIONS, NO_SLIP, block_mesh, cloud_properties,  # noqa: E402
                          constant, control, fields, local_interaction, manual_injection,
                          positions, spring_slider_dashpot, system)
from foam_case import write  # noqa: E402

BOX_PATCHES = [("top", "wall", ["z+"], ""), ("bottom", "wall", ["z-"], ""),
               ("walls", "wall", ["x-", "x+", "y-", "y+"], "")]
WALLS = ["top", "bottom", "walls"]


def closed_box(repo, name, fluid, times, note, size_mm, cells, beads, collision, points):
    """tutorials/<name>: glass beads (rho_p = 2500) at `points` under sphereDrag and gravity in
    a box closed by no-slip walls (DPMFoam takes its pressure level from PIMPLE's pRefCell).
    fluid: (phase, rho, nu); times: controlDict's (end, deltaT, writeInterval); beads: (d,
    youngsModulus); collision: spring_slider_dashpot() or NO_COLLISIONS."""
    root = os.path.join(repo, "tutorials", name)
    phase = fluid[0]
    constant(root, *fluid)
    system(root)
    write(root, "system/controlDict", "dictionary", control(*times, note))
    write(root, "system/blockMeshDict", "dictionary", block_mesh(size_mm, cells, BOX_PATCHES))
    fields(root, phase, [(wall, NO_SLIP) for wall in WALLS])
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud_properties(
        phase, 2500, beads[1], "cellPoint", "sphereDrag;\ngravity;",
        manual_injection("model1", beads[0]), local_interaction(WALLS), collision))
    write(root, "constant/kinematicCloudPositions", "vectorField", positions(points))


def settling_in_liquid(repo):
    # the bead at the centre of a cell (x, y) and of the cell at z = 52-56 mm, on no cell face
    closed_box(
        repo, "settlingInLiquid", ("water", 1000, 1e-6), (0.3, 2e-4, 0.01),
        "One glass bead (d = 1 mm, rho_p = 2500) settling from rest in water in a closed "
        "20 x 20 x 60 mm box\n// of 4 mm cells; sphereDrag and gravity only. Schiller-Naumann "
        "terminal velocity: 0.1459 m/s\n// (Re = 146, relaxation time 25 ms). Runs under "
        "DPMFoam and fsimFoam alike (tools/crosscheck).",
        (20, 20, 60), (5, 5, 15), (0.001, "1e8"), NO_COLLISIONS, [(0.010, 0.010, 0.054)])


def column_positions(d, n_side, layers, pitch, x0, z0, jitter, seed):
    rng = random.Random(seed)
    pts = []
    for k in range(layers):
        for j in range(n_side):
            for i in range(n_side):
                pts.append((x0 + pitch * i + rng.uniform(-jitter, jitter),
                            x0 + pitch * j + rng.uniform(-jitter, jitter),
                            z0 + pitch * k + rng.uniform(-jitter, jitter)))
    # the jitter keeps every bead apart and off the cell faces (multiples of 5 mm)
    for p in pts:
        assert all(abs(c / 0.005 - round(c / 0.005)) > 1e-6 for c in p)
    assert pitch - 2 * math.sqrt(3) * jitter > d
    return pts


def settling_column(repo, n_side=10, layers=10, youngs="5e5", end=0.1, dt=1e-4, seed=38):
    closed_box(
        repo, "settlingColumn", ("air", 1.2, 1.5e-5), (end, dt, 0.004),
        "1,000 glass beads (d = 2 mm, rho_p = 2500) on a loose lattice (10 layers of 10 x 10) "
        "fall through air\n// onto the floor of a closed 30 x 30 x 40 mm box of 5 mm cells "
        "and settle into a bed about\n// 9 mm high. sphereDrag, gravity, Hertzian "
        "spring-slider-dashpot contacts. Runs under DPMFoam\n// and fsimFoam alike "
        "(tools/crosscheck).",
        (30, 30, 40), (6, 6, 8), (0.002, youngs),
        spring_slider_dashpot(0.002, youngs, "air", (0.3, 0.3), (0.3, 0.3)),
        column_positions(0.002, n_side, layers, 0.0026, 0.0033, 0.004, 0.00015, seed))


if __name__ == "__main__":
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    settling_in_liquid(repo)
    settling_column(repo)
    print("wrote tutorials/settlingInLiquid and tutorials/settlingColumn")
