//! Particle–fluid coupling: the paper's two models.
//!
//! - [`direct`]: resolved particles (grid finer than the spheres), no-slip on each sphere and
//!   the force from the stress integral over its surface (paper §2.1, paper eq. 4–6).
//! - [`drag`]: unresolved particles (grid about the particle size), volume-averaged
//!   Navier–Stokes with fluid fraction ε and a drag closure per particle (paper §2.2,
//!   paper eq. 7–16).

pub mod direct;
pub mod drag;
