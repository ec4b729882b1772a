//! Several wheels of a vehicle on one rail in every direction
//! (`vehicle.wheels` with `dynamics.directions = "all"`): each wheel's
//! contact closed in three directions per harmonic as
//! [`super::coupling::contact_point`], the wheels coupled through the rail head's
//! transfer receptances in three directions (the multiple-wheel
//! moving-irregularity model of [`super::vehicle`], Wu and Thompson 2005,
//! Nielsen 2003, extended to the tangential directions).
//!
//! # Equations
//! Wheel `j` runs `s_j` behind the leading one. Unknowns: the forces on
//! the wheels at their contacts `f_j = (F_x, F_y, -N)_j`; the contact
//! points' relative displacement at wheel `j` is
//! ```text
//! d_j = A_w,j f_j + sum_l A_r(x_j; x_l) f_l,                             (1)
//! ```
//! `A_r(x_j; x_l)` the head's displacement at wheel `j`'s place per unit
//! force at wheel `l`'s (the point receptance for `l = j`), `x_j = x - s_j`
//! for the leading wheel at `x`. Each wheel's contact law
//! ([`super::coupling::contact_point`] eq. 1, its own mean loads): `N_j = k_H,j (r_j +
//! d_j,z)`, `xi_j = (i w / V) d_j,xy`, `(F_x, F_y)_j = C_N,j N_j + C_xi,j
//! xi_j`: a `3n x 3n` linear system per harmonic and place, solved for a
//! unit input `r_j` at each wheel. A profile harmonic reaches wheel `j` as
//! wheel `i` meets it times `exp(i k (s_i - s_j))`, as in
//! [`super::vehicle`] eq. 1, and each wheel sees the profile through its
//! own patch and its own parametric path (the static deflection under all
//! the wheels' loads, [`super::vehicle::parametric_paths`]).
//!
//! Limits: far apart (`A_r(x_j; x_l) -> 0`) each wheel is the single
//! wheel's [`super::contact_dynamics::ContactDynamics`]; without creep
//! slopes the normal forces are the vertical coupled model's with the
//! head's vertical receptances.

use super::contact_dynamics::{ContactSignals, Rail3, WheelSide};
use super::coupling::contact_point::ContactLaw;
use super::coupling::creep_response::CreepResponse;
use super::discrete_dynamics::harmonics;
use super::track::discrete3::Discrete3Error;
use super::track::section::Mat4;
use super::vehicle::{BAY_PLACES, bay_place, inputs_as_met, parametric_paths, static_receptances};
use super::{ContactVariations, TrackDynamics};
use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;

/// One wheel of the vehicle in every direction.
#[derive(Debug, Clone)]
pub struct VehicleWheel3 {
    /// Distance behind the leading wheel (m).
    pub behind: f64,
    /// The wheel's receptance at its contact.
    pub side: WheelSide,
    /// Its contact at its mean loads (the steady slopes).
    pub law: ContactLaw,
    /// The creep forces' frequency response replacing the steady slopes,
    /// if any.
    pub response: Option<CreepResponse>,
    /// Mean normal force (N), for the parametric excitation.
    pub mean_load: f64,
    /// The rail it runs on: 0 the first, 1 the second rail of the
    /// wheelset (its wheel 1; a wheel on the second rail at the same
    /// `behind` as one on the first is the same wheelset's other wheel).
    pub rail: usize,
}

/// The channels of [`ContactSignals`], in the table's order.
const CHANNELS: usize = 5;

/// Several wheels' contact dynamics at one speed over one periodic
/// stretch, tabulated.
#[derive(Debug, Clone)]
pub struct ContactVehicle {
    rail: Rail3,
    wheels: Vec<VehicleWheel3>,
    /// Speed (m/s) and stretch (nodes, spacing) of the table.
    key: (f64, usize, f64),
    /// Per harmonic `n = 1..=n_max` (outer) and place of the leading wheel
    /// (inner: [`BAY_PLACES`] over a bay on the discrete track, one on the
    /// continuous), the responses: row `CHANNELS i + c` (channel `c` of
    /// wheel `i`: normal force, longitudinal force, longitudinal and
    /// lateral creepage) per unit input at wheel `j` (column).
    table: Vec<Vec<DMatrix<Complex64>>>,
    /// Each wheel's parametric path on the discrete track (m), at its own
    /// positions of the stretch.
    paths: Vec<Vec<f64>>,
}

impl ContactVehicle {
    /// Tabulates the responses of `wheels` (the first the leading one,
    /// `behind` 0) for a stretch of `nodes` samples every `dx` (m) at
    /// `speed` (m/s, > 0) in parallel over the harmonics.
    pub fn new(
        rail: Rail3,
        wheels: Vec<VehicleWheel3>,
        nodes: usize,
        dx: f64,
        speed: f64,
    ) -> Result<Self, Discrete3Error> {
        assert!(speed > 0.0, "the vehicle runs forwards (speed = {speed} m/s)");
        let length = nodes as f64 * dx;
        let n = wheels.len();
        let table = (1..=harmonics(nodes, dx, speed))
            .into_par_iter()
            .map(|h| {
                let w = 2.0 * PI * h as f64 * speed / length;
                // The wheels' blocks: each wheel's point receptance, and
                // between the two wheels of one wheelset (the same place,
                // two rails) the wheelset's transfer receptance.
                let own: Vec<Mat4> = (0..n * n)
                    .map(|p| {
                        let (j, l) = (&wheels[p / n], &wheels[p % n]);
                        if p / n == p % n {
                            j.side.receptance_between(w, speed, j.rail, j.rail)
                        } else if j.behind == l.behind && j.rail != l.rail {
                            j.side.receptance_between(w, speed, j.rail, l.rail)
                        } else {
                            Mat4::zeros()
                        }
                    })
                    .collect();
                let laws: Vec<ContactLaw> = wheels
                    .iter()
                    .map(|c| c.response.as_ref().map_or(c.law, |r| c.law.at_frequency(&r.at(w / (2.0 * PI)))))
                    .collect();
                // Per place, the rail's [j][l] blocks (with the rotation
                // about z where a wheel's law has the spin's channel).
                let spin = laws.iter().any(|l| l.force_per_spin.is_some());
                let rails: Vec<Vec<Mat4>> = match &rail {
                    Rail3::Continuous(model) => {
                        // The head's displacement at x_j = -s_j under a force
                        // at x_l = -s_l: distance s_l - s_j.
                        let distances: Vec<f64> =
                            (0..n * n).map(|p| wheels[p % n].behind - wheels[p / n].behind).collect();
                        vec![model.heads(w, &distances, spin)?]
                    }
                    Rail3::Discrete { model, .. } => {
                        let d = model.section.track.sleeper_spacing;
                        let pairs: Vec<(f64, f64)> = (0..BAY_PLACES)
                            .flat_map(|p| {
                                let x = d * p as f64 / BAY_PLACES as f64;
                                let wheels = &wheels;
                                (0..n * n).map(move |q| (x - wheels[q % n].behind, x - wheels[q / n].behind))
                            })
                            .collect();
                        model.heads(&pairs, w, spin)?.chunks(n * n).map(|c| c.to_vec()).collect()
                    }
                };
                // The two rails are not coupled (their sleepers' rocking
                // is left out); the second rail is the first's mirror image
                // in the common axes (y to the right): M A M, M = diag(1, -1,
                // 1, -1) (the rotation about z, an axial vector, changes
                // sign in a mirror that keeps z).
                let rails: Vec<Vec<Mat4>> = rails
                    .into_iter()
                    .map(|blocks| {
                        blocks
                            .into_iter()
                            .enumerate()
                            .map(|(p, a)| match (wheels[p / n].rail, wheels[p % n].rail) {
                                (0, 0) => a,
                                (1, 1) => mirror(&a),
                                _ => Mat4::zeros(),
                            })
                            .collect()
                    })
                    .collect();
                Ok(rails.iter().map(|a_r| solve(&own, a_r, &laws, w, speed)).collect())
            })
            .collect::<Result<Vec<_>, Discrete3Error>>()?;
        // Each rail's wheels' paths under that rail's loads.
        let mut paths = vec![vec![0.0; nodes]; n];
        if let Rail3::Discrete { vertical, sleeper_x0, .. } = &rail {
            for r in 0..2 {
                let on: Vec<usize> = (0..n).filter(|&i| wheels[i].rail == r).collect();
                if on.is_empty() {
                    continue;
                }
                let behind: Vec<f64> = on.iter().map(|&i| wheels[i].behind).collect();
                let loads: Vec<f64> = on.iter().map(|&i| wheels[i].mean_load).collect();
                let statics = static_receptances(vertical, &behind);
                let rail_paths = parametric_paths(&statics, vertical.spacing, &behind, &loads, *sleeper_x0, nodes, dx);
                for (i, p) in on.into_iter().zip(rail_paths) {
                    paths[i] = p;
                }
            }
        }
        Ok(ContactVehicle { rail, wheels, key: (speed, nodes, dx), table, paths })
    }

    /// Each wheel's contact variations along one period of the profile it
    /// sees (`profiles[wheel]`, m, rail top up, sampled every `dx`), eq. 1,
    /// with the parametric excitation on the discrete track.
    pub fn signals(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactSignals> {
        let nodes = profiles[0].len();
        assert_eq!(
            (speed, nodes, dx),
            self.key,
            "the contact dynamics is tabulated for one speed and stretch (built with the growth study's)"
        );
        let length = nodes as f64 * dx;
        let s: Vec<f64> = self.wheels.iter().map(|w| w.behind).collect();
        let met = inputs_as_met(profiles, &self.paths, &s, self.table.len(), length);
        met.iter()
            .enumerate()
            .map(|(i, seen)| {
                let mut out = std::array::from_fn::<_, CHANNELS, _>(|_| vec![0.0; nodes]);
                for m in 0..nodes {
                    let x = m as f64 * dx;
                    let (p, q, t) = match &self.rail {
                        Rail3::Discrete { vertical, sleeper_x0, .. } => {
                            bay_place(vertical.spacing, *sleeper_x0, sleeper_x0 + x + s[i])
                        }
                        Rail3::Continuous(_) => (0, 0, 0.0),
                    };
                    for (h, (row, r)) in self.table.iter().zip(seen).enumerate() {
                        let h = h + 1;
                        let phase = Complex64::from_polar(1.0, 2.0 * PI * h as f64 * x / length);
                        let weight = if 2 * h == nodes { 1.0 } else { 2.0 } / nodes as f64;
                        for (c, channel) in out.iter_mut().enumerate() {
                            let mut sum = Complex64::new(0.0, 0.0);
                            for (j, rj) in r.iter().enumerate() {
                                let a = row[p][(CHANNELS * i + c, j)];
                                let b = row[q][(CHANNELS * i + c, j)];
                                sum += ((1.0 - t) * a + t * b) * rj;
                            }
                            channel[m] += weight * (sum * phase).re;
                        }
                    }
                }
                let [normal, force_x, creepage_x, creepage_y, spin] = out;
                ContactSignals { normal, force_x, creepage_x, creepage_y, spin }
            })
            .collect()
    }
}

/// The second rail's block of the first's in the common axes: `M A M`,
/// `M = diag(1, -1, 1, -1)` (the lateral direction mirrored, and with it
/// the rotation about z).
fn mirror(a: &Mat4) -> Mat4 {
    let sign = [1.0, -1.0, 1.0, -1.0];
    Mat4::from_fn(|r, c| a[(r, c)] * (sign[r] * sign[c]))
}

/// Eq. 1 for unit inputs at each wheel: the responses (rows `CHANNELS i +
/// c`, columns the input's wheel) with the wheels' blocks `own[j n + l]`
/// (a wheel's point receptance, or the wheelset's between its two wheels), the
/// rail's blocks `a_r[j n + l]` (at wheel `j` under a force at wheel `l`)
/// and the wheels' laws at angular frequency `omega` (rad/s) and speed
/// `speed` (m/s).
fn solve(own: &[Mat4], a_r: &[Mat4], laws: &[ContactLaw], omega: f64, speed: f64) -> DMatrix<Complex64> {
    let n = laws.len();
    let iwv = Complex64::new(0.0, omega / speed);
    let one = Complex64::new(1.0, 0.0);
    let blocks: Vec<Mat4> = a_r.iter().zip(own).map(|(r, w)| r + w).collect();
    // The relative displacements per force, A (3n x 3n), and the relative
    // rotations about z per force, R (n x 3n).
    let a = DMatrix::from_fn(3 * n, 3 * n, |r, c| blocks[(r / 3) * n + c / 3][(r % 3, c % 3)]);
    let rot = DMatrix::from_fn(n, 3 * n, |j, c| blocks[j * n + c / 3][(3, c % 3)]);
    let mut m = DMatrix::<Complex64>::zeros(3 * n, 3 * n);
    let mut rhs = DMatrix::<Complex64>::zeros(3 * n, n);
    for (j, law) in laws.iter().enumerate() {
        // Rows 3j, 3j+1: F - C_N N - C_xi (i w / V) (A f)_xy = 0, N = -f_z.
        for e in 0..2 {
            let row = 3 * j + e;
            m[(row, row)] += one;
            m[(row, 3 * j + 2)] += law.force_per_normal[e];
            for l in 0..2 {
                let c = law.force_per_creepage[e][l] * iwv;
                for col in 0..3 * n {
                    m[(row, col)] -= c * a[(3 * j + l, col)];
                }
            }
            if let Some(per_spin) = law.force_per_spin {
                let c = per_spin[e] * iwv;
                for col in 0..3 * n {
                    m[(row, col)] -= c * rot[(j, col)];
                }
            }
        }
        // Row 3j+2: (A f)_z + f_z / k_H = -r_j.
        let row = 3 * j + 2;
        for col in 0..3 * n {
            m[(row, col)] = a[(row, col)];
        }
        m[(row, row)] += Complex64::new(1.0 / law.stiffness, 0.0);
        rhs[(row, j)] = -one;
    }
    let f = m.lu().solve(&rhs).expect("the contacts' system is regular for passive wheels and track");
    let d = &a * &f;
    let spins = &rot * &f;
    DMatrix::from_fn(CHANNELS * n, n, |r, j| {
        let (i, c) = (r / CHANNELS, r % CHANNELS);
        match c {
            0 => -f[(3 * i + 2, j)],
            1 => f[(3 * i, j)],
            2 => iwv * d[(3 * i, j)],
            3 => iwv * d[(3 * i + 1, j)],
            _ if laws[i].force_per_spin.is_some() => iwv * spins[(i, j)],
            _ => Complex64::new(0.0, 0.0),
        }
    })
}

impl TrackDynamics for ContactVehicle {
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations> {
        self.signals(profiles, dx, speed).into_iter().map(ContactVariations::Every).collect()
    }

    fn describe_resonances(&self) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        if let Rail3::Discrete { vertical, .. } = &self.rail {
            out.push(("pinned-pinned: the rail between two sleepers".into(), vertical.pinned_pinned_frequency()));
        }
        out
    }

    fn forces_smooth_rail(&self) -> bool {
        matches!(self.rail, Rail3::Discrete { .. })
    }

    fn wheels(&self) -> usize {
        self.wheels.len()
    }

    fn rail_of(&self, wheel: usize) -> usize {
        self.wheels[wheel].rail
    }
}
