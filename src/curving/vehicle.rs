//! The curve and the vehicle of a steady-curving calculation: a single
//! wheelset, or a bogie of two wheelsets on a primary suspension, on a
//! curve of given radius, cant and speed, with traction or braking.

/// The curve. It turns to the left: its centre is on the left (positive
/// `Y`), so the left rail is the low (inner) rail.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curve {
    /// Radius (m), > 0; infinite for tangent track.
    pub radius: f64,
    /// Cant (m): the high rail's height above the low rail.
    pub cant: f64,
    /// Distance between the rails' running circles for the cant (m;
    /// 1.5 m on standard gauge).
    pub rail_spacing: f64,
    /// Speed (m/s).
    pub speed: f64,
}

/// Gravity (m/s^2).
pub const GRAVITY: f64 = 9.81;

impl Curve {
    /// Curvature (1/m).
    pub fn curvature(&self) -> f64 {
        1.0 / self.radius
    }

    /// The track plane's tilt (rad).
    pub fn cant_angle(&self) -> f64 {
        (self.cant / self.rail_spacing).asin()
    }

    /// The uncompensated lateral acceleration in the track plane (m/s^2),
    /// outwards: `V^2 / R cos(theta) - g sin(theta)`.
    pub fn lateral_acceleration(&self) -> f64 {
        let (s, c) = self.cant_angle().sin_cos();
        self.speed * self.speed * self.curvature() * c - GRAVITY * s
    }

    /// The acceleration normal to the track plane (m/s^2), downwards:
    /// `g cos(theta) + V^2 / R sin(theta)`.
    pub fn normal_acceleration(&self) -> f64 {
        let (s, c) = self.cant_angle().sin_cos();
        GRAVITY * c + self.speed * self.speed * self.curvature() * s
    }

    /// Cant deficiency (m): the cant that would balance the speed, less the
    /// cant.
    pub fn cant_deficiency(&self) -> f64 {
        self.lateral_acceleration() / self.normal_acceleration() * self.rail_spacing
    }
}

/// The primary suspension between a wheelset and the bogie frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Primary {
    /// Longitudinal stiffness per axlebox (N/m).
    pub longitudinal: f64,
    /// Lateral stiffness per axlebox (N/m).
    pub lateral: f64,
    /// Half the lateral distance between the axleboxes (m).
    pub half_spacing: f64,
}

impl Primary {
    /// The wheelset's yaw stiffness against the frame (N m/rad): `2 k_x d^2`.
    pub fn yaw_stiffness(&self) -> f64 {
        2.0 * self.longitudinal * self.half_spacing * self.half_spacing
    }

    /// The wheelset's lateral stiffness against the frame (N/m): `2 k_y`.
    pub fn lateral_stiffness(&self) -> f64 {
        2.0 * self.lateral
    }
}

/// What runs through the curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Vehicle {
    /// One wheelset, free in yaw and lateral shift (no suspension): the
    /// carried load acts at its centre.
    Wheelset,
    /// A bogie: two wheelsets `half_wheelbase` ahead of and behind the
    /// frame's centre, each on the primary suspension; the frame carries
    /// the lateral load, each wheelset its share of the vertical load. The
    /// secondary suspension's yaw stiffness is not modelled (the car body
    /// does not steer the frame).
    Bogie {
        /// Half the wheelbase (m).
        half_wheelbase: f64,
        /// The primary suspension.
        primary: Primary,
    },
}

impl Vehicle {
    /// The wheelsets' longitudinal positions (m, forward positive): leading first.
    pub fn axles(&self) -> Vec<f64> {
        match self {
            Vehicle::Wheelset => vec![0.0],
            Vehicle::Bogie { half_wheelbase, .. } => vec![*half_wheelbase, -*half_wheelbase],
        }
    }
}

/// The loads on each wheelset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// The weight each wheelset carries (N), its own included: the mass
    /// `Q / g` feels the curve's accelerations.
    pub axle_load: f64,
    /// Height of the carried mass's centre above the rails (m): its
    /// lateral force there shifts load to the high rail.
    pub centre_height: f64,
    /// Longitudinal creep force per wheelset (N): positive traction,
    /// negative braking.
    pub traction: f64,
}
