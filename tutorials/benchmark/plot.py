#!/usr/bin/env python3
"""The paper's section 3.3 benchmark with the direct model: the suspension's settling velocity.

fsim reports v_m, the spheres' mean velocity in the frame of zero volume flux
(postProcessing/sedimentation). For scale: an isolated sphere's terminal velocity
(Schiller-Naumann), which a suspension settles below, and Richardson & Zaki's hindered
settling (1 - phi)^n with n = 4.45 Re_t^-0.1 (1 < Re_t < 200); a box of 500 spheres hinders
a little more than an unbounded suspension. The same case with the drag-law model
(../benchmarkDragLaw) is drawn beside it when that tutorial has been run: the paper's section
3.3 compares the two models. Prints the figures and draws benchmark.png.
"""
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


def root(f, lo, hi):
    """Bisection: f(lo) < 0 < f(hi)."""
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def monitor(path):
    columns = path.read_text().splitlines()[0].lstrip("#").split()
    data = np.loadtxt(path, comments="#", ndmin=2)
    return {name: data[:, k] for k, name in enumerate(columns)}


rho_f = entry("constant/transportProperties", r"^\s*rho\.\w+\s+([0-9.eE+-]+)\s*;")
mu = rho_f * entry("constant/transportProperties", r"^\s*nu\s+([0-9.eE+-]+)\s*;")
rho_p = entry("constant/kinematicCloudProperties", r"^\s*rho0\s+([0-9.eE+-]+)\s*;")
g = abs(entry("constant/g", r"value\s*\(\s*[0-9.eE+-]+\s+(-?[0-9.eE+-]+)"))

m = monitor(case / "postProcessing/sedimentation/0/sedimentation.dat")
t, v, phi = m["Time"], m["settlingVelocity"], m["phi"][0]
times = sorted((float(p.name), p) for p in case.iterdir()
               if p.is_dir() and re.fullmatch(r"[0-9.eE+-]+", p.name))
cloud = pv.read(times[-1][1] / "particles.vtu")
fluid = pv.read(times[-1][1] / "fluid.vtk")
d = cloud.point_data["d"].mean()
stokes = (rho_p - rho_f) * g * d ** 2 / (18 * mu)
isolated = root(lambda u: u * (1 + 0.15 * (rho_f * u * d / mu) ** 0.687) - stokes, 0, stokes)
re_t = rho_f * isolated * d / mu
n = 4.45 * re_t ** -0.1
richardson_zaki = isolated * (1 - phi) ** n
start = min(0.02, t[-1] / 2)  # after the start-up
developed = v[t >= start].mean()

print(f"{len(cloud.points)} spheres, d = {1e6 * d:g} um, rho_p = {rho_p:g} kg/m^3, in gas of "
      f"rho = {rho_f:g} kg/m^3; phi = {phi:.4f}, r/h = {d / 2 / fluid.spacing[0]:.2f}")
print(f"settling velocity v_m at t = {t[-1]:g} s: {v[-1]:.4f} m/s; mean over {start:g}-"
      f"{t[-1]:g} s: {developed:.4f} m/s (Re = {rho_f * developed * d / mu:.2f})")
print(f"isolated sphere (Schiller-Naumann): {isolated:.4f} m/s (Re_t = {re_t:.2f}); "
      f"{'below it: hindered' if developed < isolated else 'NOT below it'}")
print(f"Richardson-Zaki, n = 4.45 Re_t^-0.1 = {n:.2f}: {richardson_zaki:.4f} m/s; "
      f"fsim {developed / richardson_zaki:.2f} of it")
drag_law = case.parent / "benchmarkDragLaw"
curves = []
try:
    f = monitor(drag_law / "postProcessing/fluid/0/fluid.dat")
    c = monitor(drag_law / "postProcessing/cloud/0/cloud.dat")
    slip = (1 - phi) * (f["Uy"] - np.interp(f["Time"], c["Time"], c["Uy"]))
    curves.append((f["Time"], slip))
    print(f"the drag-law model on the same case (../benchmarkDragLaw): "
          f"{slip[f['Time'] >= start].mean():.4f} m/s over {start:g}-{f['Time'][-1]:g} s")
except OSError:
    print("(run ../benchmarkDragLaw to compare with the drag-law model)")

fluid = fluid.cell_data_to_point_data()
plane = fluid.slice(normal="z", origin=fluid.center)
plane.point_data["U_y"] = plane.point_data["U"][:, 1]
limit = float(np.abs(plane.point_data["U_y"]).max())
spheres = pv.PolyData(np.asarray(cloud.points)).glyph(
    geom=pv.Sphere(radius=d / 2, theta_resolution=16, phi_resolution=16), orient=False,
    scale=False)
plotter = pv.Plotter(off_screen=True, window_size=(560, 1000))
plotter.set_background("white")
plotter.add_mesh(plane, scalars="U_y", cmap="coolwarm", clim=(-limit, limit),
                 show_scalar_bar=False)
plotter.add_mesh(spheres, color="#d9a441", smooth_shading=True)
plotter.add_mesh(pv.Box(fluid.bounds).outline(), color="black", line_width=2)
plotter.view_vector((0.55, 0.35, 1.0), viewup=(0.0, 1.0, 0.0))
plotter.reset_camera(bounds=fluid.bounds)
plotter.camera.zoom(1.2)
image = plotter.screenshot(return_img=True)
plotter.close()
rows = np.where((image < 250).any(axis=(1, 2)))[0]
cols = np.where((image < 250).any(axis=(0, 2)))[0]
image = image[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]  # without the white margins

fig = plt.figure(figsize=(12.5, 6.8), constrained_layout=True)
grid = fig.add_gridspec(1, 4, width_ratios=[0.8, 0.04, 0.06, 1.5])
a = fig.add_subplot(grid[0])
a.imshow(image)
a.set_axis_off()
a.set_title(f"t = {times[-1][0]:g} s: spheres, and $u_y$ on the\nmid-plane (gravity along -y)",
            fontsize=10)
bar = fig.colorbar(plt.cm.ScalarMappable(plt.Normalize(-limit, limit), "coolwarm"),
                   cax=fig.add_subplot(grid[1]))
bar.set_label("gas velocity $u_y$ (m/s)")
bar.ax.yaxis.set_ticks_position("left")
bar.ax.yaxis.set_label_position("left")
b = fig.add_subplot(grid[3])
b.plot(t, v, lw=1.5, label="direct model: $v_m$, frame of zero volume flux")
for time, slip in curves:
    b.plot(time, slip, lw=1, color="tab:purple",
           label="drag-law model (../benchmarkDragLaw)")
b.axhline(isolated, color="tab:red", ls="--",
          label=f"isolated sphere (Schiller-Naumann), {isolated:.3f} m/s")
b.axhline(richardson_zaki, color="tab:green", ls="--",
          label=f"Richardson-Zaki, n = {n:.2f}, {richardson_zaki:.3f} m/s")
b.set_ylim(0, 1.15 * isolated)
b.set_xlabel("t (s)")
b.set_ylabel("settling velocity (m/s)")
b.set_title(f"direct model: mean {developed:.3f} m/s over {start:g}-{t[-1]:g} s", fontsize=10)
b.grid(alpha=0.3)
b.legend(loc="lower right", fontsize=9)
fig.savefig(case / "benchmark.png", dpi=100)
print("wrote benchmark.png")
