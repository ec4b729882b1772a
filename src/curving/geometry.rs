//! The wheelset on the track: both wheels' and both rails' profiles placed
//! in the track's cross-section, and the vertical gap between each wheel
//! and its rail for a pose of the wheelset (lateral shift, height, roll).
//!
//! Track axes: `Y` lateral (m), positive to the left looking in the
//! direction of travel; `Z` up (m), 0 at the rails' crowns before their
//! inclination. Each rail is its profile turned towards the track's centre
//! by the inclination (about its crown) and placed so that the gauge,
//! measured between the gauge faces `gauge_depth` below the rail's top, is
//! the track's gauge. Each wheel is its profile, flange inwards, with its
//! flange back (the profile's first point) at half the flange-back spacing
//! from the wheelset's centre; the wheelset's pose turns and shifts it
//! (roll `phi` raises the left wheel: `(Y, Z) -> (Y cos phi - Z sin phi,
//! Y sin phi + Z cos phi)`).
//!
//! Yaw is not part of the pose: the contact points' longitudinal shift
//! with the angle of attack (a few mm at the 5-10 mrad of a curve) is
//! neglected, as in EN 15302's planar contact geometry.

use super::profile::Profile;

/// Left (0) or right (1), looking in the direction of travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The left wheel and rail (positive `Y`).
    Left = 0,
    /// The right wheel and rail.
    Right = 1,
}

impl Side {
    /// Both sides, left first.
    pub const BOTH: [Side; 2] = [Side::Left, Side::Right];

    /// +1 on the left, -1 on the right: the direction of the field side.
    pub fn outwards(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }

    /// "left" or "right".
    pub fn name(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
        }
    }
}

/// The wheelset's profiles and dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelsetShape {
    /// Left and right wheel profiles.
    pub wheels: [Profile; 2],
    /// Each wheel's radius at its tape circle (m).
    pub radius: [f64; 2],
    /// Distance between the flange backs (m).
    pub flange_back: f64,
}

/// The track's profiles and dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackShape {
    /// Left and right rail profiles.
    pub rails: [Profile; 2],
    /// Gauge (m), between the gauge faces at `gauge_depth`.
    pub gauge: f64,
    /// Depth below the rail's top at which the gauge is measured (m; 14 mm
    /// in EN 13848-1).
    pub gauge_depth: f64,
    /// Rail inclination (rad), towards the track's centre (atan(1/40)).
    pub inclination: f64,
}

/// The wheelset's pose in the track's cross-section.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose {
    /// Lateral shift of the wheelset's centre (m), positive to the left.
    pub y: f64,
    /// Height of the axle's centre (m).
    pub z: f64,
    /// Roll (rad), positive raising the left wheel.
    pub roll: f64,
}

/// Where a wheel comes closest to its rail (a local minimum of the gap).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closest {
    /// Lateral position in the track (m).
    pub lateral: f64,
    /// Vertical gap (m), negative where the profiles overlap.
    pub gap: f64,
    /// The rail's slope `dZ/dY` there (1).
    pub slope: f64,
    /// The gap's second derivative along `Y` (1/m).
    pub gap_curvature: f64,
    /// The rail profile's curvature in its normal plane (1/m, convex
    /// positive).
    pub rail_curvature: f64,
    /// The wheel's rolling radius there (m).
    pub rolling_radius: f64,
    /// The wheel profile's lateral coordinate there (m from the tape
    /// circle, positive to the field side).
    pub wheel_lateral: f64,
}

impl Closest {
    /// The contact angle (rad) on `side`: positive where the rail's
    /// surface rises towards the field side (the tread's cone, the flange).
    pub fn contact_angle(&self, side: Side) -> f64 {
        (self.slope * side.outwards()).atan()
    }

    /// The contact's normal, out of the rail, `(n_Y, n_Z)`.
    pub fn normal(&self) -> (f64, f64) {
        let k = (1.0 + self.slope * self.slope).sqrt();
        (-self.slope / k, 1.0 / k)
    }

    /// The gap's curvature sum across the rolling direction in the contact's
    /// normal plane, `B = g'' cos^3(delta) / 2` (1/m).
    pub fn curvature_b(&self) -> f64 {
        let c = self.normal().1;
        0.5 * self.gap_curvature * c * c * c
    }

    /// The curvature sum along the rolling direction, `A = cos(delta) /
    /// (2 r)` (1/m): the wheel's radius in the normal plane is `r /
    /// cos(delta)`.
    pub fn curvature_a(&self) -> f64 {
        0.5 * self.normal().1 / self.rolling_radius
    }
}

/// A geometry that cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// The rail profile has no gauge face at the gauge depth.
    #[error("the {side} rail ({name}) has no gauge face {depth_mm} mm below its top: the profile ends above it")]
    NoGaugeFace {
        /// The rail's side.
        side: &'static str,
        /// Its profile's name.
        name: String,
        /// The gauge depth (mm).
        depth_mm: f64,
    },
    /// The wheel does not reach its rail at this pose.
    #[error("the {side} wheel does not lie over its rail at a lateral shift of {y_mm:.2} mm")]
    OffRail {
        /// The side.
        side: &'static str,
        /// The lateral shift (mm).
        y_mm: f64,
    },
    /// No roll puts both wheels on their rails.
    #[error("no roll within +-{0} rad puts both wheels on their rails at a lateral shift of {1:.2} mm")]
    NoRoll(f64, f64),
}

/// Grid step of the search for the closest points (m).
const SEARCH_STEP: f64 = 1e-4;
/// Step of the gap's second difference (m).
const CURVATURE_STEP: f64 = 1e-4;

/// Both wheels and rails, placed.
#[derive(Debug, Clone)]
pub struct Geometry {
    wheelset: WheelsetShape,
    track: TrackShape,
    /// Each rail's crown in the track (m).
    rail_axis: [f64; 2],
    /// Each tape circle's distance from the wheelset's centre (m).
    tape: [f64; 2],
    /// Each rail's surface sampled every [`SEARCH_STEP`]: `(Y, Z)` (m).
    rail_samples: [Vec<(f64, f64)>; 2],
}

impl Geometry {
    /// Places the profiles.
    pub fn new(wheelset: WheelsetShape, track: TrackShape) -> Result<Geometry, GeometryError> {
        let mut rail_axis = [0.0; 2];
        for side in Side::BOTH {
            let rail = &track.rails[side as usize];
            let gauge_face =
                gauge_face(rail, track.inclination, track.gauge_depth).ok_or_else(|| GeometryError::NoGaugeFace {
                    side: side.name(),
                    name: rail.name().to_string(),
                    depth_mm: track.gauge_depth * 1e3,
                })?;
            // The gauge face (at a negative turned coordinate) lies at gauge / 2.
            rail_axis[side as usize] = side.outwards() * (0.5 * track.gauge - gauge_face);
        }
        let tape = [0, 1].map(|i| 0.5 * wheelset.flange_back - wheelset.wheels[i].range().0);
        let mut g = Geometry { wheelset, track, rail_axis, tape, rail_samples: [Vec::new(), Vec::new()] };
        for side in Side::BOTH {
            let axis = g.rail_axis[side as usize];
            let (lo, hi) = g.track.rails[side as usize].range();
            let (lo, hi) = if side == Side::Left { (axis + lo, axis + hi) } else { (axis - hi, axis - lo) };
            let n = ((hi - lo) / SEARCH_STEP).ceil() as usize;
            g.rail_samples[side as usize] = (0..=n)
                .filter_map(|k| {
                    let y = lo + (hi - lo) * k as f64 / n as f64;
                    g.rail_height(side, y).map(|z| (y, z))
                })
                .collect();
        }
        Ok(g)
    }

    /// The wheelset's shape.
    pub fn wheelset(&self) -> &WheelsetShape {
        &self.wheelset
    }

    /// The track's shape.
    pub fn track(&self) -> &TrackShape {
        &self.track
    }

    /// The lateral position of a rail's crown (m).
    pub fn rail_axis(&self, side: Side) -> f64 {
        self.rail_axis[side as usize]
    }

    /// Half the distance between the tape circles (m).
    pub fn tape_half_spacing(&self) -> f64 {
        0.5 * (self.tape[0] + self.tape[1])
    }

    /// The rail's height (m) at track position `y` (m) and the rail
    /// profile's own coordinate there; None off the profile.
    pub fn rail_height(&self, side: Side, y: f64) -> Option<f64> {
        let rail = &self.track.rails[side as usize];
        let turned = (y - self.rail_axis[side as usize]) * side.outwards();
        let (s, c) = self.track.inclination.sin_cos();
        // Solve u c - z(u) s = turned for the profile's own u.
        let mut u = turned;
        for _ in 0..60 {
            let next = (turned + rail.height(u)? * s) / c;
            if (next - u).abs() < 1e-13 {
                u = next;
                break;
            }
            u = next;
        }
        Some(u * s + rail.height(u)? * c)
    }

    /// The wheel's surface at track position `y` for `pose`: its height
    /// (m) and the wheel profile's coordinate there (m); None off the
    /// profile.
    pub fn wheel_point(&self, side: Side, pose: &Pose, y: f64) -> Option<(f64, f64)> {
        let i = side as usize;
        let wheel = &self.wheelset.wheels[i];
        let (r0, tape, out) = (self.wheelset.radius[i], self.tape[i], side.outwards());
        let (s, c) = pose.roll.sin_cos();
        // Wheelset axes: Yw = out (tape + q), Zw = -(r0 + F(q)).
        // Track: y = pose.y + Yw c - Zw s.
        let mut q = ((y - pose.y) * out) / c - tape;
        for _ in 0..60 {
            let radius = r0 + wheel.height(q)?;
            let next = ((y - pose.y - radius * s) * out) / c - tape;
            if (next - q).abs() < 1e-13 {
                q = next;
                break;
            }
            q = next;
        }
        let radius = r0 + wheel.height(q)?;
        let yw = out * (tape + q);
        Some((pose.z + yw * s - radius * c, q))
    }

    /// The vertical gap between wheel and rail at `y` (m).
    pub fn gap(&self, side: Side, pose: &Pose, y: f64) -> Option<f64> {
        Some(self.wheel_point(side, pose, y)?.0 - self.rail_height(side, y)?)
    }

    /// The local minima of the gap on `side`, one per valley (minima
    /// separated by less than 1 um of rise are one), closest first.
    pub fn closest(&self, side: Side, pose: &Pose) -> Vec<Closest> {
        let samples = self.samples(side, pose);
        let mut minima: Vec<(usize, f64)> = Vec::new();
        for k in 1..samples.len().saturating_sub(1) {
            let (g0, g1, g2) = (samples[k - 1].1, samples[k].1, samples[k + 1].1);
            if g1 <= g0 && g1 < g2 {
                minima.push((k, g1));
            }
        }
        // One per valley: merge neighbours whose separating rise is < 1 um.
        let mut valleys: Vec<(usize, f64)> = Vec::new();
        for (k, g) in minima {
            if let Some(last) = valleys.last_mut() {
                let rise = samples[last.0..=k].iter().map(|s| s.1).fold(f64::MIN, f64::max);
                if rise - last.1.max(g) < 1e-6 {
                    if g < last.1 {
                        *last = (k, g);
                    }
                    continue;
                }
            }
            valleys.push((k, g));
        }
        let mut out: Vec<Closest> = valleys
            .into_iter()
            .filter_map(|(k, _)| self.refine(side, pose, samples[k - 1].0, samples[k + 1].0))
            .collect();
        out.sort_by(|a, b| a.gap.total_cmp(&b.gap));
        out
    }

    /// The minimum of the gap in `[a, b]` by golden sections, with its
    /// slopes and curvatures.
    fn refine(&self, side: Side, pose: &Pose, mut a: f64, mut b: f64) -> Option<Closest> {
        let g = |y: f64| self.gap(side, pose, y).unwrap_or(f64::INFINITY);
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let (mut c, mut d) = (b - ratio * (b - a), a + ratio * (b - a));
        let (mut gc, mut gd) = (g(c), g(d));
        while b - a > 1e-10 {
            if gc < gd {
                (b, d, gd) = (d, c, gc);
                c = b - ratio * (b - a);
                gc = g(c);
            } else {
                (a, c, gc) = (c, d, gd);
                d = a + ratio * (b - a);
                gd = g(d);
            }
        }
        self.at(side, pose, 0.5 * (a + b))
    }

    /// The geometry at track position `y` (m): the gap, the rail's slope and
    /// curvature, the wheel's radius there.
    fn at(&self, side: Side, pose: &Pose, y: f64) -> Option<Closest> {
        let h = CURVATURE_STEP;
        let (gm, g0, gp) = (self.gap(side, pose, y - h)?, self.gap(side, pose, y)?, self.gap(side, pose, y + h)?);
        let (rm, r0, rp) = (self.rail_height(side, y - h)?, self.rail_height(side, y)?, self.rail_height(side, y + h)?);
        let slope = (rp - rm) / (2.0 * h);
        let rail_second = (rp - 2.0 * r0 + rm) / (h * h);
        let (_, q) = self.wheel_point(side, pose, y)?;
        let radius = self.wheelset.radius[side as usize] + self.wheelset.wheels[side as usize].height(q)?;
        Some(Closest {
            lateral: y,
            gap: g0,
            slope,
            gap_curvature: (gp - 2.0 * g0 + gm) / (h * h),
            rail_curvature: -rail_second / (1.0 + slope * slope).powf(1.5),
            rolling_radius: radius,
            wheel_lateral: q,
        })
    }

    /// The gap sampled every [`SEARCH_STEP`] across the rail.
    fn samples(&self, side: Side, pose: &Pose) -> Vec<(f64, f64)> {
        self.rail_samples[side as usize]
            .iter()
            .filter_map(|&(y, z)| self.wheel_point(side, pose, y).map(|(w, _)| (y, w - z)))
            .collect()
    }
}

/// The turned profile's gauge face: the turned lateral coordinate (m,
/// negative) of the gauge-side point `depth` below the turned profile's
/// top.
fn gauge_face(rail: &Profile, inclination: f64, depth: f64) -> Option<f64> {
    let (s, c) = inclination.sin_cos();
    let (lo, hi) = rail.range();
    let turned = |u: f64| rail.height(u).map(|z| (u * c - z * s, u * s + z * c));
    let n = 20_000;
    let points: Vec<(f64, f64, f64)> = (0..=n)
        .filter_map(|k| {
            let u = lo + (hi - lo) * k as f64 / n as f64;
            turned(u).map(|(y, z)| (u, y, z))
        })
        .collect();
    let top = points.iter().map(|p| p.2).fold(f64::MIN, f64::max);
    let level = top - depth;
    // The first crossing of the level from the gauge side.
    let k = points.windows(2).position(|w| w[0].2 <= level && w[1].2 > level)?;
    let (mut a, mut b) = (points[k].0, points[k + 1].0);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if turned(m)?.1 <= level { a = m } else { b = m }
    }
    Some(turned(0.5 * (a + b))?.0)
}
