//! A measured roughness record as the typed values the study receives:
//! the samples as read, the processing asked for, and what the processing
//! made of them (the processing itself: [`crate::growth::record`]).

use super::ProfileHarmonic;
use std::path::PathBuf;

/// A record as read: positions and heights in SI.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordSamples {
    /// The file it was read from (as resolved).
    pub file: PathBuf,
    /// Positions along the rail (m), increasing evenly.
    pub positions: Vec<f64>,
    /// Heights (m, up positive).
    pub heights: Vec<f64>,
    /// The 1-based line of each sample in the file (empty where the
    /// samples did not come from a file: a run file's stored record).
    pub lines: Vec<usize>,
    /// The position unit of the file ("m" or "mm").
    pub position_unit: String,
    /// The height unit of the file ("um", "mm" or "m").
    pub height_unit: String,
}

impl RecordSamples {
    /// The record's spacing (m): its length over its intervals.
    pub fn spacing(&self) -> f64 {
        let n = self.positions.len();
        (self.positions[n - 1] - self.positions[0]) / (n - 1) as f64
    }

    /// `file:line` of sample `i` (the file alone where lines are unknown).
    pub fn at(&self, i: usize) -> String {
        match self.lines.get(i) {
            Some(l) => format!("{}:{l}", self.file.display()),
            None => self.file.display().to_string(),
        }
    }

    /// SHA-256 of the samples (positions then heights, little-endian f64
    /// bits), in hex: the record's fingerprint in the resolved config.
    pub fn sha256(&self) -> String {
        use sha2::{Digest, Sha256};
        let mut h = Sha256::new();
        for v in self.positions.iter().chain(&self.heights) {
            h.update(v.to_le_bytes());
        }
        h.finalize().iter().map(|b| format!("{b:02x}")).collect()
    }
}

/// The pre-processing and the window (the config's `roughness` keys).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Processing {
    /// Spike removal threshold `k` (robust standard deviations of the
    /// second difference); None: no spike removal.
    pub spike_threshold: Option<f64>,
    /// Wheel radius of the curvature processing (m); None: none.
    pub curvature_radius: Option<f64>,
    /// Remove the window's least-squares line.
    pub detrend: bool,
    /// The window's first position in the record (m); None: the record's
    /// first sample.
    pub window_start: Option<f64>,
    /// Shortest wavelength kept (m).
    pub wavelength_min: f64,
    /// Longest wavelength kept (m).
    pub wavelength_max: f64,
}

/// A removed spike (or pit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spike {
    /// The sample of the run that departed most from the line that replaced it.
    pub index: usize,
    /// Samples replaced.
    pub width: usize,
    /// Its height above the replacing line (m; negative for a pit).
    pub height: f64,
}

/// What the processing did, for the terminal and the run file.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordReport {
    /// Spikes removed: (position in the record (m), height (m), samples).
    pub spikes: Vec<(f64, f64, usize)>,
    /// Curvature processing: the deepest fill (m) and the samples raised.
    pub filled: Option<(f64, usize)>,
    /// Detrending: the slope removed (1).
    pub slope: Option<f64>,
    /// The window: first sample's index and position (m), samples `M`.
    pub window: (usize, f64, usize),
    /// Whole windows the record holds.
    pub windows: usize,
    /// The step at the seam of the periodic stretch, first sample minus
    /// last of the window (m), and the rms step between neighbouring
    /// samples inside it (m).
    pub seam: (f64, f64),
    /// rms of the processed window about its mean (m), and of the
    /// harmonics kept (m).
    pub rms: (f64, f64),
}

/// A measured record made the rail's initial irregularity.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredRoughness {
    /// The record as read (stored in the run file: a resumed run rebuilds
    /// the profile from it).
    pub samples: RecordSamples,
    /// The processing asked for.
    pub processing: Processing,
    /// The profile's harmonics, phases for absolute X.
    pub harmonics: Vec<ProfileHarmonic>,
    /// What the processing did.
    pub report: RecordReport,
}
