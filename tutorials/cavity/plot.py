#!/usr/bin/env python3
"""Lid-driven cavity at Re = 100: the centre lines against Ghia, Ghia & Shin (1982).

Reads the last time directory, prints the largest difference from Ghia et al.'s Table I (u on
the vertical centre line) and Table II (v on the horizontal one) over the lid speed (bound
2 %, as tests/fluid/cavity.rs holds the same flow), and draws cavity.png.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

# U. Ghia, K. N. Ghia, C. T. Shin, J. Comput. Phys. 48, 387-411 (1982), Re = 100 columns
GHIA_Y = [1.0000, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000, 0.4531,
          0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547, 0.0000]
GHIA_U = [1.00000, 0.84123, 0.78871, 0.73722, 0.68717, 0.23151, 0.00332, -0.13641, -0.20581,
          -0.21090, -0.15662, -0.10150, -0.06434, -0.04775, -0.04192, -0.03717, 0.00000]
GHIA_X = [1.0000, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000, 0.2344,
          0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625, 0.0000]
GHIA_V = [0.00000, -0.05906, -0.07391, -0.08864, -0.10313, -0.16914, -0.22445, -0.24533,
          0.05454, 0.17527, 0.17507, 0.16077, 0.12317, 0.10890, 0.10091, 0.09233, 0.00000]

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (field_axes, finish, keyword, monitor, save,  # noqa: E402
                      time_directories, vector)

nu = keyword(case, "constant/transportProperties", "nu")
lid = vector(case, "0/U", r"movingWall\s*\{[^}]*uniform")[0]
time, last = time_directories(case)[-1]
mesh = pv.read(last / "fluid.vtk")
nx, ny, _ = (d - 1 for d in mesh.dimensions)
side = mesh.bounds[1] - mesh.bounds[0]
u = mesh.cell_data["U"].reshape(ny, nx, 3)  # [j, i, component], one cell thick
h = side / nx
centres = (np.arange(nx) + 0.5) * h


def mid(values, axis):
    """Values on the mid-line (x or y = side/2, a cell face): 4-point cubic interpolation."""
    k = nx // 2
    w = np.array([-1, 9, 9, -1]) / 16
    return np.tensordot(np.take(values, range(k - 2, k + 2), axis=axis), w, axes=([axis], [0]))


# with the wall values, as Ghia's tables have them
y_line = np.concatenate([[0], centres / side, [1]])
u_line = np.concatenate([[0], mid(u[:, :, 0], axis=1) / lid, [1]])
x_line = np.concatenate([[0], centres / side, [1]])
v_line = np.concatenate([[0], mid(u[:, :, 1], axis=0) / lid, [0]])
err_u = np.max(np.abs(np.interp(GHIA_Y, y_line, u_line) - GHIA_U))
err_v = np.max(np.abs(np.interp(GHIA_X, x_line, v_line) - GHIA_V))

fluid = monitor(case, "fluid")
energy = fluid["kineticEnergy"]
steps_per_unit = int(round(1 / fluid["deltaT"][-1]))
change = abs(energy[-1] / energy[max(0, len(energy) - 1 - steps_per_unit)] - 1)

print(f"Lid-driven cavity, Re = {lid * side / nu:g}, {nx} x {ny} cells, t = {time:g} s "
      f"(kinetic energy changed {change:.1e} over the last second: steady)")
print(f"u on x = 0.5 against Ghia et al. (1982): max |u - Ghia| / U_lid = {100 * err_u:.2f} %")
print(f"v on y = 0.5 against Ghia et al. (1982): max |v - Ghia| / U_lid = {100 * err_v:.2f} %")
print(f"bound 2 %: {'within' if max(err_u, err_v) < 0.02 else 'OUTSIDE'}")

fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True,
                              gridspec_kw={"width_ratios": [1.25, 1, 1]})
speed = np.linalg.norm(u[:, :, :2], axis=2)
image = a.pcolormesh(centres, centres, speed, cmap="viridis", shading="auto")
a.streamplot(centres, centres, u[:, :, 0], u[:, :, 1], color="w", density=1.2, linewidth=0.7)
a.set_xlim(0, side)
a.set_ylim(0, side)
field_axes(fig, a, image, "x (m)", "y (m)",
           f"speed and streamlines, t = {time:g} s (lid moves right)", "|U| (m/s)")

b.plot(u_line, y_line, "C0", lw=2, label="fsim")
b.plot(GHIA_U, GHIA_Y, "ko", mfc="none", label="Ghia et al. (1982)")
finish(b, "u / U on the vertical centre line x = 0.5", "y / L",
       f"max |u - Ghia| = {100 * err_u:.2f} % of U", legend=dict(loc="lower right"))

c.plot(x_line, v_line, "C3", lw=2, label="fsim")
c.plot(GHIA_X, GHIA_V, "ks", mfc="none", label="Ghia et al. (1982)")
finish(c, "x / L", "v / U on the horizontal centre line y = 0.5",
       f"max |v - Ghia| = {100 * err_v:.2f} % of U", legend=dict(loc="lower left"))
save(fig, case / "cavity.png", dpi=110)
