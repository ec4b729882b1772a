//! What a run file holds, as the writer receives it: the run's record
//! (its own module, so that the run file and the field units, which both
//! read it, do not import each other).

use crate::contact::Elements;
use crate::growth::record::RecordSamples;
use crate::growth::state::RunState;
use crate::levels::Band;
use crate::params::{Operation, TrafficClass};
use crate::rail_grid::RailGrid;

/// Everything a run file holds.
#[derive(Debug, Clone)]
pub struct RunRecord<'a> {
    /// Title of the run.
    pub title: &'a str,
    /// Contact model name.
    pub contact_model: &'a str,
    /// Resolved config TOML.
    pub config: &'a str,
    /// Rail grid.
    pub grid: &'a RailGrid,
    /// The contact elements the fields are on.
    pub elements: &'a Elements,
    /// Hertz semi-axes (a, b) at the mean normal force (m): the scale of
    /// the fixed grid's normalised coordinates.
    pub mean_patch: (f64, f64),
    /// Wavelengths of the spectra (m), longest first.
    pub wavelengths: &'a [f64],
    /// The run's state.
    pub state: &'a RunState,
    /// Passages the run will have when complete.
    pub passes_planned: usize,
    /// Why the study stopped before `passes_planned` (it is then complete).
    pub stop_reason: Option<&'a str>,
    /// The traffic classes of a growth study (empty for one passage).
    pub classes: &'a [TrafficClass],
    /// The measured record of the initial roughness, if any.
    pub record: Option<&'a RecordSamples>,
    /// The bands of the roughness levels.
    pub bands: &'a [Band],
    /// Each band's limit (dB re 1 um; inf: none).
    pub limit: &'a [f64],
    /// The limit's name ("ISO 3095").
    pub limit_name: &'a str,
    /// The traffic in the operator's units (a growth study's `[traffic]`).
    pub operation: Option<&'a Operation>,
    /// The two rails' names, the first's first, where the run has the
    /// wheelset's second rail (its state is `state.second_rail`).
    pub rail_names: Option<&'a [String; 2]>,
    /// The wear law's regimes ([`crate::wear::WearLaw::regimes`]): the
    /// meanings of `wear_regime`'s values 1, 2, ...
    pub wear_regimes: &'a [&'a str],
}
