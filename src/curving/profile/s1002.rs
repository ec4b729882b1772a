//! The S1002 wheel profile (EN 13715), by its defining sections A-H.
//!
//! The profile height `F(s)` (mm) is the wheel's radius less its radius at
//! the tape circle, at the lateral coordinate `s` (mm) from the tape circle,
//! positive towards the field side (the flange at negative `s`, its back at
//! `s = -70`). Sections (EN 13715 annex, S1002):
//!
//! ```text
//! A  32.15796 <= s <= 60           F = 1.364323640 - 0.066666667 s          (1:15)
//! B  -26 <= s < 32.15796           F = polynomial of degree 8
//! C  -35 <= s < -26                F = -(polynomial of degree 7)
//! D  -38.426669071 <= s < -35      F = 16.446 - sqrt(13^2 - (s + 26.210665)^2)
//! E  -39.764473993 <= s < D        F = -93.576667419 - 2.747477419 s
//! F  -49.662510381 <= s < E        F = 8.834924130 + sqrt(20^2 - (s + 58.558326413)^2)
//! G  -62.764705882 <= s < F        F = 16 + sqrt(12^2 - (s + 55)^2)         (flange top)
//! H  -70 <= s < G                  F = 9.519259302 + sqrt(20.5^2 - (s + 49.5)^2)
//! ```

/// Section B's coefficients, `F = sum b_k s^k` (signs included).
const B: [f64; 9] = [
    0.0,
    -3.358537058e-02,
    1.565681624e-03,
    -2.810427944e-05,
    5.844240864e-08,
    -1.562379023e-08,
    5.309217349e-15,
    -5.957839843e-12,
    2.646656573e-13,
];

/// Section C's coefficients, `F = sum c_k s^k` (signs included).
const C: [f64; 8] = [
    -4.320221063e+03,
    -1.038384026e+03,
    -1.065501873e+02,
    -6.051367875,
    -2.054332446e-01,
    -4.169739389e-03,
    -4.687195829e-05,
    -2.252755540e-07,
];

/// The sections' bounds (mm), from the flange back to the field side.
pub const BOUNDS: [f64; 9] =
    [-70.0, -62.764705882, -49.662510381, -39.764473993, -38.426669071, -35.0, -26.0, 32.15796, 60.0];

fn polynomial(c: &[f64], s: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * s + k)
}

fn arc(a: f64, r: f64, c: f64, s: f64) -> f64 {
    a + (r * r - (s + c) * (s + c)).max(0.0).sqrt()
}

/// S1002's height `F(s)` (mm) at `s` (mm, from the tape circle, positive to
/// the field side); None outside [-70, 60].
pub fn height_mm(s: f64) -> Option<f64> {
    if !(BOUNDS[0]..=BOUNDS[8]).contains(&s) {
        return None;
    }
    Some(if s < BOUNDS[1] {
        arc(9.519259302, 20.5, 49.5, s)
    } else if s < BOUNDS[2] {
        arc(16.0, 12.0, 55.0, s)
    } else if s < BOUNDS[3] {
        arc(8.834924130, 20.0, 58.558326413, s)
    } else if s < BOUNDS[4] {
        -93.576667419 - 2.747477419 * s
    } else if s < BOUNDS[5] {
        16.446 - (169.0 - (s + 26.210665) * (s + 26.210665)).max(0.0).sqrt()
    } else if s < BOUNDS[6] {
        polynomial(&C, s)
    } else if s < BOUNDS[7] {
        polynomial(&B, s)
    } else {
        1.364323640 - 0.066666667 * s
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defining_dimensions() {
        // Tape circle, flange height 28 mm at s = -55, flange thickness
        // 32.5 mm at 10 mm above the tape circle (from the back at -70).
        assert!(height_mm(0.0).unwrap().abs() < 1e-9);
        assert!((height_mm(-55.0).unwrap() - 28.0).abs() < 1e-9);
        assert!((height_mm(-37.5).unwrap() - 10.0).abs() < 1e-3, "{} mm", height_mm(-37.5).unwrap()); // 1 um
        assert_eq!(height_mm(-70.1), None);
        assert_eq!(height_mm(60.1), None);
    }

    #[test]
    fn sections_meet_within_a_micrometre() {
        for &s in &BOUNDS[1..8] {
            let (l, r) = (height_mm(s - 1e-9).unwrap(), height_mm(s).unwrap());
            assert!((l - r).abs() < 1e-3, "jump {} mm at s = {s}", l - r);
        }
    }
}
