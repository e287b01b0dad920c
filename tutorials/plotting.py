"""What the tutorials' plot.py scripts share: reading a case (its dictionaries' entries, its time
directories, its postProcessing monitors), pyvista's off-screen pictures, the axes' finish,
the references more than one tutorial draws and the whole of what impacts and impactsDamped,
and shearLift and shearLiftTomiyama, draw.

A plot.py, run from any folder, finds this file in the parent of its own:

    case = Path(__file__).resolve().parent
    sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
"""
import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv
from vtkmodules.vtkCommonCore import vtkLogger

NUMBER = r"[0-9.eE+-]+"


# --- the case --------------------------------------------------------------------------------

def entry(case, file, pattern):
    """The number that `pattern`'s group matches first in the case's `file` (^ at each line)."""
    return float(re.search(pattern, (Path(case) / file).read_text(), re.M).group(1))


def keyword(case, file, key):
    """The value of the entry `key value;` (or `key [dimensions] value;`) in the case's `file`;
    `key` is a regular expression, as rho\\.\\w+ for the phase's density."""
    return entry(case, file, rf"^\s*{key}\s+(?:\[[^\]]*\]\s*)?({NUMBER})\s*;")


def vector(case, file, pattern):
    """The vector `(x y z)` that follows `pattern` first in the case's `file`, as three floats."""
    three = r"\s+".join([f"({NUMBER})"] * 3)
    found = re.search(rf"{pattern}\s*\(\s*{three}\s*\)", (Path(case) / file).read_text(), re.M)
    return tuple(float(value) for value in found.groups())


def properties(case):
    """The fluid's density rho.<phase> and kinematic viscosity nu (constant/transportProperties),
    the particles' density rho0 (constant/kinematicCloudProperties) and gravity (constant/g, a
    vector): rho_f, nu, rho_p, g."""
    return (keyword(case, "constant/transportProperties", r"rho\.\w+"),
            keyword(case, "constant/transportProperties", "nu"),
            keyword(case, "constant/kinematicCloudProperties", "rho0"),
            vector(case, "constant/g", "value"))


def inlet_velocity(case):
    """The inletVelocity of the patch `bottom` in the case's 0/U.<phase>, as three floats."""
    return vector(case, next(Path(case).glob("0/U.*")),
                  r"bottom\s*\{[^}]*inletVelocity\s+uniform")


def time_directories(case):
    """The case's time directories, 0 with them, as (time, folder) pairs in time order."""
    return sorted((float(p.name), p) for p in Path(case).iterdir()
                  if p.is_dir() and re.fullmatch(NUMBER, p.name))


def monitor(case, name):
    """The monitor postProcessing/<name>/0/<name>.dat as its columns, by their header's names."""
    path = Path(case) / "postProcessing" / name / "0" / f"{name}.dat"
    columns = path.read_text().splitlines()[0].lstrip("#").split()
    data = np.loadtxt(path, comments="#", ndmin=2)
    return {column: data[:, k] for k, column in enumerate(columns)}


# --- references ------------------------------------------------------------------------------

def root(f, lo, hi):
    """Bisection: f(lo) < 0 < f(hi)."""
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def schiller_naumann(drive, rho, d, mu, hi):
    """The velocity u, in 0..hi, at which a sphere of diameter d under Schiller-Naumann drag,
    u (1 + 0.15 Re^0.687) with Re = rho u d / mu, balances `drive` (a Stokes velocity)."""
    return root(lambda u: u * (1 + 0.15 * (rho * u * d / mu) ** 0.687) - drive, 0, hi)


def sangani_acrivos(phi):
    """Paper eq. 17 (Sangani & Acrivos 1982, simple cubic array)."""
    c = phi ** (1 / 3)
    return 1 / (1 - 1.7601 * c + phi - 1.5593 * phi ** 2 + 3.9799 * phi ** (8 / 3)
                - 3.0734 * phi ** (10 / 3))


# --- pictures --------------------------------------------------------------------------------

def offscreen_plotter(window_size):
    """A pyvista plotter that draws off the screen on white, without VTK's notes about a missing
    X server."""
    pv.OFF_SCREEN = True
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    plotter = pv.Plotter(off_screen=True, window_size=window_size)
    plotter.set_background("white")
    return plotter


def screenshot(plotter, crop=False):
    """The plotter's picture as an RGB array, the plotter closed; with crop, without its white
    margins."""
    image = plotter.screenshot(return_img=True)
    plotter.close()
    if crop:
        rows = np.where((image < 250).any(axis=(1, 2)))[0]
        cols = np.where((image < 250).any(axis=(0, 2)))[0]
        image = image[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]
    return image


def spheres_over_slice(fluid, centres, d, window_size, resolution, scale=1, **style):
    """The spheres of diameter d at `centres` in the box of `fluid` (a pyvista grid), over the
    vertical fluid velocity u_y (times `scale`) on the box's mid-plane z in coolwarm, seen from
    the front, the right and above, its white margins cropped; and the largest |u_y|, the colour
    scale's limit. `style` goes to the spheres' add_mesh."""
    plane = fluid.cell_data_to_point_data().slice(normal="z", origin=fluid.center)
    plane.point_data["U_y"] = scale * plane.point_data["U"][:, 1]
    limit = float(np.abs(plane.point_data["U_y"]).max())
    spheres = pv.PolyData(np.asarray(centres)).glyph(
        geom=pv.Sphere(radius=d / 2, theta_resolution=resolution, phi_resolution=resolution),
        orient=False, scale=False)
    plotter = offscreen_plotter(window_size)
    plotter.add_mesh(plane, scalars="U_y", cmap="coolwarm", clim=(-limit, limit),
                     show_scalar_bar=False)
    plotter.add_mesh(spheres, color="#d9a441", smooth_shading=True, **style)
    plotter.add_mesh(pv.Box(fluid.bounds).outline(), color="black", line_width=2)
    plotter.view_vector((0.55, 0.35, 1.0), viewup=(0.0, 1.0, 0.0))
    plotter.reset_camera(bounds=fluid.bounds)
    plotter.camera.zoom(1.2)
    return screenshot(plotter, crop=True), limit


def picture_beside_plot(image, limit, title, label, figsize, widths):
    """A figure of a picture from spheres_over_slice (titled, size 10) and its colour bar of u_y
    over -limit..limit (labelled `label`), beside axes for a plot, which it returns with the
    figure; `widths` are the picture's and the plot's."""
    fig = plt.figure(figsize=figsize, constrained_layout=True)
    grid = fig.add_gridspec(1, 4, width_ratios=[widths[0], 0.04, 0.06, widths[1]])
    show(fig.add_subplot(grid[0]), image, title, fontsize=10)
    left_colorbar(fig, fig.add_subplot(grid[1]), -limit, limit, "coolwarm", label)
    return fig, fig.add_subplot(grid[3])


def show(ax, image, title, **title_style):
    """A rendered picture on the axes `ax`, without axes, under `title`."""
    ax.imshow(image)
    ax.set_axis_off()
    ax.set_title(title, **title_style)


def left_colorbar(fig, cax, lo, hi, cmap, label):
    """A colour bar of `cmap` over lo..hi in the axes `cax`, its ticks and label on the left (of
    a picture drawn by pyvista)."""
    bar = fig.colorbar(plt.cm.ScalarMappable(plt.Normalize(lo, hi), cmap), cax=cax, label=label)
    bar.ax.yaxis.set_ticks_position("left")
    bar.ax.yaxis.set_label_position("left")
    return bar


def field_axes(fig, ax, image, xlabel, ylabel, title, label, **colorbar):
    """Axes that show a field in a plane: equal scales, the labels, the title (size 10) and the
    colour bar of `image` (the field's pcolormesh), labelled `label`."""
    ax.set_aspect("equal")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    fig.colorbar(image, ax=ax, label=label, **colorbar)


def finish(ax, xlabel, ylabel, title=None, legend=None, fontsize=10):
    """The axes' labels, their title (at `fontsize`), a light grid and, when `legend` is True or
    holds ax.legend's keywords, the legend."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title is not None:
        ax.set_title(title, fontsize=fontsize)
    ax.grid(alpha=0.3)
    if legend is True:
        ax.legend()
    elif legend:
        ax.legend(**legend)


def settling_references(ax, isolated, particle, hindered, label, top, ylabel, title):
    """Finishes axes of a settling velocity against t (s) with the references of the paper's
    section 3.3 benchmark: an isolated `particle`'s terminal velocity (Schiller-Naumann, dashed
    red) and a hindered one, `hindered` (dashed green, labelled `label`); y from 0 to `top` times
    the isolated velocity, the legend at the lower right."""
    ax.axhline(isolated, color="tab:red", ls="--",
               label=f"isolated {particle} (Schiller-Naumann), {isolated:.3f} m/s")
    ax.axhline(hindered, color="tab:green", ls="--", label=label)
    ax.set_ylim(0, top * isolated)
    finish(ax, "t (s)", ylabel, title, legend=dict(loc="lower right", fontsize=9))


# --- impacts and impactsDamped -----------------------------------------------------------------

def coefficient(case, model, key):
    """`key` of the sub-dictionary <model>Coeffs in the case's kinematicCloudProperties."""
    text = (Path(case) / "constant/kinematicCloudProperties").read_text()
    block = re.search(rf"{model}Coeffs\s*\{{([^}}]*)\}}", text).group(1)
    return float(re.search(rf"^\s*{key}\s+({NUMBER})\s*;", block, re.M).group(1))


def restitution(alpha, h=2e-4):
    """e of x'' = -x^1.5 - alpha x^0.25 x' from x = 0, x' = 1 (RK4, the exit interpolated)."""
    def f(x, v):
        return -max(x, 0.0) ** 1.5 - alpha * max(x, 0.0) ** 0.25 * v
    x, v = 0.0, 1.0
    while True:
        k1x, k1v = v, f(x, v)
        k2x, k2v = v + h / 2 * k1v, f(x + h / 2 * k1x, v + h / 2 * k1v)
        k3x, k3v = v + h / 2 * k2v, f(x + h / 2 * k2x, v + h / 2 * k2v)
        k4x, k4v = v + h * k3v, f(x + h * k3x, v + h * k3v)
        xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if xn < 0:
            return -(v + x / (x - xn) * (vn - v))
        x, v = xn, vn


def impacts(case):
    """The post-processing of tutorials/impacts and impactsDamped (tools/make_impacts_crosscheck.py
    writes both): restitution, tangential velocity and spin after each impact, against theory.

    Restitution: the contact's normal equation m x'' = -k x^1.5 - alpha sqrt(m k) x^0.25 x'
    (DPMFoam's pairSpringSliderDashpot and wallSpringSliderDashpot) scales to x'' = -x^1.5 -
    alpha x^0.25 x', so its restitution e depends on alpha alone; it has no closed form, and
    restitution() integrates it (RK4). Oblique impacts: a rigid-body impact with normal impulse
    J_n = m* (1 + e) v_n gives a tangential impulse of at most Coulomb's mu J_n, and at most what
    stops the slip (the bead then leaves rolling: 5/7 of its tangential velocity against a
    wall). Beads (ids as the injectors list them): 0 -> 3 head-on, 1 -> 4 at 45 deg, 2 normal on
    the wall x = 48 mm, 5 at 45 deg on it. Prints each quantity and draws <case>.png."""
    case = Path(case)
    alpha_pair, mu_pair = coefficient(case, "pairSpringSliderDashpot", "alpha"), \
        coefficient(case, "pairSpringSliderDashpot", "mu")
    alpha_wall, mu_wall = coefficient(case, "wallSpringSliderDashpot", "alpha"), \
        coefficient(case, "wallSpringSliderDashpot", "mu")

    t, x, u, w = [], [], [], []
    for time, folder in time_directories(case):
        beads = pv.read(folder / "particles.vtu")
        order = np.argsort(beads.point_data["id"])
        t.append(time)
        x.append(np.asarray(beads.points)[order])
        u.append(np.asarray(beads.point_data["U"])[order])
        w.append(np.asarray(beads.point_data["omega"])[order])
        d = float(beads.point_data["d"][0])
    t, x, u, w = map(np.array, (t, x, u, w))
    r = d / 2

    # before (t = 0) and after (the last time) every impact
    e_pair = -(u[-1, 3, 0] - u[-1, 0, 0]) / (u[0, 3, 0] - u[0, 0, 0])
    e_wall = -u[-1, 2, 0] / u[0, 2, 0]
    e_wall45 = -u[-1, 5, 0] / u[0, 5, 0]
    vn, vt = u[0, 5, 0], u[0, 5, 1]                       # the 45 deg wall impact
    wall_coulomb = (vt - mu_wall * (1 + e_wall45) * vn,
                    -mu_wall * (1 + e_wall45) * vn / (0.4 * r))
    wall_rolling = (5 / 7 * vt, -5 / 7 * vt / r)
    # the 45 deg pair: its normal and slip directions
    n, s = np.array([1, 1]) / np.sqrt(2), np.array([1, -1]) / np.sqrt(2)
    vn_pair = u[0, 1, :2] @ n
    us_pair = u[0, 1, :2] @ s
    normal = (1 + e_pair) / 2 * vn_pair * n

    def pair(jt):
        """The 45 deg target's (U_x, U_y, omega_z) for a tangential impulse per mass jt."""
        target = normal + jt * s
        return target[0], target[1], jt / (0.4 * r)

    pair_coulomb = pair(mu_pair * (1 + e_pair) / 2 * vn_pair)
    pair_rolling = pair(us_pair / 7)

    e_pair_theory, e_wall_theory = restitution(alpha_pair), restitution(alpha_wall)
    print(f"Impacts: {x.shape[1]} beads of d = {1e3 * d:g} mm at 1 m/s; pair alpha "
          f"{alpha_pair:g}, mu {mu_pair:g}; wall alpha {alpha_wall:g}, mu {mu_wall:g}")
    rows = [
        ("pair head-on: restitution", e_pair, e_pair_theory, None),
        ("wall normal: restitution", e_wall, e_wall_theory, None),
        ("wall 45 deg: restitution", e_wall45, e_wall_theory, None),
        ("wall 45 deg: tangential velocity (m/s)", u[-1, 5, 1], wall_coulomb[0], wall_rolling[0]),
        ("wall 45 deg: spin (rad/s)", w[-1, 5, 2], wall_coulomb[1], wall_rolling[1]),
        ("pair 45 deg: target U.x (m/s)", u[-1, 4, 0], pair_coulomb[0], pair_rolling[0]),
        ("pair 45 deg: target U.y (m/s)", u[-1, 4, 1], pair_coulomb[1], pair_rolling[1]),
        ("pair 45 deg: spin (rad/s)", w[-1, 4, 2], pair_coulomb[2], pair_rolling[2]),
    ]
    for name, value, first, second in rows:
        if second is None:
            print(f"{name}: {value:.6g}; e(alpha) of the contact's equation {first:.6g} "
                  f"({100 * (value / first - 1):+.2f} %)")
        else:
            print(f"{name}: {value:.6g}; Coulomb's mu J_n {first:.6g}, rolling {second:.6g}")
    impulse = w[-1, 5, 2] / wall_coulomb[1]
    rolling = abs(u[-1, 5, 1] + r * w[-1, 5, 2]) < 1e-3   # the contact point at rest
    print(f"wall 45 deg: tangential impulse {impulse:.3f} mu J_n "
          f"({'the slip stopped: rolling' if rolling else 'sliding'})")

    fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
    labels = ["0 head-on", "1 at 45°", "2 wall, normal", "3 target of 0", "4 target of 1",
              "5 wall, 45°"]
    for k, label in enumerate(labels):
        a.plot(1e3 * x[:, k, 0], 1e3 * x[:, k, 1], ".-", ms=3, lw=0.8, label=label)
        a.add_patch(plt.Circle(1e3 * x[0, k, :2], 1e3 * r, fill=False, color="0.4"))
    a.axvline(48, color="k", lw=3)
    a.set_aspect("equal")
    finish(a, "x (mm)", "y (mm)", f"the beads' paths, every {1e3 * (t[1] - t[0]):g} ms "
           "(circles: at t = 0)", legend=dict(fontsize=8, loc="upper center"))

    b.plot(1e3 * t, u[:, 3, 0] - u[:, 0, 0], label="pair head-on, $u_3 - u_0$")
    b.plot(1e3 * t, -u[:, 2, 0], "--", label="wall, normal, $-u_2$")
    b.plot(1e3 * t, -u[:, 5, 0], ":", lw=2, label="wall, 45°, $-u_5$")
    b.axhline(e_pair_theory, color="k", lw=0.8, ls="--",
              label=f"e(α = {alpha_pair:g}) = {e_pair_theory:.4f}")
    finish(b, "t (ms)", "normal velocity, approaching < 0 (m/s)",
           f"restitution: pair {e_pair:.4f}, wall {e_wall:.4f}", legend=dict(fontsize=9))

    c.plot(1e3 * t, u[:, 5, 1], label="wall 45°: bead's tangential velocity $v_y$")
    c.plot(1e3 * t, -r * w[:, 5, 2], label="wall 45°: its surface speed $-r\\omega_z$")
    c.axhline(wall_coulomb[0], color="tab:red", ls="--", lw=1,
              label=f"Coulomb (friction ≤ μ$J_n$): $v_y$ ≥ {wall_coulomb[0]:.3f}")
    c.axhline(wall_rolling[0], color="k", ls=":", lw=1.5,
              label=f"rolling: $v_y = r\\omega$ = {wall_rolling[0]:.3f}")
    c.set_ylim(0, 1.05)
    finish(c, "t (ms)", "m/s", f"friction at the wall: {impulse:.2f} μ$J_n$",
           legend=dict(fontsize=9, loc="lower left"))
    save(fig, case / f"{case.name}.png", dpi=100)


def shear_lift(case):
    """The post-processing of tutorials/shearLift and shearLiftTomiyama
    (tools/make_force_crosscheck.py writes both): the bead's x and U_x, fsim's and DPMFoam's
    (crosscheck_reference.csv), against the drift where drag balances the lift
    (tools/force_crosscheck_references.py: Saffman 1965 and Mei 1992, or Tomiyama's C_l, as
    DPMFoam v1912 writes them); draws <case>.png."""
    import sys
    sys.path.insert(0, str(Path(case).parent.parent / "tools"))
    from force_crosscheck_references import shear_lift as balance
    rho_f, nu, rho_p, g = properties(case)
    d = keyword(case, "constant/kinematicCloudProperties", "value")
    wall = vector(case, "0/U.water", r"right\s*\{[^}]*value\s+uniform")[2]
    mesh = (case / "system" / "blockMeshDict").read_text()
    scale = float(re.search(r"^scale\s+([0-9.eE+-]+);", mesh, re.M).group(1))
    width = scale * float(re.search(r"\(0 0 0\)\s*\(([0-9.]+) 0 0\)", mesh).group(1))
    gamma = wall / (width / 2)
    cloud = (case / "constant" / "kinematicCloudProperties").read_text()
    if "TomiyamaLift" in cloud:  # shearLiftTomiyama
        lift, label = "Tomiyama", "Tomiyama"
        sigma = keyword(case, "constant/kinematicCloudProperties", "sigma")
    else:
        lift, label, sigma = "SaffmanMei", "Saffman-Mei", 0.07
    drift, slip, cl = balance(gamma, d, rho_p, rho_f, nu, lift, sigma)
    x0 = vector(case, "constant/kinematicCloudPositions", r"^")[0]

    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
    t_line = np.linspace(0, 1.2, 50)  # the drift from the start
    a.plot(t_line, 1e3 * (x0 + drift * t_line), "k--", label=f"{label} by hand, {1e3 * drift:.3f} mm/s")
    b.axhline(1e3 * drift, color="k", ls="--", label=f"{label} by hand")
    dx = dpmfoam_reference(case, "particles.position.x.mean")
    du = dpmfoam_reference(case, "particles.U.x.mean")
    if dx is not None:
        a.plot(dx[0], 1e3 * dx[1], "o", ms=3, color="tab:blue", label="DPMFoam v1912")
        b.plot(du[0], 1e3 * du[1], "o-", ms=3, color="tab:blue", label="DPMFoam v1912")
    t, x = particle_history(case, "position", "x")
    if len(t):
        a.plot(t, 1e3 * x, "s", ms=2.5, color="tab:orange", label="fsim")
        b.plot(*particle_history(case, "U", "x") * np.array([[1], [1e3]]), "s--", ms=2.5,
               color="tab:orange", label="fsim")
        print(f"fsim: x moved {1e3 * (x[-1] - x0):.3f} mm in {t[-1]:g} s, hand "
              f"{1e3 * drift * t[-1]:.3f} mm")
    finish(a, "t (s)", "x (mm)", f"across the shear (gamma = {gamma:g} 1/s, Cl = {cl:.3f})",
           legend=dict(fontsize=9, loc="upper left"))
    finish(b, "t (s)", "$U_x$ (mm/s)", "lateral drift velocity", legend=dict(fontsize=9))
    save(fig, case / f"{case.name}.png", 100)


def save(fig, path, dpi):
    """Writes the figure to `path` and says so."""
    fig.savefig(path, dpi=dpi)
    print(f"wrote {Path(path).name}")


# --- the cross-check cases of issue 42 -------------------------------------------------------

def particle_history(case, field, component, how="mean"):
    """fsim's history of a particle field (`U` or `position`, component x, y or z; `how` mean
    or max over the particles) from the particles.vtu of each time directory: (t, values)."""
    k = "xyz".index(component)
    times, values = [], []
    for t, folder in time_directories(case):
        path = folder / "particles.vtu"
        if not path.is_file():
            continue
        cloud = pv.read(path)
        data = np.asarray(cloud.points if field == "position" else cloud.point_data[field])
        if len(data):
            times.append(t)
            values.append(getattr(np, how)(data[:, k]))
    return np.array(times), np.array(values)


def dpmfoam_reference(case, series):
    """DPMFoam's history of `series` (a tools/crosscheck series name) from the case's
    crosscheck_reference.csv, DPMFoam's times as it wrote them: (t, values), or None."""
    path = Path(case) / "crosscheck_reference.csv"
    if not path.is_file():
        return None
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    header = lines[0].split(",")
    data = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    return data[:, 0], data[:, header.index(series)]
