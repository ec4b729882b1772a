//! Archard's wear law (J.F. Archard, *Contact and rubbing of flat surfaces*,
//! J. Appl. Phys. 24 (1953) 981-988) in rate form, as in Baeza et al. 2008,
//! Eq. (8): `w_dot = (k/H) p3 |s|`, with `k/H` (m^2/N), the normal pressure
//! `p3` (Pa) and the local slip velocity `|s|` (m/s); `w_dot` in m/s.

use crate::contact::PatchSolution;

/// Archard wear rate (m/s) at every element of a contact solution.
pub fn archard_rates(k_over_h: f64, sol: &PatchSolution) -> Vec<f64> {
    sol.pressure
        .iter()
        .zip(sol.slip_x.iter().zip(&sol.slip_y))
        .map(|(p, (sx, sy))| k_over_h * p.max(0.0) * sx.hypot(*sy))
        .collect()
}
