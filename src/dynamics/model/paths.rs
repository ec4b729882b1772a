//! The parametric excitation of the discrete supports: each wheel's
//! path on a smooth rail, the static deflection under all the wheels'
//! mean loads on its rail, `-sum_l A_jl(x, 0) N0_l` (more at mid-span than
//! above a sleeper), which the closure turns into the sleeper-passing
//! force (the position-dependent models of Hempelmann and Knothe 1996;
//! Nielsen 2003 for a bogie).

use super::closure::bay_places;
use super::{BAY_PLACES, Track, Wheel};
use crate::dynamics::track::discrete::DiscreteTrack;
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// Frequency (Hz) at which the static receptance is read (its real part):
/// far below the track's resonances.
const STATIC_HZ: f64 = 0.1;

/// Each wheel's path on a smooth rail of `track` (m, positive up, zero
/// mean) at its own positions `x_min + i dx`, `nodes` of them: on the
/// discrete track under its rail's wheels' mean loads, zeros on the
/// continuous.
pub(super) fn wheel_paths(track: &Track, wheels: &[Wheel], nodes: usize, dx: f64) -> Vec<Vec<f64>> {
    let n = wheels.len();
    let mut paths = vec![vec![0.0; nodes]; n];
    if let Track::Discrete { vertical, sleeper_x0, .. } = track {
        for r in 0..2 {
            let on: Vec<usize> = (0..n).filter(|&i| wheels[i].rail == r).collect();
            if on.is_empty() {
                continue;
            }
            let behind: Vec<f64> = on.iter().map(|&i| wheels[i].behind).collect();
            let loads: Vec<f64> = on.iter().map(|&i| wheels[i].mean_load).collect();
            let statics = static_receptances(vertical, &behind);
            let rail_paths = parametric_paths(&statics, vertical.spacing, &behind, &loads, *sleeper_x0, nodes, dx);
            for (i, p) in on.into_iter().zip(rail_paths) {
                paths[i] = p;
            }
        }
    }
    paths
}

/// The static receptance matrices (m/N, the real part at [`STATIC_HZ`])
/// of wheels `behind` (m) the leading one, at the leading wheel's
/// [`BAY_PLACES`] places across a bay of `track`.
pub fn static_receptances(track: &DiscreteTrack, behind: &[f64]) -> Vec<DMatrix<f64>> {
    let n = behind.len();
    let offsets: Vec<f64> = behind.iter().map(|b| -b).collect();
    track
        .vehicle_receptances(&bay_places(track.spacing), &offsets, 2.0 * PI * STATIC_HZ)
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
/// ([`static_receptances`]) interpolated linearly between the places.
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
