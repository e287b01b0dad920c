"""Settling of a periodic configuration of spheres in the Rotne-Prager-Yamakawa approximation:
an independent reference for the direct model's free suspensions (tools/sedimentation_sweep.py).

The RPY mobility is the Stokeslet averaged over two sphere surfaces. In Fourier space it is

    M(k) = sinc^2(k a) (I - k k / k^2) / (mu k^2)

(Rotne & Prager, J. Chem. Phys. 50, 4831 (1969); Yamakawa, J. Chem. Phys. 53, 436 (1970); the
Fourier form e.g. Beenakker, J. Chem. Phys. 85, 1581 (1986)), and its periodic sum over the
reciprocal lattice of a cube of side L,

    M_ij = 1/(mu L^3) sum_{k != 0} sinc^2(k a) (I - k k / k^2) / k^2 cos(k . (x_i - x_j)),

is the mobility of N spheres in a periodic box, their images included. Leaving out k = 0 is the
mean pressure gradient that carries the spheres' weight: velocities are relative to the box
mean, the frame of zero volume flux in which fsim's sedimentation monitor measures v_m. The
sum is cut at |k| = K; the self term's tail is added as its continuum integral,
1/(6 pi^2 mu a^2 K), and the pair terms' oscillating tails are left out. At K a = 20 (the
default) a single sphere's mobility is within 2e-4 of Hasimoto's series (tested); pair terms
change by under 3e-4 from K a = 10 to 20.

What RPY leaves out: near-field hydrodynamics (lubrication and the many-body reflections at
gaps below about a radius). It is exact to O(a^3/r^3) in the pair mobility, and its single
sphere in a periodic lattice follows Hasimoto's 1 - 1.7601 phi^{1/3} + phi (tested).

`settling(centres, a, L, phi)` returns, in units of the isolated sphere's Stokes velocity and
for the driving force of a sedimenting suspension ((1 - phi) of the buoyant weight, as in fsim):
- `mobility`: the mean velocity when every sphere carries the same force (a free suspension);
- `resistance`: 1/F of the same spheres held fixed, i.e. moving at one common velocity
  (a fixed random array; Koch & Hill's F).
"""
import math

import numpy as np


def mobility_matrix(centres, a, length, ka_max=20.0, chunk=100_000):
    """The 3N x 3N periodic RPY mobility, times 6 pi mu a (so an isolated sphere's is I)."""
    x = np.asarray(centres, dtype=float)
    n_max = int(math.ceil(ka_max * length / (2 * math.pi * a)))
    r = np.arange(-n_max, n_max + 1)
    k = np.stack(np.meshgrid(r, r, r, indexing="ij"), -1).reshape(-1, 3) * (2 * math.pi / length)
    k2 = (k ** 2).sum(1)
    k_cut = 2 * math.pi * n_max / length
    keep = (k2 > 0) & (k2 <= k_cut ** 2)
    k, k2 = k[keep], k2[keep]
    n = len(x)
    m = np.zeros((n, 3, n, 3))
    for start in range(0, len(k2), chunk):
        kc, k2c = k[start:start + chunk], k2[start:start + chunk]
        ka = np.sqrt(k2c) * a
        weight = (np.sin(ka) / ka) ** 2 / k2c / length ** 3
        phase = x @ kc.T
        c, s = np.cos(phase), np.sin(phase)
        for p in range(3):
            for q in range(p, 3):
                w = weight * ((p == q) - kc[:, p] * kc[:, q] / k2c)
                block = (c * w) @ c.T + (s * w) @ s.T
                m[:, p, :, q] += block
                if q != p:
                    m[:, q, :, p] += block
    m = m.reshape(3 * n, 3 * n) + np.eye(3 * n) / (6 * math.pi ** 2 * a ** 2 * k_cut)
    return m * 6 * math.pi * a


def box_settling(centres, a, box, axis=1, ka_max=20.0, chunk=200_000):
    """Mean velocity along `axis` of equal spheres under equal forces in a periodic box, over
    their Stokes velocity, with the (1 - phi) of a sedimenting suspension's drive: the
    reciprocal-lattice sum of mobility_matrix, for a box of any sides, reduced to the
    structure factor |sum_i exp(i k.x_i)|^2 (only the mean is wanted)."""
    x, box = np.asarray(centres, float), np.asarray(box, float)
    k_max = ka_max / a
    axes = [np.arange(-math.ceil(k_max * s / (2 * math.pi)),
                      math.ceil(k_max * s / (2 * math.pi)) + 1) * 2 * math.pi / s for s in box]
    k = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    k2 = (k ** 2).sum(1)
    keep = (k2 > 0) & (k2 <= k_max ** 2)
    k, k2 = k[keep], k2[keep]
    total = 0.0
    for s in range(0, len(k2), chunk):
        kc, k2c = k[s:s + chunk], k2[s:s + chunk]
        ka = np.sqrt(k2c) * a
        phase = x @ kc.T
        structure = np.cos(phase).sum(0) ** 2 + np.sin(phase).sum(0) ** 2
        total += np.sum((np.sin(ka) / ka) ** 2 / k2c * (1 - kc[:, axis] ** 2 / k2c) * structure)
    # the self term's tail beyond k_max as its continuum integral
    mean = 6 * math.pi * a / box.prod() * total / len(x) + 1 / (math.pi * a * k_max)
    phi = len(x) * 4 / 3 * math.pi * a ** 3 / box.prod()
    return (1 - phi) * mean


def settling(centres, a, length, phi, ka_max=20.0, axes=(0, 1, 2)):
    """Mean settling velocity of a free suspension and 1/F of the fixed array, both over the
    Stokes velocity and averaged over the directions of gravity `axes` (all three: a random
    packing's isotropy; one, for a microstructure that settling has made anisotropic)."""
    m = mobility_matrix(centres, a, length, ka_max)
    n = len(centres)
    mob, res = [], []
    for axis in axes:
        e = np.zeros(3 * n)
        e[axis::3] = 1.0
        mob.append(e @ m @ e / n)
        res.append(n / (e @ np.linalg.solve(m, e)))
    return dict(mobility=(1 - phi) * float(np.mean(mob)),
                resistance=(1 - phi) * float(np.mean(res)))


def main():
    """Ensemble means over random packings (those of the sedimentation sweep) at several N,
    extrapolated to N -> infinity linearly in N^{-1/3}, and the Richardson-Zaki fit."""
    import argparse
    import direct_cases
    ap = argparse.ArgumentParser(description=main.__doc__)
    ap.add_argument("--phi", type=float, nargs="+", default=[0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3])
    ap.add_argument("--particles", type=int, nargs="+", default=[27, 64, 125])
    ap.add_argument("--samples", type=int, default=500, help="spheres per (phi, N): packings = this / N")
    ap.add_argument("--ka-max", type=float, default=10.0)
    a = ap.parse_args()
    inf = []
    for phi in a.phi:
        x, y = [], []
        for count in a.particles:
            length = (count * 4 / 3 * math.pi / phi) ** (1 / 3)
            gap = (0.5 if phi < 0.25 else 0.1) / 3  # the sweep's min gap at r/h = 3, over a
            runs = [settling(direct_cases.periodic_packing([length] * 3, 2.0, count, seed=s,
                                                           min_gap=gap), 1.0, length, phi,
                             a.ka_max)
                    for s in range(1, 1 + max(2, a.samples // count))]
            mob = np.array([r["mobility"] for r in runs])
            fixed = np.mean([r["resistance"] for r in runs])
            print(f"phi {phi:.3f} N {count:4d} ({len(runs)} packings): free {mob.mean():.4f} "
                  f"+- {mob.std(ddof=1) / math.sqrt(len(mob)):.4f}, fixed 1/F {fixed:.4f}",
                  flush=True)
            x.append(count ** (-1 / 3))
            y.append(mob.mean())
        slope, v_inf = np.polyfit(x, y, 1)
        inf.append(v_inf)
        print(f"phi {phi:.3f} N -> infinity: {v_inf:.4f}")
    xs = np.log(1 - np.array(a.phi))
    ys = np.log(inf)
    n, log_v0 = np.polyfit(xs, ys, 1)
    print(f"Richardson-Zaki fit of the extrapolated values: n = {n:.2f}, V_0 = {math.exp(log_v0):.3f}")


if __name__ == "__main__":
    main()
