"""References that `tools/study` compares a study's results with, keyed by tutorial name.

A reference is repository code: study never runs code from a case directory. Each entry of
REFERENCES gives, for one tutorial,

- `values(case) -> {name: value}`: the reference values of one point, computed from that
  point's own dictionaries (so a sweep over `nu` or `phi` gets each point's own reference);
- `measure(case) -> {name: value}` (optional): quantities measured from the point's output
  that are not a monitor's final or mean value (a fitted decay rate, a velocity along
  gravity); they become the table's `measured.<name>` columns;
- `compare`: the default pairs `table column -> reference name`; each pair gives the table's
  `reference.<name>` and `error.<column>` = |column - reference| / |reference|.

A study picks the entry with `--reference NAME` (default: the tutorial folder's name) and may
add or replace pairs with `--compare COLUMN=NAME` or the `[compare]` table of its TOML file
(docs/user-guide/studies.md). A function returns NaN where its reference does not apply.
"""
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

import foam_dict
import hindered_settling

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


@dataclass
class Reference:
    values: Callable[[Path], dict]
    compare: dict = field(default_factory=dict)
    measure: Optional[Callable[[Path], dict]] = None
    about: str = ""


# ----- reading a case's dictionaries -------------------------------------------------------

def text(case, file):
    return (Path(case) / file).read_text()


def scalar(case, file, path):
    """The number of entry `path` (`a/b/c`) of `file`, a dimensioned `[..] v` value too."""
    value = foam_dict.get_entry(text(case, file), path)
    numbers = re.findall(NUMBER, re.sub(r"\[[^\]]*\]", " ", value))
    if not numbers:
        raise ValueError(f"{file}: entry {path!r} = {value!r} is not a number")
    return float(numbers[-1])


def vector(case, file, path):
    value = foam_dict.get_entry(text(case, file), path)
    numbers = re.findall(NUMBER, re.sub(r"\[[^\]]*\]", " ", value))
    if len(numbers) < 3:
        raise ValueError(f"{file}: entry {path!r} = {value!r} is not a vector")
    return tuple(float(v) for v in numbers[-3:])


def fluid_density(case):
    """rho.<continuousPhase> (or rho) of constant/transportProperties; 1 when absent (the
    kinematic form)."""
    body = text(case, "constant/transportProperties")
    try:
        phase = foam_dict.get_entry(body, "continuousPhase")
        return scalar(case, "constant/transportProperties", f"rho.{phase}")
    except KeyError:
        try:
            return scalar(case, "constant/transportProperties", "rho")
        except KeyError:
            return 1.0


def fixed_diameter(case):
    """The diameter of constant/kinematicCloudProperties' fixedValue size distribution."""
    found = re.search(rf"fixedValueDistribution\s*\{{\s*value\s+({NUMBER})",
                      text(case, "constant/kinematicCloudProperties"))
    if not found:
        raise ValueError("constant/kinematicCloudProperties: no fixedValueDistribution value")
    return float(found.group(1))


def block_extent(case):
    """The (x, y, z) extent of system/blockMeshDict's vertices, scaled (convertToMeters or
    scale), in metres."""
    body = foam_dict.body(text(case, "system/blockMeshDict"))
    body = re.sub(r"//[^\n]*|/\*.*?\*/", " ", body, flags=re.S)
    scale = 1.0
    for key in ("convertToMeters", "scale"):
        found = re.search(rf"^\s*{key}\s+({NUMBER})\s*;", body, re.M)
        if found:
            scale = float(found.group(1))
    vertices = re.search(r"vertices\s*\((.*?)\)\s*;", body, re.S)
    points = [[float(v) for v in re.findall(NUMBER, p)]
              for p in re.findall(r"\(([^()]*)\)", vertices.group(1))]
    return tuple(scale * (max(p[k] for p in points) - min(p[k] for p in points))
                 for k in range(3))


def monitor(case, name):
    """{column: [values]} of postProcessing/<name>/<start>/<name>.dat (start times joined)."""
    base = Path(case) / "postProcessing" / name
    columns, rows = None, []
    for start in sorted((p for p in base.iterdir() if p.is_dir()),
                        key=lambda p: float(p.name)):
        for line in (start / f"{name}.dat").read_text().splitlines():
            if line.startswith("#"):
                columns = columns or line.lstrip("#").split()
            elif line.strip():
                rows.append([float(v) for v in line.split()])
    return {c: [r[k] for r in rows] for k, c in enumerate(columns)}


# ----- references --------------------------------------------------------------------------

def sangani_acrivos(phi):
    """K of the simple cubic array of spheres at solid fraction phi (paper eq. 17, Sangani &
    Acrivos 1982; within 0.15 % of Zick & Homsy's exact values up to phi = 0.125)."""
    if not 0 < phi < math.pi / 6:
        return math.nan
    c = phi ** (1 / 3)
    return 1 / (1 - 1.7601 * c + phi - 1.5593 * phi ** 2 + 3.9799 * phi ** (8 / 3)
                - 3.0734 * phi ** (10 / 3))


# Zick & Homsy (J. Fluid Mech. 115, 13-26, 1982), Table 2, simple cubic array: the exact
# (converged multipole) K at these phi, as printed (close packing pi/6 printed as 0.5236).
# The same numbers as tests/support/porous_reference.rs.
ZICK_HOMSY_SIMPLE_CUBIC = [
    (0.027, 2.008),
    (0.064, 2.810),
    (0.125, 4.292),
    (0.216, 7.442),
    (0.343, 15.4),
    (0.45, 28.1),
    (0.5236, 42.1),
]


def exact_simple_cubic(phi):
    """The exact K of the simple cubic array: Zick & Homsy's table at its phi (to its printed
    digits: 4 significant figures, 3 at phi >= 0.343), Sangani & Acrivos (eq. 17) elsewhere up
    to phi = 0.125 (within 0.15 % of the table there), beyond it the table interpolated
    linearly in ln K (as tests/support/porous_reference.rs)."""
    if not 0 < phi <= math.pi / 6 + 1e-9:
        return math.nan
    for p, k in ZICK_HOMSY_SIMPLE_CUBIC:
        if abs(phi - p) < 1e-12:
            return k
    if phi <= 0.125:
        return sangani_acrivos(phi)
    t = ZICK_HOMSY_SIMPLE_CUBIC
    for (p0, k0), (p1, k1) in zip(t, t[1:]):
        if phi <= p1:
            s = (phi - p0) / (p1 - p0)
            return math.exp(math.log(k0) + s * (math.log(k1) - math.log(k0)))
    return t[-1][1]


def ergun_eq18(phi):
    """The paper's eq. 18 (Wen & Yu below phi = 0.2, Ergun above, at Re << 1) per particle, as
    docs/numerics.md reads the garbled copy of the paper (which prints phi where the fluid
    fraction 1 - phi belongs): (1 - phi)^-4.7 below 0.2, (25/3) phi / (1 - phi)^3 above."""
    if not 0 < phi < 1:
        return math.nan
    eps = 1 - phi
    return eps ** -4.7 if phi < 0.2 else 25 / 3 * phi / eps ** 3


def schiller_naumann_terminal(drive, rho, d, mu):
    """The velocity u at which u (1 + 0.15 Re^0.687), Re = rho u d / mu, equals `drive` (the
    Stokes velocity): the terminal velocity under Schiller-Naumann drag (bisection)."""
    lo, hi = 0.0, drive
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid * (1 + 0.15 * (rho * mid * d / mu) ** 0.687) < drive:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def taylor_green(case):
    """E(T) = E0 exp(-4 nu T) at T = endTime, E0 = 1/4 (unit amplitude); the decay rate 4 nu."""
    nu = scalar(case, "constant/transportProperties", "nu")
    end = scalar(case, "system/controlDict", "endTime")
    return {"kineticEnergy": 0.25 * math.exp(-4 * nu * end), "decayRate": 4 * nu}


def taylor_green_measure(case):
    """The energy's decay rate: least-squares slope of -ln E against t over every step."""
    m = monitor(case, "fluid")
    t, e = m["Time"], [math.log(v) for v in m["kineticEnergy"]]
    n = len(t)
    if n < 2:
        return {"decayRate": math.nan}
    tm, em = sum(t) / n, sum(e) / n
    slope = (sum((a - tm) * (b - em) for a, b in zip(t, e))
             / sum((a - tm) ** 2 for a in t))
    return {"decayRate": -slope}


def channel(case):
    """Plane Poiseuille flow at bulk velocity U between walls H apart (along y): the driving
    kinematic pressure gradient 12 nu U / H^2."""
    nu = scalar(case, "constant/transportProperties", "nu")
    ubar = math.hypot(*vector(case, "system/fvOptions", "momentumSource/Ubar"))
    height = block_extent(case)[1]
    return {"drivingGradient": 12 * nu * ubar / height ** 2}


def porous_media(case):
    """K of the simple cubic array at the case's phi: exact (Zick & Homsy's table at its phi,
    else Sangani & Acrivos, see exact_simple_cubic), and Sangani & Acrivos' eq. 17 alone."""
    phi = scalar(case, "constant/porousParameters", "phi")
    return {"K": exact_simple_cubic(phi), "K_SA": sangani_acrivos(phi)}


def porous_media_measure(case):
    """K at steady state: the median of the direct monitor's K over the last fifth of the run
    (as the tutorial's plot.py). The final value is not used for it: the last steps are
    shortened onto endTime and K moves by up to 0.1 % on them (tutorials/porousMedia)."""
    m = monitor(case, "direct")
    t, k = m["Time"], m["K"]
    late = sorted(v for a, v in zip(t, k) if a >= 0.8 * t[-1])
    n = len(late)
    median = late[n // 2] if n % 2 else 0.5 * (late[n // 2 - 1] + late[n // 2])
    return {"K": median}


def porous_media_drag_law(case):
    """The porousMedia array under the drag-law model at h ~ 2r (its fluid fraction uniform):
    the closure's own K, the paper's eq. 18 at Re << 1 (K_eq18), beside the exact K and
    Sangani & Acrivos' eq. 17 (tools/figures/fig2_k_vs_phi_draglaw.toml)."""
    phi = scalar(case, "constant/porousParameters", "phi")
    return {"K_eq18": ergun_eq18(phi), "K": exact_simple_cubic(phi),
            "K_SA": sangani_acrivos(phi)}


def stokes_velocity(case):
    """U_Stokes = (rho_p - rho_f) |g| d^2 / (18 rho_f nu) of the case's fixed-size spheres."""
    rho_f = fluid_density(case)
    nu = scalar(case, "constant/transportProperties", "nu")
    rho_p = scalar(case, "constant/kinematicCloudProperties", "constantProperties/rho0")
    g = math.hypot(*vector(case, "constant/g", "value"))
    return (rho_p - rho_f) * g * fixed_diameter(case) ** 2 / (18 * rho_f * nu)


def settling_sphere(case):
    """One sphere in a periodic box settles as the simple cubic array of the same phi resists:
    v = U_Stokes / K(phi) (stokes_velocity)."""
    d = fixed_diameter(case)
    lx, ly, lz = block_extent(case)
    phi = math.pi * d ** 3 / 6 / (lx * ly * lz)
    stokes = stokes_velocity(case)
    return {"settlingVelocity": stokes / sangani_acrivos(phi), "stokesVelocity": stokes,
            "phi": phi}


def single_bead(case):
    """One bead under Schiller-Naumann drag and buoyant gravity: its terminal velocity."""
    rho_f = fluid_density(case)
    mu = rho_f * scalar(case, "constant/transportProperties", "nu")
    stokes = stokes_velocity(case)
    return {"settlingVelocity": schiller_naumann_terminal(stokes, rho_f, fixed_diameter(case),
                                                          mu)}


def velocity_along_gravity(case):
    """The mean particle velocity along gravity at the end (cloud monitor), positive falling."""
    g = vector(case, "constant/g", "value")
    norm = math.hypot(*g)
    m = monitor(case, "cloud")
    u = [m[c][-1] if m.get(c) else math.nan for c in ("Ux", "Uy", "Uz")]
    return {"settlingVelocity": sum(a * b for a, b in zip(u, g)) / norm}


def positions(case):
    """The bead centres of constant/kinematicCloudPositions, [(x, y, z)]."""
    body = foam_dict.body(text(case, "constant/kinematicCloudPositions"))
    body = re.sub(r"//[^\n]*|/\*.*?\*/", " ", body, flags=re.S)
    return [tuple(float(v) for v in re.findall(NUMBER, p))
            for p in re.findall(r"\(([^()]*)\)", body)]


def packed_bed(case):
    """Ergun's pressure drop across the bed (Ergun, Chem. Eng. Prog. 48, 89-94, 1952):
    dp = L [150 mu U phi^2 / (eps^3 d^2) + 1.75 rho phi U^2 / (eps^3 d)], eps = 1 - phi, with
    U the superficial velocity of the bottom inlet (0/U.water), L the bed's height (the
    beads' lowest to highest centre plus d), phi the beads' volume over the column's cross
    section times L (as tutorials/packedBed/plot.py)."""
    rho = fluid_density(case)
    mu = rho * scalar(case, "constant/transportProperties", "nu")
    d = fixed_diameter(case)
    beads = positions(case)
    phase = foam_dict.get_entry(text(case, "constant/transportProperties"), "continuousPhase")
    u = abs(vector(case, f"0/U.{phase}", "boundaryField/bottom/inletVelocity")[2])
    lx, ly, _ = block_extent(case)
    height = max(b[2] for b in beads) - min(b[2] for b in beads) + d
    phi = len(beads) * math.pi / 6 * d ** 3 / (lx * ly * height)
    eps = 1 - phi
    gradient = (150 * mu * u * phi ** 2 / (eps ** 3 * d ** 2)
                + 1.75 * rho * phi * u ** 2 / (eps ** 3 * d))
    return {"pressureDrop": gradient * height, "phi": phi}


def packed_bed_measure(case):
    """The pressure drop less the water's weight (dragLaw monitor), mean over the run's second
    half of steps (as tutorials/packedBed/plot.py): the bed oscillates on its contact springs
    at first."""
    drop = monitor(case, "dragLaw")["pressureDrop"]
    late = drop[len(drop) // 2:]
    return {"pressureDrop": sum(late) / len(late) if late else math.nan}


def fluidized_bed(case):
    """The buoyant weight of the beads per cross-section, which a fluidized bed's pressure
    drop carries: W / A = N (rho_p - rho_f) g V_p / A, V_p = pi d^3 / 6, N the beads of
    constant/kinematicCloudPositions, d the fixedValue diameter, rho_p = rho0, rho_f the
    continuous phase's rho, g = |constant/g| and A the block's extent across gravity (as
    tutorials/fluidizedBed/plot.py). The walls and the floor take part of the weight while
    the bed slugs: the tutorial run to 2 s averages 0.944 W / A over 0.1-2 s (0.948 over
    1-2 s; the drag on the beads 0.96 W, the drop measured between the first and the last
    cell layer 0.984 of the drag per area), so fsim's long-time mean stays some 5 % under
    W / A rather than converging to it."""
    rho_f = fluid_density(case)
    rho_p = scalar(case, "constant/kinematicCloudProperties", "constantProperties/rho0")
    g = vector(case, "constant/g", "value")
    d = fixed_diameter(case)
    beads = len(positions(case))
    extent = block_extent(case)
    axis = max(range(3), key=lambda k: abs(g[k]))
    area = math.prod(extent[k] for k in range(3) if k != axis)
    weight = beads * (rho_p - rho_f) * math.hypot(*g) * math.pi / 6 * d ** 3
    return {"pressureDrop": weight / area, "buoyantWeight": weight, "beads": beads}


def fluidized_bed_measure(case):
    """The dragLaw monitor's pressure drop less the gas's weight (`pressureDrop`, between the
    first and the last cell layer, as tutorials/fluidizedBed/plot.py reads it), and the drag
    on the beads against gravity per cross-section (`dragPerArea`), both the mean over the
    second half of the run in time (t > endTime / 2: 0.1-0.2 s for the tutorial's 0.2 s,
    plot.py's window; the bed collapses and lifts its first slug before)."""
    m = monitor(case, "dragLaw")
    t = m["Time"]
    if not t:
        return {"pressureDrop": math.nan, "dragPerArea": math.nan}
    g = vector(case, "constant/g", "value")
    axis = max(range(3), key=lambda k: abs(g[k]))
    up = -math.copysign(1.0, g[axis])
    extent = block_extent(case)
    area = math.prod(extent[k] for k in range(3) if k != axis)
    late = [k for k, s in enumerate(t) if s > t[-1] / 2]
    drag = m["FdParticles" + "XYZ"[axis]]
    return {"pressureDrop": sum(m["pressureDrop"][k] for k in late) / len(late),
            "dragPerArea": up * sum(drag[k] for k in late) / len(late) / area}


def suspension_fraction(case):
    """The solid fraction of the case's spheres in its block: N pi d^3 / 6 / V, N the
    positions file's count, or for fsim's randomPacking (filling the whole block) the
    nearest whole count to its volumeFraction, as the packing rounds it."""
    lx, ly, lz = block_extent(case)
    particle = math.pi / 6 * fixed_diameter(case) ** 3
    spheres = foam_dict.get_entry(text(case, "constant/kinematicCloudProperties"),
                                  "subModels/injectionModels/spheres/type")
    if spheres.strip() == "randomPacking":
        target = scalar(case, "constant/kinematicCloudProperties",
                        "subModels/injectionModels/spheres/volumeFraction")
        return round(target * lx * ly * lz / particle) * particle / (lx * ly * lz)
    return len(positions(case)) * particle / (lx * ly * lz)


def sedimentation(case):
    """A random suspension in a periodic box: the unbounded hard-sphere suspension's
    v/U_Stokes (Abade et al. 2012, tools/hindered_settling.py) and Richardson & Zaki's
    (1 - phi)^4.65 (paper eq. 21, Re < 0.2) at the case's phi (suspension_fraction). A box
    of N spheres settles slower than the unbounded suspension (the images' hindrance, about
    1.76 (phi/N)^(1/3) of U_Stokes, Hasimoto 1959)."""
    phi = suspension_fraction(case)
    return {"hardSpheres": hindered_settling.hard_spheres(phi),
            "richardsonZaki": hindered_settling.richardson_zaki(phi), "phi": phi}


def sedimentation_measure(case):
    """phi, and v_m / U_Stokes: the suspension's mean settling velocity in the frame of zero
    volume flux, v_m = (1 - phi) v_p - <eps u> along gravity, averaged over the second half of
    the run. The direct model reports it (the sedimentation monitor's settlingVelocity, every
    step); for the drag-law model it is computed at the write times of the second half from
    fluid.vti (eps, u) and particles.vtu (v_p), which needs pyvista."""
    stokes = stokes_velocity(case)
    if (Path(case) / "postProcessing" / "sedimentation").is_dir():
        m = monitor(case, "sedimentation")
        t, v = m["Time"], m["settlingVelocity"]
        late = [b for a, b in zip(t, v) if a >= 0.5 * t[-1]]
        return {"phi": m["phi"][0], "settlingRatio": sum(late) / len(late) / stokes}
    import numpy as np
    import pyvista as pv
    g = np.array(vector(case, "constant/g", "value"))
    down = g / np.linalg.norm(g)
    times = sorted((float(p.name), p) for p in Path(case).iterdir()
                   if p.is_dir() and re.fullmatch(NUMBER, p.name)
                   and (p / "particles.vtu").is_file())
    phi, late = math.nan, []
    for t, folder in times:
        fluid = pv.read(folder / "fluid.vti")
        eps = np.asarray(fluid.cell_data["alpha"])
        u = np.asarray(fluid.cell_data["U"]) @ down
        v = np.asarray(pv.read(folder / "particles.vtu").point_data["U"]) @ down
        phi = 1 - eps.mean() if math.isnan(phi) else phi
        if t >= 0.5 * times[-1][0] and t > 0:
            late.append((1 - phi) * v.mean() - (eps * u).mean())
    return {"phi": float(phi), "settlingRatio": float(sum(late) / len(late) / stokes)}


REFERENCES = {
    "taylorGreen": Reference(
        taylor_green, measure=taylor_green_measure,
        compare={"fluid.kineticEnergy.final": "kineticEnergy",
                 "measured.decayRate": "decayRate"},
        about="the exact decaying vortex: E(endTime) and the decay rate 4 nu"),
    "channel": Reference(
        channel, compare={"fluid.drivingGradient.final": "drivingGradient"},
        about="plane Poiseuille flow: the driving gradient 12 nu U / H^2"),
    "porousMedia": Reference(
        porous_media, measure=porous_media_measure,
        compare={"measured.K": "K", "direct.K.final": "K"},
        about="simple cubic array: the exact K (Zick & Homsy's table; Sangani & Acrivos, "
              "paper eq. 17, between its points up to phi = 0.125)"),
    "porousMediaDragLaw": Reference(
        porous_media_drag_law, compare={"dragLaw.K.final": "K_eq18"},
        about="the simple cubic array under the drag-law model at h ~ 2r: the closure's K, "
              "paper eq. 18 at Re << 1 (Wen & Yu below phi = 0.2, Ergun above)"),
    "settlingSphere": Reference(
        settling_sphere, compare={"sedimentation.settlingVelocity.final": "settlingVelocity"},
        about="a sphere in a periodic box: U_Stokes / K(phi) (Sangani & Acrivos)"),
    "settlingInLiquid": Reference(
        single_bead, measure=velocity_along_gravity,
        compare={"measured.settlingVelocity": "settlingVelocity"},
        about="one bead: the Schiller-Naumann terminal velocity"),
    "packedBed": Reference(
        packed_bed, measure=packed_bed_measure,
        compare={"measured.pressureDrop": "pressureDrop"},
        about="a fixed bed: Ergun's pressure drop (Ergun 1952), the monitor's mean over the "
              "second half of the run"),
    "sedimentation": Reference(
        sedimentation, measure=sedimentation_measure,
        compare={"measured.settlingRatio": "hardSpheres"},
        about="a random suspension: v_m / U_Stokes against the unbounded random hard-sphere "
              "suspension (Abade et al. 2012); a periodic box of N spheres hinders more"),
    "fluidizedBed": Reference(
        fluidized_bed, measure=fluidized_bed_measure,
        compare={"measured.pressureDrop": "pressureDrop"},
        about="a fluidized bed: the beads' buoyant weight per cross-section W / A, against "
              "the monitor's mean drop over the second half of the run"),
}
