#!/usr/bin/env python3
"""Write the initial velocity of the 2-D Taylor-Green vortex as an OpenFOAM field.

    u =  U0 sin(x) cos(y),   v = -U0 cos(x) sin(y),   w = 0      on [0, 2 pi)^2 x [0, Lz)

sampled at cell centres. It is an exact solution of the Navier-Stokes equations whose kinetic
energy decays as exp(-4 nu t) (Taylor & Green 1937). Used by tutorials/taylorGreen and by
tools/bench to build cases of any size:

    python3 tools/make_taylor_green.py CASE_DIR NX NY NZ [--gzip]

writes CASE_DIR/0/U (or 0/U.gz). The block geometry lives in CASE_DIR/system/blockMeshDict.
"""
import argparse
import gzip
import math
import os

HEADER = """/*--------------------------------*- C++ -*----------------------------------*\\
  fsim: particles in a fluid at the particle scale
\\*---------------------------------------------------------------------------*/
FoamFile
{
    version     2.0;
    format      ascii;
    class       volVectorField;
    location    "0";
    object      U;
}
// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

// 2-D Taylor-Green vortex, written by tools/make_taylor_green.py
dimensions      [0 1 -1 0 0 0 0];

"""


def field_text(nx, ny, nz, u0=1.0):
    hx = 2.0 * math.pi / nx
    hy = 2.0 * math.pi / ny
    lines = [HEADER, f"internalField   nonuniform List<vector>\n{nx * ny * nz}\n(\n"]
    row = []
    for j in range(ny):
        y = (j + 0.5) * hy
        for i in range(nx):
            x = (i + 0.5) * hx
            row.append(f"({u0 * math.sin(x) * math.cos(y)!r} {-u0 * math.cos(x) * math.sin(y)!r} 0)\n")
    body = "".join(row)
    lines.append(body * nz)
    lines.append(")\n;\n\nboundaryField\n{\n    \".*\"\n    {\n        type            cyclic;\n    }\n}\n")
    return "".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("nx", type=int)
    ap.add_argument("ny", type=int)
    ap.add_argument("nz", type=int)
    ap.add_argument("--gzip", action="store_true", help="write 0/U.gz")
    a = ap.parse_args()
    os.makedirs(os.path.join(a.case, "0"), exist_ok=True)
    text = field_text(a.nx, a.ny, a.nz).encode()
    if a.gzip:
        with gzip.GzipFile(os.path.join(a.case, "0", "U.gz"), "wb", mtime=0) as f:
            f.write(text)
    else:
        with open(os.path.join(a.case, "0", "U"), "wb") as f:
            f.write(text)


if __name__ == "__main__":
    main()
