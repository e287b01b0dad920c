"""What the tutorials' plot.py scripts share: reading a case (its dictionaries' entries, its time
directories, its postProcessing monitors), pyvista's off-screen pictures, the axes' finish and
the references more than one tutorial draws.

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


def save(fig, path, dpi):
    """Writes the figure to `path` and says so."""
    fig.savefig(path, dpi=dpi)
    print(f"wrote {Path(path).name}")
