#!/usr/bin/env python3
"""Particle settling (DEM only): the loose packing collapses into a bed at rest.

Prints whether the bed is at rest (every bead below 1 % of the free-fall speed of its mean
drop, the rms speed below 1e-4 m/s), the largest overlap against the 1 % of d the linear
springs must stay under (both as tools/tests/test_tutorials.py checks them) and the bed's
solid fraction; draws particleSettling.png: the cloud at the start and at the end (pyvista)
and its kinetic energy over time.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (left_colorbar, monitor, offscreen_plotter, save,  # noqa: E402
                      screenshot, show, time_directories)

times = time_directories(case)
(t0, first), (t1, last) = times[0], times[-1]
start, end = pv.read(first / "particles.vtu"), pv.read(last / "particles.vtu")
box = pv.read(last / "fluid.vtk").bounds

x, d = end.points, end.point_data["d"]
speed = np.linalg.norm(end.point_data["U"], axis=1)
drop = start.points[:, 2].mean() - x[:, 2].mean()
free_fall = np.sqrt(2 * 9.81 * drop)
# solid fraction of the bed's core: spheres whose centres lie more than 2 d from its floor
# and top, over that slab of the box
top = np.percentile(x[:, 2] + d / 2, 99)
lo, hi = box[4] + 2 * d.mean(), top - 2 * d.mean()
inside = (x[:, 2] > lo) & (x[:, 2] < hi)
area = (box[1] - box[0]) * (box[3] - box[2])
solid = np.sum(np.pi / 6 * d[inside] ** 3) / (area * (hi - lo))

cloud_monitor = monitor(case, "cloud")
t, energy = cloud_monitor["Time"], cloud_monitor["kineticEnergy"]
rotation, overlap = cloud_monitor["rotationalEnergy"], cloud_monitor["maxOverlapOverD"][-1]

rest = speed.max() < 0.01 * free_fall and np.sqrt(np.mean(speed ** 2)) < 1e-4
print(f"Particle settling: {len(d)} beads, d = {1e3 * d.min():.2f}-{1e3 * d.max():.2f} mm, "
      f"t = {t1:g} s")
print(f"mean drop {1e3 * drop:.1f} mm; largest speed {1e3 * speed.max():.3f} mm/s "
      f"(at rest below 1 % of sqrt(2 g drop) = {1e3 * 0.01 * free_fall:.1f} mm/s), "
      f"rms {np.sqrt(np.mean(speed ** 2)):.1e} m/s (bound 1e-4): "
      f"{'at rest' if rest else 'NOT at rest'}")
print(f"largest overlap {100 * overlap:.3f} % of d (bound 1 %): "
      f"{'within' if overlap < 0.01 else 'OUTSIDE'}")
print(f"solid fraction of the bed's core {solid:.3f} (the loose start: 0.3; random packings of "
      "frictional spheres settle at about 0.55-0.64, less next to walls)")


def render(cloud):
    plotter = offscreen_plotter((560, 760))
    spheres = cloud.glyph(geom=pv.Sphere(radius=0.5, theta_resolution=12, phi_resolution=12),
                          scale="d", orient=False)
    spheres.point_data["z"] = 1e3 * spheres.points[:, 2]
    plotter.add_mesh(spheres, scalars="z", cmap="viridis", clim=[0, 1e3 * box[5]],
                     show_scalar_bar=False)
    plotter.add_mesh(pv.Box(box).outline(), color="k", line_width=2)
    plotter.view_vector((1.0, -0.9, 0.55))
    plotter.reset_camera(bounds=box)
    plotter.camera.zoom(1.15)
    return screenshot(plotter)


fig = plt.figure(figsize=(14, 6.2), constrained_layout=True)
grid = fig.add_gridspec(1, 4, width_ratios=[1, 1, 0.06, 1.4])
for k, (cloud, time) in enumerate([(start, t0), (end, t1)]):
    show(fig.add_subplot(grid[k]), render(cloud),
         ["loose random packing", "settled bed"][k] + f", t = {time:g} s")
left_colorbar(fig, fig.add_subplot(grid[2]), 0, 1e3 * box[5], "viridis",
              "height of the bead's centre (mm)")
b = fig.add_subplot(grid[3])
b.semilogy(t, energy, label="translational")
b.semilogy(t, np.maximum(rotation, 1e-30), label="rotational")
b.set_xlabel("t (s)")
b.set_ylabel("kinetic energy of the cloud (J)")
b.set_ylim(max(1e-14, min(energy.min(), rotation[rotation > 0].min()) / 3), None)
b.set_title(f"largest overlap {100 * overlap:.2f} % of d (bound 1 %), "
            f"bed solid fraction {solid:.2f}", fontsize=10)
b.grid(alpha=0.3, which="both")
b.legend()
save(fig, case / "particleSettling.png", dpi=100)
