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
from foam_case import write  # noqa: E402
from make_drag_tutorials import COMMON_SYSTEM, block_mesh, control, positions  # noqa: E402


def constant(root, phase, rho, nu):
    write(root, "constant/transportProperties", "dictionary", f"""
continuousPhase {phase};

rho.{phase}     {rho};

transportModel  Newtonian;

nu              {nu};
""")
    write(root, f"constant/turbulenceProperties.{phase}", "dictionary", """
simulationType  laminar;
""")
    write(root, "constant/g", "uniformDimensionedVectorField", """
dimensions      [0 1 -2 0 0 0 0];

value           (0 0 -9.81);
""")
    for rel, body in COMMON_SYSTEM.items():
        write(root, rel, "dictionary", body)


def closed_box_fields(root, phase, walls):
    """Fluid at rest in a box closed by no-slip walls (DPMFoam takes its pressure level
    from PIMPLE's pRefCell)."""
    u = "\ndimensions      [0 1 -1 0 0 0 0];\n\ninternalField   uniform (0 0 0);\n\n" \
        "boundaryField\n{\n"
    p = "\ndimensions      [0 2 -2 0 0 0 0];\n\ninternalField   uniform 0;\n\n" \
        "boundaryField\n{\n"
    for name in walls:
        u += f"    {name}\n    {{\n        type            noSlip;\n    }}\n\n"
        p += (f"    {name}\n    {{\n        type            fixedFluxPressure;\n"
              f"        value           $internalField;\n    }}\n\n")
    write(root, f"0/U.{phase}", "volVectorField", u.rstrip("\n") + "\n}\n")
    write(root, "0/p", "volScalarField", p.rstrip("\n") + "\n}\n")


def collisions(d, youngs, alpha_pair, alpha_wall, mu_pair, mu_wall, phase):
    return f"""
    collisionModel pairCollision;

    pairCollisionCoeffs
    {{
        maxInteractionDistance  {d};
        writeReferredParticleCloud no;

        pairModel pairSpringSliderDashpot;

        pairSpringSliderDashpotCoeffs
        {{
            useEquivalentSize   no;
            alpha               {alpha_pair};
            b                   1.5;
            mu                  {mu_pair};
            cohesionEnergyDensity 0;
            collisionResolutionSteps 12;
        }};

        wallModel wallSpringSliderDashpot;

        wallSpringSliderDashpotCoeffs
        {{
            useEquivalentSize no;
            collisionResolutionSteps 12;
            youngsModulus   {youngs};
            poissonsRatio   0.23;
            alpha           {alpha_wall};
            b               1.5;
            mu              {mu_wall};
            cohesionEnergyDensity 0;
        }};

        U     U.{phase};
    }}
"""


def cloud(phase, rho0, youngs, d, interpolation, walls, collision):
    local = "".join(f"""            {w}
            {{
                type rebound;
                e    0.97;
                mu   0.09;
            }}
""" for w in walls)
    return f"""
solution
{{
    active          true;
    coupled         true;
    transient       yes;
    cellValueSourceCorrection off;

    interpolationSchemes
    {{
        rho.{phase}     cell;
        U.{phase}       {interpolation};
        mu.{phase}      cell;
    }}

    integrationSchemes
    {{
        U               Euler;
    }}

    sourceTerms
    {{
        schemes
        {{
            U semiImplicit 1;
        }}
    }}
}}

constantProperties
{{
    parcelTypeId    1;
    rhoMin          1e-15;
    minParcelMass   1e-15;
    rho0            {rho0};
    youngsModulus   {youngs};
    poissonsRatio   0.35;
    constantVolume  false;
    alphaMax        0.99;
}}

subModels
{{
    particleForces
    {{
        sphereDrag;
        gravity;
    }}

    injectionModels
    {{
        model1
        {{
            type            manualInjection;
            massTotal       0;
            parcelBasisType fixed;
            nParticle       1;
            SOI             0;
            positionsFile   "kinematicCloudPositions";
            U0              (0 0 0);
            sizeDistribution
            {{
                type        fixedValue;
                fixedValueDistribution
                {{
                    value   {d};
                }}
            }}
        }}
    }}

    dispersionModel none;

    patchInteractionModel localInteraction;

    localInteractionCoeffs
    {{
        patches
        (
{local}        );
    }}

    heatTransferModel none;

    surfaceFilmModel none;
{collision}
    stochasticCollisionModel none;

    radiation off;
}}

cloudFunctions
{{}}
"""


BOX_PATCHES = [("top", "wall", ["z+"], ""), ("bottom", "wall", ["z-"], ""),
               ("walls", "wall", ["x-", "x+", "y-", "y+"], "")]
WALLS = ["top", "bottom", "walls"]


def settling_in_liquid(root):
    root = os.path.join(root, "tutorials", "settlingInLiquid")
    constant(root, "water", 1000, 1e-6)
    write(root, "system/controlDict", "dictionary", control(
        0.3, 2e-4, 0.01,
        "One glass bead (d = 1 mm, rho_p = 2500) settling from rest in water in a closed "
        "20 x 20 x 60 mm box\n// of 4 mm cells; sphereDrag and gravity only. Schiller-Naumann "
        "terminal velocity: 0.1459 m/s\n// (Re = 146, relaxation time 25 ms). Runs under "
        "DPMFoam and fsimFoam alike (tools/crosscheck)."))
    write(root, "system/blockMeshDict", "dictionary", block_mesh(
        (20, 20, 60), (5, 5, 15), BOX_PATCHES))
    closed_box_fields(root, "water", WALLS)
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud(
        "water", 2500, "1e8", 0.001, "cellPoint", WALLS, "\n    collisionModel none;\n"))
    # the centre of a cell (x, y) and of the cell at z = 52-56 mm, on no cell face
    write(root, "constant/kinematicCloudPositions", "vectorField",
          positions([(0.010, 0.010, 0.054)]))


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


def settling_column(root, n_side=10, layers=10, youngs="5e5", end=0.1, dt=1e-4, seed=38):
    root = os.path.join(root, "tutorials", "settlingColumn")
    constant(root, "air", 1.2, 1.5e-5)
    write(root, "system/controlDict", "dictionary", control(
        end, dt, 0.004,
        "1,000 glass beads (d = 2 mm, rho_p = 2500) on a loose lattice (10 layers of 10 x 10) "
        "fall through air\n// onto the floor of a closed 30 x 30 x 40 mm box of 5 mm cells "
        "and settle into a bed about\n// 9 mm high. sphereDrag, gravity, Hertzian "
        "spring-slider-dashpot contacts. Runs under DPMFoam\n// and fsimFoam alike "
        "(tools/crosscheck)."))
    write(root, "system/blockMeshDict", "dictionary", block_mesh(
        (30, 30, 40), (6, 6, 8), BOX_PATCHES))
    closed_box_fields(root, "air", WALLS)
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud(
        "air", 2500, youngs, 0.002, "cellPoint", WALLS,
        collisions(0.002, youngs, 0.3, 0.3, 0.3, 0.3, "air")))
    pts = column_positions(0.002, n_side, layers, 0.0026, 0.0033, 0.004, 0.00015, seed)
    write(root, "constant/kinematicCloudPositions", "vectorField", positions(pts))


if __name__ == "__main__":
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    settling_in_liquid(repo)
    settling_column(repo)
    print("wrote tutorials/settlingInLiquid and tutorials/settlingColumn")
