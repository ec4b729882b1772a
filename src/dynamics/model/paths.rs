//! The parametric excitation of the discrete supports: each wheel's
//! path on a smooth rail, the static deflection under all the wheels'
//! mean loads on its rail, `-sum_l A_jl(x, 0) N0_l` (more at mid-span than
//! above a sleeper), which the closure turns into the sleeper-passing
//! force (the position-dependent models of Hempelmann and Knothe 1996;
//! Nielsen 2003 for a bogie).

use super::places::{Places, load_and_watched};
use super::{Track, Wheel};
use crate::dynamics::track::discrete::DiscreteTrack;
use crate::dynamics::track::discrete3::{Discrete3Error, layout_at};
use crate::dynamics::track::layout::Layout;
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Frequency (Hz) at which the static receptance is read (its real part):
/// far below the track's resonances.
const STATIC_HZ: f64 = 0.1;

/// Each wheel's path on a smooth rail of `track` (m, positive up, zero
/// mean) at its own positions `x_min + i dx`, `nodes` of them: on the
/// discrete track under its rail's wheels' mean loads, zeros on the
/// continuous.
///
/// # Errors
/// Where a layout's static receptances do not converge.
pub(super) fn wheel_paths(
    track: &Track,
    wheels: &[Wheel],
    nodes: usize,
    dx: f64,
) -> Result<Vec<Vec<f64>>, Discrete3Error> {
    let n = wheels.len();
    let mut paths = vec![vec![0.0; nodes]; n];
    if let Track::Discrete { vertical, sleeper_x0, layout, .. } = track {
        let places = Places::new(layout, *sleeper_x0);
        for r in 0..2 {
            let on: Vec<usize> = (0..n).filter(|&i| wheels[i].rail == r).collect();
            if on.is_empty() {
                continue;
            }
            let behind: Vec<f64> = on.iter().map(|&i| wheels[i].behind).collect();
            let loads: Vec<f64> = on.iter().map(|&i| wheels[i].mean_load).collect();
            let statics = static_receptances(vertical, layout, &behind)?;
            let rail_paths = parametric_paths(&statics, &places, &behind, &loads, nodes, dx);
            for (i, p) in on.into_iter().zip(rail_paths) {
                paths[i] = p;
            }
        }
    }
    Ok(paths)
}

/// The static receptance matrices (m/N, the real part at [`STATIC_HZ`])
/// of wheels `behind` (m) the leading one, at the leading wheel's places
/// ([`Places`]) on `layout`'s period of `track`.
///
/// # Errors
/// Where a layout's semi-infinite track does not converge.
pub fn static_receptances(
    track: &DiscreteTrack,
    layout: &Layout,
    behind: &[f64],
) -> Result<Vec<DMatrix<f64>>, Discrete3Error> {
    let n = behind.len();
    let omega = 2.0 * PI * STATIC_HZ;
    let positions = Places::new(layout, 0.0).positions();
    let real = |a: &[Complex64]| DMatrix::from_fn(n, n, |i, j| a[i * n + j].re);
    if track.is_one_bay(layout) {
        let offsets: Vec<f64> = behind.iter().map(|b| -b).collect();
        return Ok(track.vehicle_receptances(&positions, &offsets, omega).iter().map(|a| real(a)).collect());
    }
    let pairs = load_and_watched(&positions, behind);
    let a = track.layout_receptances(layout, &pairs, omega).map_err(layout_at(omega))?;
    Ok(a.chunks(n * n).map(real).collect())
}

/// The path of each wheel (`behind` the leading one, m; mean loads
/// `loads`, N) on a smooth rail (m, positive up, zero mean) at its own
/// positions `x_min + i dx`, `nodes` of them: the static deflection under
/// all the wheels' mean loads, `-sum_l A_jl(x, 0) N0_l`, from `statics`
/// ([`static_receptances`]) interpolated linearly between the `places`.
pub fn parametric_paths(
    statics: &[DMatrix<f64>],
    places: &Places,
    behind: &[f64],
    loads: &[f64],
    nodes: usize,
    dx: f64,
) -> Vec<Vec<f64>> {
    let n = behind.len();
    (0..n)
        .map(|j| {
            let path: Vec<f64> = (0..nodes)
                .map(|i| {
                    let (p, q, t) = places.locate(places.start() + i as f64 * dx + behind[j]);
                    let row = |m: &DMatrix<f64>| (0..n).map(|l| m[(j, l)] * loads[l]).sum::<f64>();
                    -((1.0 - t) * row(&statics[p]) + t * row(&statics[q]))
                })
                .collect();
            let mean = path.iter().sum::<f64>() / nodes.max(1) as f64;
            path.iter().map(|v| v - mean).collect()
        })
        .collect()
}
