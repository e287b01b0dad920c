#!/usr/bin/env python3
"""Bead-bead and bead-wall impacts (Hertzian spring-slider-dashpot): restitution, tangential
velocity and spin after each impact, against what theory gives.

Restitution: the contact's normal equation m x'' = -k x^1.5 - alpha sqrt(m k) x^0.25 x' (DPMFoam's
pairSpringSliderDashpot and wallSpringSliderDashpot) scales to x'' = -x^1.5 - alpha x^0.25 x', so
its restitution e depends on alpha alone; it has no closed form, and the script integrates it
(RK4). Oblique impacts: a rigid-body impact with normal impulse J_n = m* (1 + e) v_n gives a
tangential impulse of at most Coulomb's mu J_n, and at most what stops the slip (the bead then
leaves rolling: 5/7 of its tangential velocity against a wall). Beads (ids as the injectors list
them): 0 -> 3 head-on, 1 -> 4 at 45 deg, 2 normal on the wall x = 48 mm, 5 at 45 deg on it.
Prints each quantity and draws <case>.png.
"""
import re
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import NUMBER, finish, save, time_directories  # noqa: E402

CLOUD = "constant/kinematicCloudProperties"


def coefficient(model, key):
    """`key` of the sub-dictionary <model>Coeffs in the cloud's file."""
    block = re.search(rf"{model}Coeffs\s*\{{([^}}]*)\}}", (case / CLOUD).read_text()).group(1)
    return float(re.search(rf"^\s*{key}\s+({NUMBER})\s*;", block, re.M).group(1))


def restitution(alpha, h=2e-4):
    """e of x'' = -x^1.5 - alpha x^0.25 x' from x = 0, x' = 1 (RK4, the exit interpolated)."""
    def f(x, v):
        return -max(x, 0.0) ** 1.5 - alpha * max(x, 0.0) ** 0.25 * v
    x, v = 0.0, 1.0
    while True:
        k1x, k1v = v, f(x, v)
        k2x, k2v = v + h / 2 * k1v, f(x + h / 2 * k1x, v + h / 2 * k1v)
        k3x, k3v = v + h / 2 * k2v, f(x + h / 2 * k2x, v + h / 2 * k2v)
        k4x, k4v = v + h * k3v, f(x + h * k3x, v + h * k3v)
        xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if xn < 0:
            return -(v + x / (x - xn) * (vn - v))
        x, v = xn, vn


alpha_pair, mu_pair = coefficient("pairSpringSliderDashpot", "alpha"), \
    coefficient("pairSpringSliderDashpot", "mu")
alpha_wall, mu_wall = coefficient("wallSpringSliderDashpot", "alpha"), \
    coefficient("wallSpringSliderDashpot", "mu")

t, x, u, w = [], [], [], []
for time, folder in time_directories(case):
    beads = pv.read(folder / "particles.vtu")
    order = np.argsort(beads.point_data["id"])
    t.append(time)
    x.append(np.asarray(beads.points)[order])
    u.append(np.asarray(beads.point_data["U"])[order])
    w.append(np.asarray(beads.point_data["omega"])[order])
    d = float(beads.point_data["d"][0])
t, x, u, w = map(np.array, (t, x, u, w))
r = d / 2

# before (t = 0) and after (the last time) every impact
e_pair = -(u[-1, 3, 0] - u[-1, 0, 0]) / (u[0, 3, 0] - u[0, 0, 0])
e_wall = -u[-1, 2, 0] / u[0, 2, 0]
e_wall45 = -u[-1, 5, 0] / u[0, 5, 0]
vn, vt = u[0, 5, 0], u[0, 5, 1]                       # the 45 deg wall impact
wall_coulomb = (vt - mu_wall * (1 + e_wall45) * vn, -mu_wall * (1 + e_wall45) * vn / (0.4 * r))
wall_rolling = (5 / 7 * vt, -5 / 7 * vt / r)
n, s = np.array([1, 1]) / np.sqrt(2), np.array([1, -1]) / np.sqrt(2)   # 45 deg pair: normal, slip
vn_pair = u[0, 1, :2] @ n
us_pair = u[0, 1, :2] @ s
normal = (1 + e_pair) / 2 * vn_pair * n


def pair(jt):
    """The 45 deg target's (U_x, U_y, omega_z) for a tangential impulse per mass jt."""
    target = normal + jt * s
    return target[0], target[1], jt / (0.4 * r)


pair_coulomb = pair(mu_pair * (1 + e_pair) / 2 * vn_pair)
pair_rolling = pair(us_pair / 7)

e_pair_theory, e_wall_theory = restitution(alpha_pair), restitution(alpha_wall)
print(f"Impacts: {x.shape[1]} beads of d = {1e3 * d:g} mm at 1 m/s; pair alpha {alpha_pair:g}, "
      f"mu {mu_pair:g}; wall alpha {alpha_wall:g}, mu {mu_wall:g}")
rows = [
    ("pair head-on: restitution", e_pair, e_pair_theory, None),
    ("wall normal: restitution", e_wall, e_wall_theory, None),
    ("wall 45 deg: restitution", e_wall45, e_wall_theory, None),
    ("wall 45 deg: tangential velocity (m/s)", u[-1, 5, 1], wall_coulomb[0], wall_rolling[0]),
    ("wall 45 deg: spin (rad/s)", w[-1, 5, 2], wall_coulomb[1], wall_rolling[1]),
    ("pair 45 deg: target U.x (m/s)", u[-1, 4, 0], pair_coulomb[0], pair_rolling[0]),
    ("pair 45 deg: target U.y (m/s)", u[-1, 4, 1], pair_coulomb[1], pair_rolling[1]),
    ("pair 45 deg: spin (rad/s)", w[-1, 4, 2], pair_coulomb[2], pair_rolling[2]),
]
for name, value, first, second in rows:
    if second is None:
        print(f"{name}: {value:.6g}; e(alpha) of the contact's equation {first:.6g} "
              f"({100 * (value / first - 1):+.2f} %)")
    else:
        print(f"{name}: {value:.6g}; Coulomb's mu J_n {first:.6g}, rolling {second:.6g}")
impulse = w[-1, 5, 2] / wall_coulomb[1]
rolling = abs(u[-1, 5, 1] + r * w[-1, 5, 2]) < 1e-3   # the contact point at rest
print(f"wall 45 deg: tangential impulse {impulse:.3f} mu J_n "
      f"({'the slip stopped: rolling' if rolling else 'sliding'})")

fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
labels = ["0 head-on", "1 at 45°", "2 wall, normal", "3 target of 0", "4 target of 1",
          "5 wall, 45°"]
for k, label in enumerate(labels):
    a.plot(1e3 * x[:, k, 0], 1e3 * x[:, k, 1], ".-", ms=3, lw=0.8, label=label)
    a.add_patch(plt.Circle(1e3 * x[0, k, :2], 1e3 * r, fill=False, color="0.4"))
a.axvline(48, color="k", lw=3)
a.set_aspect("equal")
finish(a, "x (mm)", "y (mm)", f"the beads' paths, every {1e3 * (t[1] - t[0]):g} ms "
       "(circles: at t = 0)", legend=dict(fontsize=8, loc="upper center"))

b.plot(1e3 * t, u[:, 3, 0] - u[:, 0, 0], label="pair head-on, $u_3 - u_0$")
b.plot(1e3 * t, -u[:, 2, 0], "--", label="wall, normal, $-u_2$")
b.plot(1e3 * t, -u[:, 5, 0], ":", lw=2, label="wall, 45°, $-u_5$")
b.axhline(e_pair_theory, color="k", lw=0.8, ls="--",
          label=f"e(α = {alpha_pair:g}) = {e_pair_theory:.4f}")
finish(b, "t (ms)", "normal velocity, approaching < 0 (m/s)",
       f"restitution: pair {e_pair:.4f}, wall {e_wall:.4f}", legend=dict(fontsize=9))

c.plot(1e3 * t, u[:, 5, 1], label="wall 45°: bead's tangential velocity $v_y$")
c.plot(1e3 * t, -r * w[:, 5, 2], label="wall 45°: its surface speed $-r\\omega_z$")
c.axhline(wall_coulomb[0], color="tab:red", ls="--", lw=1,
          label=f"Coulomb (friction ≤ μ$J_n$): $v_y$ ≥ {wall_coulomb[0]:.3f}")
c.axhline(wall_rolling[0], color="k", ls=":", lw=1.5,
          label=f"rolling: $v_y = r\\omega$ = {wall_rolling[0]:.3f}")
c.set_ylim(0, 1.05)
finish(c, "t (ms)", "m/s", f"friction at the wall: {impulse:.2f} μ$J_n$",
       legend=dict(fontsize=9, loc="lower left"))
save(fig, case / f"{case.name}.png", dpi=100)
