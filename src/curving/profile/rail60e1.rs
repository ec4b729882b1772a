//! The 60E1 (UIC60) rail head (EN 13674-1), by its drawing's arcs.
//!
//! The head is three tangent arcs of radii 300, 80 and 13 mm on either
//! side of the rail's axis and a flank of slope 1:20 below them; the arcs
//! end at the drawing's widths 20.456, 52.053 and 72.000 mm. The R300
//! arc's centre lies on the axis 300 mm below the crown; each next centre
//! lies on the line from the last centre through the breakpoint, so that
//! the arcs are tangent (G1).
//!
//! Height `z(u)` (mm, up, 0 at the crown) at the lateral coordinate `u`
//! (mm from the axis); the head is symmetric.

/// Radii of the three arcs (mm).
const RADII: [f64; 3] = [300.0, 80.0, 13.0];
/// Half-widths where each arc ends (mm).
pub const BREAKS: [f64; 3] = [20.456 / 2.0, 52.053 / 2.0, 72.000 / 2.0];
/// Lateral run per unit height of the flank below the R13 arc (1:20).
const FLANK: f64 = 1.0 / 20.0;
/// How far the flank reaches below its start (mm).
const FLANK_DEPTH: f64 = 20.0;

/// The arcs' centres `(u, z)` (mm).
pub fn centres() -> [(f64, f64); 3] {
    let mut c = [(0.0, -RADII[0]); 3];
    for i in 1..3 {
        let (u0, z0) = c[i - 1];
        let angle = ((BREAKS[i - 1] - u0) / RADII[i - 1]).asin();
        let d = RADII[i - 1] - RADII[i];
        c[i] = (u0 + d * angle.sin(), z0 + d * angle.cos());
    }
    c
}

/// Where the flank starts `(u, z)` (mm): the R13 arc at the head's width.
pub fn flank_start() -> (f64, f64) {
    let (u, z) = centres()[2];
    let angle = ((BREAKS[2] - u) / RADII[2]).asin();
    (u + RADII[2] * angle.sin(), z + RADII[2] * angle.cos())
}

/// The head's height `z(u)` (mm); None beyond the flank's reach.
pub fn height_mm(u: f64) -> Option<f64> {
    let u = u.abs();
    let centres = centres();
    for (i, &end) in BREAKS.iter().enumerate() {
        if u <= end {
            let (cu, cz) = centres[i];
            return Some(cz + (RADII[i] * RADII[i] - (u - cu) * (u - cu)).max(0.0).sqrt());
        }
    }
    let (u0, z0) = flank_start();
    let depth = (u - u0) / FLANK;
    (depth <= FLANK_DEPTH).then_some(z0 - depth)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crown_and_breakpoints() {
        assert_eq!(height_mm(0.0), Some(0.0));
        // Continuous at the breakpoints and tangent (slopes within 1e-9).
        let slope = |u: f64, h: f64| (height_mm(u + h).unwrap() - height_mm(u - h).unwrap()) / (2.0 * h);
        for &b in &BREAKS[..2] {
            let (l, r) = (height_mm(b - 1e-9).unwrap(), height_mm(b + 1e-9).unwrap());
            assert!((l - r).abs() < 1e-6);
            let (sl, sr) = (slope(b - 1e-4, 1e-5), slope(b + 1e-4, 1e-5));
            assert!((sl - sr).abs() < 1e-3, "{sl} {sr} at {b}");
        }
        let (u, _) = flank_start();
        assert!((u - 36.0).abs() < 1e-9);
    }
}
