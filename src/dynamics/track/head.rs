//! The rail head's receptances in three directions over a frequency sweep
//! (what `corrugation track` writes beside the vertical ones): the discrete
//! track's point receptances at places across a sleeper bay, the continuous
//! track's, and the transfer receptances between the wheels of a vehicle,
//! each a 4 x 4 matrix (the head's displacement in direction `i` per unit
//! force on the head in direction `j`, and its rotation about `z` per
//! force and per moment about `z`; axes of [`super::section`]: `x` along
//! the rail, `y` across to the right, `z` down).

use super::TrackConfig;
use super::continuous3::Continuous3;
use super::discrete3::{Discrete3, Discrete3Error};
use super::section::Mat4;
use rayon::prelude::*;
use std::f64::consts::PI;

/// The head's receptances (m/N; the rotation's rad/N and rad/(N m)) over a
/// sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadResponse {
    /// The contact's offset right of the rail's centre line (m).
    pub contact_offset: f64,
    /// Discrete track, point receptances, `[position][frequency]`.
    pub discrete: Vec<Vec<Mat4>>,
    /// Continuous track, point receptance, `[frequency]`.
    pub continuous: Vec<Mat4>,
    /// Discrete track, displacement at each distance ahead of a unit force at
    /// each source, `[source][distance][frequency]` (empty for one wheel).
    pub transfer: Vec<Vec<Vec<Mat4>>>,
    /// Continuous track, `[distance][frequency]`.
    pub continuous_transfer: Vec<Vec<Mat4>>,
}

/// The head's receptances of `track` with the contact `contact_offset` (m)
/// right of the centre line at `frequency` (Hz), at `position` (m from a
/// sleeper) and between wheels `distances` (m) apart with the force at
/// `source` (m from a sleeper); in parallel over the frequencies.
pub fn head_response(
    track: &TrackConfig,
    contact_offset: f64,
    frequency: &[f64],
    position: &[f64],
    source: &[f64],
    distances: &[f64],
) -> Result<HeadResponse, Discrete3Error> {
    let discrete = Discrete3::new(track, contact_offset);
    let continuous = Continuous3::new(track, contact_offset);
    // Every place pair of one frequency in one Floquet integral: the points,
    // then each source's transfers.
    let mut pairs: Vec<(f64, f64)> = position.iter().map(|&x| (x, x)).collect();
    for &x0 in source {
        pairs.extend(distances.iter().map(|&l| (x0, x0 + l)));
    }
    let mut along = vec![0.0];
    along.extend_from_slice(distances);
    let by_frequency: Vec<(Vec<Mat4>, Vec<Mat4>)> = frequency
        .par_iter()
        .map(|f| {
            let w = 2.0 * PI * f;
            Ok((discrete.head_receptances4(&pairs, w)?, continuous.head_receptances4(w, &along)?))
        })
        .collect::<Result<_, Discrete3Error>>()?;
    let n = position.len();
    let discrete_out = (0..n).map(|p| by_frequency.iter().map(|(d, _)| d[p]).collect()).collect();
    let continuous_out = by_frequency.iter().map(|(_, c)| c[0]).collect();
    let transfer = if distances.is_empty() {
        Vec::new()
    } else {
        (0..source.len())
            .map(|s| {
                (0..distances.len())
                    .map(|l| by_frequency.iter().map(|(d, _)| d[n + s * distances.len() + l]).collect())
                    .collect()
            })
            .collect()
    };
    let continuous_transfer =
        (0..distances.len()).map(|l| by_frequency.iter().map(|(_, c)| c[1 + l]).collect()).collect();
    Ok(HeadResponse {
        contact_offset,
        discrete: discrete_out,
        continuous: continuous_out,
        transfer,
        continuous_transfer,
    })
}
