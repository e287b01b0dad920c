"""Case directories for the benchmarks, written from scratch in a scratch folder.

The same Taylor-Green case is written for fsimFoam and for OpenFOAM's icoFoam so both solve
the same problem on the same grid; the solver settings for icoFoam are those of its cavity
tutorial (PISO, 2 correctors, PCG/DIC to 1e-6, smoothSolver for U).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import make_taylor_green  # noqa: E402

BANNER = "/* written by tools/bench */\n"


def foam_file(klass, obj, body):
    return (BANNER + "FoamFile\n{\n    version 2.0;\n    format ascii;\n"
            f"    class {klass};\n    object {obj};\n}}\n\n{body}\n")


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def taylor_green(case, n, steps, dt, nu=0.01, write_interval=None, scheme=None):
    """A periodic 2 pi box of n^3 cells with the 2-D Taylor-Green vortex, run for `steps` steps."""
    end = steps * dt
    wi = write_interval if write_interval is not None else steps
    write(os.path.join(case, "system/controlDict"), foam_file("dictionary", "controlDict", f"""
application icoFoam;
startFrom startTime;
startTime 0;
stopAt endTime;
endTime {end!r};
deltaT {dt!r};
writeControl timeStep;
writeInterval {wi};
purgeWrite 0;
writeFormat ascii;
writePrecision 12;
timePrecision 8;
"""))
    patches = "\n".join(
        f"    {a} {{ type cyclic; neighbourPatch {b}; faces (({f})); }}"
        for a, b, f in [("left", "right", "0 4 7 3"), ("right", "left", "1 2 6 5"),
                        ("bottom", "top", "0 1 5 4"), ("top", "bottom", "3 7 6 2"),
                        ("back", "front", "0 3 2 1"), ("front", "back", "4 5 6 7")])
    write(os.path.join(case, "system/blockMeshDict"), foam_file("dictionary", "blockMeshDict", f"""
convertToMeters 6.283185307179586;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) ({n} {n} {n}) simpleGrading (1 1 1));
edges ();
boundary
(
{patches}
);
mergePatchPairs ();
"""))
    write(os.path.join(case, "constant/transportProperties"),
          foam_file("dictionary", "transportProperties", f"nu [0 2 -1 0 0 0 0] {nu!r};"))
    write(os.path.join(case, "0/p"), foam_file("volScalarField", "p", """
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField { ".*" { type cyclic; } }
"""))
    write(os.path.join(case, "system/fvSchemes"), foam_file("dictionary", "fvSchemes", """
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; grad(p) Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; }
laplacianSchemes { default Gauss linear orthogonal; }
interpolationSchemes { default linear; }
snGradSchemes { default orthogonal; }
"""))
    write(os.path.join(case, "system/fvSolution"), foam_file("dictionary", "fvSolution", """
solvers
{
    p { solver PCG; preconditioner DIC; tolerance 1e-06; relTol 0.05; }
    pFinal { $p; relTol 0; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-05; relTol 0; }
}
PISO { nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }
""" + (f"fsim {{ timeScheme {scheme}; }}\n" if scheme else "")))
    text = make_taylor_green.field_text(n, n, n)
    write(os.path.join(case, "0/U"), text)
    return end
