#!/usr/bin/env python3
"""Spheres settling in a periodic box: the mean settling velocity against the same spheres'
Rotne-Prager-Yamakawa (RPY) mobility.

fsim reports v_m, the spheres' mean velocity in the frame of zero volume flux
(postProcessing/sedimentation). The reference is the far-field (RPY) mobility of the spheres
where they are at each write time, summed over the periodic images of this box (as
tools/periodic_rpy.py does for cubes): it holds the box's hindrance, which for 48 spheres is
large, and leaves out the near field and inertia (Re here about 0.3). At r/h = 3 fsim settles
27-sphere packings at 0.96 of it (docs/richardson_zaki.md). Prints both and draws
sedimentation.png.
"""
import math
import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv
from vtkmodules.vtkCommonCore import vtkLogger

pv.OFF_SCREEN = True
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)  # no notes about a missing X server
case = Path(__file__).resolve().parent


def entry(file, pattern):
    return float(re.search(pattern, (case / file).read_text(), re.M).group(1))


rho_f = entry("constant/transportProperties", r"^\s*rho\.\w+\s+([0-9.eE+-]+)\s*;")
nu = entry("constant/transportProperties", r"^\s*nu\s+([0-9.eE+-]+)\s*;")
rho_p = entry("constant/kinematicCloudProperties", r"^\s*rho0\s+([0-9.eE+-]+)\s*;")
g = abs(entry("constant/g", r"value\s*\(\s*[0-9.eE+-]+\s+(-?[0-9.eE+-]+)"))


def rpy_settling(centres, a, box, axis=1, ka_max=20.0, chunk=200_000):
    """Mean velocity along `axis` of equal spheres under equal forces in a periodic box, over
    their Stokes velocity, with the (1 - phi) of a sedimenting suspension's drive: the
    reciprocal-lattice sum of tools/periodic_rpy.py, for a box of any sides, reduced to the
    structure factor |sum_i exp(i k.x_i)|^2 (only the mean is wanted)."""
    x, box = np.asarray(centres, float), np.asarray(box, float)
    k_max = ka_max / a
    axes = [np.arange(-math.ceil(k_max * s / (2 * math.pi)),
                      math.ceil(k_max * s / (2 * math.pi)) + 1) * 2 * math.pi / s for s in box]
    k = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    k2 = (k ** 2).sum(1)
    keep = (k2 > 0) & (k2 <= k_max ** 2)
    k, k2 = k[keep], k2[keep]
    total = 0.0
    for s in range(0, len(k2), chunk):
        kc, k2c = k[s:s + chunk], k2[s:s + chunk]
        ka = np.sqrt(k2c) * a
        phase = x @ kc.T
        structure = np.cos(phase).sum(0) ** 2 + np.sin(phase).sum(0) ** 2
        total += np.sum((np.sin(ka) / ka) ** 2 / k2c * (1 - kc[:, axis] ** 2 / k2c) * structure)
    # the self term's tail beyond k_max as its continuum integral
    mean = 6 * math.pi * a / box.prod() * total / len(x) + 1 / (math.pi * a * k_max)
    phi = len(x) * 4 / 3 * math.pi * a ** 3 / box.prod()
    return (1 - phi) * mean


monitor = case / "postProcessing/sedimentation/0/sedimentation.dat"
columns = monitor.read_text().splitlines()[0].lstrip("#").split()
data = np.loadtxt(monitor, comments="#", ndmin=2)
t = data[:, columns.index("Time")]
v = data[:, columns.index("settlingVelocity")]
phi = data[0, columns.index("phi")]

times = sorted((float(p.name), p) for p in case.iterdir()
               if p.is_dir() and re.fullmatch(r"[0-9.eE+-]+", p.name))
fluid = pv.read(times[-1][1] / "fluid.vtk")
box = np.array(fluid.bounds[1::2]) - np.array(fluid.bounds[0::2])
rpy = []
for time, folder in times:
    cloud = pv.read(folder / "particles.vtu")
    d = cloud.point_data["d"]
    rpy.append((time, rpy_settling(cloud.points, d.mean() / 2, box)))
d = d.mean()
stokes = (rho_p - rho_f) * g * d ** 2 / (18 * rho_f * nu)
rpy_t, rpy_v = np.array(rpy).T

second_half = t >= t[-1] / 2
v_mean = v[second_half].mean() / stokes
rpy_mean = rpy_v[rpy_t >= t[-1] / 2].mean()
hard_spheres = 1 - 6.5464 * phi * (1 - 3.348 * phi + 7.426 * phi ** 2 - 10.034 * phi ** 3
                                   + 5.882 * phi ** 4)
print(f"{len(cloud.points)} spheres, d = {1e3 * d:g} mm, rho_p / rho_f = {rho_p / rho_f:g}, "
      f"phi = {phi:.4f}, r/h = {d / 2 / fluid.spacing[0]:g}; U_Stokes = {100 * stokes:.3f} cm/s, "
      f"Re = v d / nu = {v[-1] * d / nu:.2f}")
print(f"settling velocity at t = {t[-1]:g} s: {100 * v[-1]:.3f} cm/s; mean over "
      f"{t[-1] / 2:g}-{t[-1]:g} s: {100 * v_mean * stokes:.3f} cm/s = {v_mean:.4f} U_Stokes")
print(f"RPY mobility of the same spheres (write times {rpy_t[rpy_t >= t[-1] / 2].min():g}-"
      f"{t[-1]:g} s): {rpy_mean:.4f} U_Stokes; fsim / RPY = {v_mean / rpy_mean:.3f} "
      "(27-sphere packings at r/h = 3: 0.96)")
print(f"for scale, an unbounded random suspension at this phi: {hard_spheres:.3f} U_Stokes "
      f"(Abade et al. 2012), Richardson-Zaki n = 4.8: {(1 - phi) ** 4.8:.3f}; a box of "
      f"{len(cloud.points)} spheres hinders more (Hasimoto: about 1.76 (phi/N)^(1/3) = "
      f"{1.76 * (phi / len(cloud.points)) ** (1 / 3):.2f})")

# the picture: spheres and the vertical fluid velocity on the mid-plane, and v_m(t)
point_fluid = fluid.cell_data_to_point_data()
plane = point_fluid.slice(normal="z", origin=fluid.center)
plane.point_data["U_y"] = 100 * plane.point_data["U"][:, 1]
limit = float(np.abs(plane.point_data["U_y"]).max())
cloud = pv.read(times[-1][1] / "particles.vtu")
spheres = pv.PolyData(np.asarray(cloud.points)).glyph(
    geom=pv.Sphere(radius=d / 2, theta_resolution=24, phi_resolution=24), orient=False,
    scale=False)
plotter = pv.Plotter(off_screen=True, window_size=(620, 900))
plotter.set_background("white")
plotter.add_mesh(plane, scalars="U_y", cmap="coolwarm", clim=(-limit, limit),
                 show_scalar_bar=False)
plotter.add_mesh(spheres, color="#d9a441", smooth_shading=True, specular=0.3)
plotter.add_mesh(pv.Box(fluid.bounds).outline(), color="black", line_width=2)
plotter.view_vector((0.55, 0.35, 1.0), viewup=(0.0, 1.0, 0.0))
plotter.reset_camera(bounds=fluid.bounds)
plotter.camera.zoom(1.2)
image = plotter.screenshot(return_img=True)
plotter.close()
rows = np.where((image < 250).any(axis=(1, 2)))[0]
cols = np.where((image < 250).any(axis=(0, 2)))[0]
image = image[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]  # without the white margins

fig = plt.figure(figsize=(12.5, 6.5), constrained_layout=True)
grid = fig.add_gridspec(1, 4, width_ratios=[1, 0.04, 0.06, 1.4])
a = fig.add_subplot(grid[0])
a.imshow(image)
a.set_axis_off()
a.set_title(f"t = {times[-1][0]:g} s: spheres, and $u_y$ on the mid-plane\n(gravity along -y)",
            fontsize=10)
bar = fig.colorbar(plt.cm.ScalarMappable(plt.Normalize(-limit, limit), "coolwarm"),
                   cax=fig.add_subplot(grid[1]))
bar.set_label("fluid velocity $u_y$ (cm/s)")
bar.ax.yaxis.set_ticks_position("left")
bar.ax.yaxis.set_label_position("left")
b = fig.add_subplot(grid[3])
b.plot(t, v / stokes, lw=2, label="fsim: $v_m$, frame of zero volume flux")
b.plot(rpy_t, rpy_v, "ks", label="RPY mobility of the same spheres (far field, Stokes)")
b.axhline(hard_spheres, color="0.5", ls=":",
          label="unbounded random suspension (Abade et al. 2012)")
b.set_xlabel("t (s)")
b.set_ylabel("settling velocity / U_Stokes")
b.set_ylim(0, 1.1 * max(hard_spheres, rpy_v.max()))
b.set_title(f"mean over {t[-1] / 2:g}-{t[-1]:g} s: {v_mean:.3f} U_Stokes = "
            f"{100 * v_mean * stokes:.2f} cm/s; {v_mean / rpy_mean:.2f} of RPY", fontsize=10)
b.grid(alpha=0.3)
b.legend(loc="lower right", fontsize=9)
fig.savefig(case / "sedimentation.png", dpi=100)
print("wrote sedimentation.png")
