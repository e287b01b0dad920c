#!/usr/bin/env python3
"""Writes tutorials/benchmarkDragLaw: the drag-law variant of the paper's section 3.3 benchmark
as a DPMFoam-style case directory for fsimFoam.

    tools/make_benchmark_drag_law.py [REPO_ROOT]

Gas-solid: air (rho_f = 1.2 kg/m3, mu_f = 1.8e-5 Pa s, nu = 1.5e-5 m2/s), 500 particles of
d = 100 um and rho_p = 1500 kg/m3 at random non-overlapping positions (seeded), in a box of
24r x 72r x 24r (1.2 x 3.6 x 1.2 mm) periodic on all six faces, gravity along -y (the long
axis), 0.1 s of physical time. Drag-law grid h = 2r: 12 x 36 x 12 cells. The paper's own
model (its closure, eq. 7 with the pressure-gradient force eq. 10, trilinear stencils eq.
14-16), as the paper's section 3.3 ran it: constant/couplingProperties
`dragLawCoeffs { form paper; ... }` and `paper` in particleForces. fsim imposes the mean
pressure gradient that carries the mixture's weight in the fully periodic box.

Contacts: a linear spring-dashpot soft enough (kn = 0.1 N/m, contact time about 0.2 ms) that
the DEM takes a few sub-steps per fluid step; at the suspension's relative speeds (below
0.1 m/s) the overlap stays under 6 % of d.
"""
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dpmfoam_case import (CYCLIC, block_mesh, cloud_properties, constant, control,  # noqa: E402
                          fields, manual_injection, positions, standard_wall_interaction,
                          system)
from foam_case import write  # noqa: E402

R = 50e-6
D = 2 * R
BOX = (24 * R, 72 * R, 24 * R)
CELLS = (12, 36, 12)
COUNT = 500
SEED = 3


def random_positions(count, seed):
    """`count` centres in the periodic box, no two closer than 1.05 d (periodic distance)."""
    rng = random.Random(seed)
    points = []
    min_d2 = (1.05 * D) ** 2
    while len(points) < count:
        p = tuple(rng.uniform(0.0, L) for L in BOX)
        ok = True
        for q in points:
            d2 = 0.0
            for a in range(3):
                x = abs(p[a] - q[a])
                x = min(x, BOX[a] - x)
                d2 += x * x
            if d2 < min_d2:
                ok = False
                break
        if ok:
            points.append(p)
    return points


NOTE = """
// The paper's section 3.3 gas-solid benchmark, drag-law model. 'paper' is fsim's name for
// the paper's closure (eq. 11-12); DPMFoam would need ErgunWenYuDrag here instead.
"""

LINEAR_SPRING_DASHPOT = f"""
    collisionModel pairCollision;

    pairCollisionCoeffs
    {{
        maxInteractionDistance  {D:g};

        pairModel pairLinearSpringDashpot;

        pairLinearSpringDashpotCoeffs
        {{
            kn      0.1;    // N/m: contact time about 0.2 ms
            e       0.9;
            mu      0.1;
            collisionResolutionSteps 10;
        }}

        wallModel wallLinearSpringDashpot;

        wallLinearSpringDashpotCoeffs
        {{
            kn      0.2;
            e       0.9;
            mu      0.1;
            collisionResolutionSteps 10;
        }}
    }}
"""


def cloud():
    """The paper's closure, gravity and the pressure-gradient force; soft linear contacts."""
    return cloud_properties(
        "air", 1500, "1e8", "cellPoint", "paper;\ngravity;\npressureGradient;",
        manual_injection("model1", f"{D:g}"), standard_wall_interaction("0.9", "0.1"),
        LINEAR_SPRING_DASHPOT, note=NOTE)


def benchmark(repo):
    root = os.path.join(repo, "tutorials", "benchmarkDragLaw")
    constant(root, "air", 1.2, "1.5e-05", g="0 -9.81 0", align_rho=True)
    write(root, "constant/couplingProperties", "dictionary", """
// fsim's own: the paper's drag-law model (section 2.2) as its section 3.3 benchmark ran it.

model           dragLaw;

dragLawCoeffs
{
    form                  paper;
    velocityInterpolation trilinear;
    voidFraction          trilinear;
}
""")
    # fsim's own block (DPMFoam ignores it): the viscous term implicit, so that the step
    # follows the Courant number and maxDeltaT instead of the explicit bound
    # 1/(sum|u|/h + 2 nu sum 1/h^2) (about 5e-5 s here).
    system(root, fv_solution_extra="\nfsim\n{\n    timeScheme      EulerImplicit;\n}\n")
    write(root, "system/controlDict", "dictionary", control(
        0.1, 5e-5, 0.05,
        "The paper's section 3.3 benchmark, drag-law variant: 500 particles (d = 100 um, "
        "rho_p = 1500)\n// in air, a 24r x 72r x 24r box periodic on all faces, gravity "
        "along -y, h = 2r, 0.1 s.\n// The gas rises through the heavy suspension at about 0.4 m/s (the frame has zero total\n// momentum). With the implicit viscous term (system/fvSolution) the step follows maxCo\n// (0.8; upwind advection is stable to 1) and maxDeltaT.")
        .replace("DPMFoam", "fsimFoam")
        .replace("writeControl    runTime;", "writeControl    adjustableRunTime;")
        .replace("adjustTimeStep  no;", "adjustTimeStep  yes;\n\nmaxCo           0.8;\n\nmaxDeltaT       1e-4;"))
    names = ["x", "y", "z"]
    patches = []
    for a in range(3):
        lo, hi = f"cyclic{names[a].upper()}1", f"cyclic{names[a].upper()}2"
        patches.append((lo, "cyclic", [f"{names[a]}-"], f"        neighbourPatch {hi};\n"))
        patches.append((hi, "cyclic", [f"{names[a]}+"], f"        neighbourPatch {lo};\n"))
    mm = tuple(round(L * 1e3, 6) for L in BOX)
    write(root, "system/blockMeshDict", "dictionary", block_mesh(mm, CELLS, patches))
    fields(root, "air", [(name, CYCLIC) for name, _, _, _ in patches], gap="")
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud())
    write(root, "constant/kinematicCloudPositions", "vectorField",
          positions(random_positions(COUNT, SEED)))


if __name__ == "__main__":
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(
        os.path.dirname(os.path.abspath(__file__)))
    benchmark(repo)
