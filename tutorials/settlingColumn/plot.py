#!/usr/bin/env python3
"""A column of glass beads settling into a bed in air (drag-law model with Hertzian contacts, a
DPMFoam cross-check case).

Until the first layer lands, every bead falls freely: its mean velocity is -(1 - rho_f/rho_p)
g t (the drag at these speeds is a few per cent of the weight). The bed then builds up from
the floor; a uniform bed of height H holds the N beads at a solid fraction N V_p / (A H), and
its centres' mean height is about H/2. Prints the bed's mean height, top and solid fraction
against the random packings' 0.55-0.64 (looser next to walls), and draws settlingColumn.png:
the beads seen from the side at six times, the mean velocity and the heights against time.
`tools/crosscheck tutorials/settlingColumn` compares the same run with DPMFoam's.
"""
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import finish, monitor, properties, save, time_directories  # noqa: E402

rho_f, _, rho_p, g = properties(case)
reduced = (1 - rho_f / rho_p) * abs(g[2])
times = time_directories(case)
clouds = [(t, pv.read(folder / "particles.vtu")) for t, folder in times]
box = pv.read(times[-1][1] / "fluid.vtk").bounds
area = (box[1] - box[0]) * (box[3] - box[2])
d = clouds[0][1].point_data["d"]
n, volume = len(d), float(np.sum(np.pi / 6 * d ** 3))
r = float(d.mean()) / 2

t_write = np.array([t for t, _ in clouds])
mean_z = np.array([c.points[:, 2].mean() for _, c in clouds])
top_z = np.array([c.points[:, 2].max() for _, c in clouds])
cloud = monitor(case, "cloud")
t, uz = cloud["Time"], cloud["Uz"]
landing = np.sqrt(2 * (clouds[0][1].points[:, 2].min() - r - box[4]) / reduced)
early = t < landing

height = 2 * (mean_z[-1] - box[4])
solid = volume / (area * height)
loose, close = (volume / (area * phi) for phi in (0.55, 0.64))
free_fall = np.max(np.abs(uz[early] + reduced * t[early])) / (reduced * landing)
print(f"Settling column: {n} beads of d = {2e3 * r:g} mm, rho_p = {rho_p:g} kg/m^3 in air, "
      f"{1e3 * (box[1] - box[0]):g} x {1e3 * (box[3] - box[2]):g} mm floor")
print(f"until the first layer lands ({1e3 * landing:.0f} ms) the mean velocity follows free "
      f"fall within {100 * free_fall:.1f} % (bound 5 %): "
      f"{'within' if free_fall < 0.05 else 'OUTSIDE'}")
print(f"at t = {t_write[-1]:g} s: mean height of the centres {1e3 * mean_z[-1]:.3f} mm, highest "
      f"centre {1e3 * top_z[-1]:.2f} mm, mean velocity {1e3 * uz[-1]:+.2f} mm/s "
      f"(peak {1e3 * uz.min():.0f} mm/s)")
print(f"bed height 2 x mean height = {1e3 * height:.2f} mm: solid fraction {solid:.3f} (random "
      f"packings 0.55-0.64, looser by the walls and the floor: {1e3 * close:.2f}-"
      f"{1e3 * loose:.2f} mm)")

fig = plt.figure(figsize=(13, 8.5), constrained_layout=True)
top, bottom = fig.subfigures(2, 1, height_ratios=[0.9, 1])
shown = [clouds[k] for k in np.linspace(0, len(clouds) - 1, 6).round().astype(int)]
limit = reduced * landing
axes = top.subplots(1, len(shown), sharey=True)
for k, (a, (time, c)) in enumerate(zip(axes, shown)):
    order = np.argsort(c.points[:, 0])  # the front layer drawn last
    dots = a.scatter(1e3 * c.points[order, 1], 1e3 * c.points[order, 2], s=6,
                     c=c.point_data["U"][order, 2], cmap="coolwarm", vmin=-limit, vmax=limit)
    a.set_xlim(1e3 * box[2], 1e3 * box[3])
    a.set_ylim(1e3 * box[4], 1e3 * box[5])
    a.set_aspect("equal")
    a.set_title(f"t = {time:g} s", fontsize=10)
    a.set_xlabel("y (mm)")
axes[0].set_ylabel("z (mm)")
top.colorbar(dots, ax=axes, label="bead velocity $U_z$ (m/s)", shrink=0.75)
u, h = bottom.subplots(1, 2)
u.plot(t, uz, lw=1.5, label="fsim, mean bead velocity (postProcessing/cloud)")
u.plot(t[early], -reduced * t[early], color="k", ls="--", lw=1,
       label="free fall, $-(1 - \\rho_f/\\rho_p)\\,g\\,t$")
u.axvline(landing, color="grey", lw=0.8, ls=":")
finish(u, "t (s)", "mean $U_z$ (m/s)",
       f"free fall until the first layer lands, {1e3 * landing:.0f} ms",
       legend=dict(loc="center right", fontsize=9))
h.plot(t_write, 1e3 * mean_z, "o-", ms=3, label="fsim, mean height of the centres")
h.plot(t_write, 1e3 * top_z, "s-", ms=3, color="tab:purple", label="fsim, highest centre")
h.axhspan(1e3 * (box[4] + close / 2), 1e3 * (box[4] + loose / 2), color="tab:green", alpha=0.2,
          label="H/2 of a uniform bed at solid fraction 0.64-0.55")
finish(h, "t (s)", "height (mm)", f"bed at {t_write[-1]:g} s: solid fraction {solid:.2f}",
       legend=dict(loc="upper right", fontsize=9))
save(fig, case / "settlingColumn.png", 100)
