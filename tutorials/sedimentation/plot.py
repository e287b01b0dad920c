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
import sys
from pathlib import Path

import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (finish, monitor, picture_beside_plot, properties, save,  # noqa: E402
                      spheres_over_slice, time_directories)
sys.path.insert(0, str(case.parents[1] / "tools"))  # tools/, for periodic_rpy.py
from periodic_rpy import box_settling  # noqa: E402

rho_f, nu, rho_p, g = properties(case)
g = abs(g[1])


m = monitor(case, "sedimentation")
t, v, phi = m["Time"], m["settlingVelocity"], m["phi"][0]

times = time_directories(case)
fluid = pv.read(times[-1][1] / "fluid.vtk")
box = np.array(fluid.bounds[1::2]) - np.array(fluid.bounds[0::2])
rpy = []
for time, folder in times:
    cloud = pv.read(folder / "particles.vtu")
    d = cloud.point_data["d"]
    rpy.append((time, box_settling(cloud.points, d.mean() / 2, box)))
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
cloud = pv.read(times[-1][1] / "particles.vtu")
image, limit = spheres_over_slice(fluid, cloud.points, d, (620, 900), 24, scale=100,
                                  specular=0.3)
fig, b = picture_beside_plot(image, limit, f"t = {times[-1][0]:g} s: spheres, and $u_y$ on the "
                             "mid-plane\n(gravity along -y)", "fluid velocity $u_y$ (cm/s)",
                             figsize=(12.5, 6.5), widths=(1, 1.4))
b.plot(t, v / stokes, lw=2, label="fsim: $v_m$, frame of zero volume flux")
b.plot(rpy_t, rpy_v, "ks", label="RPY mobility of the same spheres (far field, Stokes)")
b.axhline(hard_spheres, color="0.5", ls=":",
          label="unbounded random suspension (Abade et al. 2012)")
b.set_ylim(0, 1.1 * max(hard_spheres, rpy_v.max()))
finish(b, "t (s)", "settling velocity / U_Stokes",
       f"mean over {t[-1] / 2:g}-{t[-1]:g} s: {v_mean:.3f} U_Stokes = "
       f"{100 * v_mean * stokes:.2f} cm/s; {v_mean / rpy_mean:.2f} of RPY",
       legend=dict(loc="lower right", fontsize=9))
save(fig, case / "sedimentation.png", dpi=100)
