//! The growth study's parameters: the dynamics, the traffic (its scaling
//! and classes), the initial roughness and the stop rule. Their models live
//! in [`crate::growth`]; these are the typed values they receive.

use crate::loads::ImposedLoads;

/// Vehicle-track dynamics of a growth study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DynamicsKind {
    /// Only the imposed `load.harmonics` (no feedback of the profile).
    Imposed,
    /// Linear receptance model (wheel mass, Hertz spring, the `[track]`
    /// smeared into a continuous support).
    Receptance {
        /// Unsprung mass per wheel (kg).
        unsprung_mass: f64,
    },
    /// The Timoshenko rail on discrete supports (`[track]`), the
    /// receptance depending on the wheel's place in the sleeper bay, with
    /// the supports' parametric excitation.
    Discrete {
        /// Unsprung mass per wheel (kg).
        unsprung_mass: f64,
    },
}

impl std::fmt::Display for DynamicsKind {
    /// The model in the config's words (`dynamics.model`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DynamicsKind::Imposed => write!(f, "imposed (the imposed loads only, no feedback of the profile)"),
            DynamicsKind::Receptance { unsprung_mass } => {
                write!(f, "receptance (continuous track), unsprung mass {unsprung_mass} kg")
            }
            DynamicsKind::Discrete { unsprung_mass } => {
                write!(f, "discrete (Timoshenko rail on discrete supports), unsprung mass {unsprung_mass} kg")
            }
        }
    }
}

impl DynamicsKind {
    /// The unsprung mass of a track model (kg); None for imposed loads.
    pub fn unsprung_mass(&self) -> Option<f64> {
        match self {
            DynamicsKind::Imposed => None,
            DynamicsKind::Receptance { unsprung_mass } | DynamicsKind::Discrete { unsprung_mass } => {
                Some(*unsprung_mass)
            }
        }
    }

    /// The same model with another unsprung mass (kg).
    pub fn with_unsprung_mass(self, mass: f64) -> Self {
        match self {
            DynamicsKind::Imposed => DynamicsKind::Imposed,
            DynamicsKind::Receptance { .. } => DynamicsKind::Receptance { unsprung_mass: mass },
            DynamicsKind::Discrete { .. } => DynamicsKind::Discrete { unsprung_mass: mass },
        }
    }
}

/// A multi-passage growth study on the periodic stretch [x_min, x_max).
#[derive(Debug, Clone, PartialEq)]
pub struct GrowthParams {
    /// Simulated passages.
    pub passes: usize,
    /// How many real passages one simulated passage stands for.
    pub traffic: TrafficScaling,
    /// Store the rail profile and wear every this many passages (and the last).
    pub store_every: usize,
    /// Rewrite the run file (a checkpoint) every this many passages.
    pub checkpoint_every: usize,
    /// Passages whose contact-patch history is stored.
    pub contact_history: Vec<usize>,
    /// Initial irregularity.
    pub roughness: Roughness,
    /// Dynamics model.
    pub dynamics: DynamicsKind,
    /// The directions its track model moves in (`dynamics.directions`).
    pub directions: Directions,
    /// When the study stops before `passes`.
    pub stop: StopRule,
    /// The traffic classes (`[[traffic.mix]]`, shares summing to 1; one
    /// class of the base config without `[traffic]`).
    pub classes: Vec<TrafficClass>,
    /// The traffic in the operator's units (`[traffic]`'s axle loads and
    /// axles per day), where given.
    pub operation: Operation,
}

/// The traffic in the operator's units: what converts wheel passages of
/// the rail into million gross tonnes and days ([`crate::levels::forecast`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Operation {
    /// Gross mass per axle of each traffic class, in class order (kg);
    /// None where not given (no tonnes).
    pub axle_loads: Option<Vec<f64>>,
    /// Axles over the rail per day, each one wheel passage of the rail
    /// (1/d); None where not given (no days).
    pub axles_per_day: Option<f64>,
}

impl Operation {
    /// The traffic's units with the classes' `shares` (1, summing to 1).
    pub fn units(&self, shares: &[f64]) -> crate::levels::forecast::Units {
        crate::levels::forecast::Units::new(self.axle_loads.as_deref(), self.axles_per_day, shares)
    }
}

/// The directions of a growth study's track dynamics (`dynamics.directions`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Directions {
    /// Vertical: the normal force alone (with `[wheelset]`, the torsional
    /// feedback on the creepage): the models before the dynamics in every
    /// direction, bit for bit.
    Vertical,
    /// Every direction: the rail head's and the wheel's receptances in three
    /// directions closed with the creep forces
    /// ([`crate::dynamics::model`]).
    All {
        /// The contact's lateral offset from the rail's centre line, to the
        /// right looking along the rail (m).
        contact_offset: f64,
        /// How the creep forces answer a variation at its own frequency
        /// (`dynamics.creep_forces`).
        creep_forces: CreepForces,
        /// Whether the spin creepage's variation is in the loop (the rail
        /// head's and the wheel's rotation about the vertical,
        /// `dynamics.spin`).
        spin: bool,
    },
}

/// The creep forces' answer to the dynamic variations of creepage and
/// normal force in the dynamics in every direction
/// (`dynamics.creep_forces`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CreepForces {
    /// The steady creep curve's slopes (FASTSIM): the force follows the
    /// creepage without delay.
    Steady,
    /// The frequency-dependent creep coefficients measured on the
    /// passage's own transient contact solver
    /// ([`crate::dynamics::coupling::creep_response`]): the force lags and falls
    /// where the patch is rolled over in a time comparable to the period.
    Transient,
}

/// When a growth study stops before its planned passages (`growth.stop`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum StopRule {
    /// Runs every planned passage.
    #[default]
    Never,
    /// Stops after a passage in which the wheel left the rail, at a passage
    /// whose dynamic force takes N below F_x / mu (full sliding: that
    /// passage is not recorded), or once the corrugation has stopped
    /// growing: its rms grew by less than `rate` (dB per 1e5 real
    /// passages) over the last [`crate::growth::stop::SATURATION_WINDOW`]
    /// passages.
    Saturation {
        /// Growth rate of the rms below which the corrugation counts as
        /// saturated (dB per 1e5 real passages).
        rate: f64,
    },
    /// Stops after the passage at which a band's roughness level reaches
    /// its limit from below (`levels.limit`; [`crate::levels`]).
    Limit,
}

/// How `m`, the real passages one simulated passage stands for, is chosen
/// (the rule: [`crate::growth::traffic`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrafficScaling {
    /// The same `m` for every passage.
    Fixed {
        /// Real passages per simulated passage (1).
        scale: f64,
        /// Bound on `q` the run is checked against (1).
        max_update_ratio: f64,
    },
    /// `m` chosen per passage to keep `q <= max_update_ratio`.
    Adaptive {
        /// The first passage's `m` (upper bound) (1).
        initial: f64,
        /// Largest `m` (1).
        max: f64,
        /// Bound on `q`, the relative profile change per update (1).
        max_update_ratio: f64,
    },
}

/// Name of the one class of a study without `[traffic]`.
pub const BASE_NAME: &str = "base";

/// Whether `classes` are a mix from `[traffic]` rather than the one class
/// of the base config.
pub fn is_mix(classes: &[TrafficClass]) -> bool {
    !matches!(classes, [c] if c.name == BASE_NAME)
}

/// One class of traffic (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct TrafficClass {
    /// Name (letters, digits, `_`, `-`), for the output and messages.
    pub name: String,
    /// Rolling speed V (m/s).
    pub speed: f64,
    /// Mean normal force (N).
    pub normal_force: f64,
    /// Mean longitudinal force on the wheel (N).
    pub longitudinal_force: f64,
    /// Unsprung mass per wheel (kg).
    pub unsprung_mass: f64,
    /// Share of the real wheel passages (1; the shares of a mix sum to 1).
    pub share: f64,
    /// The class's vehicle: its wheels behind the leading one (m), where
    /// it differs from `vehicle.wheels`.
    pub wheels: Option<Vec<f64>>,
}

impl TrafficClass {
    /// The imposed loads as wheels of this class see them: the class's mean
    /// normal and longitudinal force with the harmonics of `base`.
    pub fn loads(&self, base: &ImposedLoads) -> ImposedLoads {
        ImposedLoads { normal_force: self.normal_force, longitudinal_force: self.longitudinal_force, ..base.clone() }
    }
}

/// One harmonic of the rail profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileHarmonic {
    /// Amplitude (m).
    pub amplitude: f64,
    /// Wavelength (m).
    pub wavelength: f64,
    /// Phase (rad): height = amplitude sin(2 pi X / wavelength + phase).
    pub phase: f64,
}

/// The initial irregularity.
#[derive(Debug, Clone, PartialEq)]
pub enum Roughness {
    /// A smooth rail.
    None,
    /// Explicit harmonics.
    Harmonics(Vec<ProfileHarmonic>),
    /// Seeded random, band-limited roughness.
    Random {
        /// Seed of the generator.
        seed: u64,
        /// rms height (m).
        rms: f64,
        /// Shortest wavelength (m).
        wavelength_min: f64,
        /// Longest wavelength (m).
        wavelength_max: f64,
    },
    /// Seeded random roughness with a one-third-octave level spectrum.
    Levels {
        /// Seed of the generator.
        seed: u64,
        /// The bands.
        bands: Vec<LevelBand>,
    },
    /// A measured record, processed and resampled onto the stretch.
    Measured(Box<super::record::MeasuredRoughness>),
}

impl Roughness {
    /// The same roughness drawn with another seed (the seeded kinds; the
    /// others are returned as they are).
    pub fn with_seed(&self, seed: u64) -> Roughness {
        match self {
            Roughness::Random { rms, wavelength_min, wavelength_max, .. } => {
                Roughness::Random { seed, rms: *rms, wavelength_min: *wavelength_min, wavelength_max: *wavelength_max }
            }
            Roughness::Levels { bands, .. } => Roughness::Levels { seed, bands: bands.clone() },
            other => other.clone(),
        }
    }

    /// The generator's seed of a seeded kind.
    pub fn seed(&self) -> Option<u64> {
        match self {
            Roughness::Random { seed, .. } | Roughness::Levels { seed, .. } => Some(*seed),
            _ => None,
        }
    }
}

pub use crate::levels::density::LevelBand;
