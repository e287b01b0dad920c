#!/usr/bin/env python3
"""Reference hindered-settling functions U(phi)/U_0 for monodisperse spheres at low Reynolds
number, in the frame of zero volume flux, and the Richardson-Zaki exponent each implies over a
set of volume fractions.

    tools/hindered_settling.py [--phi 0.02 0.05 0.1 0.15 0.2 0.25 0.3]

- `hard_spheres(phi)`: the sedimentation coefficient of *random* (equilibrium hard-sphere)
  configurations, every sphere under the same force, from the exact Stokes hydrodynamics of
  periodic systems extrapolated to infinite size (HYDROMULTIPOLE: Abade, Cichocki,
  Ekiel-Jezewska, Naegele & Wajnryb, J. Chem. Phys. 136, 104902 (2012)), as fitted by Riest,
  Eckert, Richtering & Naegele, Soft Matter 11, 2821 (2015):
  K = 1 - 6.5464 phi (1 - 3.348 phi + 7.426 phi^2 - 10.034 phi^3 + 5.882 phi^4).
  Its phi^2 coefficient, 6.5464 x 3.348 = 21.92, is the exact two- and three-body result
  (Cichocki, Ekiel-Jezewska & Wajnryb, J. Chem. Phys. 117, 1231 (2002)); its phi term is
  Batchelor's 6.55. This is what a solver that settles random packings must reproduce.
- `richardson_zaki(phi, n)`: the experimental correlation, n = 4.65 at Re < 0.2 (Richardson &
  Zaki 1954), 5.1 (Garside & Al-Dibouni 1977). Experiments measure suspensions that have
  settled long enough to build their own pair structure; random packings are not that
  structure (Brzinski & Durian, arXiv:1710.09314, separate the data into a non-Brownian
  branch, n = 4.48, and a Brownian one, 5.6, whose structure is that of equilibrium hard
  spheres).
"""
import argparse
import math

import numpy as np


def hard_spheres(phi):
    """K(phi) of random hard-sphere suspensions (Abade et al. 2012, fit of Riest et al. 2015)."""
    return 1.0 - 6.5464 * phi * (1.0 - 3.348 * phi + 7.426 * phi ** 2 - 10.034 * phi ** 3
                                 + 5.882 * phi ** 4)


def richardson_zaki(phi, n=4.65):
    return (1.0 - phi) ** n


def batchelor(phi):
    """Dilute limit, Batchelor (J. Fluid Mech. 52, 245 (1972))."""
    return 1.0 - 6.55 * phi


def exponent(phi, ratio):
    """Least-squares Richardson-Zaki fits of ratio = V_0/U_0 (1 - phi)^n on the logarithms:
    (n with V_0 free, V_0/U_0) and n with V_0 = U_0."""
    x = np.log(1.0 - np.asarray(phi, dtype=float))
    y = np.log(np.asarray(ratio, dtype=float))
    A = np.stack([np.ones_like(x), x], axis=1)
    (c, n), *_ = np.linalg.lstsq(A, y, rcond=None)
    return float(n), float(math.exp(c)), float(np.sum(x * y) / np.sum(x * x))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--phi", type=float, nargs="+",
                    default=[0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3])
    a = ap.parse_args()
    print(f"{'phi':>6} {'hard spheres':>13} {'RZ 4.65':>8} {'GA 5.1':>8} {'n_eff':>6}")
    for p in a.phi:
        k = hard_spheres(p)
        print(f"{p:6.3f} {k:13.4f} {richardson_zaki(p):8.4f} {richardson_zaki(p, 5.1):8.4f} "
              f"{math.log(k) / math.log(1 - p):6.2f}")
    n, v0, n1 = exponent(a.phi, [hard_spheres(p) for p in a.phi])
    print(f"Richardson-Zaki fit of the hard-sphere reference over these phi: n = {n:.2f} "
          f"(V_0 = {v0:.3f} U_0); with V_0 = U_0: n = {n1:.2f}")


if __name__ == "__main__":
    main()
