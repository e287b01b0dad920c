#!/usr/bin/env python3
"""A liquid-fluidized bed of glass beads (WenYuDrag, pressureGradient, virtualMass), a
DPMFoam cross-check case of issue 42.

A uniform bed of N beads of diameter d over the column's cross-section A at solid fraction
phi is N pi d^3 / (6 phi A) high, and its beads' mean height is half that. Draws
liquidFluidizedBed.png: the beads' mean height, fsim's and DPMFoam's
(crosscheck_reference.csv), against the heights that Richardson-Zaki's and Garside and
Al-Dibouni's fluidization correlations and WenYuDrag's own uniform balance give
(tools/force_crosscheck_references.py liquidFluidizedBed).
"""
import math
import re
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
sys.path.insert(0, str(case.parent.parent / "tools"))  # force_crosscheck_references.py
from force_crosscheck_references import liquid_fluidized_bed  # noqa: E402
from plotting import (dpmfoam_reference, finish, inlet_velocity, keyword,  # noqa: E402
                      particle_history, properties, save)

rho_f, nu, rho_p, g = properties(case)
d = keyword(case, "constant/kinematicCloudProperties", "value")
u = inlet_velocity(case)[2]
mesh = (case / "system" / "blockMeshDict").read_text()
scale = float(re.search(r"^scale\s+([0-9.eE+-]+);", mesh, re.M).group(1))
side = r"\(0 0 0\)\s*\(([0-9.]+) 0 0\)\s*\(\S+ ([0-9.]+) 0\)"
corner = [float(x) * scale for x in re.search(side, mesh).groups()]
area = corner[0] * corner[1]
positions = (case / "constant" / "kinematicCloudPositions").read_text()
beads = int(re.search(r"^(\d+)\s*$", positions, re.M).group(1))
walls = "symmetry" not in re.search(r"walls\s*\{\s*type (\w+)", mesh).group(0)
porosity = liquid_fluidized_bed(u, d, rho_p, rho_f, nu, math.sqrt(area), beads, area, walls)


def mean_height(eps):
    return beads * math.pi * d ** 3 / 6 / ((1 - eps) * area) / 2


fig, ax = plt.subplots(figsize=(8, 4.8), constrained_layout=True)
styles = ["tab:green", "tab:olive", "tab:purple", "k"]
for (name, eps), color in zip(porosity.items(), styles):
    ax.axhline(1e3 * mean_height(eps), color=color, ls="--", lw=1,
               label=f"{name}: solid fraction {1 - eps:.3f}")
dpm = dpmfoam_reference(case, "particles.position.z.mean")
if dpm is not None:
    ax.plot(dpm[0], 1e3 * dpm[1], "o-", ms=3, color="tab:blue", label="DPMFoam v1912")
t, z = particle_history(case, "position", "z")
if len(t):
    ax.plot(t, 1e3 * z, "s--", ms=2.5, color="tab:orange", label="fsim")
    late = t >= 0.3
    print(f"fsim: mean bead height over {t[late][0]:g}-{t[-1]:g} s {1e3 * np.mean(z[late]):.3f} mm")
ax.axvspan(0.3, 0.8, color="0.93", zorder=0)
finish(ax, "t (s)", "mean bead height (mm)",
       f"{beads} beads of {1e3 * d:g} mm fluidized by water at {u:g} m/s",
       legend=dict(fontsize=8, loc="upper right"))
save(fig, case / "liquidFluidizedBed.png", 100)
