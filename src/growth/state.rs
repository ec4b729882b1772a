//! What a growth study carries from one passage to the next: the rail
//! profile, one row per passage done, the stored rail states and patch
//! histories. The run file holds exactly this ([`crate::output::run_file`]),
//! so a resumed study continues from what it reads back.

use crate::passage::PatchHistory;
use ndarray::Array2;

/// One simulated passage's summary row.
#[derive(Debug, Clone, PartialEq)]
pub struct PassRow {
    /// Passage index (0-based).
    pub index: i64,
    /// Real passages represented up to and including this one (1).
    pub traffic: f64,
    /// Real passages this simulated one stands for (1).
    pub traffic_scale: f64,
    /// rms of the corrugation on the centre line after this passage (m).
    pub rms_corrugation: f64,
    /// Volume removed from the rail grid by this passage, unscaled (m^3).
    pub removed_volume: f64,
    /// CPU time of the passage (s).
    pub cpu_seconds: f64,
    /// Relative profile change of the update, q = m max_k |W_k| / |R_k| (1);
    /// see [`crate::growth::traffic`].
    pub update_ratio: f64,
    /// Steps of the stretch where the wheel left the rail (N <= 0) (1).
    pub contact_loss_steps: f64,
    /// The passage's normal contact: 0 Hertz, 1 the nonlinear profile
    /// contact, 2 the linear profile contact, 3 the nonlinear profile
    /// contact with the linear contact's equivalent roughness.
    pub profile_contact: f64,
    /// Steps at which the linear profile contact's pressure vanished well
    /// inside the patch (1).
    pub clipped_steps: f64,
    /// Index of the passage's traffic class (0 without a mix).
    pub traffic_class: usize,
    /// The leading wheel's wear volume per regime of the wear law, as a
    /// share of its total (1; [`crate::wear::WearLaw::regimes`]' order;
    /// empty in files written before the wear laws).
    pub wear_regime_share: Vec<f64>,
    /// Amplitude spectrum of the centre-line profile after the passage (m),
    /// on the record's `wavelengths`.
    pub spectrum: Vec<f64>,
    /// Amplitude spectrum of the contact-filtered profile after the passage
    /// (m): the profile averaged across the mean patch width with the Hertz
    /// line-load weight, the line the wheel sees and the dynamics is driven by.
    pub filtered_spectrum: Vec<f64>,
    /// Roughness-driven growth rate of each harmonic of the
    /// contact-filtered profile over this passage (dB per 1e5 real
    /// passages), on the record's `wavelengths`: the profile's change by
    /// the wear less the smooth rail's (`W - W_0`), `20 lg(|R - m (W -
    /// W_0)| / |R|) 1e5 / m` per harmonic, the exponential growth or decay
    /// of the roughness. Where the smooth rail wears no pattern (`W_0`
    /// uniform) the profile's own change.
    pub growth_rate: Vec<f64>,
    /// Amplitude of each harmonic of the contact-filtered wear one passage
    /// of the class leaves on the smooth rail, `W_0` (m per wheel passage),
    /// on the record's `wavelengths`: the forced pattern (the discrete
    /// supports' sleeper passing, imposed load harmonics), which deepens
    /// linearly with traffic whatever the roughness; zero where the smooth
    /// rail wears none (empty in files written before it was recorded).
    pub forced_wear: Vec<f64>,
    /// The rail's roughness level in each band after the passage (dB re 1
    /// um; [`crate::levels`]: the running band's lines, mean-square
    /// averaged).
    pub roughness_level: Vec<f64>,
    /// Roughness-driven growth rate of each band's level over this passage
    /// (dB per 1e5 real wheel passages): the level the profile's change by
    /// `W - W_0` leaves, as `growth_rate` per harmonic.
    pub level_rate: Vec<f64>,
    /// The forced pattern's rms in each band (m per wheel passage): the
    /// band level's measure of `W_0` over the running band (empty where the
    /// smooth rail wears none, or in files written before it was recorded).
    pub forced_band_wear: Vec<f64>,
}

/// A stored rail state.
#[derive(Debug, Clone, PartialEq)]
pub struct RailSnapshot {
    /// Passage index.
    pub index: i64,
    /// Real passages represented (1).
    pub traffic: f64,
    /// Surface height change, shape (ny, nx) (m, wear negative).
    pub profile: Array2<f64>,
    /// Wear depth of this passage, shape (ny, nx) (m, positive).
    pub wear: Array2<f64>,
}

/// The state of a run after some passages: everything a run file holds
/// that changes from passage to passage, and everything a resumed run
/// needs.
#[derive(Debug, Clone, PartialEq)]
pub struct RunState {
    /// Rail surface height change after the passages done, shape (ny, nx)
    /// (m, wear negative).
    pub profile: Array2<f64>,
    /// One row per passage done.
    pub rows: Vec<PassRow>,
    /// Stored rail states.
    pub rail: Vec<RailSnapshot>,
    /// Stored patch histories: (passage index, history); with several
    /// wheels the leading wheel's.
    pub histories: Vec<(i64, PatchHistory)>,
    /// The other wheels' histories of the same stored passages (passage
    /// index, the second wheel's first); only passages with several wheels.
    pub wheel_histories: Vec<(i64, Vec<PatchHistory>)>,
    /// The rail's roughness level in each band before the first passage
    /// (dB re 1 um); empty until the study fills it in.
    pub initial_level: Vec<f64>,
    /// The wheelset's second rail's state (its profile, rows, stored
    /// states and its wheel's histories; its rows' traffic is the first
    /// rail's), where the study has one.
    pub second_rail: Option<Box<RunState>>,
}
