//! The growth loop's dynamics in every direction (`dynamics.directions =
//! "all"`): the rail head's receptances in three directions (continuous,
//! [`super::track::continuous3`], or discrete, [`super::track::discrete3`], depending on
//! where the wheel is in the sleeper bay), the wheel's, the Hertz spring
//! and the creep forces' slopes closed per harmonic
//! ([`super::coupling::contact_point`]), so that a profile harmonic varies the
//! normal force, the creep forces and the creepages at its own frequency.
//!
//! # Equations
//! Per profile harmonic `r_n exp(i k_n X)` (`w_n = k_n V`) and place `x` in
//! the bay, [`super::coupling::contact_point::respond`] gives the responses `H_c(w_n,
//! x)` of each channel `c` (normal force, longitudinal force, longitudinal
//! and lateral creepage) per unit roughness, and
//! ```text
//! c(X) = sum_n H_c(w_n, x(X)) r_n exp(i k_n X)                      (1)
//! ```
//! with `H` tabulated at [`BAY_PLACES`] places over the whole bay (the
//! cross terms change sign between a bay's halves) and interpolated
//! linearly, as the vertical model of [`super::discrete_dynamics`], whose
//! parametric excitation (the static deflection under the wheel's own
//! load along the bay) the profile includes on the discrete track.
//!
//! **The wheel**: with `[wheelset] model = "modal"` the wheelset's modal
//! model ([`super::wheelset`]: the rigid wheelset on its primary
//! suspension, its flexible modes, the gyroscopic coupling of its spin),
//! the modelled rail's wheel its wheel 0 and the other wheel's creep forces
//! uncorrelated with this rail's profile; otherwise rigid, free above its
//! suspension in every direction, `-1 / (M w^2)` per axis (`M` the unsprung
//! mass per wheel), and its rotation about the axle at the rim: the rigid
//! wheelset's spin (`-r^2 / (2 J w^2)`, both wheels' inertia) or, with the
//! torsional `[wheelset]`, the torsional model's `T(w) V / (i w)`
//! ([`super::wheelset::torsion`] eq. 2).
//!
//! **The contact** at the mean state: the Hertz stiffness and the creep
//! forces' frequency response measured on the passage's own transient
//! solver ([`super::coupling::creep_response`], `dynamics.creep_forces =
//! "transient"`, at each harmonic's frequency), or the steady creep
//! curve's slopes (FASTSIM's, as the torsional feedback's, `"steady"`).
//!
//! **The spin** (`dynamics.spin`, on by default): the rail head's and the
//! wheel tread's rotations about the vertical at the contact (the rail's
//! lateral bending slope `chi`; the modal wheelset's yaw, the axle's
//! horizontal bending, the wheels' axial modes) vary the spin creepage at
//! the harmonic's frequency, and the creep forces answer through the creep
//! response's spin column (or FASTSIM's steady slope): eq. 1 of
//! [`super::coupling::contact_point`] with its spin row. The rigid wheel does not
//! turn about the vertical (its rail head still does).
//!
//! What the passage receives: the normal force's variation, the lateral
//! creepage's, the spin's, and the longitudinal creepage's (creepage
//! control) or force's (force control: the force the dynamics transmits,
//! the creepage the passage's contact solver finds).

use super::coupling::contact_point::{ContactLaw, ContactResponse, respond};
use super::coupling::creep_response::CreepResponse;
use super::discrete_dynamics::{harmonics, parametric_path};
use super::track::continuous3::Continuous3;
use super::track::discrete::DiscreteTrack;
use super::track::discrete3::{Discrete3, Discrete3Error};
use super::track::section::{Mat3, Mat4, pad};
use super::wheelset::torsion::WheelsetTorsion;
use super::wheelset::{Dir, WheelsetModel, dof};
use super::{ContactVariations, TrackDynamics};
use num_complex::Complex64;
use rayon::prelude::*;
use rustfft::FftPlanner;
use std::f64::consts::PI;

/// Places across one sleeper bay (both ends included) at which the
/// discrete track's responses are tabulated (every `d / 16`).
pub const BAY_PLACES: usize = 17;

/// The rail under the wheel.
#[derive(Debug, Clone, Copy)]
pub enum Rail3 {
    /// On continuous (smeared) supports.
    Continuous(Continuous3),
    /// On discrete supports, the stretch's first node above a sleeper at
    /// `sleeper_x0` (m); `vertical` the same track's vertical model, for the
    /// parametric excitation.
    Discrete {
        /// The rail head in three directions.
        model: Discrete3,
        /// The vertical model of the same track.
        vertical: DiscreteTrack,
        /// A sleeper's position along the rail (m).
        sleeper_x0: f64,
    },
}

/// The wheel's side of the contact.
#[derive(Debug, Clone)]
pub enum WheelSide {
    /// The rigid wheel (module docs).
    Rigid(Wheel3),
    /// The wheelset's modal model ([`super::wheelset`]), the modelled
    /// rail's wheel its wheel 0, spinning at `spin` (rad/s, `V / r`), the
    /// other wheel's creep forces uncorrelated with this rail's profile.
    Modal {
        /// The wheelset.
        model: WheelsetModel,
        /// Spin speed (rad/s).
        spin: f64,
    },
}

impl WheelSide {
    /// The wheel's receptance at the contact in the rail's axes (m/N; x
    /// along with the rim's rotation, y across to the right, z down, and
    /// the tread's rotation about z in rad/N, rad/(N m)) at `omega`
    /// (rad/s) and `speed` (m/s). The wheelset's axes have y to the left
    /// and z up: its (x, y, z, psi) block of wheel 0 turns by `S = diag(1,
    /// -1, -1, -1)` on both sides (the rotation about z is an axial vector:
    /// turned half round x it changes sign with z).
    pub fn receptance(&self, omega: f64, speed: f64) -> Mat4 {
        self.receptance_between(omega, speed, 0, 0)
    }

    /// The displacement of wheel `at`'s contact per unit force at wheel
    /// `from`'s (m/N; wheel 0 the first rail's, 1 the second's; both in
    /// the rail's common axes, x along, y to the right, z down): the
    /// modal wheelset's block `S H_(at, from) S` (the point receptance for
    /// `at == from`), with the tread's rotation about z. The rigid wheel has
    /// no second wheel (zero between two) and no rotation about z.
    pub fn receptance_between(&self, omega: f64, speed: f64, at: usize, from: usize) -> Mat4 {
        match self {
            WheelSide::Rigid(w) if at == from => pad(&w.receptance(omega, speed)),
            WheelSide::Rigid(_) => Mat4::zeros(),
            WheelSide::Modal { model, spin } => {
                let h = model.receptance(omega, *spin);
                let sign = [1.0, -1.0, -1.0, -1.0];
                Mat4::from_fn(|a, b| h[(dof(at, DIRECTIONS[a]), dof(from, DIRECTIONS[b]))] * (sign[a] * sign[b]))
            }
        }
    }

    /// The wheel's resonances for reports (label, Hz).
    fn resonances(&self) -> Vec<(String, f64)> {
        match self {
            WheelSide::Rigid(w) => w.torsion.map_or_else(Vec::new, |t| {
                vec![("the wheelset's torsion: the wheels twisting against each other".into(), t.resonance())]
            }),
            // The modes at rest (`check` prints their split while spinning).
            WheelSide::Modal { model, .. } => model
                .modes()
                .iter()
                .filter(|m| m.frequency > 0.0)
                .map(|m| (format!("wheelset: {}", m.name), m.frequency))
                .collect(),
        }
    }
}

/// The wheelset's directions of the rail's x, y, z and the rotation about z.
const DIRECTIONS: [Dir; 4] = [Dir::X, Dir::Y, Dir::Z, Dir::Psi];

/// The wheel at the contact (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel3 {
    /// Unsprung mass per wheel M (kg).
    pub mass: f64,
    /// Rolling radius r (m).
    pub radius: f64,
    /// Polar moment of inertia of one wheel with its half axle J (kg m^2).
    pub polar_inertia: f64,
    /// The wheelset's torsion, where configured.
    pub torsion: Option<WheelsetTorsion>,
}

impl Wheel3 {
    /// The wheel's receptance at the contact (m/N; x along with the rim's
    /// rotation, y across, z down) at `omega` (rad/s) and `speed` (m/s).
    pub fn receptance(&self, omega: f64, speed: f64) -> Mat3 {
        let mass = Complex64::new(-1.0 / (self.mass * omega * omega), 0.0);
        let rotation = match self.torsion {
            Some(t) => t.creepage_per_force(omega, speed) / Complex64::new(0.0, omega / speed),
            None => Complex64::new(-self.radius * self.radius / (2.0 * self.polar_inertia * omega * omega), 0.0),
        };
        Mat3::from_diagonal(&nalgebra::Vector3::new(mass + rotation, mass, mass))
    }
}

/// The dynamic variations of one wheel's contact along the stretch (zero
/// mean), at the profile's samples.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSignals {
    /// Normal force (N).
    pub normal: Vec<f64>,
    /// Longitudinal creep force on the wheel (N).
    pub force_x: Vec<f64>,
    /// Longitudinal creepage (1).
    pub creepage_x: Vec<f64>,
    /// Lateral creepage (1).
    pub creepage_y: Vec<f64>,
    /// Spin (1/m; zeros without the spin's channel).
    pub spin: Vec<f64>,
}

/// The contact dynamics of one wheel at one speed over one periodic
/// stretch, tabulated.
#[derive(Debug, Clone)]
pub struct ContactDynamics {
    rail: Rail3,
    wheel: WheelSide,
    law: ContactLaw,
    /// The creep forces' frequency response that replaces the law's steady
    /// slopes per harmonic, if any.
    response: Option<CreepResponse>,
    /// Mean normal force (N), for the parametric excitation.
    mean_load: f64,
    /// Speed (m/s) and stretch (nodes, spacing) of the table.
    key: (f64, usize, f64),
    /// Responses per harmonic `n = 1..=n_max` (rows) at the places.
    table: Vec<Vec<ContactResponse>>,
}

impl ContactDynamics {
    /// Tabulates the responses for a stretch of `nodes` samples every `dx`
    /// (m) at `speed` (m/s): the harmonics up to
    /// [`super::discrete_dynamics::F_MAX`], in parallel. The contact closes
    /// with `law`, or, where `response` is given, with its Hertz stiffness
    /// and the creep forces' frequency response at each harmonic's
    /// frequency ([`ContactLaw::at_frequency`]).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        rail: Rail3,
        wheel: WheelSide,
        law: ContactLaw,
        response: Option<CreepResponse>,
        mean_load: f64,
        nodes: usize,
        dx: f64,
        speed: f64,
    ) -> Result<Self, Discrete3Error> {
        let length = nodes as f64 * dx;
        let n_max = harmonics(nodes, dx, speed);
        let spin = law.force_per_spin.is_some();
        let table = (1..=n_max)
            .into_par_iter()
            .map(|n| {
                let w = 2.0 * PI * n as f64 * speed.abs() / length;
                let a_w = wheel.receptance(w, speed.abs());
                let heads = match &rail {
                    Rail3::Continuous(c) => c.heads(w, &[0.0], spin)?,
                    Rail3::Discrete { model, .. } => {
                        let d = model.section.track.sleeper_spacing;
                        let places: Vec<(f64, f64)> = (0..BAY_PLACES)
                            .map(|p| {
                                let x = d * p as f64 / (BAY_PLACES - 1) as f64;
                                (x, x)
                            })
                            .collect();
                        model.heads(&places, w, spin)?
                    }
                };
                let law_w = response.as_ref().map_or(law, |r| law.at_frequency(&r.at(w / (2.0 * PI))));
                Ok(heads.iter().map(|a_r| respond(&(a_w + a_r), &law_w, w, speed.abs())).collect())
            })
            .collect::<Result<Vec<_>, Discrete3Error>>()?;
        Ok(ContactDynamics { rail, wheel, law, response, mean_load, key: (speed, nodes, dx), table })
    }

    /// The wheel's place in the bay, `x` (m) from the stretch's start above
    /// a sleeper, as a fractional index into the tabulated places (0 on the
    /// continuous track).
    fn place(&self, x: f64) -> f64 {
        match &self.rail {
            Rail3::Continuous(_) => 0.0,
            Rail3::Discrete { model, .. } => {
                let d = model.section.track.sleeper_spacing;
                x.rem_euclid(d) / d * (BAY_PLACES - 1) as f64
            }
        }
    }

    /// The contact's variations along one period of `profile` (m, rail top
    /// up, sampled every `dx`), eq. 1, with the parametric excitation on
    /// the discrete track.
    pub fn signals(&self, profile: &[f64], dx: f64, speed: f64) -> ContactSignals {
        let n = profile.len();
        assert_eq!(
            (speed, n, dx),
            self.key,
            "the contact dynamics is tabulated for one speed and stretch (built with the growth study's)"
        );
        let path = match &self.rail {
            Rail3::Discrete { vertical, sleeper_x0, .. } => {
                parametric_path(vertical, self.mean_load, *sleeper_x0, n, dx)
            }
            Rail3::Continuous(_) => vec![0.0; n],
        };
        let mut buf: Vec<Complex64> = profile.iter().zip(&path).map(|(r, p)| Complex64::new(r + p, 0.0)).collect();
        FftPlanner::<f64>::new().plan_fft_forward(n).process(&mut buf);
        let length = n as f64 * dx;
        let places = self.table.first().map_or(1, |r| r.len());
        let mut out = ContactSignals {
            normal: vec![0.0; n],
            force_x: vec![0.0; n],
            creepage_x: vec![0.0; n],
            creepage_y: vec![0.0; n],
            spin: vec![0.0; n],
        };
        for i in 0..n {
            // The first sample above a sleeper.
            let x = i as f64 * dx;
            let s = self.place(x);
            let p = (s.floor() as usize).min(places.saturating_sub(2));
            let t = if places > 1 { s - p as f64 } else { 0.0 };
            let mut acc = [0.0f64; 5];
            for (m, row) in self.table.iter().enumerate() {
                let k = m + 1;
                let (a, b) = (&row[p], &row[(p + 1).min(places - 1)]);
                let mix = |u: Complex64, v: Complex64| (1.0 - t) * u + t * v;
                let h = [
                    mix(a.normal, b.normal),
                    mix(a.force[0], b.force[0]),
                    mix(a.creepage[0], b.creepage[0]),
                    mix(a.creepage[1], b.creepage[1]),
                    mix(a.spin, b.spin),
                ];
                let phase = Complex64::from_polar(1.0, 2.0 * PI * k as f64 * x / length) * buf[k];
                let weight = if 2 * k == n { 1.0 } else { 2.0 } / n as f64;
                for (sum, hc) in acc.iter_mut().zip(h) {
                    let hc = if speed >= 0.0 { hc } else { hc.conj() };
                    *sum += weight * (hc * phase).re;
                }
            }
            out.normal[i] = acc[0];
            out.force_x[i] = acc[1];
            out.creepage_x[i] = acc[2];
            out.creepage_y[i] = acc[3];
            out.spin[i] = acc[4];
        }
        out
    }

    /// The contact law it closes the loop with (the steady slopes).
    pub fn law(&self) -> &ContactLaw {
        &self.law
    }

    /// The creep forces' frequency response that replaces the steady
    /// slopes, if any.
    pub fn creep_response(&self) -> Option<&CreepResponse> {
        self.response.as_ref()
    }
}

impl TrackDynamics for ContactDynamics {
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations> {
        vec![ContactVariations::Every(self.signals(&profiles[0], dx, speed))]
    }

    fn describe_resonances(&self) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        if let Rail3::Discrete { vertical, .. } = &self.rail {
            out.push(("pinned-pinned: the rail between two sleepers".into(), vertical.pinned_pinned_frequency()));
        }
        out.extend(self.wheel.resonances());
        if let WheelSide::Rigid(w) = &self.wheel {
            let (speed, ..) = self.key;
            let c = self.law.force_per_creepage[0][0].norm();
            // Where the creep force's damping of the rim's spin meets its inertia.
            let corner = c * w.radius * w.radius / (2.0 * w.polar_inertia * speed.abs()) / (2.0 * PI);
            out.push(("the rim's spin: force held below, creepage above".into(), corner));
        }
        out
    }

    fn forces_smooth_rail(&self) -> bool {
        matches!(self.rail, Rail3::Discrete { .. })
    }
}
