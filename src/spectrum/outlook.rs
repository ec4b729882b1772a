//! When each band of a rail reaches its limit, from the linear growth
//! spectrum: a forecast that belongs to the track, the traffic and the
//! roughness's spectrum, not to the stretch a study runs on (book:
//! docs/src/guide/when-to-grind.md).
//!
//! A band's level now is the roughness's own (its [`RoughnessDensity`]
//! between the band's edges: for a measured record the whole record's
//! EN 15610 level). Its change with traffic is the spectrum's
//! ([`BandSeries`]): the roughness carried by the update `E(n)` over every
//! harmonic of the supercell that falls in the band, fed by every harmonic
//! the sleepers couple to it, plus the forced pattern's deepening `Phi(n)
//! F`. With `S(n)` the band's mean square of roughness on the spectrum's
//! harmonics (the same density sampled on them) and `Q(n)` the forced
//! pattern's,
//!
//! ```text
//! L(n) = 10 lg((ms_0 S(n) / S(0) + Q(n)) / r0^2)
//! ```
//!
//! so `L(0)` is the roughness's level exactly and the growth is the
//! spectrum's. A band is forecast where the spectrum measured its
//! wavelengths (both edges inside `spectrum.wavelength_min ..
//! wavelength_max`), at least one of the supercell's harmonics falls in it,
//! and, for a measured record, its nominal centre is at most a quarter of
//! the record (EN 15610's rule); the others are listed with the reason.
//!
//! This is the linear regime's forecast: it holds while the roughness stays
//! small against what makes the contact non-linear (loss of contact, the
//! patch's size). Its horizon is the traffic at which the roughness on
//! every harmonic the spectrum measured has grown tenfold in rms (+20 dB,
//! a convention, not a property of the contact): a
//! crossing beyond it is an extrapolation, and says so. (Past it a growing
//! mode's tail, coupled into a decaying band by the sleepers, would carry
//! that band to its limit on the strength of a pattern a hundred times the
//! roughness measured.)

use super::forecast::{BandGrowth, BandSeries};
use crate::levels::density::RoughnessDensity;
use crate::levels::forecast::first_crossing;
use crate::levels::{Band, LEVEL_FLOOR, R0};
use std::f64::consts::PI;

/// Traffic over which a band's initial rate is taken (wheel passages).
const RATE_STEP: f64 = 1e3;

/// The growth of the bands' mean square that ends the linear horizon (1:
/// +20 dB).
const HORIZON_GROWTH: f64 = 100.0;

/// The levels against traffic are given up to this many times the linear
/// horizon.
const REACH: f64 = 10.0;

/// One band's forecast.
#[derive(Debug, Clone, PartialEq)]
pub struct BandOutlook {
    /// The band.
    pub band: Band,
    /// The supercell's harmonics in it (conjugate pairs once).
    pub lines: f64,
    /// Its level now (dB re 1 um).
    pub level: f64,
    /// The roughness's growth rate now (dB per 1e5 wheel passages; NaN
    /// where the band holds no roughness).
    pub rate: f64,
    /// Its limit (dB re 1 um; inf: none).
    pub limit: f64,
    /// Wheel passages until it reaches the limit (0: at or above it now;
    /// inf: never within 1e15).
    pub passages: f64,
    /// Its level after each traffic of [`Outlook::traffic`] (dB re 1 um).
    pub levels: Vec<f64>,
}

/// The forecast of every band.
#[derive(Debug, Clone, PartialEq)]
pub struct Outlook {
    /// The bands forecast.
    pub rows: Vec<BandOutlook>,
    /// The bands left out, with why.
    pub left_out: Vec<(Band, String)>,
    /// The traffic the levels are given at (wheel passages): the asked
    /// traffic up to ten times the horizon.
    pub traffic: Vec<f64>,
    /// The linear horizon (wheel passages; inf: none): where the bands'
    /// roughness has grown tenfold in rms (see the module doc).
    pub horizon: f64,
}

impl BandOutlook {
    /// Whether the band reaches its limit beyond the linear horizon.
    pub fn extrapolated(&self, outlook: &Outlook) -> bool {
        self.passages.is_finite() && self.passages > outlook.horizon
    }
}

/// What the forecast is of.
pub struct Inputs<'a> {
    /// The spectrum's update.
    pub growth: &'a BandGrowth,
    /// The rail (0: the first).
    pub rail: usize,
    /// The roughness now.
    pub density: &'a RoughnessDensity,
    /// The record's length (m), for a measured record.
    pub record_length: Option<f64>,
    /// The spectrum's wavelengths (m): shortest, longest.
    pub measured: (f64, f64),
    /// The candidate bands and their limits (dB re 1 um).
    pub bands: &'a [(Band, f64)],
    /// The traffic to give the levels at (wheel passages).
    pub traffic: &'a [f64],
}

/// The forecast of each band (see the module doc).
pub fn outlook(i: &Inputs) -> Outlook {
    // The horizon: over every harmonic the spectrum measured, whichever
    // bands are asked for.
    let between = |a: f64, b: f64| i.density.between(a, b);
    let (k_low, k_high) = (2.0 * PI / i.measured.1, 2.0 * PI / i.measured.0);
    let all = i.growth.band(i.rail, &between, k_low * (1.0 - 1e-9), k_high * (1.0 + 1e-9));
    let now = all.at(0.0).roughness;
    let total = |n: f64| {
        let ms = all.at(n);
        ms.roughness + ms.forced
    };
    let horizon = if now > 0.0 { first_crossing(&total, HORIZON_GROWTH * now) } else { f64::INFINITY };
    // The levels against traffic up to REACH times the horizon: beyond it
    // the linear regime's levels are hundreds of dB past any roughness.
    let traffic: Vec<f64> = i.traffic.iter().copied().filter(|n| *n <= REACH * horizon).collect();
    let (mut rows, mut left_out, mut empty) = (Vec::new(), Vec::new(), Vec::new());
    for &(band, limit) in i.bands {
        let (k_low, k_high) = (2.0 * PI / band.upper, 2.0 * PI / band.lower);
        if band.lower < i.measured.0 * (1.0 - 1e-9) || band.upper > i.measured.1 * (1.0 + 1e-9) {
            left_out.push((band, "outside the spectrum's wavelengths (spectrum.wavelength_min, _max)".into()));
            continue;
        }
        if let Some(l) = i.record_length
            && band.wavelength > l / 4.0 * (1.0 + 1e-9)
        {
            left_out.push((band, format!("longer than a quarter of the {l} m record (EN 15610)")));
            continue;
        }
        let lines = i.growth.lines(i.rail, k_low, k_high);
        if lines == 0.0 {
            empty.push((band, i.growth.classes_for(k_low, k_high)));
            continue;
        }
        let between = |a: f64, b: f64| i.density.between(a, b);
        let series = i.growth.band(i.rail, &between, k_low, k_high);
        let level = Level::new(series, i.density.between(k_low, k_high));
        let now = level.at(0.0);
        let passages = if now >= limit {
            0.0
        } else if limit.is_finite() {
            first_crossing(&|n| level.at(n), limit)
        } else {
            f64::INFINITY
        };
        rows.push(BandOutlook {
            band,
            lines,
            level: now,
            rate: level.rate(),
            limit,
            passages,
            levels: traffic.iter().map(|n| level.at(*n)).collect(),
        });
    }
    // The bands without a harmonic: the classes that give each one.
    let needed = empty.iter().map(|(_, m)| *m).max().unwrap_or(1);
    let why = format!("no harmonic of the supercell in it (spectrum.classes = {needed} puts one in each)");
    left_out.extend(empty.into_iter().map(|(band, _)| (band, why.clone())));
    Outlook { rows, left_out, traffic, horizon }
}

/// A band's level against traffic.
struct Level {
    series: BandSeries,
    /// The roughness's mean square in the band now (m^2).
    now: f64,
    /// The same on the spectrum's harmonics (m^2).
    sampled: f64,
}

impl Level {
    fn new(series: BandSeries, now: f64) -> Self {
        let sampled = series.at(0.0).roughness;
        Level { series, now, sampled }
    }

    /// The band's mean square after `n` wheel passages (m^2).
    fn mean_square(&self, n: f64) -> f64 {
        let ms = self.series.at(n);
        let rough = if self.sampled > 0.0 { self.now * ms.roughness / self.sampled } else { self.now };
        rough + ms.forced
    }

    /// The level after `n` wheel passages (dB re 1 um).
    fn at(&self, n: f64) -> f64 {
        let total = self.mean_square(n);
        if !total.is_finite() {
            return f64::INFINITY;
        }
        (10.0 * (total / (R0 * R0)).log10()).max(LEVEL_FLOOR)
    }

    /// The roughness's rate now (dB per 1e5 wheel passages).
    fn rate(&self) -> f64 {
        if self.sampled <= 0.0 || self.now <= 0.0 {
            return f64::NAN;
        }
        10.0 * (self.series.at(RATE_STEP).roughness / self.sampled).log10() / RATE_STEP * 1e5
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::{BandSet, all_bands};
    use crate::spectrum::forecast::fixture::{diagonal, smooth};
    use num_complex::Complex64;

    /// A rate smooth in wavenumber (per wheel passage): +1.7 dB per 1e5 at
    /// long wavelengths, zero at 31.4 mm, decaying below.
    fn rate(k: f64) -> f64 {
        2e-6 * (1.0 - k / 200.0)
    }

    fn forecast(length: f64, first: usize, last: usize, density: &RoughnessDensity) -> Outlook {
        let growth = BandGrowth::new(&smooth(length, first, last, &rate)).unwrap();
        let bands: Vec<(Band, f64)> = all_bands(BandSet::ThirdOctave).into_iter().map(|b| (b, 0.0)).collect();
        outlook(&Inputs {
            growth: &growth,
            rail: 0,
            density,
            record_length: Some(0.6),
            measured: (0.01, 0.15),
            bands: &bands,
            traffic: &[0.0, 1e6],
        })
    }

    #[test]
    fn two_supercells_forecast_the_same_bands() {
        // A flat density (1 um rms over 10-150 mm) on supercells of 480 and
        // 600 mm (harmonics 10-150 mm): each band's level now is the
        // density's, whatever the lattice. In every band (the longest hold
        // one harmonic) the level after 1e6 wheel passages agrees within
        // 0.3 dB and, where the band grows at 0.1 dB per 1e5 or more, the
        // traffic to a 0 dB limit within 10 %: the rate's slope across each
        // harmonic's interval carries the band's fast-growing edge.
        let density = RoughnessDensity::flat(1e-12, 0.01, 0.15);
        let a = forecast(0.48, 4, 48, &density);
        let b = forecast(0.6, 4, 60, &density);
        assert_eq!(a.rows.len(), b.rows.len(), "{:?} / {:?}", a.left_out, b.left_out);
        let (mut reached, mut compared) = (0, 0);
        for (x, y) in a.rows.iter().zip(&b.rows) {
            let k = (2.0 * PI / x.band.upper, 2.0 * PI / x.band.lower);
            let own = 10.0 * (density.between(k.0, k.1) / 1e-12).log10();
            assert!((x.level - own).abs() < 1e-9 && (y.level - own).abs() < 1e-9, "{}", x.band.label());
            compared += 1;
            assert!((x.levels[1] - y.levels[1]).abs() < 0.3, "{}: {:?} vs {:?}", x.band.label(), x.levels, y.levels);
            // The rate now is the rate at the band's wavenumbers.
            let centre = rate(2.0 * PI / x.band.wavelength) * 1e5 * 20.0 / std::f64::consts::LN_10;
            assert!((x.rate - centre).abs() < 0.15, "{}: {} vs {centre}", x.band.label(), x.rate);
            if x.rate >= 0.1 {
                reached += 1;
                let spread = x.passages.max(y.passages) / x.passages.min(y.passages) - 1.0;
                assert!(spread < 0.1, "{}: {} vs {}", x.band.label(), x.passages, y.passages);
            }
        }
        assert!(compared >= 8, "{compared} bands compared");
        assert!(reached >= 3, "{reached} bands reach the limit");
    }

    #[test]
    fn a_band_reaches_its_limit_at_its_rate_and_a_record_line_off_the_lattice_counts() {
        // One line of 3 um at 50 mm, which no harmonic of the 120 mm
        // stretch has, on a lattice of 480 mm: the 50 mm band holds the
        // line's mean square and reaches a limit 10 dB up at the rate of
        // its harmonics (60 mm is outside the band; 48 and 53.3 mm in it).
        let line = |k: f64| (k * (1.0 - 1e-9), k * (1.0 + 1e-9), 4.5e-12);
        let density = RoughnessDensity::from_intervals(&[line(2.0 * PI / 0.05)]);
        let growth = BandGrowth::new(&diagonal(0.48, &[2e-6; 48], &[Complex64::default(); 48])).unwrap();
        let band = Band::third_octave(13);
        let limit = 10.0 * (4.5f64).log10() + 10.0;
        let o = outlook(&Inputs {
            growth: &growth,
            rail: 0,
            density: &density,
            record_length: None,
            measured: (0.01, 0.48),
            bands: &[(band, limit)],
            traffic: &[0.0, 1e6, 1e7, 1e8, 1e9, 1e12],
        });
        let row = &o.rows[0];
        assert_eq!(row.lines, 2.0);
        assert!((row.level - 10.0 * 4.5f64.log10()).abs() < 1e-9);
        let want = 10.0 / (2e-6 * 20.0 / std::f64::consts::LN_10);
        assert!((row.passages / want - 1.0).abs() < 1e-6, "{} vs {want}", row.passages);
        // The horizon: the whole roughness grown tenfold, +20 dB.
        assert!((o.horizon / (2.0 * want) - 1.0).abs() < 1e-6, "{}", o.horizon);
        assert!(!row.extrapolated(&o));
        // The levels against traffic: up to ten times the horizon (2.9e6
        // passages here), each at the rate from the level now.
        assert_eq!(o.traffic, [0.0, 1e6, 1e7]);
        for (n, l) in o.traffic.iter().zip(&row.levels) {
            let grown = row.level + 2e-6 * 20.0 / std::f64::consts::LN_10 * n;
            assert!((l - grown).abs() < 1e-6, "{n}: {l} vs {grown}");
        }
    }
}
