//! The track as configured (`[track]`): per-pad and per-sleeper values as
//! engineers give them, and the continuous model's per-length parameters
//! ([`TrackConfig::smeared`]). Defaults reproduce the track the program had
//! built in: UIC60 on 200 MN/m pads (loss factor 0.25), 0.6 m spacing,
//! 140 kg per half sleeper, 100 MN/m ballast (loss factor 1.0).

use super::rail::RailSection;
use super::receptance::{
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
