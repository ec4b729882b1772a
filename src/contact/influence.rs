//! Tangential influence coefficients of the elastic half-space for uniform
//! traction on a rectangle.
//!
//! Cerruti's solution (Johnson, *Contact Mechanics*, 1985, eq. 3.86 at z = 0):
//! a tangential point force Q_x at the origin displaces the surface point
//! (x, y), r = sqrt(x^2 + y^2), by
//!
//! ```text
//! u_x = Q_x / (2 pi G) [(1 - nu)/r + nu x^2/r^3],   u_y = Q_x / (2 pi G) nu x y / r^3
//! ```
//!
//! (and symmetrically for Q_y). For quasi-identical bodies the normal and
//! tangential problems decouple, and the displacement *difference* of the two
//! bodies under opposite tractions is twice this. Integrating over a rectangle
//! of uniform traction (Kalker, *Three-dimensional elastic bodies in rolling
//! contact*, 1990, ch. 5; the same primitives as Love's rectangle solution),
//! with `X = x - x'`, `Y = y - y'` and the corner rule
//! `[[F]] = F(Xb, Yb) - F(Xa, Yb) - F(Xb, Ya) + F(Xa, Ya)`:
//!
//! ```text
//! int int 1/r     = X asinh(Y/|X|) + Y asinh(X/|Y|)
//! int int X^2/r^3 = Y asinh(X/|Y|)
//! int int Y^2/r^3 = X asinh(Y/|X|)
//! int int X Y/r^3 = -r
//! ```
//!
//! (the `ln|X|` parts of `ln(Y + r)` cancel between corners, which makes the
//! asinh form exact and finite on element edges and at the centre).

use std::f64::consts::PI;

/// An axis-aligned rectangle (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Centre x (m).
    pub x: f64,
    /// Centre y (m).
    pub y: f64,
    /// Half-length along x (m).
    pub hx: f64,
    /// Half-width along y (m).
    pub hy: f64,
}

/// Displacement difference (m) per unit uniform traction (Pa) on a
/// rectangle, at a point: `[[c_xx, c_xy], [c_yx, c_yy]]` with `c_yx = c_xy`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Influence {
    /// u_x per unit p_x (m/Pa).
    pub xx: f64,
    /// u_x per unit p_y = u_y per unit p_x (m/Pa).
    pub xy: f64,
    /// u_y per unit p_y (m/Pa).
    pub yy: f64,
}

/// X asinh(Y/|X|), zero on X = 0.
fn xa(x: f64, y: f64) -> f64 {
    if x == 0.0 { 0.0 } else { x * (y / x.abs()).asinh() }
}

/// The primitives (1/r, X^2/r^3, Y^2/r^3, XY/r^3) at one corner.
fn corner(x: f64, y: f64) -> [f64; 4] {
    let a = xa(x, y); // X asinh(Y/|X|)
    let b = xa(y, x); // Y asinh(X/|Y|)
    [a + b, b, a, -(x * x + y * y).sqrt()]
}

/// Influence of uniform traction on `rect` at point (`x`, `y`) for shear
/// modulus `g` (Pa) and Poisson's ratio `nu`: displacement difference of two
/// identical half-spaces (m per Pa).
pub fn influence(rect: &Rect, x: f64, y: f64, g: f64, nu: f64) -> Influence {
    let (xa_, xb) = (x - rect.x - rect.hx, x - rect.x + rect.hx);
    let (ya, yb) = (y - rect.y - rect.hy, y - rect.y + rect.hy);
    let c_bb = corner(xb, yb);
    let c_ab = corner(xa_, yb);
    let c_ba = corner(xb, ya);
    let c_aa = corner(xa_, ya);
    let i = |k: usize| c_bb[k] - c_ab[k] - c_ba[k] + c_aa[k];
    // Two bodies: 2 / (2 pi G) = 1 / (pi G).
    let s = 1.0 / (PI * g);
    Influence { xx: s * ((1.0 - nu) * i(0) + nu * i(1)), xy: s * nu * i(3), yy: s * ((1.0 - nu) * i(0) + nu * i(2)) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cerruti point-load kernel (two bodies) integrated by a tensor Gauss
    /// rule on a sub-grid of the rectangle.
    fn quadrature(rect: &Rect, x: f64, y: f64, g: f64, nu: f64, n: usize) -> Influence {
        let gl = [
            (-0.906179845938664, 0.236926885056189),
            (-0.538469310105683, 0.478628670499366),
            (0.0, 0.568888888888889),
            (0.538469310105683, 0.478628670499366),
            (0.906179845938664, 0.236926885056189),
        ];
        let mut out = Influence::default();
        let (dx, dy) = (2.0 * rect.hx / n as f64, 2.0 * rect.hy / n as f64);
        for i in 0..n {
            for j in 0..n {
                let (cx, cy) = (rect.x - rect.hx + (i as f64 + 0.5) * dx, rect.y - rect.hy + (j as f64 + 0.5) * dy);
                for (u, wu) in gl {
                    for (v, wv) in gl {
                        let (px, py) = (cx + 0.5 * dx * u, cy + 0.5 * dy * v);
                        let (rx, ry) = (x - px, y - py);
                        let r = rx.hypot(ry);
                        let w = wu * wv * 0.25 * dx * dy / (PI * g);
                        out.xx += w * ((1.0 - nu) / r + nu * rx * rx / r.powi(3));
                        out.xy += w * nu * rx * ry / r.powi(3);
                        out.yy += w * ((1.0 - nu) / r + nu * ry * ry / r.powi(3));
                    }
                }
            }
        }
        out
    }

    #[test]
    fn matches_quadrature_near_and_far() {
        let (g, nu) = (8.08e10, 0.3);
        let rect = Rect { x: 0.001, y: -0.0005, hx: 3e-4, hy: 5e-4 };
        // Far field and near field (outside the rectangle, close to an edge).
        for (x, y) in [(0.02, 0.013), (-0.004, 0.002), (0.0014, 0.0001), (0.001, 0.00009)] {
            let c = influence(&rect, x, y, g, nu);
            let q = quadrature(&rect, x, y, g, nu, 40);
            for (a, b) in [(c.xx, q.xx), (c.xy, q.xy), (c.yy, q.yy)] {
                assert!((a - b).abs() <= 1e-6 * c.xx.abs(), "({x},{y}): {a} vs {b}");
            }
        }
    }

    #[test]
    fn self_influence_is_finite_and_symmetric() {
        let (g, nu) = (8.08e10, 0.3);
        let sq = Rect { x: 0.0, y: 0.0, hx: 1e-3, hy: 1e-3 };
        let c = influence(&sq, 0.0, 0.0, g, nu);
        assert!(c.xx.is_finite() && c.xx > 0.0 && c.xy.abs() < 1e-30);
        assert!((c.xx - c.yy).abs() < 1e-12 * c.xx, "square: xx = yy");
        // Closed form at the centre of a square of side 2h:
        // int int 1/r = 8 h asinh(1), int int x^2/r^3 = 4 h asinh(1).
        let h = 1e-3;
        let expect = (8.0 * h * (1.0f64).asinh() * (1.0 - nu) + nu * 4.0 * h * (1.0f64).asinh()) / (PI * g);
        assert!((c.xx - expect).abs() < 1e-12 * expect);
    }

    #[test]
    fn reciprocity() {
        // Influence of element A at the centre of B equals that of B at A for
        // equal-area elements (Betti), up to the element-averaging error; exact
        // for mirror-image elements.
        let (g, nu) = (8.08e10, 0.28);
        let a = Rect { x: 0.0, y: 0.0, hx: 2e-4, hy: 3e-4 };
        let b = Rect { x: 1.3e-3, y: -0.7e-3, hx: 2e-4, hy: 3e-4 };
        let ab = influence(&a, b.x, b.y, g, nu);
        let ba = influence(&b, a.x, a.y, g, nu);
        assert!((ab.xx - ba.xx).abs() < 1e-12 * ab.xx);
        assert!((ab.xy - ba.xy).abs() < 1e-12 * ab.xx);
        assert!((ab.yy - ba.yy).abs() < 1e-12 * ab.yy);
    }
}
