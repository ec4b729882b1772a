//! The rail and its supports. Here: the track as configured (`[track]`): per-pad and per-sleeper values as
//! engineers give them, and the continuous model's per-length parameters
//! ([`TrackConfig::smeared`]). Defaults reproduce the track the program had
//! built in: UIC60 on 200 MN/m pads (loss factor 0.25), 0.6 m spacing,
//! 140 kg per half sleeper, 100 MN/m ballast (loss factor 1.0), rail loss
//! factor 0.02.
//!
//! The supports in the other directions ([`Supports3`], for the rail
//! head's receptances in three directions): estimates, to be overridden
//! with measured values where a track has them. A fastening's lateral and
//! longitudinal stiffness is a fraction of its vertical one (the pad in
//! shear, the clips): 50 MN/m each, a quarter of the default pad (Thompson,
//! *Railway Noise and Vibration*, 2009, ch. 3, gives lateral pad stiffnesses
//! of 1/10 to 1/2 of the vertical); the ballast's lateral and longitudinal
//! resistance of a half sleeper 50 MN/m each (Knothe and Grassie, *Veh.
//! Syst. Dyn.* 22 (1993) 209-262, report lateral ballast stiffnesses below
//! the vertical); the pad's footprint 0.15 m x 0.15 m (a 60E1 foot is 150
//! mm wide), whose vertical stiffness spread over it restrains the rail's
//! roll and pitch, `k_p b^2 / 12` and `k_p l^2 / 12`. The layers' damping
//! (loss factor or dampers) is the vertical one's in every direction, a
//! viscous damper scaled with the stiffness (the same loss factor at a
//! frequency).

pub mod continuous3;
pub mod discrete;
pub mod discrete3;
#[cfg(test)]
mod floquet;
pub mod head;
pub mod layout;
pub mod rail;
pub mod response;
pub mod scattering;
pub mod section;
pub mod waves;

use self::rail::RailSection;
use crate::dynamics::receptance::{
    BALLAST_LOSS_FACTOR, BALLAST_STIFFNESS_PER_HALF_SLEEPER, HALF_SLEEPER_MASS, PAD_LOSS_FACTOR, PAD_STIFFNESS_PER_PAD,
    SLEEPER_SPACING, TrackParams,
};

/// Damping of a resilient layer: a loss factor or a viscous damper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    /// Hysteretic loss factor eta (1): stiffness k (1 + i eta).
    LossFactor(f64),
    /// Viscous damper c (N s/m, per pad or per sleeper end): k + i w c.
    Viscous(f64),
}

/// The track as configured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackConfig {
    /// Rail preset name.
    pub rail_name: &'static str,
    /// The rail section (the preset with any overrides).
    pub rail: RailSection,
    /// Sleeper spacing d (m).
    pub sleeper_spacing: f64,
    /// Pad stiffness per pad (N/m).
    pub pad_stiffness: f64,
    /// Pad damping.
    pub pad_damping: Damping,
    /// Sleeper mass per rail (kg: half a sleeper).
    pub sleeper_mass: f64,
    /// Ballast stiffness per sleeper end (N/m).
    pub ballast_stiffness: f64,
    /// Ballast damping.
    pub ballast_damping: Damping,
    /// Rail loss factor eta_r (1): the rail's own damping, on its bending,
    /// shear, axial and torsional stiffnesses.
    pub rail_loss_factor: f64,
    /// The supports in the other directions.
    pub supports: Supports3,
}

/// The supports' stiffnesses in the lateral and longitudinal directions
/// and the pad's footprint (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Supports3 {
    /// Pad (fastening) stiffness across the rail, per pad (N/m).
    pub pad_lateral_stiffness: f64,
    /// Pad (fastening) stiffness along the rail, per pad (N/m).
    pub pad_longitudinal_stiffness: f64,
    /// Pad width across the rail (m): its roll stiffness `k_p b^2 / 12`.
    pub pad_width: f64,
    /// Pad length along the rail (m): its pitch stiffness `k_p l^2 / 12`.
    pub pad_length: f64,
    /// Ballast stiffness across the track, per sleeper end (N/m).
    pub ballast_lateral_stiffness: f64,
    /// Ballast stiffness along the track, per sleeper end (N/m).
    pub ballast_longitudinal_stiffness: f64,
}

/// Rail loss factor (1): the rail's own damping (Thompson 2009, ch. 3,
/// uses 0.02).
pub const RAIL_LOSS_FACTOR: f64 = 0.02;

impl Default for Supports3 {
    fn default() -> Self {
        Supports3 {
            pad_lateral_stiffness: 50e6,
            pad_longitudinal_stiffness: 50e6,
            pad_width: 0.15,
            pad_length: 0.15,
            ballast_lateral_stiffness: 50e6,
            ballast_longitudinal_stiffness: 50e6,
        }
    }
}

impl Default for TrackConfig {
    fn default() -> Self {
        TrackConfig {
            rail_name: "UIC60",
            rail: RailSection::preset("UIC60").expect("preset"),
            sleeper_spacing: SLEEPER_SPACING,
            pad_stiffness: PAD_STIFFNESS_PER_PAD,
            pad_damping: Damping::LossFactor(PAD_LOSS_FACTOR),
            sleeper_mass: HALF_SLEEPER_MASS,
            ballast_stiffness: BALLAST_STIFFNESS_PER_HALF_SLEEPER,
            ballast_damping: Damping::LossFactor(BALLAST_LOSS_FACTOR),
            rail_loss_factor: RAIL_LOSS_FACTOR,
            supports: Supports3::default(),
        }
    }
}

impl TrackConfig {
    /// The continuous model's per-length parameters: every support value
    /// divided by the sleeper spacing (shear stiffness and rotary inertia
    /// are the discrete Timoshenko model's; the Euler-Bernoulli rail does
    /// not use them).
    pub fn smeared(&self) -> TrackParams {
        let d = self.sleeper_spacing;
        let (pad_loss_factor, pad_damping) = match self.pad_damping {
            Damping::LossFactor(eta) => (eta, 0.0),
            Damping::Viscous(c) => (0.0, c / d),
        };
        let (ballast_loss_factor, ballast_damping) = match self.ballast_damping {
            Damping::LossFactor(eta) => (eta, 0.0),
            Damping::Viscous(c) => (0.0, c / d),
        };
        TrackParams {
            bending_stiffness: self.rail.bending_stiffness,
            rail_mass: self.rail.mass,
            pad_stiffness: self.pad_stiffness / d,
            pad_loss_factor,
            sleeper_mass: self.sleeper_mass / d,
            ballast_stiffness: self.ballast_stiffness / d,
            ballast_loss_factor,
            pad_damping,
            ballast_damping,
        }
    }
}
