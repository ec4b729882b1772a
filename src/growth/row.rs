//! One rail's row of a growth passage: the profile update `r -= m W`, the
//! passage's row (rms, spectra, growth rates, band levels), the stored
//! state and histories ([`RowKeep::apply`]), the same for each rail of the
//! wheelset.

use super::contact_filtered_line;
use super::state::{PassRow, RailSnapshot, RunState};
use crate::harmonics::{amplitudes, growth_rates};
use crate::levels::{BandLevels, LEVEL_FLOOR, R0, level_rates};
use crate::metrics::rms_corrugation;
use crate::passage::PatchHistory;
use crate::rail_grid::RailGrid;
use ndarray::Array2;

/// What a passage's row needs besides its rail's wear: the same for each
/// rail of the wheelset.
pub(super) struct RowKeep<'s> {
    pub(super) pass: usize,
    pub(super) class: usize,
    pub(super) cpu_seconds: f64,
    /// Real passages this one stands for (1).
    pub(super) m: f64,
    pub(super) update_ratio: f64,
    pub(super) profile_contact: f64,
    pub(super) grid: &'s RailGrid,
    pub(super) centre: usize,
    /// The mean patch's lateral semi-axis (m).
    pub(super) mean_b: f64,
    pub(super) levels: &'s BandLevels,
    /// Whether the rail's state is stored after this passage.
    pub(super) store: bool,
    pub(super) keep_history: bool,
}

impl RowKeep<'_> {
    /// Updates a rail's `state` with its `wear` of one passage (`r -= m
    /// W`; with its leading wheel's share of it per wear regime; `forced`
    /// the smooth rail's wear `W_0` of the passage's class where it wears a
    /// pattern, whose part of the change the growth rate leaves out), appends
    /// its row, its stored state and its wheels' histories
    /// (the leading wheel's, the others') where kept; `(loss, clipped)`
    /// its steps without contact and with the linear contact's patch
    /// opened. Returns the row.
    pub(super) fn apply(
        &self,
        state: &mut RunState,
        (wear, wear_regime_share): (Array2<f64>, Vec<f64>),
        forced: Option<&Array2<f64>>,
        (history, others): (PatchHistory, Vec<PatchHistory>),
        (loss, clipped): (usize, usize),
    ) -> PassRow {
        let line = |p: &Array2<f64>| p.row(self.centre).to_vec();
        let filtered = |p: &Array2<f64>| contact_filtered_line(p, self.grid, self.mean_b);
        let previous = state.rows.last();
        let before = match previous {
            Some(r) => r.filtered_spectrum.clone(),
            None => amplitudes(&filtered(&state.profile)),
        };
        let m = self.m;
        let traffic = previous.map_or(0.0, |r| r.traffic) + m;
        let levels_before = previous.map_or_else(|| state.initial_level.clone(), |r| r.roughness_level.clone());
        state.profile.scaled_add(-m, &wear);
        let roughness_level = self.levels.levels(&state.profile);
        let filtered_spectrum = amplitudes(&filtered(&state.profile));
        // The roughness-driven change: the profile as the wear less the
        // smooth rail's would have left it, r - m (W - W_0).
        let (driven, forced_wear, driven_level, forced_band_wear) = match forced {
            Some(w0) => {
                let mut r = state.profile.clone();
                r.scaled_add(m, w0);
                let band_rms = self.levels.levels(w0).iter().map(|l| rms_of_level(*l)).collect();
                (amplitudes(&filtered(&r)), amplitudes(&filtered(w0)), self.levels.levels(&r), band_rms)
            }
            None => {
                (filtered_spectrum.clone(), vec![0.0; filtered_spectrum.len()], roughness_level.clone(), Vec::new())
            }
        };
        let row = PassRow {
            index: self.pass as i64,
            traffic,
            traffic_scale: m,
            rms_corrugation: rms_corrugation(state.profile.view(), self.grid),
            removed_volume: wear.sum() * self.grid.dx * self.grid.dy,
            cpu_seconds: self.cpu_seconds,
            update_ratio: self.update_ratio,
            traffic_class: self.class,
            contact_loss_steps: loss as f64,
            profile_contact: self.profile_contact,
            clipped_steps: clipped as f64,
            wear_regime_share,
            // Below 1e-12 m (1 pm) an amplitude is numerical noise.
            growth_rate: growth_rates(&before, &driven, m, 1e-12),
            forced_wear,
            spectrum: amplitudes(&line(&state.profile)),
            filtered_spectrum,
            level_rate: level_rates(&levels_before, &driven_level, m),
            forced_band_wear,
            roughness_level,
        };
        if self.store {
            state.rail.push(RailSnapshot { index: self.pass as i64, traffic, profile: state.profile.clone(), wear });
        }
        if self.keep_history {
            state.histories.push((self.pass as i64, history));
            if !others.is_empty() {
                state.wheel_histories.push((self.pass as i64, others));
            }
        }
        state.rows.push(row.clone());
        row
    }
}

/// The rms (m) of a band level `l` (dB re 1 um); 0 at the floor.
fn rms_of_level(l: f64) -> f64 {
    if l <= LEVEL_FLOOR { 0.0 } else { R0 * 10f64.powf(l / 20.0) }
}
