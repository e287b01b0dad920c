//! OpenFOAM's `sizeDistribution` of an injection model, sampled in diameter.

use super::scalar_in;
use crate::case::control_dict::choice;
use crate::case::dictionary::Dict;
use crate::case::error::CaseError;
use crate::particles::SplitMix64;

/// OpenFOAM's `sizeDistribution`, sampled in diameter.
#[derive(Clone, Debug)]
pub(super) enum SizeDistribution {
    Fixed(f64),
    Uniform {
        min: f64,
        max: f64,
    },
    Normal {
        mean: f64,
        sd: f64,
        min: f64,
        max: f64,
    },
}

impl SizeDistribution {
    pub(super) fn read(m: &Dict) -> Result<SizeDistribution, CaseError> {
        let s = m.get_dict("sizeDistribution")?;
        let kind = choice(s, "type", &["fixedValue", "uniform", "normal"], None)?;
        let positive = |x: f64| x > 0.0;
        Ok(match kind {
            0 => {
                let c = s.get_dict("fixedValueDistribution")?;
                SizeDistribution::Fixed(scalar_in(c, "value", None, positive, "a diameter > 0")?)
            }
            1 => {
                let c = s.get_dict("uniformDistribution")?;
                let min = scalar_in(c, "minValue", None, positive, "a diameter > 0")?;
                let max = scalar_in(c, "maxValue", None, |x| x >= min, ">= minValue")?;
                SizeDistribution::Uniform { min, max }
            }
            _ => {
                let c = s.get_dict("normalDistribution")?;
                let min = scalar_in(c, "minValue", None, positive, "a diameter > 0")?;
                let max = scalar_in(c, "maxValue", None, |x| x >= min, ">= minValue")?;
                let (mean, sd) = if c.contains("mu") {
                    (
                        c.get_scalar("mu")?,
                        scalar_in(c, "sigma", None, |x| x >= 0.0, ">= 0")?,
                    )
                } else {
                    (
                        c.get_scalar("expectation")?,
                        scalar_in(c, "variance", None, |x| x >= 0.0, ">= 0")?
                            / std::f64::consts::SQRT_2,
                    )
                };
                SizeDistribution::Normal { mean, sd, min, max }
            }
        })
    }

    /// One diameter. The truncated normal is sampled by rejection (Box–Muller), exact for
    /// any window; a window far in the tail falls back to its nearest bound.
    pub(super) fn sample(&self, rng: &mut SplitMix64) -> f64 {
        match *self {
            SizeDistribution::Fixed(d) => d,
            SizeDistribution::Uniform { min, max } => min + rng.next_f64() * (max - min),
            SizeDistribution::Normal { mean, sd, min, max } => {
                for _ in 0..10_000 {
                    let u1 = 1.0 - rng.next_f64();
                    let u2 = rng.next_f64();
                    let z = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
                    let d = mean + sd * z;
                    if (min..=max).contains(&d) {
                        return d;
                    }
                }
                mean.clamp(min, max)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn truncated_normal_has_the_requested_moments() {
        // v1912 form: variance 2e-4 means a standard deviation 2e-4/√2
        let d = SizeDistribution::Normal {
            mean: 1e-3,
            sd: 2e-4 / std::f64::consts::SQRT_2,
            min: 0.0,
            max: 1.0,
        };
        let mut rng = SplitMix64::new(1);
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| d.sample(&mut rng)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!((mean - 1e-3).abs() < 2e-6, "mean {mean}");
        let sd = var.sqrt();
        assert!(
            (sd / (2e-4 / std::f64::consts::SQRT_2) - 1.0).abs() < 0.01,
            "sd {sd}"
        );
        // truncation at the mean keeps the upper half only: mean + sd √(2/π)
        let half = SizeDistribution::Normal {
            mean: 1e-3,
            sd: 1e-4,
            min: 1e-3,
            max: 1.0,
        };
        let m2 = (0..n).map(|_| half.sample(&mut rng)).sum::<f64>() / n as f64;
        let want = 1e-3 + 1e-4 * (2.0 / std::f64::consts::PI).sqrt();
        assert!((m2 - want).abs() < 1e-6, "{m2} vs {want}");
    }

    #[test]
    fn uniform_sizes_fill_their_window_evenly() {
        let d = SizeDistribution::Uniform { min: 1.0, max: 3.0 };
        let mut rng = SplitMix64::new(7);
        let xs: Vec<f64> = (0..100_000).map(|_| d.sample(&mut rng)).collect();
        assert!(xs.iter().all(|x| (1.0..3.0).contains(x)));
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        assert!((mean - 2.0).abs() < 0.01, "mean {mean}");
    }
}
