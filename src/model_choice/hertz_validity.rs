//! Where the Hertz normal contact is good enough on a corrugated rail: the
//! measured validity map (`hertz_validity.csv` next to this file, made by
//! `scripts/validity_map.sh`).
//!
//! Per harmonic corrugation (wavelength, amplitude) the map holds the
//! relative difference between `contact.normal = "hertz"` and `"profile"`
//! in the first harmonic of one passage's wear (complex: amplitude and
//! phase; it drives growth) on `growth_exact.toml`'s scene (100 kN, 20 kN,
//! 100 km/h, receptance dynamics). A corrugation is in the Hertz region
//! when that difference is within [`HERTZ_LIMIT`]. Between measured points
//! the difference is interpolated bilinearly in (ln wavelength,
//! ln amplitude); outside the measured ranges the nearest edge is used;
//! a point whose runs failed (full sliding) counts as outside the region.

use std::sync::OnceLock;

/// The largest difference between the Hertz and the profile contact in the
/// wear's first harmonic that the Hertz region admits (1).
pub const HERTZ_LIMIT: f64 = 0.05;

/// Twice the nonlinear profile contact's noise floor at
/// [`PROFILE_NOISE_ELEMENT`]. The floor is the corrugation
/// amplitude whose wear harmonic the sub-element wandering of the patch
/// over the grid drowns (the contact point moves by R dr/dX; elements enter
/// and leave contact whole): about 2.5 um at 0.4 mm elements (60 mm
/// corrugation, scripts/validity_map.sh: the wear harmonic per um of
/// amplitude is 3 times its large-amplitude value at 1 um, 1.8 times at
/// 0.2 mm elements). First order in the element: scaled with `contact.dx`.
pub const PROFILE_NOISE_AMPLITUDE: f64 = 5e-6;

/// The element length at which [`PROFILE_NOISE_AMPLITUDE`] holds (m).
pub const PROFILE_NOISE_ELEMENT: f64 = 4e-4;

/// The measured map.
#[derive(Debug, Clone, PartialEq)]
pub struct HertzValidity {
    /// Wavelengths (m), increasing.
    wavelengths: Vec<f64>,
    /// Amplitudes (m), increasing.
    amplitudes: Vec<f64>,
    /// Differences (1) by (amplitude, wavelength), infinite where a run failed.
    difference: Vec<Vec<f64>>,
}

impl HertzValidity {
    /// The map built into the program.
    pub fn builtin() -> &'static HertzValidity {
        static MAP: OnceLock<HertzValidity> = OnceLock::new();
        MAP.get_or_init(|| {
            HertzValidity::parse(include_str!("hertz_validity.csv")).expect("the built-in validity map parses")
        })
    }

    /// Parses the CSV of `scripts/validity_map.sh` (`validity.csv`).
    pub fn parse(text: &str) -> Result<HertzValidity, String> {
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let header: Vec<&str> = lines.next().ok_or("empty map")?.split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).ok_or(format!("no column {name}"));
        let (cl, ca, cd) = (col("wavelength")?, col("amplitude")?, col("harmonic_difference")?);
        let mut points = Vec::new();
        for line in lines {
            let f: Vec<&str> = line.split(',').collect();
            let num = |i: usize| f.get(i).and_then(|v| v.trim().parse::<f64>().ok()).ok_or(format!("bad row: {line}"));
            let d = num(cd)?;
            points.push((num(cl)?, num(ca)?, if d.is_finite() { d } else { f64::INFINITY }));
        }
        let mut wavelengths: Vec<f64> = points.iter().map(|p| p.0).collect();
        let mut amplitudes: Vec<f64> = points.iter().map(|p| p.1).collect();
        for v in [&mut wavelengths, &mut amplitudes] {
            v.sort_by(f64::total_cmp);
            v.dedup();
        }
        let mut difference = vec![vec![f64::NAN; wavelengths.len()]; amplitudes.len()];
        for (l, a, d) in points {
            let i = wavelengths.iter().position(|w| *w == l).expect("listed");
            let j = amplitudes.iter().position(|w| *w == a).expect("listed");
            difference[j][i] = d;
        }
        if difference.iter().flatten().any(|d| d.is_nan()) {
            return Err("the map is not a full wavelength x amplitude grid".into());
        }
        Ok(HertzValidity { wavelengths, amplitudes, difference })
    }

    /// The difference (1) at a corrugation of `wavelength` (m) and
    /// `amplitude` (m); infinite where the map's runs failed nearby.
    pub fn difference(&self, wavelength: f64, amplitude: f64) -> f64 {
        let (i0, i1, u) = bracket(&self.wavelengths, wavelength);
        let (j0, j1, v) = bracket(&self.amplitudes, amplitude);
        let d = &self.difference;
        let corners = [
            (d[j0][i0], (1.0 - u) * (1.0 - v)),
            (d[j0][i1], u * (1.0 - v)),
            (d[j1][i0], (1.0 - u) * v),
            (d[j1][i1], u * v),
        ];
        corners.iter().filter(|(_, w)| *w > 0.0).map(|(d, w)| d * w).sum()
    }

    /// Whether the corrugation lies in the Hertz region.
    pub fn hertz_is_valid(&self, wavelength: f64, amplitude: f64) -> bool {
        self.difference(wavelength, amplitude) <= HERTZ_LIMIT
    }
}

/// Neighbours and weight of `x` among increasing `xs`, in ln x, clamped.
fn bracket(xs: &[f64], x: f64) -> (usize, usize, f64) {
    let n = xs.len();
    if n == 1 || x <= xs[0] {
        return (0, 0, 0.0);
    }
    if x >= xs[n - 1] {
        return (n - 1, n - 1, 0.0);
    }
    let i = xs.windows(2).position(|w| x < w[1]).expect("inside");
    (i, i + 1, (x / xs[i]).ln() / (xs[i + 1] / xs[i]).ln())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_in_logs_and_treats_failures_as_outside() {
        let csv =
            "wavelength,amplitude,harmonic_difference\n0.01,1e-6,0.02\n0.04,1e-6,0.01\n0.01,4e-6,0.2\n0.04,4e-6,nan\n";
        let m = HertzValidity::parse(csv).unwrap();
        assert!((m.difference(0.01, 1e-6) - 0.02).abs() < 1e-15);
        // Halfway in ln wavelength: the mean.
        assert!((m.difference(0.02, 1e-6) - 0.015).abs() < 1e-12);
        // Clamped below the smallest amplitude and above the longest wavelength.
        assert!((m.difference(0.1, 1e-7) - 0.01).abs() < 1e-15);
        assert!(m.hertz_is_valid(0.02, 1e-6) && !m.hertz_is_valid(0.01, 4e-6));
        assert!(m.difference(0.03, 3e-6).is_infinite());
        assert!(
            HertzValidity::parse("wavelength,amplitude,harmonic_difference\n0.01,1e-6,0.1\n0.02,2e-6,0.1\n").is_err()
        );
    }

    #[test]
    fn builtin_map_parses() {
        let m = HertzValidity::builtin();
        assert!(m.wavelengths.len() >= 5 && m.amplitudes.len() >= 5);
    }
}
