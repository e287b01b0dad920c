"""The dictionaries of a DPMFoam case (one that OpenFOAM v1912's `blockMesh && DPMFoam` and
fsimFoam both run), as the tutorials' generators write them, each parameterised by what the
cases vary: blockMeshDict, controlDict, fvSchemes and fvSolution, the fluid's constant/ files,
the fields 0/U.<phase> and 0/p, and kinematicCloudProperties with its injectors, wall
interaction and collision model. tools/foam_case.py writes the files (their FoamFile header).

Used by tools/make_drag_tutorials.py, make_benchmark_drag_law.py, make_settling_crosscheck.py
and make_impacts_crosscheck.py; tools/direct_cases.py takes its injection blocks.
"""
import textwrap

from foam_case import write

# --- system/ -------------------------------------------------------------------------------


def block_mesh(size_mm, cells, patches):
    """One hex block of size_mm (mm) in cells[0] x cells[1] x cells[2] cells; `patches` are
    (name, type, faces among x- x+ y- y+ z- z+, extra lines of the patch)."""
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


def control(end, dt, write_interval, note):
    """controlDict of a DPMFoam run to `end` in fixed steps dt, written every write_interval;
    `note` (its lines after the first start with //) heads the file."""
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


def system(root, fv_solution_extra=""):
    """system/fvSchemes and system/fvSolution (COMMON_SYSTEM, for the phase air or water),
    fv_solution_extra at the end of fvSolution."""
    for rel, body in COMMON_SYSTEM.items():
        if rel == "system/fvSolution":
            body += fv_solution_extra
        write(root, rel, "dictionary", body)


# --- constant/ and 0/ ----------------------------------------------------------------------


def constant(root, phase, rho, nu, g="0 0 -9.81", rho_note="", align_rho=False):
    """constant/transportProperties (a Newtonian `phase` of density rho and viscosity nu, the
    comment line rho_note above rho), turbulenceProperties.<phase> (laminar) and g. With
    align_rho, rho's value stands in the column of the other entries' values."""
    key = f"rho.{phase}"
    rho_line = f"{key:<16}{rho};" if align_rho else f"{key}     {rho};"
    write(root, "constant/transportProperties", "dictionary", f"""
continuousPhase {phase};

{rho_note}{rho_line}

transportModel  Newtonian;

nu              {nu};
""")
    write(root, f"constant/turbulenceProperties.{phase}", "dictionary", """
simulationType  laminar;
""")
    write(root, "constant/g", "uniformDimensionedVectorField", f"""
dimensions      [0 1 -2 0 0 0 0];

value           ({g});
""")


# A patch's conditions: (its entries in 0/U.<phase>, in 0/p).
FIXED_FLUX = "type            fixedFluxPressure;\nvalue           $internalField;"
NO_SLIP = ("type            noSlip;", FIXED_FLUX)
SYMMETRY = ("type            symmetry;",) * 2
CYCLIC = ("type            cyclic;",) * 2


def inlet(phase, u):
    """The gas or liquid entering at u (m/s, along z) through the beds' interstices."""
    return (f"type            interstitialInletVelocity;\n"
            f"inletVelocity   uniform (0 0 {u});\n"
            f"value           uniform (0 0 {u});\n"
            f"phi             phi.{phase};\n"
            f"alpha           alpha.{phase};", FIXED_FLUX)


def outlet(phase):
    """Leaving at the fixed pressure 0; flowing back in at rest."""
    return (f"type            pressureInletOutletVelocity;\n"
            f"phi             phi.{phase};\n"
            f"inletValue      uniform (0 0 0);\n"
            f"value           uniform (0 0 0);",
            "type            fixedValue;\nvalue           $internalField;")


def fields(root, phase, patches, gap="\n"):
    """0/U.<phase> and 0/p, the fluid at rest; `patches` are (name, conditions), conditions as
    NO_SLIP or inlet(); `gap` stands between two patches' entries."""
    def field(dimensions, value, k):
        entries = gap.join(f"    {name}\n    {{\n{textwrap.indent(cond[k], ' ' * 8)}\n    }}\n"
                           for name, cond in patches)
        return (f"\ndimensions      [{dimensions}];\n\ninternalField   uniform {value};\n\n"
                f"boundaryField\n{{\n{entries}}}\n")
    write(root, f"0/U.{phase}", "volVectorField", field("0 1 -1 0 0 0 0", "(0 0 0)", 0))
    write(root, "0/p", "volScalarField", field("0 2 -2 0 0 0 0", "0", 1))


# --- constant/kinematicCloudProperties ------------------------------------------------------


def size_distribution(d, compact=False):
    """The injectors' sizeDistribution: every diameter d (as written)."""
    value = (f"fixedValueDistribution {{ value {d}; }}" if compact else
             f"fixedValueDistribution\n{{\n    value   {d};\n}}")
    return textwrap.indent(f"sizeDistribution\n{{\n    type        fixedValue;\n"
                           f"{textwrap.indent(value, ' ' * 4)}\n}}\n", " " * 12)


def manual_injection(name, d, positions_file="kinematicCloudPositions", u0="0 0 0",
                     compact=False):
    """An injector `name` of single beads of diameter d at the centres of positions_file,
    all at t = 0 with velocity u0."""
    return f"""
        {name}
        {{
            type            manualInjection;
            massTotal       0;
            parcelBasisType fixed;
            nParticle       1;
            SOI             0;
            positionsFile   "{positions_file}";
            U0              ({u0});
{size_distribution(d, compact)}        }}
"""


def local_interaction(patches):
    """The beads rebound from each of `patches` with e 0.97 and mu 0.09."""
    local = "".join(f"""            {p}
            {{
                type rebound;
                e    0.97;
                mu   0.09;
            }}
""" for p in patches)
    return f"""    patchInteractionModel localInteraction;

    localInteractionCoeffs
    {{
        patches
        (
{local}        );
    }}
"""


def standard_wall_interaction(e, mu, note=""):
    """The beads rebound from every wall with e and mu; `note`, a comment line above."""
    comment = f"    // {note}\n" if note else ""
    return comment + f"""    patchInteractionModel standardWallInteraction;

    standardWallInteractionCoeffs
    {{
        type rebound;
        e    {e};
        mu   {mu};
    }}
"""


NO_COLLISIONS = "\n    collisionModel none;\n"


def spring_slider_dashpot(d, youngs, phase, pair, wall, steps=12):
    """Hertzian contacts between beads of diameter d and of beads with the walls (DPMFoam's
    pairSpringSliderDashpot and wallSpringSliderDashpot): pair and wall are (alpha, mu);
    `steps` collision sub-steps per contact."""
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
            alpha               {pair[0]};
            b                   1.5;
            mu                  {pair[1]};
            cohesionEnergyDensity 0;
            collisionResolutionSteps {steps};
        }};

        wallModel wallSpringSliderDashpot;

        wallSpringSliderDashpotCoeffs
        {{
            useEquivalentSize no;
            collisionResolutionSteps {steps};
            youngsModulus   {youngs};
            poissonsRatio   0.23;
            alpha           {wall[0]};
            b               1.5;
            mu              {wall[1]};
            cohesionEnergyDensity 0;
        }};

        U     U.{phase};
    }}
"""


def cloud_properties(phase, rho0, youngs, interpolation, forces, injectors, walls, collision,
                     note=""):
    """kinematicCloudProperties: beads of density rho0 and Young's modulus youngs, the fluid's
    velocity interpolated by `interpolation` (cell, cellPoint); `forces`, the particleForces
    entries (unindented lines); `injectors`, manual_injection()s; `walls`, local_interaction()
    or standard_wall_interaction(); `collision`, spring_slider_dashpot() or NO_COLLISIONS;
    `note`, comment lines heading the file."""
    return f"""{note}
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
{textwrap.indent(forces, " " * 8)}
    }}

    injectionModels
    {{{injectors}    }}

    dispersionModel none;

{walls}
    heatTransferModel none;

    surfaceFilmModel none;
{collision}
    stochasticCollisionModel none;

    radiation off;
}}

cloudFunctions
{{}}
"""


def positions(points, digits=6):
    """A vectorField of the centres `points`, each to `digits` significant digits."""
    body = f"\n{len(points)}\n(\n"
    for p in points:
        body += f"({p[0]:.{digits}g} {p[1]:.{digits}g} {p[2]:.{digits}g})\n"
    return body + ")\n"
