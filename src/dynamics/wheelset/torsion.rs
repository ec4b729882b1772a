//! The wheelset's torsional mode (`[wheelset]`): the two wheels of an axle
//! coupled by its torsional stiffness, in the frequency domain like the
//! vertical dynamics, so that the longitudinal creepage of the modelled
//! wheel responds to the variation of its normal force (the feedback of
//! the torsional models of driven and braked wheelsets; Grassie and
//! Kalousek, Proc. IMechE F 207 (1993) 57-68, and Grassie, Proc. IMechE F
//! (2009), doi:10.1243/09544097JRRT264, reviews of corrugation, name the
//! wheelset's torsional resonance the wavelength-fixing mechanism of
//! rutting).
//!
//! # Equations
//!
//! **Wheelset** (polar inertia `J` per wheel with its half axle, axle
//! torsional stiffness `k_t* = k_t (1 + i eta_t)`, rolling radius `r`;
//! time dependence `exp(+i w t)`). A longitudinal force `F` on the wheel
//! at the contact (positive forwards) brakes its spin: `J theta_L'' = -r
//! F_L - k_t* (theta_L - theta_R)`, `J theta_R'' = k_t* (theta_L -
//! theta_R) - r F_R`. The other rail's wheel carries its mean force only
//! (its rail's roughness is not correlated with this one's: `F_R = 0` in
//! the variation), so
//!
//! ```text
//! theta_L = -r F_L (k_t* - J w^2) / (J w^2 (J w^2 - 2 k_t*)),          (1)
//! ```
//!
//! the wheels twisting against each other at the torsional resonance
//! `w_t = sqrt(2 k_t / J)` ([`WheelsetTorsion::resonance`]) and the
//! anti-resonance `sqrt(k_t / J)` where the other wheel holds this one
//! still.
//!
//! **Creepage.** `xi_x = (V - r Omega) / V` (the wheel's slip over the
//! rolling speed, positive where the rim at the contact runs forwards
//! relative to the rail, the convention in which the force on the wheel
//! is `F = -C xi` in the linear theory), so `dxi = -r i w theta_L / V`:
//!
//! ```text
//! dxi = T(w) dF,   T(w) = r^2 i w (k_t* - J w^2) / (V J w^2 (J w^2 - 2 k_t*)).   (2)
//! ```
//!
//! **Closed loop.** The contact's force varies with its normal force and
//! creepage about the mean state, `dF = C_N dN + C_xi dxi` (the steady
//! creep curve's slopes at the mean load and creepage, from FASTSIM:
//! quasi-static, the transient of the creep force itself is the passage's
//! contact solver's), hence per harmonic of the dynamic normal force
//!
//! ```text
//! dxi = T C_N / (1 - C_xi T) dN.                                         (3)
//! ```
//!
//! Far below the resonance (`T ~ -i r^2 / (2 J w V)`, the free wheelset)
//! the wheelset's spin follows and `dF -> 0`: the drive or brake torque
//! holds the force (force control); at the resonance too (the wheels
//! twist freely, `|T|` peaks); at the anti-resonance `T = 0` and the
//! creepage is held (creepage control, `dF = C_N dN`); above the
//! resonance `T ~ -i r^2 / (J w V)`, the wheel's inertia against the creep
//! force's damping of its spin `|C_xi| r^2 / V`, and the creepage is held
//! above the corner `w_c = |C_xi| r^2 / (J V)` (716 Hz for 30 kg m^2, 0.5
//! m, 100 km/h and the paper's patch). The passage then runs with the
//! creepage `xi_0 + dxi(X)`
//! prescribed (`load.control = "creepage"`, `rolling.creepage_x = xi_0`,
//! the mean drive torque `r F(xi_0)` its result).

use crate::dynamics::apply_periodic_response;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Torsional stiffness of a freight axle between its wheels (N m/rad):
/// 3 MN m/rad, which with [`WHEEL_POLAR_INERTIA`] puts the first torsional
/// mode at 71 Hz (measured modes of freight and passenger wheelsets lie
/// at 40-100 Hz).
pub const AXLE_TORSIONAL_STIFFNESS: f64 = 3e6;

/// Polar moment of inertia of a wheel with its half axle (kg m^2): 30 kg
/// m^2, a 0.5 m radius freight wheel of about 350 kg.
pub const WHEEL_POLAR_INERTIA: f64 = 30.0;

/// Loss factor of the axle's torsion (1): 0.02, lightly damped steel.
pub const AXLE_TORSIONAL_LOSS_FACTOR: f64 = 0.02;

/// The wheelset's torsion (eq. 1, 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetTorsion {
    /// Axle torsional stiffness k_t (N m/rad).
    pub stiffness: f64,
    /// Loss factor eta_t of the axle's torsion (1).
    pub loss_factor: f64,
    /// Polar moment of inertia J of each wheel with its half axle (kg m^2).
    pub inertia: f64,
    /// Rolling radius r (m).
    pub radius: f64,
}

impl WheelsetTorsion {
    /// The torsional resonance `sqrt(2 k_t / J) / (2 pi)` (Hz), undamped.
    pub fn resonance(&self) -> f64 {
        (2.0 * self.stiffness / self.inertia).sqrt() / (2.0 * PI)
    }

    /// The creepage per longitudinal force `T(w)` (1/N) of eq. 2 at
    /// angular frequency `omega` (rad/s, > 0) and speed `speed` (m/s).
    pub fn creepage_per_force(&self, omega: f64, speed: f64) -> Complex64 {
        let k = Complex64::new(self.stiffness, self.stiffness * self.loss_factor);
        let jw2 = self.inertia * omega * omega;
        let i_w = Complex64::new(0.0, omega);
        self.radius * self.radius * i_w * (k - jw2) / (speed * jw2 * (jw2 - 2.0 * k))
    }
}

/// The closed loop of eq. 3: the wheelset's torsion and the creep curve's
/// slopes at the mean state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionFeedback {
    /// The wheelset.
    pub torsion: WheelsetTorsion,
    /// `dF/dN` at constant creepage (1).
    pub force_per_normal: f64,
    /// `dF/dxi` at constant normal force (N), negative.
    pub force_per_creepage: f64,
}

impl TorsionFeedback {
    /// `dxi / dN` (1/N) of eq. 3 at frequency `f_hz` (Hz, > 0), speed
    /// `speed` (m/s).
    pub fn creepage_per_normal_force(&self, f_hz: f64, speed: f64) -> Complex64 {
        let t = self.torsion.creepage_per_force(2.0 * PI * f_hz, speed);
        t * self.force_per_normal / (1.0 - self.force_per_creepage * t)
    }

    /// The longitudinal force's variation per normal force's, `dF / dN =
    /// C_N / (1 - C_xi T)` (1): `C_N` far above the resonance (creepage
    /// held), 0 far below (torque held).
    pub fn force_per_normal_force(&self, f_hz: f64, speed: f64) -> Complex64 {
        let t = self.torsion.creepage_per_force(2.0 * PI * f_hz, speed);
        self.force_per_normal / (1.0 - self.force_per_creepage * t)
    }

    /// The creepage's variation (1, zero mean) along one period of the
    /// dynamic normal force `normal` (N, sampled every `dx` m) of a wheel
    /// at `speed` (m/s): eq. 3 per harmonic.
    pub fn creepage(&self, normal: &[f64], dx: f64, speed: f64) -> Vec<f64> {
        apply_periodic_response(normal, dx, speed, |f| {
            if f == 0.0 { Complex64::new(0.0, 0.0) } else { self.creepage_per_normal_force(f, speed) }
        })
    }
}
