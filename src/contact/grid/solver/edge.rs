//! What a step says when its contact area reaches the fixed grid's edge:
//! which elements, and for the nonlinear profile contact what the rail does
//! under the patch and by how much to enlarge the grid.

use super::FixedGrid;
use crate::contact::RailContact;
use crate::contact::grid::RailSurface;
use crate::contact::grid::tangential::ContactSet;
use crate::hertz::{Curvatures, HertzShape};

impl FixedGrid {
    /// The elements in contact must keep off the grid's edge: the leading
    /// columns that supply the earlier displacements, one element elsewhere.
    /// The step's patch centre is at `position` (m) under `n_force` (N).
    pub(super) fn check_inside(&self, set: &ContactSet, position: f64, n_force: f64) -> Result<(), String> {
        let (nx, ny, lead) = (self.grid.nx, self.grid.ny, self.spec.lead_columns());
        match set.element.iter().find(|&&k| {
            let (ix, iy) = (k % nx, k / nx);
            ix < lead || ix + 1 >= nx || iy == 0 || iy + 1 >= ny
        }) {
            Some(&k) => Err(format!(
                "the contact area reaches the edge of the potential-contact grid at element ({}, {}) of {nx} x {ny}: \
                 the patch is larger than the grid was sized for{}",
                k % nx,
                k / nx,
                match &self.surface {
                    Some(RailContact::Profile(s)) => self.outgrown(s, position, n_force),
                    Some(RailContact::Linear(_)) => " (the linear profile contact's patch, moved and stretched by the \
                                                     corrugation under it: raise contact.profile_grid_scale)"
                        .to_string(),
                    None => String::new(),
                }
            )),
            None => Ok(()),
        }
    }

    /// What the profile did to the patch at `position` under `n_force`, and
    /// the grid that would hold it: the Hertz patch of the gap's local
    /// quadratic, the curvature sums less half the rail's curvature over
    /// the patch (second differences over half the smooth-rail semi-axes):
    /// a trough lengthens the patch, a crest widens it.
    /// The local quadratic leaves out the profile's higher terms, which
    /// flatten a trough towards the patch ends: the estimate is long (8 %
    /// over a harmonic trough of 44 % of the wheel's curvature, more over
    /// short troughs; tests/profile_contact.rs), so the value it names
    /// holds the patch; it is said when a step's patch has reached the
    /// grid's edge, not used to refuse a passage beforehand.
    fn outgrown(&self, surface: &RailSurface, position: f64, n_force: f64) -> String {
        let c = self.spec.curvatures;
        let smooth = HertzShape::new(c, self.spec.elastic).and_then(|s| s.patch(n_force));
        let Ok(smooth) = smooth else {
            return String::new();
        };
        let (hx, hy) = (0.5 * smooth.a, 0.5 * smooth.b);
        let r = |x: f64, y: f64| surface.height(position + x, y);
        let r_xx = (r(-hx, 0.0) - 2.0 * r(0.0, 0.0) + r(hx, 0.0)) / (hx * hx);
        let r_yy = (r(0.0, -hy) - 2.0 * r(0.0, 0.0) + r(0.0, hy)) / (hy * hy);
        let local = Curvatures { a: c.a - 0.5 * r_xx, b: c.b - 0.5 * r_yy };
        let here = format!(
            "the rail's curvature under the patch r_xx = {r_xx:.3} 1/m, r_yy = {r_yy:.3} 1/m against the gap's \
             2A = {:.3}, 2B = {:.3} 1/m",
            2.0 * c.a,
            2.0 * c.b
        );
        // A crest sharper than the wheel: the wheel meets the next crests too,
        // far from the patch centre, where no local quadratic reaches.
        if -r_xx > 2.0 * c.a || -r_yy > 2.0 * c.b {
            let text = format!(
                " ({here}: a crest sharper than the wheel, the patch splits onto the neighbouring crests; a grid \
                 sized from the Hertz patch does not hold them: raise contact.profile_grid_scale, or this \
                 corrugation is beyond what the contact of one wheel on a corrugated rail is meant for)"
            );
            return text;
        }
        match HertzShape::new(local, self.spec.elastic).and_then(|s| s.patch(n_force)) {
            Ok(p) => {
                let ratio = (p.a / self.spec.a_max).max(p.b / self.spec.b_max);
                let raise = if ratio > 1.0 {
                    format!(
                        "set contact.profile_grid_scale to at least {:.2} times its value",
                        (1.05 * ratio * 20.0).ceil() / 20.0
                    )
                } else {
                    "raise contact.profile_grid_scale".to_string()
                };
                let text = format!(
                    " ({here}: the patch about {:.2} x {:.2} mm where the grid holds {:.2} x {:.2} mm; {raise}; \
                     the patch then reaches |y| = {:.2} mm, which rail.half_width must cover)",
                    2e3 * p.a,
                    2e3 * p.b,
                    2e3 * self.spec.a_max,
                    2e3 * self.spec.b_max,
                    1e3 * p.b
                );
                text
            }
            Err(_) => format!(
                " ({here}: the corrugation here is as curved as the wheel, the patch spreads over the trough; no \
                 potential-contact grid sized from the Hertz patch holds it)"
            ),
        }
    }
}
