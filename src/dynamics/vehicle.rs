//! Several wheels of a vehicle on one rail (`[vehicle] wheels`): the
//! moving-irregularity model with the wheels coupled through the rail's
//! transfer receptances (the multiple-wheel models of Wu and Thompson,
//! 2005, and Nielsen, 2003, the latter's two-wheelset bogie against field
//! data; Grassie et al. 1982 for one wheel).
//!
//! Wheel `j` runs `s_j` behind the leading one (`s_0 = 0`); the loads stand
//! still and the rail is pulled through at the speed `V > 0`, so when
//! wheel `i` is at `X` wheel `j` is at `X + s_i - s_j`. A profile harmonic
//! `r_k exp(i k X)` (`w = k V`) reaches wheel `j` with the phase
//! `exp(i k (s_i - s_j))`, and with `y_w = alpha_w P_j` (the wheel's
//! mass), `alpha_c P_j` (the contact spring) and the rail's displacement
//! under wheel `j`, `sum_l A_jl P_l` (`A_jl` the rail's displacement at
//! wheel `j` under a unit force at wheel `l`: the point receptance on the
//! diagonal, the transfer receptances off it), the contact closes
//! (module [`super::receptance`], eq. 5, for every wheel):
//!
//! ```text
//! sum_l M_jl P_l = r_j,   M = (alpha_w + alpha_c) I + A(w),
//! P_i(X) = sum_k H_i(k) r_k exp(i k X),
//! H_i(k) = sum_j [M^-1]_ij exp(i k (s_i - s_j)).                      (1)
//! ```
//!
//! Far apart (`A_jl -> 0` for `j != l`) every wheel's `H_i` is the single
//! wheel's `1 / (alpha_w + alpha_c + alpha_r)`. Two wheels a whole number
//! of wavelengths apart meet the harmonic in phase and each sees
//! `1 / (alpha_w + alpha_c + alpha_r(0) + alpha_r(L))`; half a wavelength
//! off, `... - alpha_r(L)`: the wave between the wheels raises or lowers
//! the rail's receptance as the wheels see it, which is the mechanism that
//! can fix a wavelength to the wheel spacing.
//!
//! On the continuous track `A` depends on the frequency alone
//! ([`CoupledReceptance`]). On the discrete track it depends on where the
//! wheels are in the sleeper bay too ([`DiscreteVehicle`]: the
//! position-dependent approximation of [`super::discrete_dynamics`],
//! tabulated over the leading wheel's place across a whole bay), and each
//! wheel's path includes the static deflection under all the wheels'
//! loads (the parametric excitation).

use super::discrete_dynamics::harmonics;
use super::receptance::{ReceptanceModel, WheelParams};
use super::track::discrete::DiscreteTrack;
use super::{ContactVariations, TrackDynamics};
use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;
use rustfft::FftPlanner;
use std::f64::consts::PI;

/// Places of the leading wheel across one sleeper bay at which the
/// discrete vehicle's receptances are tabulated (every `d / 16`, the single
/// wheel's spacing of [`super::discrete_dynamics::POSITIONS`] over the
/// half bay).
pub const BAY_PLACES: usize = 16;

/// One wheel of the vehicle as the track sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledWheel {
    /// Distance behind the leading wheel (m).
    pub behind: f64,
    /// The wheel (unsprung mass).
    pub wheel: WheelParams,
    /// Linearised Hertz contact stiffness at its mean load (N/m).
    pub contact_stiffness: f64,
    /// Its mean normal force (N), for the parametric excitation.
    pub mean_load: f64,
}

impl CoupledWheel {
    /// Its wheel and contact receptance `alpha_w + alpha_c` (m/N).
    fn own(&self, omega: f64) -> Complex64 {
        self.wheel.receptance(omega) + 1.0 / self.contact_stiffness
    }
}

/// `[M^-1]` of eq. 1 for the rail's receptance matrix `a` (row-major `n x
/// n`, m/N) and the wheels' own receptances on its diagonal (m/N).
fn inverse(a: &[Complex64], own: &[Complex64]) -> DMatrix<Complex64> {
    let n = own.len();
    let m = DMatrix::from_fn(n, n, |i, j| a[i * n + j] + if i == j { own[i] } else { Complex64::new(0.0, 0.0) });
    m.try_inverse().expect("a passive track's receptance matrix plus the wheels' is invertible")
}

/// Each wheel's force from each wheel's input by a coupling per harmonic:
/// `P_i = sum_j G_ij(f) Q_j` at `f = V m / L` (signed harmonic `m`),
/// `G(-f) = conj G(f)`, the Nyquist harmonic by `Re G` and the mean
/// dropped (as [`super::apply_periodic_response`]). `coupling(bin)` gives `G` at
/// the harmonic `bin = 1..=N/2`.
fn couple(inputs: &[Vec<f64>], coupling: impl Fn(usize) -> DMatrix<Complex64>) -> Vec<Vec<f64>> {
    let (n, nodes) = (inputs.len(), inputs[0].len());
    let mut planner = FftPlanner::<f64>::new();
    let (fwd, inv) = (planner.plan_fft_forward(nodes), planner.plan_fft_inverse(nodes));
    let spectra: Vec<Vec<Complex64>> = inputs
        .iter()
        .map(|q| {
            let mut buf: Vec<Complex64> = q.iter().map(|v| Complex64::new(*v, 0.0)).collect();
            fwd.process(&mut buf);
            buf
        })
        .collect();
    let mut out = vec![vec![Complex64::new(0.0, 0.0); nodes]; n];
    for bin in 1..=nodes / 2 {
        let g = coupling(bin);
        let g = if 2 * bin == nodes { g.map(|v| Complex64::new(v.re, 0.0)) } else { g };
        for i in 0..n {
            let (mut up, mut down) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
            for j in 0..n {
                up += g[(i, j)] * spectra[j][bin];
                down += g[(i, j)].conj() * spectra[j][nodes - bin];
            }
            out[i][bin] = up;
            if 2 * bin != nodes {
                out[i][nodes - bin] = down;
            }
        }
    }
    out.into_iter()
        .map(|mut p| {
            inv.process(&mut p);
            p.iter().map(|c| c.re / nodes as f64).collect()
        })
        .collect()
}

/// The wheels coupled through the continuous track (closed form).
#[derive(Debug, Clone, PartialEq)]
pub struct CoupledReceptance {
    /// The leading wheel's model (track, wheel, contact spring), for its
    /// resonances.
    pub model: ReceptanceModel,
    /// The wheels, the leading one first.
    pub wheels: Vec<CoupledWheel>,
}

impl CoupledReceptance {
    /// The receptance matrix `A(w)` (m/N, row-major) at angular frequency
    /// `omega` (rad/s): `A_jl = alpha_r(|s_j - s_l|)`.
    pub fn rail_matrix(&self, omega: f64) -> Vec<Complex64> {
        let s: Vec<f64> = self.wheels.iter().map(|w| w.behind).collect();
        s.iter().flat_map(|a| s.iter().map(move |b| self.model.track.rail_transfer_receptance(omega, a - b))).collect()
    }

    /// `G_ij(f) = [M^-1]_ij exp(i k (s_i - s_j))` of eq. 1 (N/m) at
    /// frequency `f_hz` (Hz, > 0) and speed `speed` (m/s, > 0): wheel
    /// `i`'s force per unit input seen by wheel `j`.
    pub fn coupling(&self, f_hz: f64, speed: f64) -> DMatrix<Complex64> {
        let w = 2.0 * PI * f_hz;
        let own: Vec<Complex64> = self.wheels.iter().map(|c| c.own(w)).collect();
        let inv = inverse(&self.rail_matrix(w), &own);
        let k = w / speed;
        let s: Vec<f64> = self.wheels.iter().map(|c| c.behind).collect();
        DMatrix::from_fn(own.len(), own.len(), |i, j| inv[(i, j)] * Complex64::from_polar(1.0, k * (s[i] - s[j])))
    }

    /// `H_i(f)` of eq. 1 (N/m) for each wheel, every wheel seeing the same
    /// profile: the rows' sums of [`Self::coupling`].
    pub fn force_per_roughness(&self, f_hz: f64, speed: f64) -> Vec<Complex64> {
        let g = self.coupling(f_hz, speed);
        (0..g.nrows()).map(|i| g.row(i).iter().sum()).collect()
    }
}

impl CoupledReceptance {
    /// The leading wheel's dynamic normal force (N, zero mean) where every
    /// wheel sees `profile`.
    pub fn force_from_profile(&self, profile: &[f64], dx: f64, speed: f64) -> Vec<f64> {
        self.wheel_forces(&vec![profile.to_vec(); self.wheels.len()], dx, speed).swap_remove(0)
    }

    /// Each wheel's dynamic normal force (N, zero mean) from the profile it
    /// sees (see [`TrackDynamics::contact_variations`]).
    pub fn wheel_forces(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<Vec<f64>> {
        assert!(speed > 0.0, "the vehicle runs forwards (speed = {speed} m/s)");
        let length = profiles[0].len() as f64 * dx;
        couple(profiles, |bin| self.coupling(speed * bin as f64 / length, speed))
    }
}

impl TrackDynamics for CoupledReceptance {
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations> {
        ContactVariations::normals(self.wheel_forces(profiles, dx, speed))
    }

    fn describe_resonances(&self) -> Vec<(String, f64)> {
        self.model.describe_resonances()
    }

    fn wheels(&self) -> usize {
        self.wheels.len()
    }
}

/// The wheels coupled through the discrete track, at one speed over one
/// periodic stretch.
#[derive(Debug, Clone)]
pub struct DiscreteVehicle {
    track: DiscreteTrack,
    wheels: Vec<CoupledWheel>,
    /// First sleeper's position along the rail (m).
    sleeper_x0: f64,
    /// Speed (m/s) and stretch (nodes, spacing) the table was built for.
    key: (f64, usize, f64),
    /// `[M^-1]` of eq. 1 for the harmonics n = 1..=n_max (outer) at the
    /// leading wheel's [`BAY_PLACES`] places (inner).
    table: Vec<Vec<DMatrix<Complex64>>>,
    /// The static receptance matrix (m/N, real part at 0.1 Hz) at the
    /// leading wheel's places.
    statics: Vec<DMatrix<f64>>,
}

impl DiscreteVehicle {
    /// The model of `wheels` on `track`, for a stretch of `nodes` samples
    /// every `dx` (m) starting at a sleeper at `sleeper_x0` (m), at `speed`
    /// (m/s, > 0). Tabulates the receptance matrices of the harmonics up to
    /// [`super::discrete_dynamics::F_MAX`] at [`BAY_PLACES`] places (about
    /// 3 times the single wheel's time for two wheels, 6 for four).
    pub fn new(
        track: DiscreteTrack,
        wheels: Vec<CoupledWheel>,
        sleeper_x0: f64,
        nodes: usize,
        dx: f64,
        speed: f64,
    ) -> Self {
        assert!(speed > 0.0, "the vehicle runs forwards (speed = {speed} m/s)");
        let length = nodes as f64 * dx;
        let leaders = bay_places(track.spacing);
        let offsets: Vec<f64> = wheels.iter().map(|w| -w.behind).collect();
        let table = (1..=harmonics(nodes, dx, speed))
            .into_par_iter()
            .map(|h| {
                let w = 2.0 * PI * h as f64 * speed / length;
                let own: Vec<Complex64> = wheels.iter().map(|c| c.own(w)).collect();
                track.vehicle_receptances(&leaders, &offsets, w).iter().map(|a| inverse(a, &own)).collect()
            })
            .collect();
        let behind: Vec<f64> = wheels.iter().map(|w| w.behind).collect();
        let statics = static_receptances(&track, &behind);
        DiscreteVehicle { track, wheels, sleeper_x0, key: (speed, nodes, dx), table, statics }
    }

    /// The leading wheel's place in the bay when it is at `x` (m): the
    /// tabulated place before it, the one after (periodic over
    /// [`BAY_PLACES`]) and the weight of the one after.
    fn place(&self, x: f64) -> (usize, usize, f64) {
        bay_place(self.track.spacing, self.sleeper_x0, x)
    }

    /// The path of each wheel on a smooth rail (m, positive up, zero mean)
    /// at its own positions `x_min + i dx`: the static deflection under
    /// all the wheels' mean loads, `-sum_l A_jl(x, 0) N0_l`.
    pub fn parametric_profiles(&self, nodes: usize, dx: f64) -> Vec<Vec<f64>> {
        let behind: Vec<f64> = self.wheels.iter().map(|w| w.behind).collect();
        let loads: Vec<f64> = self.wheels.iter().map(|w| w.mean_load).collect();
        parametric_paths(&self.statics, self.track.spacing, &behind, &loads, self.sleeper_x0, nodes, dx)
    }
}

/// Each wheel's input (the profile it sees plus its parametric path,
/// `profiles[j] + paths[j]`, transformed) as wheel `i` meets it, for the
/// harmonics `h = 1..=harmonics` of a stretch of `length` (m): `[i][h -
/// 1][j] = r_j,h exp(i k_h (s_i - s_j))`, `s` the wheels' distances
/// behind the leading one (m; eq. 1).
pub fn inputs_as_met(
    profiles: &[Vec<f64>],
    paths: &[Vec<f64>],
    behind: &[f64],
    harmonics: usize,
    length: f64,
) -> Vec<Vec<Vec<Complex64>>> {
    let n = behind.len();
    let fft = FftPlanner::<f64>::new().plan_fft_forward(profiles[0].len());
    let inputs: Vec<Vec<Complex64>> = paths
        .iter()
        .zip(profiles)
        .map(|(path, profile)| {
            let mut buf: Vec<Complex64> = profile.iter().zip(path).map(|(r, p)| Complex64::new(r + p, 0.0)).collect();
            fft.process(&mut buf);
            buf
        })
        .collect();
    (0..n)
        .map(|i| {
            (1..=harmonics)
                .map(|h| {
                    let k = 2.0 * PI * h as f64 / length;
                    (0..n).map(|j| inputs[j][h] * Complex64::from_polar(1.0, k * (behind[i] - behind[j]))).collect()
                })
                .collect()
        })
        .collect()
}

/// The static receptance matrices (m/N, the real part at 0.1 Hz) of wheels
/// `behind` (m) the leading one, at the leading wheel's [`BAY_PLACES`]
/// places across a bay of `track`.
pub fn static_receptances(track: &DiscreteTrack, behind: &[f64]) -> Vec<DMatrix<f64>> {
    let n = behind.len();
    let offsets: Vec<f64> = behind.iter().map(|b| -b).collect();
    track
        .vehicle_receptances(&bay_places(track.spacing), &offsets, 2.0 * PI * 0.1)
        .iter()
        .map(|a| DMatrix::from_fn(n, n, |i, j| a[i * n + j].re))
        .collect()
}

/// The leading wheel's place in a bay of `spacing` (m) whose first sleeper
/// is at `sleeper_x0` (m) when it is at `x` (m): the tabulated place before
/// it, the one after (periodic over [`BAY_PLACES`]) and the weight of the
/// one after.
pub fn bay_place(spacing: f64, sleeper_x0: f64, x: f64) -> (usize, usize, f64) {
    let u = (x - sleeper_x0).rem_euclid(spacing) / spacing * BAY_PLACES as f64;
    let p = (u.floor() as usize).min(BAY_PLACES - 1);
    (p, (p + 1) % BAY_PLACES, u - p as f64)
}

/// The path of each wheel (`behind` the leading one, m; mean loads
/// `loads`, N) on a smooth rail (m, positive up, zero mean) at its own
/// positions `x_min + i dx`, `nodes` of them: the static deflection under
/// all the wheels' mean loads, `-sum_l A_jl(x, 0) N0_l`, from `statics`
/// ([`static_receptances`]).
pub fn parametric_paths(
    statics: &[DMatrix<f64>],
    spacing: f64,
    behind: &[f64],
    loads: &[f64],
    sleeper_x0: f64,
    nodes: usize,
    dx: f64,
) -> Vec<Vec<f64>> {
    let n = behind.len();
    (0..n)
        .map(|j| {
            let path: Vec<f64> = (0..nodes)
                .map(|i| {
                    let (p, q, t) = bay_place(spacing, sleeper_x0, sleeper_x0 + i as f64 * dx + behind[j]);
                    let row = |m: &DMatrix<f64>| (0..n).map(|l| m[(j, l)] * loads[l]).sum::<f64>();
                    -((1.0 - t) * row(&statics[p]) + t * row(&statics[q]))
                })
                .collect();
            let mean = path.iter().sum::<f64>() / nodes.max(1) as f64;
            path.iter().map(|v| v - mean).collect()
        })
        .collect()
}

/// The leading wheel's tabulated places across a bay of `spacing` (m).
fn bay_places(spacing: f64) -> Vec<f64> {
    (0..BAY_PLACES).map(|p| spacing * p as f64 / BAY_PLACES as f64).collect()
}

impl TrackDynamics for DiscreteVehicle {
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations> {
        ContactVariations::normals(self.wheel_forces(profiles, dx, speed))
    }

    fn describe_resonances(&self) -> Vec<(String, f64)> {
        vec![("pinned-pinned: the rail between two sleepers".into(), self.track.pinned_pinned_frequency())]
    }

    fn forces_smooth_rail(&self) -> bool {
        true
    }

    fn wheels(&self) -> usize {
        self.wheels.len()
    }
}

impl DiscreteVehicle {
    /// The leading wheel's dynamic normal force (N, zero mean) where every
    /// wheel sees `profile`.
    pub fn force_from_profile(&self, profile: &[f64], dx: f64, speed: f64) -> Vec<f64> {
        self.wheel_forces(&vec![profile.to_vec(); self.wheels.len()], dx, speed).swap_remove(0)
    }

    /// Each wheel's dynamic normal force (N, zero mean) from the profile it
    /// sees (see [`TrackDynamics::contact_variations`]).
    pub fn wheel_forces(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<Vec<f64>> {
        let nodes = profiles[0].len();
        assert_eq!(
            (speed, nodes, dx),
            self.key,
            "the discrete vehicle is tabulated for one speed and stretch (built with the growth study's)"
        );
        let length = nodes as f64 * dx;
        let s: Vec<f64> = self.wheels.iter().map(|w| w.behind).collect();
        let met = inputs_as_met(profiles, &self.parametric_profiles(nodes, dx), &s, self.table.len(), length);
        met.iter()
            .enumerate()
            .map(|(i, seen)| {
                (0..nodes)
                    .map(|m| {
                        let x = m as f64 * dx;
                        let (p, q, t) = self.place(self.sleeper_x0 + x + s[i]);
                        let mut force = 0.0;
                        for (h, (row, r)) in self.table.iter().zip(seen).enumerate() {
                            let h = h + 1;
                            let mut sum = Complex64::new(0.0, 0.0);
                            for (j, rj) in r.iter().enumerate() {
                                sum += ((1.0 - t) * row[p][(i, j)] + t * row[q][(i, j)]) * rj;
                            }
                            // A real input: harmonic h and its mirror give
                            // 2 Re[...] / N (the Nyquist harmonic once).
                            let phase = Complex64::from_polar(1.0, 2.0 * PI * h as f64 * x / length);
                            let weight = if 2 * h == nodes { 1.0 } else { 2.0 };
                            force += weight * (sum * phase).re / nodes as f64;
                        }
                        force
                    })
                    .collect()
            })
            .collect()
    }
}
