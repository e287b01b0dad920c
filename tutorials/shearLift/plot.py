#!/usr/bin/env python3
"""One bead settling in a vertical linear shear flow with SaffmanMeiLiftForce (shearLift) or
TomiyamaLift (shearLiftTomiyama), a DPMFoam cross-check case of issue 42.

The water moves along z at u_z = gamma (x - width/2) between two walls sliding in opposite
directions; the bead settles through it with the slip s_z and the lift
m rho_f/rho_p Cl (s x curl u) drives it across the stream lines at the speed where drag
balances it (tools/force_crosscheck_references.py shearLift solves that balance: Saffman 1965
and Mei 1992, or Tomiyama's C_l, as DPMFoam v1912 writes them). Draws <case>.png: the
bead's x and U_x, fsim's and DPMFoam's (crosscheck_reference.csv), against that drift.
"""
import re
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
sys.path.insert(0, str(case.parent.parent / "tools"))  # force_crosscheck_references.py
from force_crosscheck_references import shear_lift  # noqa: E402
from plotting import (dpmfoam_reference, finish, keyword, particle_history,  # noqa: E402
                      properties, save, vector)

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
drift, slip, cl = shear_lift(gamma, d, rho_p, rho_f, nu, lift, sigma)
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
