//! A [`DemSnapshot`] as named `f64` arrays, the form of the restart state (`restart.bin`):
//! vectors flattened `x y z` per particle, ids and face numbers as exact integers in `f64`
//! (ids below 2⁵³), booleans as 0/1. Particles stay in the engine's current order, which a
//! bit-for-bit continuation needs.

use super::dem::DemSnapshot;
use super::neighbour_list::ContactHistory;
use super::particle_state::ParticleState;
use crate::Vec3;

/// Names of the arrays, all prefixed `dem.` so they sit beside the fluid's.
pub const DEM_RESTART_NAMES: [&str; 15] = [
    "dem.position",
    "dem.velocity",
    "dem.angularVelocity",
    "dem.diameter",
    "dem.density",
    "dem.id",
    "dem.fixed",
    "dem.externalForce",
    "dem.externalTorque",
    "dem.contactForce",
    "dem.contactTorque",
    "dem.referencePosition",
    "dem.pairHistory",
    "dem.wallHistory",
    "dem.clock",
];

fn flat(v: &[Vec3]) -> Vec<f64> {
    v.iter().flat_map(|x| x.iter().copied()).collect()
}

fn unflat(v: &[f64]) -> Vec<Vec3> {
    v.chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect()
}

impl DemSnapshot {
    /// The arrays in [`DEM_RESTART_NAMES`] order.
    pub fn to_arrays(&self) -> Vec<(&'static str, Vec<f64>)> {
        let p = &self.particles;
        let pairs: Vec<f64> = self
            .history
            .pairs
            .iter()
            .flat_map(|&(a, b, x)| [a as f64, b as f64, x[0], x[1], x[2]])
            .collect();
        let walls: Vec<f64> = self
            .history
            .walls
            .iter()
            .flat_map(|&(a, f, x)| [a as f64, f as f64, x[0], x[1], x[2]])
            .collect();
        let values = vec![
            flat(&p.position),
            flat(&p.velocity),
            flat(&p.angular_velocity),
            p.diameter.clone(),
            p.density.clone(),
            p.id.iter().map(|&i| i as f64).collect(),
            p.fixed.iter().map(|&f| f as u8 as f64).collect(),
            flat(&p.external_force),
            flat(&p.external_torque),
            flat(&p.contact_force),
            flat(&p.contact_torque),
            flat(&self.reference_position),
            pairs,
            walls,
            vec![self.time, self.steps as f64],
        ];
        DEM_RESTART_NAMES.iter().copied().zip(values).collect()
    }

    /// Reads the arrays back through `get` (by name); the error names the bad array.
    pub fn from_arrays<'a>(get: impl Fn(&str) -> Option<&'a [f64]>) -> Result<DemSnapshot, String> {
        let need = |name: &str| get(name).ok_or_else(|| format!("no array '{name}'"));
        let n = need("dem.diameter")?.len();
        let sized = |name: &str, per: usize| -> Result<&'a [f64], String> {
            let v = need(name)?;
            if v.len() == per * n {
                Ok(v)
            } else {
                Err(format!(
                    "array '{name}' has {} values, expected {}",
                    v.len(),
                    per * n
                ))
            }
        };
        let records = |name: &str| -> Result<&'a [f64], String> {
            let v = need(name)?;
            if v.len() % 5 == 0 {
                Ok(v)
            } else {
                Err(format!("array '{name}' is not made of 5-value records"))
            }
        };
        let particles = ParticleState {
            position: unflat(sized("dem.position", 3)?),
            velocity: unflat(sized("dem.velocity", 3)?),
            angular_velocity: unflat(sized("dem.angularVelocity", 3)?),
            diameter: sized("dem.diameter", 1)?.to_vec(),
            density: sized("dem.density", 1)?.to_vec(),
            id: sized("dem.id", 1)?.iter().map(|&x| x as u64).collect(),
            fixed: sized("dem.fixed", 1)?.iter().map(|&x| x != 0.0).collect(),
            external_force: unflat(sized("dem.externalForce", 3)?),
            external_torque: unflat(sized("dem.externalTorque", 3)?),
            contact_force: unflat(sized("dem.contactForce", 3)?),
            contact_torque: unflat(sized("dem.contactTorque", 3)?),
        };
        let history = ContactHistory {
            pairs: records("dem.pairHistory")?
                .chunks_exact(5)
                .map(|r| (r[0] as u64, r[1] as u64, Vec3::new(r[2], r[3], r[4])))
                .collect(),
            walls: records("dem.wallHistory")?
                .chunks_exact(5)
                .map(|r| (r[0] as u64, r[1] as u8, Vec3::new(r[2], r[3], r[4])))
                .collect(),
        };
        let clock = need("dem.clock")?;
        let [time, steps] = clock else {
            return Err("array 'dem.clock' must hold [time, steps]".to_string());
        };
        Ok(DemSnapshot {
            particles,
            reference_position: unflat(sized("dem.referencePosition", 3)?),
            history,
            time: *time,
            steps: *steps as u64,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_snapshot_survives_the_round_trip_bit_for_bit() {
        let mut p = ParticleState::default();
        p.push(7, [0.1, 0.2, 0.3], 1e-3, 2500.0);
        p.push(3, [0.4, 0.5, 0.6], 2e-3, 1500.0);
        p.velocity[1] = Vec3::new(1.0 / 3.0, -2.5e-7, 9.0);
        p.fixed[0] = true;
        p.contact_force[0] = Vec3::new(f64::MIN_POSITIVE, 1e300, -0.0);
        let s = DemSnapshot {
            reference_position: p.position.clone(),
            particles: p,
            history: ContactHistory {
                pairs: vec![(3, 7, Vec3::new(1e-9, -2e-9, 3e-9))],
                walls: vec![(7, 4, Vec3::new(0.0, 1e-12, 0.0))],
            },
            time: 0.123456789,
            steps: 98765,
        };
        let arrays = s.to_arrays();
        let back = DemSnapshot::from_arrays(|name| {
            arrays
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| v.as_slice())
        })
        .unwrap();
        assert_eq!(back, s);
        assert_eq!(
            back.particles.contact_force[0][2].to_bits(),
            (-0.0f64).to_bits()
        );
        let missing = DemSnapshot::from_arrays(|name| {
            arrays
                .iter()
                .find(|(n, _)| *n == name && name != "dem.velocity")
                .map(|(_, v)| v.as_slice())
        });
        assert_eq!(missing.unwrap_err(), "no array 'dem.velocity'");
    }
}
