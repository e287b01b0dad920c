#!/usr/bin/env python3
"""Writers of fully periodic direct-model cases (settling spheres), shared by the tutorials'
generator, the sedimentation sweep and the benchmark.

    tools/direct_cases.py            rewrites tutorials/settlingSphere, sedimentation, benchmark

A case is a periodic box of `cells` cells of size h, spheres of diameter d given by their
centres (kinematicCloudPositions) or by fsim's randomPacking injection, gravity along -y
(the paper's x2), the direct model with an adaptive step.
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import foam_case  # noqa: E402
from dpmfoam_case import manual_injection, size_distribution  # noqa: E402


def _write(case, rel, cls, body):
    foam_case.write(case, rel, cls, body, gap="\n")


def sphere_volume(d):
    return math.pi * d ** 3 / 6.0


def periodic_packing(length, d, count, seed, min_gap=0.0):
    """Centres of `count` spheres of diameter d in a periodic box by random sequential
    addition (no overlap, surface gaps at least min_gap across periodic faces too)."""
    rng = random.Random(seed)
    centres = []
    reach = d + min_gap
    cell = [max(1, int(L // reach)) for L in length]
    grid = {}

    def key(x):
        return tuple(int(x[a] / length[a] * cell[a]) % cell[a] for a in range(3))

    tries = 0
    while len(centres) < count:
        tries += 1
        if tries > 2000 * count:
            raise RuntimeError(f"random packing stalled at {len(centres)} of {count} spheres")
        x = [rng.random() * length[a] for a in range(3)]
        k = key(x)
        ok = True
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    nk = ((k[0] + dx) % cell[0], (k[1] + dy) % cell[1], (k[2] + dz) % cell[2])
                    for y in grid.get(nk, ()):
                        s = 0.0
                        for a in range(3):
                            t = x[a] - y[a]
                            t -= length[a] * round(t / length[a])
                            s += t * t
                        if s < reach * reach:
                            ok = False
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            centres.append(x)
            grid.setdefault(k, []).append(x)
    return centres


def write_case(case, *, cells, h, d, rho_f, nu, rho_p, end_time, write_interval,
               centres=None, random_fraction=None, seed=1, max_co=0.5, max_dt=1.0,
               kn=None, restitution=0.9, mu=0.3, coupling_extra="", title="", scheme="Euler"):
    """A periodic box of cells[0] x cells[1] x cells[2] cells of size h (m) with spheres of
    diameter d (m) and density rho_p, in a fluid of density rho_f and viscosity nu.
    Particles: `centres` (a list), or `random_fraction` (fsim's randomPacking, seeded)."""
    L = [n * h for n in cells]
    if scheme == "Euler":
        # just under the explicit viscous bound h^2/(6 nu) (paper eq. 3), which rules at h < r
        max_dt = min(max_dt, 0.95 * h * h / (6 * nu))
    _write(case, "system/blockMeshDict", "dictionary", f"""
// {title}
// A periodic box {L[0]:g} x {L[1]:g} x {L[2]:g} m, {cells[0]} x {cells[1]} x {cells[2]} cells
// (h = {h:g} m), gravity along -y.
scale   1;

vertices
(
    (0 0 0)
    ({L[0]!r} 0 0)
    ({L[0]!r} {L[1]!r} 0)
    (0 {L[1]!r} 0)
    (0 0 {L[2]!r})
    ({L[0]!r} 0 {L[2]!r})
    ({L[0]!r} {L[1]!r} {L[2]!r})
    (0 {L[1]!r} {L[2]!r})
);

blocks
(
    hex (0 1 2 3 4 5 6 7) ({cells[0]} {cells[1]} {cells[2]}) simpleGrading (1 1 1)
);

boundary
(
    left   {{ type cyclic; neighbourPatch right;  faces ((0 4 7 3)); }}
    right  {{ type cyclic; neighbourPatch left;   faces ((1 2 6 5)); }}
    bottom {{ type cyclic; neighbourPatch top;    faces ((0 1 5 4)); }}
    top    {{ type cyclic; neighbourPatch bottom; faces ((3 7 6 2)); }}
    back   {{ type cyclic; neighbourPatch front;  faces ((0 3 2 1)); }}
    front  {{ type cyclic; neighbourPatch back;   faces ((4 5 6 7)); }}
);
""")
    _write(case, "system/controlDict", "dictionary", f"""
// {title}

application     fsimFoam;

startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         {end_time:g};

deltaT          {max_dt:.6g};
adjustTimeStep  yes;
maxCo           {max_co:g};
maxDeltaT       {max_dt:.6g};

writeControl    adjustableRunTime;
writeInterval   {write_interval:g};
purgeWrite      0;

timePrecision   6;

runTimeModifiable yes;
""")
    if scheme == "EulerRKC":
        why = """    // Explicit Euler advection; the diffusion by Runge-Kutta-Chebyshev stages, as many as
    // the step needs (3 or 4 at maxCo 0.8 here), each a Laplacian with the no-slip forcing
    // imposed on it, then one projection: the step follows maxCo (and maxDeltaT), not
    // the explicit viscous bound h^2/(6 nu) (docs/numerics.md)."""
    else:
        why = """    // The paper's explicit scheme: the step sits just under its viscous bound h^2/(6 nu)
    // (maxDeltaT in controlDict), which rules at h < r; RK3 allows 1.25 times the step at
    // three times the cost per step."""
    _write(case, "system/fvSolution", "dictionary", f"""
fsim
{{
{why}
    timeScheme      {scheme};
}}
""")
    _write(case, "constant/transportProperties", "dictionary", f"""
continuousPhase fluid;

rho.fluid       {rho_f:g};

transportModel  Newtonian;
nu              {nu:g};
""")
    _write(case, "constant/g", "uniformDimensionedVectorField", """
dimensions      [0 1 -2 0 0 0 0];
value           (0 -9.81 0);
""")
    _write(case, "constant/couplingProperties", "dictionary", f"""
// fsim's own file. In a fully periodic box the mean pressure gradient that carries the
// mixture's weight is imposed (the suspension as a whole does not accelerate).
model           direct;
{coupling_extra}""")
    _write(case, "0/U.fluid", "volVectorField", """
dimensions      [0 1 -1 0 0 0 0];

internalField   uniform (0 0 0);

boundaryField
{
    ".*"
    {
        type            cyclic;
    }
}
""")
    _write(case, "0/p", "volScalarField", """
dimensions      [0 2 -2 0 0 0 0];

internalField   uniform 0;

boundaryField
{
    ".*"
    {
        type            cyclic;
    }
}
""")
    m = rho_p * sphere_volume(d)
    if kn is None:
        # soft enough for few collision sub-steps, stiff enough that a head-on impact at the
        # Stokes velocity overlaps by 0.5 % of d: t_c = pi delta / v, kn = (pi/t_c)^2 m/2
        t_c = math.pi * 0.005 * d / stokes_velocity(d, rho_p, rho_f, nu)
        kn = (math.pi / t_c) ** 2 * m / 2
    if centres is not None:
        injection = manual_injection("spheres", repr(d), compact=True).rstrip("\n")
        lines = "\n".join(f"({x[0]!r} {x[1]!r} {x[2]!r})" for x in centres)
        _write(case, "constant/kinematicCloudPositions", "vectorField", f"(\n{lines}\n)\n")
    else:
        injection = f"""
        spheres
        {{
            // fsim: a random non-overlapping packing of the box at a solid fraction
            type            randomPacking;
            box             (0 0 0) ({L[0]!r} {L[1]!r} {L[2]!r});
            volumeFraction  {random_fraction!r};
            seed            {seed};
            U0              (0 0 0);
{size_distribution(repr(d), compact=True)}        }}"""
    _write(case, "constant/kinematicCloudProperties", "dictionary", f"""
// {title}

solution
{{
    active          true;
    coupled         true;
    transient       yes;
}}

constantProperties
{{
    rho0            {rho_p:g};
}}

subModels
{{
    particleForces
    {{
        gravity;
    }}

    injectionModels
    {{{injection}
    }}

    dispersionModel none;

    patchInteractionModel standardWallInteraction;

    standardWallInteractionCoeffs
    {{
        type rebound;
        e    {restitution:g};
        mu   {mu:g};
    }}

    collisionModel pairCollision;

    pairCollisionCoeffs
    {{
        maxInteractionDistance  {d!r};

        pairModel pairLinearSpringDashpot;

        pairLinearSpringDashpotCoeffs
        {{
            kn      {kn:.6g};   // N/m
            e       {restitution:g};
            mu      {mu:g};
            collisionResolutionSteps 20;
        }}

        wallModel wallLinearSpringDashpot;

        wallLinearSpringDashpotCoeffs
        {{
            kn      {kn:.6g};
            e       {restitution:g};
            mu      {mu:g};
            collisionResolutionSteps 20;
        }}
    }}
}}
""")
    return L


def stokes_velocity(d, rho_p, rho_f, nu, g=9.81):
    """Terminal velocity of an isolated sphere in Stokes flow, 2 (rho_p - rho_f) g r^2 / (9 mu)."""
    r = d / 2
    return 2 * (rho_p - rho_f) * g * r * r / (9 * rho_f * nu)


def sangani_acrivos_inverse_k(phi):
    """1/K of a simple cubic array (paper eq. 17): the settling velocity of one sphere in a
    periodic box over its Stokes velocity."""
    c = phi ** (1.0 / 3.0)
    return (1 - 1.7601 * c + phi - 1.5593 * phi ** 2 + 3.9799 * phi ** (8.0 / 3.0)
            - 3.0734 * phi ** (10.0 / 3.0))


# ----- the tutorials -----

def settling_sphere(case):
    """One sphere (d = 2 mm, r/h = 8) settling in a 4.5 mm periodic box (36 cells: the DEM
    needs a periodic length above 2.2 d; phi = 0.046), in a liquid of 1 Pa s: Re = 0.004."""
    n, h = 36, 1.25e-4
    d = 16 * h
    return write_case(case, cells=[n, n, n], h=h, d=d, rho_f=1000.0, nu=1e-3, rho_p=2000.0,
                      end_time=0.005, write_interval=0.001,
                      centres=[[n * h / 2 + 0.3 * h, n * h / 2, n * h / 2 - 0.2 * h]],
                      max_co=0.5, max_dt=2e-4,
                      title="One sphere settling in a periodic box (tutorials/settlingSphere)")


LINEAR = """
direct
{
    // trilinear sampling for the stress integral: half the cost of tricubic; on the
    // settling sphere at r/h = 8 the terminal velocity differs by 0.01 % (README)
    interpolation   linear;
}
"""


BENCHMARK_COUPLING = LINEAR.replace("    interpolation   linear;\n", "    interpolation   linear;\n"
                                    + """    // the forced faces are rebuilt once a sphere has moved a quarter of a cell (between
    // builds they keep their geometry and take the spheres' motion): a pulled sphere's
    // drag changes by +0.3 %, the benchmark's step costs a third less (docs/benchmarks/direct.md)
    rebuildDistance 0.25;
""")


def sedimentation(case):
    """The README's default case: 48 spheres (d = 1.5 mm, r/h = 3) settling in a periodic box
    of 32 x 64 x 32 cells (8 x 16 x 8 mm) at phi = 0.083, Re_p = 0.77, for 0.2 s (about
    two diameters of fall, 1200 steps)."""
    cells, h = [32, 64, 32], 2.5e-4
    d = 6 * h
    L = [c * h for c in cells]
    centres = periodic_packing(L, d, 48, seed=1, min_gap=2 * h)
    return write_case(case, cells=cells, h=h, d=d, rho_f=1000.0, nu=6e-5, rho_p=2500.0,
                      end_time=0.2, write_interval=0.05, centres=centres, max_co=0.5,
                      max_dt=1e-3, restitution=0.5, coupling_extra=LINEAR,
                      title="Spheres settling in a periodic box (tutorials/sedimentation)")


def benchmark(case, end_time=0.1, cells_per_radius=2.5, particles=500, scheme="EulerRKC",
              max_dt=1e-4):
    """The paper's section 3.3 case: gas-solid, rho_f 1.2, rho_p 1500, mu_f 1.8e-5,
    d = 100 um, box 24r x 72r x 24r periodic, 500 particles, h = 0.4 r (60 x 180 x 60).
    `cells_per_radius` and `particles` vary it for the scaling studies (same box).
    EulerRKC (Euler advection, Chebyshev stages of the diffusion): the step follows maxCo
    0.8, about 20 us once the gas streams up through the particles (t > 1 ms), four to five
    times the explicit Euler bound h^2/(6 nu) = 4.4 us, with 3 stages of a Laplacian each.
    maxCo 0.8 rather than 0.5: the first-order step's
    error in the settling velocity at 5 ms is then about 0.7 % (0.4 % at 0.5), below the
    spatial error of h = 0.4 r, for 1.5 times fewer steps (docs/benchmarks/direct.md)."""
    r = 50e-6
    h = r / cells_per_radius
    cells = [int(round(24 * cells_per_radius)), int(round(72 * cells_per_radius)),
             int(round(24 * cells_per_radius))]
    L = [c * h for c in cells]
    centres = periodic_packing(L, 2 * r, particles, seed=3, min_gap=0.4 * r)
    return write_case(case, cells=cells, h=h, d=2 * r, rho_f=1.2, nu=1.8e-5 / 1.2,
                      rho_p=1500.0, end_time=end_time, write_interval=end_time / 5,
                      centres=centres, max_co=0.8, max_dt=max_dt, restitution=0.9,
                      coupling_extra=BENCHMARK_COUPLING, scheme=scheme,
                      title="The paper's benchmark, section 3.3 (tutorials/benchmark)")


if __name__ == "__main__":
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tutorials")
    settling_sphere(os.path.join(root, "settlingSphere"))
    sedimentation(os.path.join(root, "sedimentation"))
    benchmark(os.path.join(root, "benchmark"))
