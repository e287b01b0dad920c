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
from foam_case import write  # noqa: E402


def block_mesh(size_mm, cells, patches):
    lx, ly, lz = size_mm
    faces = {
        "x-": "(0 4 7 3)", "x+": "(2 6 5 1)", "y-": "(1 5 4 0)",
        "y+": "(3 7 6 2)", "z-": "(0 3 2 1)", "z+": "(4 5 6 7)",
    }
    out = f"""
scale   0.001;

vertices
(
    (0 0 0) ({lx} 0 0) ({lx} {ly} 0) (0 {ly} 0)
    (0 0 {lz}) ({lx} 0 {lz}) ({lx} {ly} {lz}) (0 {ly} {lz})
);

blocks
(
    hex (0 1 2 3 4 5 6 7) ({cells[0]} {cells[1]} {cells[2]}) simpleGrading (1 1 1)
);

edges
(
);

boundary
(
"""
    for name, kind, sides, extra in patches:
        out += f"    {name}\n    {{\n        type {kind};\n{extra}        faces\n        (\n"
        for s in sides:
            out += f"            {faces[s]}\n"
        out += "        );\n    }\n"
    out += ");\n\nmergePatchPairs\n(\n);\n"
    return out


def positions(points):
    body = f"\n{len(points)}\n(\n"
    for p in points:
        body += "({:.6g} {:.6g} {:.6g})\n".format(*p)
    return body + ")\n"


COMMON_SYSTEM = {
    "system/fvSchemes": """
ddtSchemes
{
    default         Euler;
}

gradSchemes
{
    default         Gauss linear;
}

divSchemes
{
    default         none;
    div(alphaPhi.air,U.air) Gauss linearUpwindV unlimited;
    div(((alpha.air*nuEff.air)*dev2(T(grad(U.air))))) Gauss linear;
    div(phiGByA,kinematicCloud:alpha) Gauss linear;
    div(alphaPhi.water,U.water) Gauss linearUpwindV unlimited;
    div(((alpha.water*nuEff.water)*dev2(T(grad(U.water))))) Gauss linear;
}

laplacianSchemes
{
    default         Gauss linear corrected;
}

interpolationSchemes
{
    default         linear;
}

snGradSchemes
{
    default         corrected;
}
""",
    "system/fvSolution": """
solvers
{
    p
    {
        solver          GAMG;
        tolerance       1e-6;
        relTol          0.01;
        smoother        DIC;
    }

    pFinal
    {
        $p;
        relTol          0;
    }

    "(U|k|epsilon|omega|R|nuTilda).*"
    {
        solver          smoothSolver;
        smoother        symGaussSeidel;
        tolerance       1e-5;
        relTol          0;
    }

    kinematicCloud:alpha
    {
        solver          GAMG;
        tolerance       1e-6;
        relTol          0;
        smoother        GaussSeidel;
    }
}

PIMPLE
{
    nOuterCorrectors 1;
    nCorrectors     2;
    momentumPredictor yes;
    nNonOrthogonalCorrectors 0;
    pRefCell        0;
    pRefValue       0;
}

relaxationFactors
{
    fields
    {
        ".*"            1;
    }
    equations
    {
        ".*"            1;
    }
}
""",
}


def cloud_properties(phase, rho0, youngs, d, interpolation, extra_forces, patches):
    local = "".join(
        f"""            {p}
            {{
                type rebound;
                e    0.97;
                mu   0.09;
            }}
""" for p in patches)
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
        ErgunWenYuDrag
        {{
            alphac alpha.{phase};
        }}
        gravity;{extra_forces}
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

    collisionModel pairCollision;

    pairCollisionCoeffs
    {{
        maxInteractionDistance  {d};
        writeReferredParticleCloud no;

        pairModel pairSpringSliderDashpot;

        pairSpringSliderDashpotCoeffs
        {{
            useEquivalentSize   no;
            alpha               0.02;
            b                   1.5;
            mu                  0.10;
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
            alpha           0.01;
            b               1.5;
            mu              0.09;
            cohesionEnergyDensity 0;
        }};

        U     U.{phase};
    }}

    stochasticCollisionModel none;

    radiation off;
}}

cloudFunctions
{{}}
"""


def control(end, dt, write_interval, note):
    return f"""
// {note}

application     DPMFoam;

startFrom       startTime;

startTime       0;

stopAt          endTime;

endTime         {end};

deltaT          {dt};

writeControl    runTime;

writeInterval   {write_interval};

purgeWrite      0;

writeFormat     ascii;

writePrecision  6;

writeCompression off;

timeFormat      general;

timePrecision   6;

runTimeModifiable yes;

adjustTimeStep  no;
"""


def fields(root, phase, inlet, u_in, outlet, walls, cyclic=()):
    u = f"""
dimensions      [0 1 -1 0 0 0 0];

internalField   uniform (0 0 0);

boundaryField
{{
    {inlet}
    {{
        type            interstitialInletVelocity;
        inletVelocity   uniform (0 0 {u_in});
        value           uniform (0 0 {u_in});
        phi             phi.{phase};
        alpha           alpha.{phase};
    }}

    {outlet}
    {{
        type            pressureInletOutletVelocity;
        phi             phi.{phase};
        inletValue      uniform (0 0 0);
        value           uniform (0 0 0);
    }}
"""
    p = f"""
dimensions      [0 2 -2 0 0 0 0];

internalField   uniform 0;

boundaryField
{{
    {inlet}
    {{
        type            fixedFluxPressure;
        value           $internalField;
    }}

    {outlet}
    {{
        type            fixedValue;
        value           $internalField;
    }}
"""
    for name, kind in walls:
        if kind == "symmetry":
            u += f"\n    {name}\n    {{\n        type            symmetry;\n    }}\n"
            p += f"\n    {name}\n    {{\n        type            symmetry;\n    }}\n"
        else:
            u += f"\n    {name}\n    {{\n        type            noSlip;\n    }}\n"
            p += (f"\n    {name}\n    {{\n        type            fixedFluxPressure;\n"
                  f"        value           $internalField;\n    }}\n")
    for name in cyclic:
        u += f"\n    {name}\n    {{\n        type            cyclic;\n    }}\n"
        p += f"\n    {name}\n    {{\n        type            cyclic;\n    }}\n"
    write(root, f"0/U.{phase}", "volVectorField", u + "}\n")
    write(root, "0/p", "volScalarField", p + "}\n")


def common_constant(root, phase, rho, nu):
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


def fluidized_bed(root):
    root = os.path.join(root, "tutorials", "fluidizedBed")
    common_constant(root, "air", 1.2, 1e-5)
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
    fields(root, "air", "bottom", 1.875, "top", [("walls", "wall"), ("frontAndBack", "symmetry")])
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud_properties(
        "air", 2526, "1e6", 0.0025, "cellPoint", "",
        ["top", "bottom", "walls", "frontAndBack"]))
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
    common_constant(root, "water", 1000, 1e-6)
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
    fields(root, "water", "bottom", 0.001, "top", [],
           cyclic=["sidesX1", "sidesX2", "sidesY1", "sidesY2"])
    write(root, "constant/kinematicCloudProperties", "dictionary", cloud_properties(
        "water", 2500, "1e7", 0.001, "cell", "",
        ["top", "bottom"]))
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
