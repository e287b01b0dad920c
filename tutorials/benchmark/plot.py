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
import sys
from pathlib import Path

import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (monitor, picture_beside_plot, properties, save,  # noqa: E402
                      schiller_naumann, settling_references, spheres_over_slice,
                      time_directories)

rho_f, nu, rho_p, g = properties(case)
mu, g = rho_f * nu, abs(g[1])

m = monitor(case, "sedimentation")
t, v, phi = m["Time"], m["settlingVelocity"], m["phi"][0]
times = time_directories(case)
cloud = pv.read(times[-1][1] / "particles.vtu")
fluid = pv.read(times[-1][1] / "fluid.vtk")
d = cloud.point_data["d"].mean()
stokes = (rho_p - rho_f) * g * d ** 2 / (18 * mu)
isolated = schiller_naumann(stokes, rho_f, d, mu, stokes)
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
    f, c = monitor(drag_law, "fluid"), monitor(drag_law, "cloud")
    slip = (1 - phi) * (f["Uy"] - np.interp(f["Time"], c["Time"], c["Uy"]))
    curves.append((f["Time"], slip))
    print(f"the drag-law model on the same case (../benchmarkDragLaw): "
          f"{slip[f['Time'] >= start].mean():.4f} m/s over {start:g}-{f['Time'][-1]:g} s")
except OSError:
    print("(run ../benchmarkDragLaw to compare with the drag-law model)")

image, limit = spheres_over_slice(fluid, cloud.points, d, (560, 1000), 16)
fig, b = picture_beside_plot(image, limit, f"t = {times[-1][0]:g} s: spheres, and $u_y$ on the\n"
                             "mid-plane (gravity along -y)", "gas velocity $u_y$ (m/s)",
                             figsize=(12.5, 6.8), widths=(0.8, 1.5))
b.plot(t, v, lw=1.5, label="direct model: $v_m$, frame of zero volume flux")
for time, slip in curves:
    b.plot(time, slip, lw=1, color="tab:purple",
           label="drag-law model (../benchmarkDragLaw)")
settling_references(b, isolated, "sphere", richardson_zaki,
                    f"Richardson-Zaki, n = {n:.2f}, {richardson_zaki:.3f} m/s", top=1.15,
                    ylabel="settling velocity (m/s)",
                    title=f"direct model: mean {developed:.3f} m/s over {start:g}-{t[-1]:g} s")
save(fig, case / "benchmark.png", dpi=100)
