//! The pair and wall contacts of one block of particles: what the pass reads
//! ([`ContactContext`]), what one block writes ([`ContactWork`]) and the evaluation itself
//! ([`evaluate_chunk`]).

use super::contact_model::ContactLaw;
use super::domain_box::{minimum_image, DomainBox};
use super::neighbour_list::{wall_distance, wall_normal};
use crate::Vec3;

/// Read-only inputs of the pair pass.
pub(super) struct ContactContext<'a> {
    pub(super) x: &'a [Vec3],
    pub(super) v: &'a [Vec3],
    pub(super) w: &'a [Vec3],
    pub(super) radius: &'a [f64],
    pub(super) inv_m: &'a [f64],
    pub(super) row_start: &'a [u32],
    pub(super) partner: &'a [u32],
    pub(super) wall_start: &'a [u32],
    pub(super) wall_face: &'a [u8],
    pub(super) domain: &'a DomainBox,
    pub(super) length: Vec3,
    pub(super) inv_l: Vec3,
    pub(super) wall_law: Option<ContactLaw>,
    pub(super) dt: f64,
}

/// What one block of particles `p0..p1` writes: its contacts' springs and wall loads, its far
/// pairs' loads, its particles' sums and the next block's "from the previous block" sums.
pub(super) struct ContactWork<'a> {
    pub(super) p0: usize,
    pub(super) p1: usize,
    pub(super) block: usize,
    pub(super) hist: &'a mut [Vec3],
    pub(super) far: &'a mut [[f64; 6]],
    pub(super) whist: &'a mut [Vec3],
    pub(super) wforce: &'a mut [Vec3],
    pub(super) wtorque: &'a mut [Vec3],
    pub(super) own: &'a mut [[f64; 6]],
    pub(super) next: Option<&'a mut [[f64; 6]]>,
}

/// Pair and wall contacts of one chunk. `PERIODIC = false` skips the minimum image.
#[inline(always)]
pub(super) fn evaluate_chunk<const PERIODIC: bool, L>(
    wk: &mut ContactWork,
    c: &ContactContext,
    pair_force: &L,
) where
    L: Fn(Vec3, f64, f64, f64, f64, Vec3, f64, &mut Vec3) -> (Vec3, Vec3),
{
    let (x, v, w, radius, inv_m) = (c.x, c.v, c.w, c.radius, c.inv_m);
    let k0 = c.row_start[wk.p0] as usize;
    let w0 = c.wall_start[wk.p0] as usize;
    let dt = c.dt;
    let (p0, p1) = (wk.p0, wk.p1);
    // partners at or beyond `far_from` are far (the rule `NeighbourList::build` uses)
    let far_from = p0 + 2 * wk.block;
    wk.own.fill([0.0; 6]);
    if let Some(next) = wk.next.as_deref_mut() {
        next.fill([0.0; 6]);
    }
    let mut far_k = 0;
    for i in p0..p1 {
        let (xi, vi, wi, ri) = (x[i], v[i], w[i], radius[i]);
        for k in c.row_start[i] as usize..c.row_start[i + 1] as usize {
            let j = c.partner[k] as usize;
            let kk = k - k0;
            let far = j >= far_from;
            let mut d = Vec3::new(xi[0] - x[j][0], xi[1] - x[j][1], xi[2] - x[j][2]);
            if PERIODIC {
                d = minimum_image(d, c.length, c.inv_l);
            }
            let rj = radius[j];
            let reach = ri + rj;
            let dist2 = d.dot(&d);
            if dist2 >= reach * reach {
                // most listed pairs stay apart: read before writing saves bandwidth
                if far {
                    if wk.far[far_k] != [0.0; 6] {
                        wk.far[far_k] = [0.0; 6];
                    }
                    far_k += 1;
                }
                if wk.hist[kk] != Vec3::zeros() {
                    wk.hist[kk] = Vec3::zeros();
                }
                continue;
            }
            let dist = dist2.sqrt();
            let nrm = d * (1.0 / dist);
            let delta = reach - dist;
            let u = Vec3::new(vi[0] - v[j][0], vi[1] - v[j][1], vi[2] - v[j][2]);
            let u_n = u.dot(&nrm);
            let spin = Vec3::new(
                ri * wi[0] + rj * w[j][0],
                ri * wi[1] + rj * w[j][1],
                ri * wi[2] + rj * w[j][2],
            );
            let sc = spin.cross(&nrm);
            let slip = Vec3::new(
                u[0] - u_n * nrm[0] - sc[0],
                u[1] - u_n * nrm[1] - sc[1],
                u[2] - u_n * nrm[2] - sc[2],
            );
            let m_eff = 1.0 / (inv_m[i] + inv_m[j]);
            let r_eff = ri * rj / reach;
            let (f, ft) = pair_force(nrm, delta, r_eff, m_eff, u_n, slip, dt, &mut wk.hist[kk]);
            let tq = nrm.cross(&ft);
            let load = [f[0], f[1], f[2], -tq[0], -tq[1], -tq[2]];
            add_load(&mut wk.own[i - p0], load, 1.0);
            if j < p1 {
                add_load(&mut wk.own[j - p0], load, -1.0);
            } else if !far {
                let next = wk.next.as_deref_mut().expect("a partner in the next block");
                add_load(&mut next[j - p1], load, -1.0);
            } else {
                wk.far[far_k] = load;
                far_k += 1;
            }
        }
        if let Some(law) = c.wall_law {
            for m in c.wall_start[i] as usize..c.wall_start[i + 1] as usize {
                let mm = m - w0;
                let f = c.wall_face[m] as usize;
                let delta = ri - wall_distance(c.domain, f, xi);
                if delta <= 0.0 {
                    wk.whist[mm] = Vec3::zeros();
                    wk.wforce[mm] = Vec3::zeros();
                    wk.wtorque[mm] = Vec3::zeros();
                    continue;
                }
                let nrm = wall_normal(f);
                // relative to the wall's own motion (exactly vi for a wall at rest)
                let uw = c.domain.wall_velocity[f];
                let vr = Vec3::new(vi[0] - uw[0], vi[1] - uw[1], vi[2] - uw[2]);
                let u_n = vr.dot(&nrm);
                let sc = (wi * ri).cross(&nrm);
                let slip = Vec3::new(
                    vr[0] - u_n * nrm[0] - sc[0],
                    vr[1] - u_n * nrm[1] - sc[1],
                    vr[2] - u_n * nrm[2] - sc[2],
                );
                let (fw, ft) = law.force(
                    nrm,
                    delta,
                    ri,
                    1.0 / inv_m[i],
                    u_n,
                    slip,
                    dt,
                    &mut wk.whist[mm],
                );
                wk.wforce[mm] = fw;
                wk.wtorque[mm] = nrm.cross(&ft) * (-ri);
            }
        }
    }
}

/// Adds a pair load to a particle's sum: the force with `sign` (+ owner, − partner), the
/// torque per unit radius `−n × F_t` as it is (the same for both).
#[inline(always)]
fn add_load(sum: &mut [f64; 6], load: [f64; 6], sign: f64) {
    for a in 0..3 {
        sum[a] += sign * load[a];
        sum[a + 3] += load[a + 3];
    }
}
