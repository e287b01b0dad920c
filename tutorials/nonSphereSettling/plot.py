#!/usr/bin/env python3
"""One non-spherical particle (sphericity phi) settling from rest in water under DPMFoam's
nonSphereDrag, a DPMFoam cross-check case of issue 42.

Haider & Levenspiel (1989), as DPMFoam v1912 writes it: Cd Re = 24 (1 + a Re^b) + c Re /
(1 + d/Re), a, b, c, d functions of phi. Solves the balance of drag and buoyant weight for the
terminal velocity (bisection; tools/force_crosscheck_references.py does the same), and draws
nonSphereSettling.png: fsim's velocity and DPMFoam's (crosscheck_reference.csv) against it and
against a sphere's (Schiller-Naumann).
"""
import math
import sys
from pathlib import Path

import matplotlib.pyplot as plt

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import (dpmfoam_reference, finish, keyword, particle_history,  # noqa: E402
                      properties, root, save)

rho_f, nu, rho_p, g = properties(case)
g = abs(g[2])
d = keyword(case, "constant/kinematicCloudProperties", "value")
phi = keyword(case, "constant/kinematicCloudProperties", "phi")
a = math.exp(2.3288 - 6.4581 * phi + 2.4486 * phi ** 2)
b = 0.0964 + 0.5565 * phi
c = math.exp(4.905 - 13.8944 * phi + 18.4222 * phi ** 2 - 10.2599 * phi ** 3)
dd = math.exp(1.4681 + 12.2584 * phi - 20.7322 * phi ** 2 + 15.8855 * phi ** 3)


def balance(v, cdre):
    """Drag less buoyant weight per unit mass: 0.75 nu rho_f Cd Re v / (rho_p d^2) - g'."""
    re = v * d / nu
    return 0.75 * rho_f * nu * cdre(re) * v / (rho_p * d * d) - (1 - rho_f / rho_p) * g


hl = root(lambda v: balance(v, lambda re: 24 * (1 + a * re ** b) + c * re / (1 + dd / re)),
          1e-9, 10)
sphere = root(lambda v: balance(v, lambda re: 24 * (1 + 0.15 * re ** 0.687)), 1e-9, 10)
print(f"phi = {phi:g}: Haider-Levenspiel terminal velocity {hl:.5f} m/s (Re = {hl * d / nu:.1f}); "
      f"a sphere {sphere:.5f} m/s")
t, v = particle_history(case, "U", "z")
if len(t):
    print(f"fsim, last: {-v[-1]:.5f} m/s ({100 * (-v[-1] - hl) / hl:+.2f} %)")
dpm = dpmfoam_reference(case, "particles.U.z.mean")
fig, ax = plt.subplots(figsize=(7.5, 4.6), constrained_layout=True)
ax.axhline(hl, color="k", ls="--", label=f"Haider-Levenspiel by hand, {hl:.4f} m/s")
ax.axhline(sphere, color="tab:red", ls=":", label=f"a sphere (Schiller-Naumann), {sphere:.4f} m/s")
if dpm is not None:
    ax.plot(dpm[0], -dpm[1], "o-", ms=3, color="tab:blue", label="DPMFoam v1912")
if len(t):
    ax.plot(t, -v, "s--", ms=2.5, color="tab:orange", label="fsim")
ax.set_ylim(0, 1.1 * sphere)
finish(ax, "t (s)", "settling velocity $-U_z$ (m/s)",
       f"nonSphereDrag, phi = {phi:g}: one particle of {1e3 * d:g} mm in water",
       legend=dict(loc="lower right", fontsize=9))
save(fig, case / "nonSphereSettling.png", 100)
