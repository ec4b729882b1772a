//! Rail roughness in the field's units: band levels in dB re 1 um
//! (EN 15610), the limit they are held against ([`limit`]: ISO 3095's rail
//! roughness limit, or a user's curve) and when a band reaches it
//! ([`forecast`]).
//!
//! The level of a band is
//!
//! ```text
//! L = 10 lg(r_rms^2 / r0^2),  r0 = 1 um,
//! ```
//!
//! `r_rms^2` the mean square of the roughness in the band. On the periodic
//! stretch of length `L_s` a profile line is exactly a sum of harmonics of
//! wavelength `L_s/n` (amplitudes `A_n`, [`crate::harmonics`]), so by
//! Parseval a band's mean square is `sum A_n^2 / 2` over the harmonics whose
//! wavelength lies in the band: no window, no leakage.
//!
//! Bands (EN 15610): base-ten one-third octaves of wavenumber, centres
//! `10^(k/10)` 1/m, edges `x 10^(+-0.05)`, labelled with their nominal
//! centre wavelengths (R10 series: 100, 80, 63, 50, 40, 31.5, 25, 20, 16,
//! 12.5, 10, 8, 6.3, 5, 4, 3.15, 2.5, 2, 1.6, 1.25, 1 mm, ...); or
//! EN 13231-3's corrugation bands 10-30, 30-100, 100-300 and 300-1000 mm
//! (labelled with their geometric centres). A stretch resolves the bands
//! whose nominal centre is at most a quarter of its length (EN 15610's rule
//! for a record; on the periodic stretch the longer harmonics are exact, and
//! `passes/growth_rate` gives them one by one), whose shortest wavelength
//! is above two rail nodes (the grid's Nyquist limit), down to 1 mm
//! (shorter roughness is filtered out by any contact patch), and which hold
//! at least one harmonic of the stretch.
//!
//! Which line: EN 15610 measures lines along the running band and averages
//! their band spectra by mean square. The rail grid's lines inside the
//! running band, `|y| <= b` of the mean patch, are taken the same way: the
//! band's mean square is the mean of the lines' mean squares (every line
//! weighs the same; the grid's lines are evenly spaced). For a profile
//! uniform across the head this is the centre line's level.

pub mod density;
pub mod forecast;
pub mod limit;

use crate::harmonics::amplitudes;
use crate::rail_grid::RailGrid;
use ndarray::Array2;

/// The reference roughness r0 of the levels (m).
pub const R0: f64 = 1e-6;

/// The lowest level written (dB re 1 um): a band whose rms is below 1 pm
/// holds numerical noise of the profile, not roughness; its level reads
/// this, and its rate 0.
pub const LEVEL_FLOOR: f64 = -120.0;

/// The shortest nominal band centre reported (m).
pub const SHORTEST_BAND: f64 = 1e-3;

/// The R10 preferred numbers: the nominal centre wavelengths of a decade of
/// one-third-octave bands (EN 15610).
const R10: [f64; 10] = [1.0, 1.25, 1.6, 2.0, 2.5, 3.15, 4.0, 5.0, 6.3, 8.0];

/// EN 13231-3's corrugation bands, wavelengths (m): [shortest, longest).
const EN13231_BANDS: [(f64, f64); 4] = [(0.300, 1.000), (0.100, 0.300), (0.030, 0.100), (0.010, 0.030)];

/// Which bands the levels are reported in (`levels.bands`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BandSet {
    /// Base-ten one-third-octave bands (EN 15610).
    #[default]
    ThirdOctave,
    /// EN 13231-3's corrugation bands 10-30, 30-100, 100-300, 300-1000 mm.
    En13231,
}

/// One band of wavelengths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// The band's label: its nominal centre wavelength (m).
    pub wavelength: f64,
    /// Shortest wavelength of the band (m), inclusive.
    pub lower: f64,
    /// Longest wavelength of the band (m), exclusive.
    pub upper: f64,
}

impl Band {
    /// The one-third-octave band of index `k`: centre wavenumber `10^(k/10)`
    /// 1/m, edges `x 10^(+-0.05)`.
    pub fn third_octave(k: i32) -> Band {
        let centre = 10f64.powf(-f64::from(k) / 10.0);
        let decade = (-k).div_euclid(10);
        let nominal = R10[(-k).rem_euclid(10) as usize] * 10f64.powi(decade);
        Band { wavelength: nominal, lower: centre * 10f64.powf(-0.05), upper: centre * 10f64.powf(0.05) }
    }

    /// Whether the wavelength `lambda` (m) lies in the band.
    pub fn contains(&self, lambda: f64) -> bool {
        self.lower <= lambda && lambda < self.upper
    }

    /// The band's label in mm as a person writes it ("31.5 mm").
    pub fn label(&self) -> String {
        format!("{} mm", crate::numerics::round_sig(self.wavelength * 1e3, 3))
    }
}

/// The bands of `set` a periodic stretch of `n` nodes spaced `dx` (m)
/// resolves, longest first (see the module doc).
pub fn resolved_bands(set: BandSet, n: usize, dx: f64) -> Vec<Band> {
    let length = n as f64 * dx;
    all_bands(set)
        .into_iter()
        .filter(|b| b.wavelength <= length / 4.0 * (1.0 + 1e-9))
        .filter(|b| b.lower > 2.0 * dx && b.wavelength >= SHORTEST_BAND * (1.0 - 1e-9))
        .filter(|b| (1..=n / 2).any(|k| b.contains(length / k as f64)))
        .collect()
}

/// The bands of `set` from 1 m down to [`SHORTEST_BAND`], longest first.
pub fn all_bands(set: BandSet) -> Vec<Band> {
    match set {
        // k = 10 lg(wavenumber in 1/m).
        BandSet::ThirdOctave => (0..=30).map(Band::third_octave).collect(),
        BandSet::En13231 => EN13231_BANDS
            .iter()
            .map(|&(lower, upper)| Band { wavelength: (lower * upper).sqrt(), lower, upper })
            .collect(),
    }
}

/// Mean squares (m^2) in each band of the line whose harmonic amplitudes
/// are `amps` (m, harmonics n = 1 .. of the stretch), given each band's
/// harmonic indices `members` (n - 1).
fn band_mean_squares(amps: &[f64], members: &[Vec<usize>]) -> Vec<f64> {
    members.iter().map(|m| m.iter().map(|&i| 0.5 * amps[i] * amps[i]).sum()).collect()
}

/// The level (dB re 1 um) of a mean square `ms` (m^2), floored at
/// [`LEVEL_FLOOR`].
pub fn level(ms: f64) -> f64 {
    let l = 10.0 * (ms / (R0 * R0)).log10();
    if l.is_nan() { LEVEL_FLOOR } else { l.max(LEVEL_FLOOR) }
}

/// The growth rate of each band between the levels `before` and `after`
/// (dB) separated by `traffic` real wheel passages, in dB per 1e5
/// passages; 0 where either level is at the floor (no roughness to grow).
pub fn level_rates(before: &[f64], after: &[f64], traffic: f64) -> Vec<f64> {
    before
        .iter()
        .zip(after)
        .map(|(b, a)| if *b > LEVEL_FLOOR && *a > LEVEL_FLOOR { (a - b) * 1e5 / traffic } else { 0.0 })
        .collect()
}

/// The band levels of the rail profiles of one run: its bands, which
/// harmonics of the stretch fall in each, and which grid lines form the
/// running band.
#[derive(Debug, Clone)]
pub struct BandLevels {
    bands: Vec<Band>,
    members: Vec<Vec<usize>>,
    rows: Vec<usize>,
}

impl BandLevels {
    /// The levels of `set` on the periodic grid `grid`, averaged over the
    /// lines `|y| <= half_band` (m; the centre line if none lies there).
    pub fn new(set: BandSet, grid: &RailGrid, half_band: f64) -> Self {
        let (n, length) = (grid.nx, grid.nx as f64 * grid.dx);
        let bands = resolved_bands(set, n, grid.dx);
        let members = bands
            .iter()
            .map(|b| (1..=n / 2).filter(|&k| b.contains(length / k as f64)).map(|k| k - 1).collect())
            .collect();
        let mut rows: Vec<usize> = (0..grid.ny).filter(|&j| grid.y(j).abs() <= half_band * (1.0 + 1e-12)).collect();
        if rows.is_empty() {
            rows.push(crate::metrics::centre_row(grid));
        }
        BandLevels { bands, members, rows }
    }

    /// The bands, longest first.
    pub fn bands(&self) -> &[Band] {
        &self.bands
    }

    /// The grid lines whose band spectra are averaged.
    pub fn rows(&self) -> &[usize] {
        &self.rows
    }

    /// The band levels (dB re 1 um) of the rail `profile` (ny, nx; m): the
    /// mean over the running band's lines of each band's mean square.
    pub fn levels(&self, profile: &Array2<f64>) -> Vec<f64> {
        let mut total = vec![0.0; self.bands.len()];
        for &j in &self.rows {
            let line = profile.row(j).to_vec();
            for (t, ms) in total.iter_mut().zip(band_mean_squares(&amplitudes(&line), &self.members)) {
                *t += ms;
            }
        }
        total.iter().map(|t| level(t / self.rows.len() as f64)).collect()
    }

    /// The band levels (dB re 1 um) of one line given by its harmonic
    /// amplitudes `amps` (m; harmonics n = 1 .. of the stretch, as
    /// `passes/spectrum` stores them).
    pub fn levels_of_spectrum(&self, amps: &[f64]) -> Vec<f64> {
        band_mean_squares(amps, &self.members).into_iter().map(level).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn third_octave_bands_have_the_nominal_labels_and_edges() {
        let labels: Vec<f64> = (10..=30).map(|k| Band::third_octave(k).wavelength * 1e3).collect();
        let want = [
            100.0, 80.0, 63.0, 50.0, 40.0, 31.5, 25.0, 20.0, 16.0, 12.5, 10.0, 8.0, 6.3, 5.0, 4.0, 3.15, 2.5, 2.0, 1.6,
            1.25, 1.0,
        ];
        for (l, w) in labels.iter().zip(want) {
            assert!((l - w).abs() < 1e-9 * w, "{l} vs {w}");
        }
        // Adjacent bands share an edge, and the edges are 10^(+-0.05) of the
        // exact centre 10^(-k/10) m.
        let (a, b) = (Band::third_octave(15), Band::third_octave(16));
        assert!((a.lower - b.upper).abs() < 1e-15);
        assert!((a.upper / 10f64.powf(-1.5) - 10f64.powf(0.05)).abs() < 1e-12);
        assert_eq!(Band::third_octave(15).label(), "31.5 mm");
        assert_eq!(Band::third_octave(22).label(), "6.3 mm");
    }

    #[test]
    fn a_stretch_resolves_up_to_a_quarter_of_its_length() {
        // 120 mm at 0.2 mm: 25 mm (<= 30 mm) is the longest band, 31.5 mm
        // (> 30 mm) is not; the shortest is 1 mm.
        let bands = resolved_bands(BandSet::ThirdOctave, 600, 2e-4);
        assert!((bands[0].wavelength - 0.025).abs() < 1e-12, "{:?}", bands[0]);
        assert!((bands.last().unwrap().wavelength - 0.001).abs() < 1e-12);
        // 600 mm: up to 125 mm; EN 13231-3's bands whose centre is under
        // 150 mm: 30-100 mm (54.8 mm) and 10-30 mm (17.3 mm).
        assert!((resolved_bands(BandSet::ThirdOctave, 3000, 2e-4)[0].wavelength - 0.125).abs() < 1e-12);
        let en = resolved_bands(BandSet::En13231, 3000, 2e-4);
        assert_eq!(en.len(), 2);
        assert!((en[0].lower - 0.03).abs() < 1e-15 && (en[1].upper - 0.03).abs() < 1e-15);
        assert!((en[1].wavelength - (0.01f64 * 0.03).sqrt()).abs() < 1e-15);
        // A coarse grid (2 mm) drops the bands it cannot resolve (lower edge
        // below two nodes, 4 mm).
        let coarse = resolved_bands(BandSet::ThirdOctave, 60, 2e-3);
        assert!(coarse.iter().all(|b| b.lower > 4e-3) && coarse.last().unwrap().wavelength > 4e-3);
    }

    /// The closed form: a line of harmonics `(n, amplitude)` of the
    /// stretch has in each band the level 10 lg(sum A^2/2 / r0^2) of the
    /// harmonics inside it.
    #[test]
    fn harmonics_give_their_closed_form_levels_within_0_1_db() {
        let grid = RailGrid { x_min: 0.0, dx: 2e-4, nx: 600, half_width: 0.01, dy: 1e-3, ny: 21 };
        let length = 0.12;
        // 30 mm (n = 4) and 24 mm (n = 5) are in different bands (31.5 mm is
        // not resolved: only 24 mm counts, in the 25 mm band); 10 and 12 mm
        // in the 10 and 12.5 mm bands; 6 and 6.32 mm... two harmonics in one
        // band (6.3 mm: 5.62-7.08 mm): n = 19 (6.32 mm) and n = 20 (6 mm).
        let harmonics = [(5, 3e-6), (10, 0.5e-6), (12, 0.2e-6), (19, 0.1e-6), (20, 0.3e-6)];
        let line: Vec<f64> = grid
            .xs()
            .iter()
            .map(|x| {
                harmonics.iter().map(|(n, a)| a * (2.0 * PI * *n as f64 * x / length + 0.7 * *n as f64).sin()).sum()
            })
            .collect();
        let profile = Array2::from_shape_fn((grid.ny, grid.nx), |(_, i)| line[i]);
        let levels = BandLevels::new(BandSet::ThirdOctave, &grid, 0.005);
        assert_eq!(levels.rows().len(), 11);
        let got = levels.levels(&profile);
        let find = |mm: f64| levels.bands().iter().position(|b| (b.wavelength - mm * 1e-3).abs() < 1e-9).unwrap();
        let closed = |amps: &[f64]| 10.0 * (amps.iter().map(|a| a * a / 2.0).sum::<f64>() / 1e-12).log10();
        for (mm, amps) in [(25.0, vec![3e-6]), (12.5, vec![0.5e-6]), (10.0, vec![0.2e-6]), (6.3, vec![0.1e-6, 0.3e-6])]
        {
            let (l, want) = (got[find(mm)], closed(&amps));
            assert!((l - want).abs() < 0.1, "{mm} mm: {l} vs {want}");
        }
        // 3e-6 sin: 3 um amplitude, 2.12 um rms, 6.53 dB.
        assert!((got[find(25.0)] - 6.532).abs() < 1e-3);
        // Empty bands are at the floor.
        assert_eq!(got[find(16.0)], LEVEL_FLOOR);
        // The same from the stored spectrum of the line.
        let from_spectrum = levels.levels_of_spectrum(&amplitudes(&line));
        assert!(got.iter().zip(&from_spectrum).all(|(a, b)| (a - b).abs() < 1e-9));
    }

    #[test]
    fn lines_across_the_running_band_average_by_mean_square() {
        // Lines at y = -1, 0, 1 mm with 1, 3 and 1 um of one harmonic (25 mm).
        let grid = RailGrid { x_min: 0.0, dx: 1e-3, nx: 100, half_width: 0.001, dy: 0.001, ny: 3 };
        let profile =
            Array2::from_shape_fn((3, 100), |(j, i)| [1e-6, 3e-6, 1e-6][j] * (2.0 * PI * 4.0 * i as f64 / 100.0).sin());
        // |y| <= 0.5 mm: the centre line alone, 4.5 um^2.
        let centre = BandLevels::new(BandSet::ThirdOctave, &grid, 0.0005);
        assert_eq!(centre.rows(), &[1]);
        let k = centre.bands().iter().position(|b| b.contains(0.025)).unwrap();
        assert!((centre.levels(&profile)[k] - 10.0 * 4.5f64.log10()).abs() < 1e-9);
        // |y| <= 1 mm: the three lines, (0.5 + 4.5 + 0.5)/3 um^2.
        let all = BandLevels::new(BandSet::ThirdOctave, &grid, 0.001);
        assert_eq!(all.rows(), &[0, 1, 2]);
        assert!((all.levels(&profile)[k] - 10.0 * (11.0f64 / 6.0).log10()).abs() < 1e-9);
        // No line inside: the centre line.
        assert_eq!(BandLevels::new(BandSet::ThirdOctave, &grid, 0.0).rows(), &[1]);
    }

    #[test]
    fn rates_are_level_changes_per_1e5_passages() {
        let r = level_rates(&[0.0, -3.0, LEVEL_FLOOR], &[1.0, -4.0, 5.0], 2e5);
        assert_eq!(r, vec![0.5, -0.5, 0.0]);
        assert_eq!(level(0.0), LEVEL_FLOOR);
        assert!((level(1e-12) - 0.0).abs() < 1e-12);
    }
}
