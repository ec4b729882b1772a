//! The vehicle-track model, assembled from its bodies: a track (the rail
//! on continuous or discrete supports, [`super::track`]), the wheels
//! (their wheelsets' receptances at the contacts, [`super::wheelset`]) on
//! one or two rails, and each wheel's contact closure
//! ([`super::coupling`]: the Hertz spring and, in every direction, the
//! creep forces' slopes or frequency response). One model answers the
//! growth loop's question for every configuration: one wheel or a
//! vehicle, the continuous or the discrete track, the vertical direction
//! alone or every direction (the moving-irregularity model, Grassie,
//! Gregory, Harrison and Johnson, *J. Mech. Eng. Sci.* 24 (1982) 77-90;
//! several wheels after Wu and Thompson, *J. Sound Vib.* 2005, and Nielsen,
//! 2003; the tangential directions after Hempelmann and Knothe, *Arch.
//! Appl. Mech.* 66 (1996) 321-339).
//!
//! # Equations
//! Wheel `j` runs `s_j` behind the leading one (`s_0 = 0`); the loads
//! stand still and the rail is pulled through at the speed `V`, so when
//! wheel `i` is at `X` wheel `j` is at `X + s_i - s_j`. Per profile
//! harmonic `r_k exp(i k X)` (`w = k |V|`) and place `x` of the leading
//! wheel in the sleeper bay, the contacts close ([`closure`]): with the
//! forces on the wheels `f_j`, the contact points' relative displacement
//! at wheel `j` is `d_j = sum_l (A_w,jl + A_r(x_j; x_l)) f_l` (the
//! wheelset's receptance between the wheels of one wheelset, the rail's
//! between wheels on one rail) and each wheel's contact law gives
//! ```text
//! N_j = k_H,j (r_j + d_j,z),   xi_j = (i w / V) d_j,xy,   (F_x, F_y)_j = C_N,j N_j + C_xi,j xi_j   (1)
//! ```
//! **The directions are a choice of the closure**: in every direction the
//! whole system; vertically the tangential forces held at zero, which
//! leaves `sum_l M_jl P_l = r_j`, `M = (alpha_w + 1 / k_H) I + A_zz`.
//! Solved for a unit input at each wheel, the responses `G_ci,j(w, x)` of
//! channel `c` of wheel `i` (normal force; in every direction the
//! longitudinal creep force, the creepages and the spin) give the
//! contact's variations ([`evaluate`])
//! ```text
//! c_i(X) = sum_k sum_j G_ci,j(w_k, x(X)) r_j,k exp(i k (s_i - s_j)) exp(i k X),   (2)
//! ```
//! `r_j` the profile wheel `j` sees plus, on the discrete track, its
//! parametric path (the static deflection under all the wheels' loads,
//! [`paths`]). On the continuous track `G` does not depend on the place
//! and eq. 2 is one inverse FFT per channel; on the discrete track `G` is
//! tabulated at [`BAY_PLACES`] places across a bay and interpolated
//! linearly (the position-dependent approximation: the coupling of the
//! harmonics `f + n V / d` is dropped, valid while `V / d` is small
//! against the frequencies of interest).
//!
//! Limits, each a test: one wheel vertically on the continuous track is
//! eq. 5 of [`super::receptance`] (bit for bit); far apart, each wheel is
//! the single wheel; without creep slopes the normal forces in every
//! direction are the vertical closure's with the head's vertical
//! receptance.

mod closure;
mod evaluate;
pub mod paths;
pub mod places;

use super::coupling::contact_point::ContactLaw;
use super::coupling::creep_response::CreepResponse;
use super::receptance::{ReceptanceModel, TrackParams, WheelParams};
use super::track::continuous3::Continuous3;
use super::track::discrete::DiscreteTrack;
use super::track::discrete3::{Discrete3, Discrete3Error};
use super::track::layout::Layout;
use super::wheelset::side::{Wheel3, WheelSide};
use super::{ContactSignals, ContactVariations, TrackDynamics};
use nalgebra::DMatrix;
use num_complex::Complex64;
use places::Places;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Places of the leading wheel across each support interval (one sleeper
/// bay: every `d / 16`) at which the discrete track's responses are
/// tabulated ([`places`]).
pub const BAY_PLACES: usize = 16;

/// Highest harmonic frequency of the profile a tabulated model transfers
/// (Hz); above it the harmonics are dropped (the contact filters them far
/// more than the track: 5 kHz is a 5.6 mm wavelength at 100 km/h). The
/// vertical model on the continuous track, in closed form, transfers
/// every harmonic.
pub const F_MAX: f64 = 5000.0;

/// The harmonics of a stretch of `nodes` samples every `dx` (m) that a
/// tabulated model transfers at `speed` (m/s): those up to [`F_MAX`] and
/// the Nyquist harmonic.
pub fn harmonics(nodes: usize, dx: f64, speed: f64) -> usize {
    ((F_MAX * nodes as f64 * dx / speed.abs()).floor() as usize).min(nodes / 2)
}

/// The track: the rail on its supports, with the rail head's receptances
/// in every direction where the model asks for them.
#[derive(Debug, Clone)]
pub enum Track {
    /// On continuous (smeared) supports: the vertical receptance in closed
    /// form ([`TrackParams`]), the head's in every direction
    /// ([`Continuous3`]) where given.
    Continuous {
        /// The vertical model.
        vertical: TrackParams,
        /// The rail head in every direction.
        head: Option<Continuous3>,
    },
    /// On discrete supports laid out by `layout` (one bay of the
    /// configured track, or a period of several supports each with its
    /// own place, pad and sleeper), its first support at `sleeper_x0`.
    Discrete {
        /// The vertical model (and the parametric excitation's statics).
        vertical: DiscreteTrack,
        /// The rail head in every direction.
        head: Option<Discrete3>,
        /// The layout's first support's position along the rail (m).
        sleeper_x0: f64,
        /// The supports of the period.
        layout: Layout,
    },
}

impl Track {
    /// The tabulated places on the discrete track.
    fn places(&self) -> Option<Places> {
        match self {
            Track::Continuous { .. } => None,
            Track::Discrete { sleeper_x0, layout, .. } => Some(Places::new(layout, *sleeper_x0)),
        }
    }

    /// Whether the rail head's receptances in every direction are given.
    fn every_direction(&self) -> bool {
        match self {
            Track::Continuous { head, .. } => head.is_some(),
            Track::Discrete { head, .. } => head.is_some(),
        }
    }
}

/// Which directions the contacts close in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Directions {
    /// The normal direction, the tangential forces held.
    Vertical,
    /// Every direction (the track needs its head's receptances).
    All,
}

/// One wheel of the vehicle as the track sees it.
#[derive(Debug, Clone)]
pub struct Wheel {
    /// Distance behind the leading wheel (m, >= 0).
    pub behind: f64,
    /// The rail it runs on: 0 the first, 1 the wheelset's second rail
    /// (a wheel on the second rail at the same `behind` as one on the
    /// first is the same wheelset's other wheel).
    pub rail: usize,
    /// The wheel's receptance at its contact.
    pub side: WheelSide,
    /// Its contact at its mean loads: the Hertz stiffness and, in every
    /// direction, the creep forces' steady slopes.
    pub law: ContactLaw,
    /// The creep forces' frequency response replacing the steady slopes,
    /// if any.
    pub response: Option<CreepResponse>,
    /// Mean normal force (N), for the parametric excitation.
    pub mean_load: f64,
}

impl Wheel {
    /// A wheel for the vertical closure: the rigid `wheel` (its unsprung
    /// mass; infinite holds it still) on a Hertz spring `stiffness` (N/m)
    /// at the mean load `mean_load` (N), `behind` (m) the leading wheel on
    /// the first rail.
    pub fn vertical(behind: f64, wheel: Wheel3, stiffness: f64, mean_load: f64) -> Self {
        let side = WheelSide::Rigid(wheel);
        Wheel { behind, rail: 0, side, law: ContactLaw::normal(stiffness), response: None, mean_load }
    }

    /// The contact law at angular frequency `omega` (rad/s): the
    /// frequency response's slopes where given.
    fn law_at(&self, omega: f64) -> ContactLaw {
        self.response.as_ref().map_or(self.law, |r| self.law.at_frequency(&r.at(omega / (2.0 * PI))))
    }
}

/// The vehicle-track model at one speed over one periodic stretch,
/// tabulated.
#[derive(Debug, Clone)]
pub struct VehicleTrack {
    track: Track,
    wheels: Vec<Wheel>,
    directions: Directions,
    /// Speed (m/s) and stretch (nodes, spacing) of the table.
    key: (f64, usize, f64),
    /// Per harmonic `k = 1..=k_max` (outer) and place of the leading wheel
    /// (inner: [`BAY_PLACES`] per support of the discrete track's period, one on the
    /// continuous), `G` of eq. 2: row `channels i + c`, column `j`.
    table: Vec<Vec<DMatrix<Complex64>>>,
    /// Each wheel's parametric path on the discrete track (m, zeros on the
    /// continuous), at its own positions of the stretch.
    paths: Vec<Vec<f64>>,
}

impl VehicleTrack {
    /// Tabulates the model of `wheels` (the first the leading one,
    /// `behind` 0) on `track` in `directions` for a stretch of `nodes`
    /// samples every `dx` (m) at `speed` (m/s; several wheels run
    /// forwards), in parallel over the harmonics: every harmonic for the
    /// vertical closure on the continuous track, those up to [`F_MAX`]
    /// otherwise.
    ///
    /// # Errors
    /// Where the rail head's receptances cannot be computed.
    ///
    /// # Panics
    /// If `directions` is [`Directions::All`] and the track has no head
    /// model, or several wheels run backwards.
    pub fn new(
        track: Track,
        wheels: Vec<Wheel>,
        directions: Directions,
        nodes: usize,
        dx: f64,
        speed: f64,
    ) -> Result<Self, Discrete3Error> {
        assert!(!wheels.is_empty(), "a vehicle has a wheel");
        assert!(wheels.len() == 1 || speed > 0.0, "the vehicle runs forwards (speed = {speed} m/s)");
        assert!(
            directions == Directions::Vertical || track.every_direction(),
            "the dynamics in every direction needs the rail head's receptances"
        );
        let length = nodes as f64 * dx;
        let closed_form = matches!(track, Track::Continuous { .. }) && directions == Directions::Vertical;
        let k_max = if closed_form { nodes / 2 } else { harmonics(nodes, dx, speed) };
        let table = (1..=k_max)
            .into_par_iter()
            .map(|k| {
                let omega = 2.0 * PI * (speed.abs() * k as f64 / length);
                closure::responses(&track, &wheels, directions, omega, speed.abs())
            })
            .collect::<Result<Vec<_>, Discrete3Error>>()?;
        let paths = paths::wheel_paths(&track, &wheels, nodes, dx)?;
        Ok(VehicleTrack { track, wheels, directions, key: (speed, nodes, dx), table, paths })
    }

    /// The channels per wheel: 1 vertically (the normal force), 5 in every
    /// direction ([`ContactSignals`]' order).
    pub fn channels(&self) -> usize {
        closure::channels(self.directions)
    }

    /// The directions it closes the contacts in.
    pub fn directions(&self) -> Directions {
        self.directions
    }

    /// `G` of eq. 2 at harmonic `k` (>= 1) and tabulated place `place`
    /// (row `channels i + c`, column `j`; per metre of profile at wheel
    /// `j`, without the phase between the wheels).
    pub fn response(&self, k: usize, place: usize) -> &DMatrix<Complex64> {
        &self.table[k - 1][place]
    }

    /// Each wheel's path on a smooth rail (m, positive up, zero mean) at
    /// its own positions of the stretch: the static deflection under all
    /// the wheels' loads on the discrete track, zeros on the continuous.
    pub fn parametric_paths(&self) -> &[Vec<f64>] {
        &self.paths
    }

    /// Each wheel's channels (eq. 2) along one period of the profile it
    /// sees (`profiles[wheel]`, m, rail top up, sampled every `dx`), with
    /// the parametric excitation on the discrete track.
    fn channels_of(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<Vec<Vec<f64>>> {
        let nodes = profiles[0].len();
        assert_eq!(
            (speed, nodes, dx),
            self.key,
            "the vehicle-track model is tabulated for one speed and stretch (built with the growth study's)"
        );
        assert_eq!(profiles.len(), self.wheels.len(), "a profile per wheel");
        let behind: Vec<f64> = self.wheels.iter().map(|w| w.behind).collect();
        evaluate::channels(
            &self.table,
            self.channels(),
            &behind,
            profiles,
            &self.paths,
            self.track.places().as_ref(),
            dx,
            speed,
        )
    }

    /// Each wheel's dynamic normal force (N, zero mean) from the profile it
    /// sees.
    pub fn normal_forces(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<Vec<f64>> {
        self.channels_of(profiles, dx, speed).into_iter().map(|mut c| c.swap_remove(0)).collect()
    }

    /// Each wheel's contact variations in every direction from the profile
    /// it sees.
    ///
    /// # Panics
    /// If the model is vertical.
    pub fn signals(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactSignals> {
        assert_eq!(self.directions, Directions::All, "the vertical model has the normal force alone");
        self.channels_of(profiles, dx, speed)
            .into_iter()
            .map(|c| {
                let [normal, force_x, creepage_x, creepage_y, spin]: [Vec<f64>; 5] =
                    c.try_into().expect("five channels");
                ContactSignals { normal, force_x, creepage_x, creepage_y, spin }
            })
            .collect()
    }

    /// The leading wheel's resonances for reports.
    fn wheel_resonances(&self) -> Vec<(String, f64)> {
        let lead = &self.wheels[0];
        let mut out = lead.side.resonances();
        if let WheelSide::Rigid(w) = &lead.side {
            let (speed, ..) = self.key;
            let c = lead.law.force_per_creepage[0][0].norm();
            // Where the creep force's damping of the rim's spin meets its inertia.
            let corner = c * w.radius * w.radius / (2.0 * w.polar_inertia * speed.abs()) / (2.0 * PI);
            out.push(("the rim's spin: force held below, creepage above".into(), corner));
        }
        out
    }
}

impl TrackDynamics for VehicleTrack {
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations> {
        match self.directions {
            Directions::Vertical => ContactVariations::normals(self.normal_forces(profiles, dx, speed)),
            Directions::All => self.signals(profiles, dx, speed).into_iter().map(ContactVariations::Every).collect(),
        }
    }

    /// On the discrete track the pinned-pinned resonance (on a layout, of
    /// each of its span lengths); on the
    /// continuous track vertically the leading wheel's resonances on it
    /// ([`ReceptanceModel`]'s labels); in every direction the leading
    /// wheel's own.
    fn describe_resonances(&self) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        match (&self.track, self.directions) {
            (Track::Discrete { vertical, layout, .. }, _) => {
                // Each of the layout's span lengths (to the millimetre).
                let mut spans: Vec<f64> = layout.bounds().windows(2).map(|w| (1e3 * (w[1] - w[0])).round()).collect();
                spans.sort_by(f64::total_cmp);
                spans.dedup();
                if spans == [(1e3 * vertical.spacing).round()] {
                    let label = "pinned-pinned: the rail between two sleepers";
                    out.push((label.into(), vertical.pinned_pinned_frequency()));
                } else {
                    for mm in spans {
                        let span = DiscreteTrack { spacing: 1e-3 * mm, ..*vertical };
                        out.push((format!("pinned-pinned: a span of {mm:.0} mm"), span.pinned_pinned_frequency()));
                    }
                }
            }
            (Track::Continuous { vertical, .. }, Directions::Vertical) => {
                let lead = &self.wheels[0];
                if let WheelSide::Rigid(w) = &lead.side {
                    let wheel = WheelParams { unsprung_mass: w.mass };
                    if let Ok(m) = ReceptanceModel::new(*vertical, wheel, lead.law.stiffness) {
                        out.extend(m.describe_resonances());
                    }
                }
            }
            (Track::Continuous { .. }, Directions::All) => {}
        }
        if self.directions == Directions::All {
            out.extend(self.wheel_resonances());
        }
        out
    }

    fn forces_smooth_rail(&self) -> bool {
        matches!(self.track, Track::Discrete { .. })
    }

    fn wheels(&self) -> usize {
        self.wheels.len()
    }

    fn rail_of(&self, wheel: usize) -> usize {
        self.wheels[wheel].rail
    }
}
