#!/usr/bin/env python3
"""The hand references of issue 42's cross-check cases (stdlib only), with DPMFoam v1912's
force equations as its sources state them (docs in each case's README.md):

    tools/force_crosscheck_references.py [settlingAddedMass|liquidFluidizedBed|shearLift|
                                          nonSphereSettling ...]

- settlingAddedMass: one sphere from rest, Schiller-Naumann drag, buoyancy and added mass,
  (rho_p + Cvm rho_f) dv/dt = (rho_p - rho_f) g - (18 mu / d^2) (1 + 0.15 Re^0.687) v,
  the fluid at rest (its DUc/Dt = 0), integrated by RK4: v(t), the initial acceleration and
  the terminal velocity.
- liquidFluidizedBed: Richardson-Zaki's fluidization correlation U / U_i = eps^n with the
  bead's Schiller-Naumann terminal velocity U_t, n from Richardson & Zaki (1954) with their
  wall term and from Garside & Al-Dibouni (1977), log10 U_i = log10 U_t - d/D.
- shearLift: one sphere settling in the linear shear u_z = gamma (x - x0): the steady slip
  (s_x, s_z) where drag balances buoyant weight and SaffmanMeiLiftForce (or TomiyamaLift),
  and the lateral drift velocity it gives.
- nonSphereSettling: nonSphereDrag's Haider & Levenspiel (1989) balance, the terminal
  velocity of a particle of volume-equivalent diameter d and sphericity phi.
"""
import math
import sys

G = 9.81


def schiller_naumann_cdre(re):
    """DPMFoam's sphereDrag: Cd Re = 24 (1 + 0.15 Re^0.687) below Re = 1000, 0.44 Re above."""
    return 24.0 * (1.0 + 0.15 * re ** 0.687) if re < 1000 else 0.44 * re


def haider_levenspiel_cdre(re, phi):
    """DPMFoam's nonSphereDrag (Haider & Levenspiel 1989, eq. 10-11): Cd Re."""
    a = math.exp(2.3288 - 6.4581 * phi + 2.4486 * phi ** 2)
    b = 0.0964 + 0.5565 * phi
    c = math.exp(4.905 - 13.8944 * phi + 18.4222 * phi ** 2 - 10.2599 * phi ** 3)
    d = math.exp(1.4681 + 12.2584 * phi - 20.7322 * phi ** 2 + 15.8855 * phi ** 3)
    return 24.0 * (1.0 + a * re ** b) + re * c / (1.0 + d / re) if re > 0 else 24.0


def drag_rate(v, d, rho_p, rho_f, nu, cdre):
    """The drag's Sp / m (1/s) at slip speed v: 0.75 mu Cd Re / (rho_p d^2)."""
    re = abs(v) * d / nu
    return 0.75 * rho_f * nu * cdre(re) / (rho_p * d * d)


def terminal(d, rho_p, rho_f, nu, cdre=schiller_naumann_cdre):
    """The speed where drag balances buoyant weight (bisection)."""
    w = G * (1 - rho_f / rho_p)
    lo, hi = 0.0, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if drag_rate(mid, d, rho_p, rho_f, nu, cdre) * mid < w:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


# ----- settlingAddedMass ---------------------------------------------------------------------

def added_mass_history(d, rho_p, rho_f, nu, cvm, t_end, dt=1e-6, every=1e-3):
    """[(t, v)] of the sphere from rest, v > 0 downward, RK4 with step dt."""
    mass_eff = 1.0 + cvm * rho_f / rho_p           # per unit particle mass
    w = G * (1 - rho_f / rho_p)

    def acc(v):
        return (w - drag_rate(v, d, rho_p, rho_f, nu, schiller_naumann_cdre) * v) / mass_eff

    out, t, v = [(0.0, 0.0)], 0.0, 0.0
    n = round(t_end / dt)
    k_every = round(every / dt)
    for k in range(1, n + 1):
        a1 = acc(v)
        a2 = acc(v + 0.5 * dt * a1)
        a3 = acc(v + 0.5 * dt * a2)
        a4 = acc(v + dt * a3)
        v += dt * (a1 + 2 * a2 + 2 * a3 + a4) / 6
        t = k * dt
        if k % k_every == 0:
            out.append((t, v))
    return out


def settling_added_mass(d=1e-3, rho_p=1500.0, rho_f=1000.0, nu=1e-6, cvm=0.5):
    hist = added_mass_history(d, rho_p, rho_f, nu, cvm, 0.3)
    plain = added_mass_history(d, rho_p, rho_f, nu, 0.0, 0.3)
    vt = terminal(d, rho_p, rho_f, nu)
    a0 = G * (rho_p - rho_f) / (rho_p + cvm * rho_f)
    print(f"settlingAddedMass: d = {d} m, rho_p = {rho_p}, Cvm = {cvm}")
    print(f"  initial acceleration g (rho_p - rho_f) / (rho_p + Cvm rho_f) = {a0:.5f} m/s2 "
          f"(without added mass {G * (rho_p - rho_f) / rho_p:.5f})")
    print(f"  terminal velocity {vt:.6f} m/s, Re = {vt * d / nu:.2f}")
    print("  t (s)   v with added mass   v without (m/s)")
    for (t, v), (_, v0) in zip(hist, plain):
        if round(t * 1000) in (1, 2, 4, 6, 10, 20, 50, 100, 150, 200, 300):
            print(f"  {t:.3f}   {v:.6f}   {v0:.6f}")
    return hist, vt, a0


# ----- liquidFluidizedBed --------------------------------------------------------------------

def richardson_zaki_n(re_t, d_over_D):
    """Richardson & Zaki (1954), with their wall term d/D."""
    if re_t < 0.2:
        return 4.65 + 19.5 * d_over_D
    if re_t < 1:
        return (4.35 + 17.5 * d_over_D) * re_t ** -0.03
    if re_t < 200:
        return (4.45 + 18 * d_over_D) * re_t ** -0.1
    if re_t < 500:
        return 4.45 * re_t ** -0.1
    return 2.39


def garside_al_dibouni_n(re_t):
    """(5.1 - n) / (n - 2.7) = 0.1 Re_t^0.9."""
    x = 0.1 * re_t ** 0.9
    return (5.1 + 2.7 * x) / (1 + x)


def wen_yu_porosity(u, d, rho_p, rho_f, nu):
    """The porosity of a uniform bed whose beads float under DPMFoam's WenYuDrag at the
    superficial velocity u: Sp = (m/rho_p) 0.75 Cd Re(alpha Re) mu alpha^-3.65 / d^2 on the
    interstitial slip u/alpha balances the buoyant weight, so
    0.75 mu Cd Re(u d/nu) u alpha^-4.65 / d^2 = (rho_p - rho_f) g."""
    lhs = 0.75 * rho_f * nu * schiller_naumann_cdre(u * d / nu) * u / d ** 2
    return (lhs / ((rho_p - rho_f) * G)) ** (1 / 4.65)


def liquid_fluidized_bed(u, d=2e-3, rho_p=2500.0, rho_f=1000.0, nu=1e-6, D=16e-3,
                         n_beads=None, area=None, walls=True):
    """walls=False: the sides are symmetry planes, no wall term (d/D = 0)."""
    D = D if walls else math.inf
    vt = terminal(d, rho_p, rho_f, nu)
    re_t = vt * d / nu
    ui = vt * 10 ** (-d / D)
    print(f"liquidFluidizedBed: d = {d} m, U = {u} m/s, U_t = {vt:.5f} m/s (Re_t = {re_t:.1f}), "
          f"d/D = {d / D:.3f}, U_i = U_t 10^(-d/D) = {ui:.5f} m/s "
          f"({'no-slip walls' if walls else 'symmetry sides: no wall term'})")
    out = {}
    n_rz = richardson_zaki_n(re_t, d / D)
    fits = [("Richardson-Zaki", n_rz, ui)]
    if walls:
        fits.append(("Richardson-Zaki without the wall's U_i", n_rz, vt))
    fits.append(("Garside-Al-Dibouni", garside_al_dibouni_n(re_t), vt))
    for name, n, u0 in fits:
        eps = (u / u0) ** (1 / n)
        line = f"  {name}: n = {n:.3f}, porosity {eps:.4f}, solid fraction {1 - eps:.4f}"
        if n_beads and area:
            h = n_beads * math.pi * d ** 3 / 6 / ((1 - eps) * area)
            line += f", bed height {1000 * h:.2f} mm, mean bead height {500 * h:.2f} mm"
        print(line)
        out[name] = eps
    eps = wen_yu_porosity(u, d, rho_p, rho_f, nu)
    line = f"  WenYuDrag's own uniform bed: porosity {eps:.4f}, solid fraction {1 - eps:.4f}"
    if n_beads and area:
        h = n_beads * math.pi * d ** 3 / 6 / ((1 - eps) * area)
        line += f", bed height {1000 * h:.2f} mm, mean bead height {500 * h:.2f} mm"
    print(line)
    out["WenYuDrag"] = eps
    return out


# ----- shearLift -----------------------------------------------------------------------------

def saffman_mei_cl(re, rew):
    """SaffmanMeiLiftForce's Cl (Saffman 1965, Mei 1992)."""
    beta = 0.5 * rew / re
    alpha = 0.3314 * math.sqrt(beta)
    f = (1 - alpha) * math.exp(-0.1 * re) + alpha
    cld = 6.46 * f if re < 40 else 6.46 * 0.0524 * math.sqrt(beta * re)
    return 3 / (2 * math.pi * math.sqrt(rew)) * cld


def tomiyama_cl(re, eo_d):
    """TomiyamaLift's Cl at the modified Eotvos number Eo_d."""
    f = 0.00105 * eo_d ** 3 - 0.0159 * eo_d ** 2 - 0.0204 * eo_d + 0.474
    if eo_d <= 4:
        return min(0.288 * math.tanh(0.121 * re), f)
    return f if eo_d <= 10 else -0.27


def shear_lift(gamma, d=1e-3, rho_p=1100.0, rho_f=1000.0, nu=1e-6, lift="SaffmanMei",
               sigma=0.07):
    """Steady slip s = Uc - U = (s_x, 0, s_z) of a sphere in u_z = gamma (x - x0) under gravity
    -z: z: Sp s_z - m (1 - rho_f/rho_p) g + lift_z = 0; x: Sp s_x + lift_x = 0, with
    lift = m rho_f/rho_p Cl (s x curl u), curl u = (0, -gamma, 0):
    s x curl u = (gamma s_z, 0, -gamma s_x). The drift velocity is U_x = -s_x."""
    w = G * (1 - rho_f / rho_p)
    rew = gamma * d * d / nu
    sx, sz = 0.0, terminal(d, rho_p, rho_f, nu)
    for _ in range(200):
        s = math.hypot(sx, sz)
        re = s * d / nu
        if lift == "SaffmanMei":
            cl = saffman_mei_cl(re, rew)
        else:
            # Tomiyama: Eo = g (rho_p - rho_f) d^2 / sigma, d_H = d (1 + 0.163 Eo^0.757)^(1/3);
            # Eo_d as Eo with d_H (DPMFoam weights g by the particle's direction of motion;
            # here the motion is nearly along g, the weight 1)
            eo = G * abs(rho_p - rho_f) * d * d / sigma
            dh = d * (1 + 0.163 * eo ** 0.757) ** (1 / 3)
            cl = tomiyama_cl(re, G * abs(rho_p - rho_f) * dh * dh / sigma)
        k = drag_rate(s, d, rho_p, rho_f, nu, schiller_naumann_cdre)   # Sp / m
        lift_coef = rho_f / rho_p * cl * gamma                         # lift / (m slip)
        sx_new = -lift_coef * sz / k
        sz_new = (w - lift_coef * sx_new) / k        # lift_z = -m rho_f/rho_p Cl gamma s_x
        sx, sz = sx_new, sz_new
    re = math.hypot(sx, sz) * d / nu
    print(f"shearLift ({lift}): d = {d} m, rho_p = {rho_p}, gamma = {gamma} 1/s, "
          f"Re_shear = {rew:.3f}")
    print(f"  slip: settling s_z = {sz:.6f} m/s (Re = {re:.3f}), Cl = {cl:.5f}, "
          f"lateral drift U_x = {-sx:.6e} m/s")
    return -sx, sz, cl


# ----- nonSphereSettling ---------------------------------------------------------------------

def non_sphere_settling(phi, d=1e-3, rho_p=2500.0, rho_f=1000.0, nu=1e-6):
    vt = terminal(d, rho_p, rho_f, nu, lambda re: haider_levenspiel_cdre(re, phi))
    vs = terminal(d, rho_p, rho_f, nu)
    vh1 = terminal(d, rho_p, rho_f, nu, lambda re: haider_levenspiel_cdre(re, 1.0))
    print(f"nonSphereSettling: d = {d} m, rho_p = {rho_p}, phi = {phi}")
    print(f"  Haider-Levenspiel terminal velocity {vt:.6f} m/s (Re = {vt * d / nu:.2f}); "
          f"a sphere: Schiller-Naumann {vs:.6f}, Haider-Levenspiel phi = 1 {vh1:.6f} m/s")
    return vt


CASES = {
    "settlingAddedMass": lambda: settling_added_mass(),
    "liquidFluidizedBed": lambda: (
        liquid_fluidized_bed(0.06, n_beads=588, area=16e-3 ** 2, walls=False),
        liquid_fluidized_bed(0.06, n_beads=588, area=16e-3 ** 2, walls=True)),
    "shearLift": lambda: (shear_lift(10.0), shear_lift(10.0, lift="Tomiyama")),
    "nonSphereSettling": lambda: non_sphere_settling(0.7),
}

if __name__ == "__main__":
    for name in sys.argv[1:] or list(CASES):
        CASES[name]()
