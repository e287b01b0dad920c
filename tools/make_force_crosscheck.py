#!/usr/bin/env python3
"""Writes issue 42's four cross-check cases against DPMFoam, one per family of DPMFoam v1912
particle forces that fsim is to accept: cases that run unchanged under OpenFOAM v1912's
`blockMesh && DPMFoam` and under `fsimFoam` once it accepts the forces. tools/crosscheck
compares them by their crosscheck.toml; tools/force_crosscheck_references.py computes their
hand references.

    tools/make_force_crosscheck.py [REPO_ROOT]

settlingAddedMass: one bead (d = 1 mm, rho_p = 1500) from rest in water, sphereDrag,
  pressureGradient, virtualMass (Cvm 0.5) and gravity, in settlingInLiquid's box.
liquidFluidizedBed: 588 glass beads (d = 2 mm, rho_p = 2500) fluidized by water at 0.06 m/s
  in a 16 x 16 mm column with symmetry-plane sides: WenYuDrag, pressureGradient,
  virtualMass, gravity, contacts.
shearLift: one bead (d = 1 mm, rho_p = 1100) settling in a vertical linear shear flow between
  two walls 16 mm apart sliding in opposite directions (gamma = 10 1/s): sphereDrag,
  SaffmanMeiLiftForce, gravity; the lateral drift. The column is 320 mm long and closed, the
  bead falls through its middle, out of reach of the flow the ends turn round (in a 192 mm
  column it reached the bead within 1 s). shearLiftTomiyama: the same with
  TomiyamaLift { sigma 0.07; }.
nonSphereSettling: settlingInLiquid with nonSphereDrag { phi 0.7; } for sphereDrag.

What each force needs in the case (found by running DPMFoam v1912): pressureGradient and
virtualMass are dictionaries naming the fluid velocity (`U U.water;`; without it DPMFoam
looks up a field `U`), and the cloud's interpolationSchemes must have `DUcDt` (the field
DUc/Dt = ddt(U) + U & grad(U) both forces interpolate); SaffmanMeiLiftForce and TomiyamaLift
the same with `curlUcDt` (curl U); virtualMass needs `Cvm`, TomiyamaLift `sigma`,
nonSphereDrag `phi`, WenYuDrag `alphac`. DPMFoam v1912 reads no fvOptions (neither system/ nor
constant/), so a column periodic in z cannot hold its water up with meanVelocityForce there.
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dpmfoam_case import (CYCLIC, FIXED_FLUX, NO_COLLISIONS, NO_SLIP, SYMMETRY,  # noqa: E402
                          block_mesh, cloud_properties, constant, control, fields, inlet,
                          local_interaction, manual_injection, outlet, positions,
                          spring_slider_dashpot, system)
from foam_case import write  # noqa: E402

BOX_PATCHES = [("top", "wall", ["z+"], ""), ("bottom", "wall", ["z-"], ""),
               ("walls", "wall", ["x-", "x+", "y-", "y+"], "")]
WALLS = ["top", "bottom", "walls"]
WATER = ("water", 1000, 1e-6)


def with_interpolation(text, entries):
    """kinematicCloudProperties with `entries` (name, scheme) added to interpolationSchemes."""
    anchor = "        mu.water      cell;\n"
    assert anchor in text
    extra = "".join(f"        {name:<13} {scheme};\n" for name, scheme in entries)
    return text.replace(anchor, anchor + extra)


def settling_box(repo, name, times, note, rho_p, forces, interpolation, d=0.001,
                 start=(0.010, 0.010, 0.054)):
    """settlingInLiquid's closed 20 x 20 x 60 mm box of 4 mm cells, one bead at `start`."""
    root = os.path.join(repo, "tutorials", name)
    constant(root, *WATER)
    system(root)
    write(root, "system/controlDict", "dictionary", control(*times, note))
    write(root, "system/blockMeshDict", "dictionary",
          block_mesh((20, 20, 60), (5, 5, 15), BOX_PATCHES))
    fields(root, "water", [(wall, NO_SLIP) for wall in WALLS])
    cloud = cloud_properties("water", rho_p, "1e8", "cellPoint", forces,
                             manual_injection("model1", d), local_interaction(WALLS),
                             NO_COLLISIONS)
    write(root, "constant/kinematicCloudProperties", "dictionary",
          with_interpolation(cloud, interpolation))
    write(root, "constant/kinematicCloudPositions", "vectorField", positions([start]))


def settling_added_mass(repo):
    settling_box(
        repo, "settlingAddedMass", (0.3, 2e-4, 0.002),
        "One bead (d = 1 mm, rho_p = 1500) settling from rest in water in a closed 20 x 20 x "
        "60 mm box of\n// 4 mm cells: sphereDrag, pressureGradient, virtualMass (Cvm 0.5), "
        "gravity. Initial acceleration\n// g (rho_p - rho_f)/(rho_p + Cvm rho_f) = 2.45 m/s2 "
        "(3.27 without the added mass); terminal velocity\n// 0.0714 m/s (Re = 71). Runs under "
        "DPMFoam and fsimFoam alike (tools/crosscheck).",
        1500,
        "sphereDrag;\npressureGradient\n{\n    U   U.water;\n}\n"
        "virtualMass\n{\n    U   U.water;\n    Cvm 0.5;\n}\ngravity;",
        [("DUcDt", "cellPoint")])


def non_sphere_settling(repo):
    settling_box(
        repo, "nonSphereSettling", (0.3, 2e-4, 0.01),
        "One non-spherical glass particle (volume-equivalent d = 1 mm, rho_p = 2500, "
        "sphericity 0.7) settling\n// from rest in water in a closed 20 x 20 x 60 mm box of 4 mm "
        "cells: nonSphereDrag (Haider-Levenspiel)\n// and gravity. Terminal velocity 0.1073 m/s "
        "(Re = 107; a sphere: 0.1459 m/s). Runs under DPMFoam\n// and fsimFoam alike "
        "(tools/crosscheck).",
        2500, "nonSphereDrag\n{\n    phi 0.7;\n}\ngravity;", [])


# ----- liquidFluidizedBed --------------------------------------------------------------------

def bed_patches(sides):
    """Inlet below, outlet above, the four sides `wall` (no-slip) or `symmetry` (slip)."""
    return [("top", "patch", ["z+"], ""), ("bottom", "patch", ["z-"], ""),
            ("walls", sides, ["x-", "x+", "y-", "y+"], "")]


def bed_positions(d, n_side, layers, pitch, x0, z0, jitter, seed, width, cell):
    """A lattice of n_side x n_side beads per layer, `pitch` apart from (x0, x0, z0),
    jittered by up to `jitter`; no bead within 50 um of a cell face (multiples of `cell`)."""
    rng = random.Random(seed)
    pts = []
    for k in range(layers):
        for j in range(n_side):
            for i in range(n_side):
                pts.append((x0 + pitch * i + rng.uniform(-jitter, jitter),
                            x0 + pitch * j + rng.uniform(-jitter, jitter),
                            z0 + pitch * k + rng.uniform(-jitter, jitter)))
    for p in pts:
        assert all(abs(c - cell * round(c / cell)) > 5e-5 for c in p), p
        assert min(p[0], p[1], width - p[0], width - p[1]) > 0.5 * d
    assert pitch - 2 * math.sqrt(3) * jitter > d
    return pts


def liquid_fluidized_bed(repo, u=0.06, d=0.002, youngs="5e5", end=0.8, dt=5e-4, seed=42,
                         sides="symmetry"):
    """The column's sides are symmetry planes (an unbounded bed): with no-slip walls of 4 mm
    cells DPMFoam's cellPoint interpolation takes the walls' zero velocity into 12 of the 16
    cell columns, and its bed settles to a solid fraction of 0.477 instead of 0.409."""
    root = os.path.join(repo, "tutorials", "liquidFluidizedBed")
    constant(root, *WATER)
    system(root)
    write(root, "system/controlDict", "dictionary", control(
        end, dt, 0.01,
        "588 glass beads (d = 2 mm, rho_p = 2500) fluidized by water entering at 0.06 m/s "
        "through the floor of\n// a 16 x 16 x 64 mm column of 4 mm cells with symmetry-plane "
        "sides: WenYuDrag, "
        "pressureGradient, virtualMass (Cvm 0.5), gravity,\n// Hertzian contacts. The bed "
        "settles from a loose lattice (solid fraction 0.38) to about 0.41.\n// Runs "
        "under DPMFoam and fsimFoam alike (tools/crosscheck)."))
    write(root, "system/blockMeshDict", "dictionary",
          block_mesh((16, 16, 64), (4, 4, 16), bed_patches(sides)))
    fields(root, "water", [("top", outlet("water")), ("bottom", inlet("water", u)),
                           ("walls", NO_SLIP if sides == "wall" else SYMMETRY)])
    forces = ("WenYuDrag\n{\n    alphac alpha.water;\n}\n"
              "pressureGradient\n{\n    U   U.water;\n}\n"
              "virtualMass\n{\n    U   U.water;\n    Cvm 0.5;\n}\ngravity;")
    cloud = cloud_properties(
        "water", 2500, youngs, "cellPoint", forces, manual_injection("model1", d),
        local_interaction(["top", "bottom", "walls"]),
        spring_slider_dashpot(d, youngs, "water", (0.3, 0.3), (0.3, 0.3)))
    write(root, "constant/kinematicCloudProperties", "dictionary",
          with_interpolation(cloud, [("DUcDt", "cellPoint")]))
    # 12 layers of 7 x 7 at a pitch of 2.1 mm: solid fraction 0.45 within the lattice, 0.38
    # over the column's section
    pts = bed_positions(d, 7, 12, 0.0021, 0.0018, 0.0016, 0.00002, seed, 0.016, 0.004)
    write(root, "constant/kinematicCloudPositions", "vectorField", positions(pts))


# ----- shearLift -----------------------------------------------------------------------------

SAFFMAN_MEI = "SaffmanMeiLiftForce\n{\n    U   U.water;\n}"
TOMIYAMA = "TomiyamaLift\n{\n    U     U.water;\n    sigma 0.07;\n}"

# Holds the water's mean vertical velocity at (nearly) 0 in the periodic column: the periodic
# pressure cannot carry the water's weight (both programs put g into the fluid's momentum), so
# a uniform pressure gradient G (its weight plus the bead's share) is raised each step instead.
# fsim refuses a zero Ubar (it names the driven axis), hence 1e-12 m/s. DPMFoam v1912 reads no
# fvOptions, so its water falls freely: the periodic column runs under fsim alone (its drift
# 1.3003 mm/s at 320 mm, against 1.3007 mm/s in the closed column the case uses).
MEAN_VELOCITY_FORCE = """
hydrostatic
{
    type            meanVelocityForce;
    active          yes;
    selectionMode   all;
    fields          (U.water);
    Ubar            (0 0 1e-12);
    relaxation      1;
}
"""


def shear_patches(periodic):
    """Sliding walls in x, symmetry planes in y; in z cyclic (periodic) or closed walls."""
    if periodic:
        ends = [("top", "cyclic", ["z+"], "        neighbourPatch bottom;\n"),
                ("bottom", "cyclic", ["z-"], "        neighbourPatch top;\n")]
    else:
        ends = [("top", "wall", ["z+"], ""), ("bottom", "wall", ["z-"], "")]
    return ends + [("left", "wall", ["x-"], ""), ("right", "wall", ["x+"], ""),
                   ("frontAndBack", "symmetry", ["y-", "y+"], "")]


def shear_lift(repo, name="shearLift", gamma=10.0, lift=SAFFMAN_MEI,
               start=(0.006, 0.010, 0.178), end=1.2, dt=5e-4, width=16, length=320,
               periodic=False):
    """A bead settling in u_z = gamma (x - width/2) between the walls x = 0 and width (mm),
    which slide at -/+ gamma width/2; symmetry planes in y. With `periodic` the column is
    cyclic in z (`length` mm) and `meanVelocityForce` holds the water's mean u_z at 0 against
    its weight (under fsim only: DPMFoam v1912 reads no fvOptions): the Couette profile is then
    an exact steady flow, and the only disturbance is the bead's own. Without it the column is
    closed above and below, and the closed ends turn the flow round: a secondary flow of
    2-3 cm/s next to them, which spreads along the column; in 192 mm it reached the bead within
    1 s, in 320 mm (the bead in the middle) it stays out of the 0.2-1.2 s window."""
    root = os.path.join(repo, "tutorials", name)
    size, cells = (width, 16, length), (width // 4, 4, length // 4)
    mid = width / 2000
    constant(root, *WATER)
    system(root)
    uw = gamma * mid
    ends = ("periodic in z, the water's mean u_z held at 0 by meanVelocityForce" if periodic
            else "closed above and below")
    write(root, "system/controlDict", "dictionary", control(
        end, dt, 0.02,
        f"One bead (d = 1 mm, rho_p = 1100) settling in water in a vertical linear shear flow, "
        f"u_z = {gamma:g} (x - {width / 2:g} mm) 1/s,\n// between two walls sliding at "
        f"-/+{uw:g} m/s ({width} x 16 x {length} mm, 4 mm cells, {ends}):\n// sphereDrag, "
        "lift and gravity. The lift drives it across the stream lines (+x). Runs under "
        "DPMFoam and\n// fsimFoam alike (tools/crosscheck)."))
    write(root, "system/blockMeshDict", "dictionary",
          block_mesh(size, cells, shear_patches(periodic)))
    end_cond = CYCLIC if periodic else NO_SLIP
    fields(root, "water", [("top", end_cond), ("bottom", end_cond),
                           ("left", (f"type            fixedValue;\nvalue           uniform "
                                     f"(0 0 {-uw:g});", FIXED_FLUX)),
                           ("right", (f"type            fixedValue;\nvalue           uniform "
                                      f"(0 0 {uw:g});", FIXED_FLUX)),
                           ("frontAndBack", SYMMETRY)])
    fv_options = os.path.join(root, "system", "fvOptions")
    if periodic:
        write(root, "system/fvOptions", "dictionary", MEAN_VELOCITY_FORCE)
    elif os.path.exists(fv_options):
        os.remove(fv_options)
    # the Couette profile from the start (its diffusion time L^2/nu is 256 s): cells x fastest
    h = 0.004
    values = []
    for k in range(cells[2]):
        for j in range(cells[1]):
            for i in range(cells[0]):
                values.append(f"(0 0 {gamma * ((i + 0.5) * h - mid):.6g})")
    path = os.path.join(root, "0", "U.water")
    text = open(path).read()
    uniform = "internalField   uniform (0 0 0);"
    assert uniform in text
    text = text.replace(uniform, "internalField   nonuniform List<vector> \n"
                        f"{len(values)}\n(\n" + "\n".join(values) + "\n)\n;")
    with open(path, "w") as f:
        f.write(text)
    u0 = gamma * (start[0] - mid) - 0.0236     # the fluid's velocity less the slip
    patches = ["left", "right", "frontAndBack"] + ([] if periodic else ["top", "bottom"])
    cloud = cloud_properties("water", 1100, "1e8", "cellPoint", f"sphereDrag;\n{lift}\ngravity;",
                             manual_injection("model1", 0.001, u0=f"0 0 {u0:.6g}"),
                             local_interaction(patches), NO_COLLISIONS)
    write(root, "constant/kinematicCloudProperties", "dictionary",
          with_interpolation(cloud, [("curlUcDt", "cellPoint")]))
    write(root, "constant/kinematicCloudPositions", "vectorField", positions([start]))


if __name__ == "__main__":
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    settling_added_mass(repo)
    liquid_fluidized_bed(repo)
    shear_lift(repo)
    shear_lift(repo, "shearLiftTomiyama", lift=TOMIYAMA)
    non_sphere_settling(repo)
    print("wrote tutorials/settlingAddedMass, liquidFluidizedBed, shearLift, shearLiftTomiyama, "
          "nonSphereSettling")
