//! A conical wheel: a straight tread of slope `gamma` (the radius falling
//! by `gamma` per unit of lateral distance towards the field side) through
//! the tape circle, on S1002's flange. The tread meets the flange by a
//! cubic (Hermite) blend over [-30, -20] mm, continuous in height and slope.
//! For closed-form checks: a wheelset of cones has the rolling-radius
//! difference `2 gamma y` while it runs on the tread.

use super::s1002;

/// Where the blend from the flange to the cone starts and ends (mm).
const BLEND: (f64, f64) = (-30.0, -20.0);

/// The cone's height `F(s)` (mm) at `s` (mm); None outside [-70, 60].
pub fn height_mm(slope: f64, s: f64) -> Option<f64> {
    if s <= BLEND.0 {
        return s1002::height_mm(s);
    }
    if s >= BLEND.1 {
        return (s <= s1002::BOUNDS[8]).then_some(-slope * s);
    }
    let h = 1e-6;
    let (f0, d0) = (s1002::height_mm(BLEND.0)?, (s1002::height_mm(BLEND.0)? - s1002::height_mm(BLEND.0 - h)?) / h);
    let (f1, d1) = (-slope * BLEND.1, -slope);
    let w = BLEND.1 - BLEND.0;
    let t = (s - BLEND.0) / w;
    let (t2, t3) = (t * t, t * t * t);
    Some(
        (2.0 * t3 - 3.0 * t2 + 1.0) * f0
            + (t3 - 2.0 * t2 + t) * w * d0
            + (-2.0 * t3 + 3.0 * t2) * f1
            + (t3 - t2) * w * d1,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn continuous_across_the_blend() {
        for s in [BLEND.0, BLEND.1] {
            let (l, r) = (height_mm(0.05, s - 1e-7).unwrap(), height_mm(0.05, s + 1e-7).unwrap());
            assert!((l - r).abs() < 1e-5, "{s}: {l} {r}");
        }
        assert_eq!(height_mm(0.05, 10.0), Some(-0.5));
        assert_eq!(height_mm(0.05, -55.0), s1002::height_mm(-55.0));
    }
}
