//! Particle state as structure-of-arrays: one contiguous array per quantity.
//!
//! Vector quantities are `Vec<Vec3>` (nalgebra's `Vector3<f64>`, 24 bytes, `[f64; 3]` in
//! memory): every pair evaluation reads all three components of
//! the same particle, so keeping them in one 24-byte record touches one cache line where three
//! separate component arrays would touch three (faster per pair: docs/benchmarks/dem.md,
//! `examples/dem_layout.rs`). The engine reorders all arrays together (a counting sort by
//! cell at each neighbour-list rebuild), so index `i` names a particle only until the next
//! rebuild; `id` is the permanent name.

use std::f64::consts::PI;

use crate::Vec3;

/// Positions, velocities and loads of every particle (SI units).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParticleState {
    /// Centre, m.
    pub position: Vec<Vec3>,
    /// Translational velocity, m/s.
    pub velocity: Vec<Vec3>,
    /// Angular velocity, rad/s.
    pub angular_velocity: Vec<Vec3>,
    /// Diameter, m.
    pub diameter: Vec<f64>,
    /// Material density, kg/m³.
    pub density: Vec<f64>,
    /// Permanent identifier (unique), kept through reordering and restarts.
    pub id: Vec<u64>,
    /// Fixed particles (porous media) never move; they act on others as infinitely massive.
    pub fixed: Vec<bool>,
    /// Hydrodynamic force set by the coupling, N; held constant over the collision sub-steps.
    pub external_force: Vec<Vec3>,
    /// Hydrodynamic torque set by the coupling, N·m.
    pub external_torque: Vec<Vec3>,
    /// Sum of contact forces from the last force evaluation, N.
    pub contact_force: Vec<Vec3>,
    /// Sum of contact torques from the last force evaluation, N·m.
    pub contact_torque: Vec<Vec3>,
}

impl ParticleState {
    /// An empty state with room for `capacity` particles.
    pub fn with_capacity(capacity: usize) -> Self {
        ParticleState {
            position: Vec::with_capacity(capacity),
            velocity: Vec::with_capacity(capacity),
            angular_velocity: Vec::with_capacity(capacity),
            diameter: Vec::with_capacity(capacity),
            density: Vec::with_capacity(capacity),
            id: Vec::with_capacity(capacity),
            fixed: Vec::with_capacity(capacity),
            external_force: Vec::with_capacity(capacity),
            external_torque: Vec::with_capacity(capacity),
            contact_force: Vec::with_capacity(capacity),
            contact_torque: Vec::with_capacity(capacity),
        }
    }

    /// Appends one free particle at rest with no loads.
    pub fn push(&mut self, id: u64, position: impl Into<Vec3>, diameter: f64, density: f64) {
        self.position.push(position.into());
        self.velocity.push(Vec3::zeros());
        self.angular_velocity.push(Vec3::zeros());
        self.diameter.push(diameter);
        self.density.push(density);
        self.id.push(id);
        self.fixed.push(false);
        self.external_force.push(Vec3::zeros());
        self.external_torque.push(Vec3::zeros());
        self.contact_force.push(Vec3::zeros());
        self.contact_torque.push(Vec3::zeros());
    }

    pub fn len(&self) -> usize {
        self.position.len()
    }

    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Mass `m = ρ π d³ / 6`.
    #[inline]
    pub fn mass(&self, i: usize) -> f64 {
        let d = self.diameter[i];
        self.density[i] * PI * d * d * d / 6.0
    }

    /// Moment of inertia of a solid sphere, `I = m d² / 10`.
    #[inline]
    pub fn moment_of_inertia(&self, i: usize) -> f64 {
        let d = self.diameter[i];
        self.mass(i) * d * d / 10.0
    }

    /// True when every array has the same length.
    pub fn is_consistent(&self) -> bool {
        let n = self.len();
        [
            self.velocity.len(),
            self.angular_velocity.len(),
            self.diameter.len(),
            self.density.len(),
            self.id.len(),
            self.fixed.len(),
            self.external_force.len(),
            self.external_torque.len(),
            self.contact_force.len(),
            self.contact_torque.len(),
        ]
        .iter()
        .all(|&m| m == n)
    }

    /// Bytes held by the particle arrays (capacity, not length).
    pub fn memory_bytes(&self) -> usize {
        let v3 = std::mem::size_of::<Vec3>();
        v3 * (self.position.capacity()
            + self.velocity.capacity()
            + self.angular_velocity.capacity()
            + self.external_force.capacity()
            + self.external_torque.capacity()
            + self.contact_force.capacity()
            + self.contact_torque.capacity())
            + 8 * (self.diameter.capacity() + self.density.capacity() + self.id.capacity())
            + self.fixed.capacity()
    }

    /// Reorders every array so that new index `k` holds old particle `order[k]`.
    /// `scratch3`/`scratch1` are reused buffers so a rebuild allocates nothing once warm.
    pub(crate) fn permute(
        &mut self,
        order: &[u32],
        scratch3: &mut Vec<Vec3>,
        scratch1: &mut Vec<f64>,
    ) {
        fn apply3(a: &mut Vec<Vec3>, order: &[u32], s: &mut Vec<Vec3>) {
            s.clear();
            s.extend(order.iter().map(|&o| a[o as usize]));
            std::mem::swap(a, s);
        }
        fn apply1(a: &mut Vec<f64>, order: &[u32], s: &mut Vec<f64>) {
            s.clear();
            s.extend(order.iter().map(|&o| a[o as usize]));
            std::mem::swap(a, s);
        }
        apply3(&mut self.position, order, scratch3);
        apply3(&mut self.velocity, order, scratch3);
        apply3(&mut self.angular_velocity, order, scratch3);
        apply3(&mut self.external_force, order, scratch3);
        apply3(&mut self.external_torque, order, scratch3);
        apply3(&mut self.contact_force, order, scratch3);
        apply3(&mut self.contact_torque, order, scratch3);
        apply1(&mut self.diameter, order, scratch1);
        apply1(&mut self.density, order, scratch1);
        let ids: Vec<u64> = order.iter().map(|&o| self.id[o as usize]).collect();
        self.id = ids;
        let fixed: Vec<bool> = order.iter().map(|&o| self.fixed[o as usize]).collect();
        self.fixed = fixed;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mass_and_inertia_of_a_sphere() {
        let mut p = ParticleState::default();
        p.push(7, Vec3::zeros(), 2.0, 3.0);
        // m = 3 π 8 / 6 = 4π; I = m d²/10 = 4π·4/10
        assert!((p.mass(0) - 4.0 * PI).abs() < 1e-14);
        assert!((p.moment_of_inertia(0) - 1.6 * PI).abs() < 1e-14);
        assert!(p.is_consistent());
    }

    #[test]
    fn permute_moves_every_array_together() {
        let mut p = ParticleState::default();
        for k in 0..4 {
            p.push(10 + k, [k as f64, 0.0, 0.0], 1.0 + k as f64, 1.0);
        }
        p.fixed[2] = true;
        let (mut s3, mut s1) = (Vec::new(), Vec::new());
        p.permute(&[2, 0, 3, 1], &mut s3, &mut s1);
        assert_eq!(p.id, vec![12, 10, 13, 11]);
        assert_eq!(p.position[0], Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(p.diameter, vec![3.0, 1.0, 4.0, 2.0]);
        assert_eq!(p.fixed, vec![true, false, false, false]);
    }
}
