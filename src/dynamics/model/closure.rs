//! The contacts closed per harmonic (eq. 1 of [`super`]): the wheels'
//! and the rail's receptances between every pair of wheels, and each
//! wheel's contact law, solved for a unit input at each wheel. The
//! directions are the closure's choice: in every direction the `3n x 3n`
//! system of the forces `f_j = (F_x, F_y, -N)_j` (with the spin's row
//! where a law has it); vertically the `n x n` system of the normal forces,
//! `M = (alpha_w + 1 / k_H) I + A_zz`, `P = M^-1 r` (Grassie et al. 1982
//! eq. 5 for one wheel; Wu and Thompson 2005 for several).

use super::places::{Places, load_and_watched};
use super::{BAY_PLACES, Directions, Track, Wheel};
use crate::dynamics::coupling::contact_point::ContactLaw;
use crate::dynamics::track::discrete3::Discrete3Error;
use crate::dynamics::track::discrete3::layout_at;
use crate::dynamics::track::section::Mat4;
use nalgebra::DMatrix;
use num_complex::Complex64;

/// The channels per wheel in `directions`: the normal force; in every
/// direction also the longitudinal creep force, the creepages and the
/// spin.
pub(super) fn channels(directions: Directions) -> usize {
    match directions {
        Directions::Vertical => 1,
        Directions::All => 5,
    }
}

/// `G` of eq. 2 of [`super`] at angular frequency `omega` (rad/s, > 0)
/// and speed `speed` (m/s, > 0), one matrix per tabulated place of the
/// leading wheel (one on the continuous track).
pub(super) fn responses(
    track: &Track,
    wheels: &[Wheel],
    directions: Directions,
    omega: f64,
    speed: f64,
) -> Result<Vec<DMatrix<Complex64>>, Discrete3Error> {
    let own = wheel_blocks(wheels, omega, speed);
    match directions {
        Directions::Vertical => {
            Ok(vertical_rail(track, wheels, omega)?.iter().map(|a| vertical(a, &own, wheels)).collect())
        }
        Directions::All => {
            let laws: Vec<ContactLaw> = wheels.iter().map(|w| w.law_at(omega)).collect();
            let spin = laws.iter().any(|l| l.force_per_spin.is_some());
            Ok(head_rail(track, wheels, omega, spin)?.iter().map(|a_r| every(&own, a_r, &laws, omega, speed)).collect())
        }
    }
}

/// The wheels' blocks `[j n + l]` (m/N): each wheel's point receptance
/// on the diagonal, the wheelset's transfer receptance between the two
/// wheels of one wheelset (the same place, two rails), zero otherwise.
fn wheel_blocks(wheels: &[Wheel], omega: f64, speed: f64) -> Vec<Mat4> {
    let n = wheels.len();
    (0..n * n)
        .map(|p| {
            let (j, l) = (&wheels[p / n], &wheels[p % n]);
            if p / n == p % n {
                j.side.receptance_between(omega, speed, j.rail, j.rail)
            } else if j.behind == l.behind && j.rail != l.rail {
                j.side.receptance_between(omega, speed, j.rail, l.rail)
            } else {
                Mat4::zeros()
            }
        })
        .collect()
}

/// Whether wheels `j` and `l` run on one rail.
fn one_rail(wheels: &[Wheel], j: usize, l: usize) -> bool {
    wheels[j].rail == wheels[l].rail
}

/// The rail's vertical receptance matrices (m/N, row-major `[j n + l]`:
/// at wheel `j` under a unit force at wheel `l`; zero between the two
/// rails, whose sleepers' rocking is left out) per place.
fn vertical_rail(track: &Track, wheels: &[Wheel], omega: f64) -> Result<Vec<Vec<Complex64>>, Discrete3Error> {
    let n = wheels.len();
    let s: Vec<f64> = wheels.iter().map(|w| w.behind).collect();
    let split = |a: Vec<Complex64>| -> Vec<Complex64> {
        a.into_iter()
            .enumerate()
            .map(|(p, v)| if one_rail(wheels, p / n, p % n) { v } else { Complex64::new(0.0, 0.0) })
            .collect()
    };
    match track {
        Track::Continuous { vertical, .. } => {
            let a = (0..n * n).map(|p| vertical.rail_transfer_receptance(omega, s[p / n] - s[p % n])).collect();
            Ok(vec![split(a)])
        }
        Track::Discrete { vertical, layout, .. } => {
            let positions = Places::new(layout, 0.0).positions();
            if !vertical.is_one_bay(layout) {
                let pairs = load_and_watched(&positions, &s);
                let a = vertical.layout_receptances(layout, &pairs, omega).map_err(layout_at(omega))?;
                return Ok(a.chunks(n * n).map(|c| split(c.to_vec())).collect());
            }
            let offsets: Vec<f64> = s.iter().map(|b| -b).collect();
            let places = computed_places(wheels);
            let computed = vertical.vehicle_receptances(&positions[..places], &offsets, omega);
            // Past mid-bay, the mirror image of the place before it (the
            // vertical receptances are even in x).
            Ok(mirrored(computed, |a| a.clone()).into_iter().map(split).collect())
        }
    }
}

/// The places whose receptances are computed: all of them, or, where the
/// wheels stand at one place (one wheel, or one wheelset's two), those up
/// to mid-bay. The bay is symmetric about a sleeper: place `p` past
/// mid-bay is place `BAY_PLACES - p` mirrored along the rail.
fn computed_places(wheels: &[Wheel]) -> usize {
    if wheels.iter().all(|w| w.behind == wheels[0].behind) { BAY_PLACES / 2 + 1 } else { BAY_PLACES }
}

/// Every place's receptances from those computed: where the half bay
/// was computed, place `p` past mid-bay is `mirror(computed[BAY_PLACES -
/// p])`.
fn mirrored<T>(mut computed: Vec<T>, mirror: impl Fn(&T) -> T) -> Vec<T> {
    for p in computed.len()..BAY_PLACES {
        let image = mirror(&computed[BAY_PLACES - p]);
        computed.push(image);
    }
    computed
}

/// A receptance seen in mirrored axes: `S A S`, `S = diag(sign)`.
fn mirror(a: &Mat4, sign: [f64; 4]) -> Mat4 {
    Mat4::from_fn(|r, c| a[(r, c)] * (sign[r] * sign[c]))
}

/// The signs of the mirror image of a place along the rail (`x -> -x`
/// about a sleeper): the longitudinal direction reversed, and with it the
/// rotation about z (an axial vector).
const ALONG: [f64; 4] = [-1.0, 1.0, 1.0, -1.0];

/// The signs of the second rail's blocks against the first's in the
/// common axes (y to the right): the lateral direction mirrored, and with
/// it the rotation about z.
const ACROSS: [f64; 4] = [1.0, -1.0, 1.0, -1.0];

/// The rail head's blocks `[j n + l]` in every direction (m/N; the
/// rotation about z where `spin`) per place: on one rail the head's
/// receptances, the second rail the first's mirror image in the common
/// axes (y to the right), zero between the rails.
fn head_rail(track: &Track, wheels: &[Wheel], omega: f64, spin: bool) -> Result<Vec<Vec<Mat4>>, Discrete3Error> {
    let n = wheels.len();
    let rails: Vec<Vec<Mat4>> = match track {
        Track::Continuous { head, .. } => {
            let head = head.as_ref().expect("checked: the head's model in every direction");
            // The head's displacement at x_j = -s_j under a force at x_l =
            // -s_l: distance s_l - s_j.
            let distances: Vec<f64> = (0..n * n).map(|p| wheels[p % n].behind - wheels[p / n].behind).collect();
            vec![head.heads(omega, &distances, spin)?]
        }
        Track::Discrete { vertical, layout, head, .. } => {
            let head = head.as_ref().expect("checked: the head's model in every direction");
            let positions = Places::new(layout, 0.0).positions();
            let behind: Vec<f64> = wheels.iter().map(|w| w.behind).collect();
            if vertical.is_one_bay(layout) {
                let pairs = load_and_watched(&positions[..computed_places(wheels)], &behind);
                let computed: Vec<Vec<Mat4>> =
                    head.heads(&pairs, omega, spin)?.chunks(n * n).map(|c| c.to_vec()).collect();
                mirrored(computed, |blocks| blocks.iter().map(|a| mirror(a, ALONG)).collect())
            } else {
                let pairs = load_and_watched(&positions, &behind);
                head.layout_heads(layout, &pairs, omega, spin)?.chunks(n * n).map(|c| c.to_vec()).collect()
            }
        }
    };
    Ok(rails
        .into_iter()
        .map(|blocks| {
            blocks
                .into_iter()
                .enumerate()
                .map(|(p, a)| match (wheels[p / n].rail, wheels[p % n].rail) {
                    (0, 0) => a,
                    (1, 1) => mirror(&a, ACROSS),
                    _ => Mat4::zeros(),
                })
                .collect()
        })
        .collect())
}

/// The vertical closure: `[M^-1]`, `M_jl = A_jl + (alpha_w,jl + [j = l]
/// / k_H,j)` with the rail's vertical receptances `a` (row-major) and the
/// wheels' blocks' `z z` entries.
fn vertical(a: &[Complex64], own: &[Mat4], wheels: &[Wheel]) -> DMatrix<Complex64> {
    let n = wheels.len();
    let m = DMatrix::from_fn(n, n, |j, l| {
        let wheel = own[j * n + l][(2, 2)];
        let wheel = if j == l { wheel + 1.0 / wheels[j].law.stiffness } else { wheel };
        a[j * n + l] + wheel
    });
    m.try_inverse().expect("a passive track's receptance matrix plus the wheels' is invertible")
}

/// The closure in every direction for unit inputs at each wheel: the
/// responses (rows `5 i + c`, columns the input's wheel) with the wheels'
/// blocks `own`, the rail's blocks `a_r` (at wheel `j` under a force at
/// wheel `l`, `[j n + l]`) and the wheels' laws at angular frequency
/// `omega` (rad/s) and speed `speed` (m/s): eq. 1 of
/// [`crate::dynamics::coupling::contact_point`] for every wheel at once.
fn every(own: &[Mat4], a_r: &[Mat4], laws: &[ContactLaw], omega: f64, speed: f64) -> DMatrix<Complex64> {
    let n = laws.len();
    let iwv = Complex64::new(0.0, omega / speed);
    let one = Complex64::new(1.0, 0.0);
    let blocks: Vec<Mat4> = a_r.iter().zip(own).map(|(r, w)| r + w).collect();
    // The relative displacements per force, A (3n x 3n), and the relative
    // rotations about z per force, R (n x 3n).
    let a = DMatrix::from_fn(3 * n, 3 * n, |r, c| blocks[(r / 3) * n + c / 3][(r % 3, c % 3)]);
    let rot = DMatrix::from_fn(n, 3 * n, |j, c| blocks[j * n + c / 3][(3, c % 3)]);
    let mut m = DMatrix::<Complex64>::zeros(3 * n, 3 * n);
    let mut rhs = DMatrix::<Complex64>::zeros(3 * n, n);
    for (j, law) in laws.iter().enumerate() {
        // Rows 3j, 3j+1: F - C_N N - C_xi (i w / V) (A f)_xy = 0, N = -f_z.
        for e in 0..2 {
            let row = 3 * j + e;
            m[(row, row)] += one;
            m[(row, 3 * j + 2)] += law.force_per_normal[e];
            for l in 0..2 {
                let c = law.force_per_creepage[e][l] * iwv;
                for col in 0..3 * n {
                    m[(row, col)] -= c * a[(3 * j + l, col)];
                }
            }
            if let Some(per_spin) = law.force_per_spin {
                let c = per_spin[e] * iwv;
                for col in 0..3 * n {
                    m[(row, col)] -= c * rot[(j, col)];
                }
            }
        }
        // Row 3j+2: (A f)_z + f_z / k_H = -r_j.
        let row = 3 * j + 2;
        for col in 0..3 * n {
            m[(row, col)] = a[(row, col)];
        }
        m[(row, row)] += Complex64::new(1.0 / law.stiffness, 0.0);
        rhs[(row, j)] = -one;
    }
    let f = m.lu().solve(&rhs).expect("the contacts' system is regular for passive wheels and track");
    let d = &a * &f;
    let spins = &rot * &f;
    let channels = channels(Directions::All);
    DMatrix::from_fn(channels * n, n, |r, j| {
        let (i, c) = (r / channels, r % channels);
        match c {
            0 => -f[(3 * i + 2, j)],
            1 => f[(3 * i, j)],
            2 => iwv * d[(3 * i, j)],
            3 => iwv * d[(3 * i + 1, j)],
            _ if laws[i].force_per_spin.is_some() => iwv * spins[(i, j)],
            _ => Complex64::new(0.0, 0.0),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::track::TrackConfig;
    use crate::dynamics::track::discrete::DiscreteTrack;
    use crate::dynamics::track::discrete3::Discrete3;
    use std::f64::consts::PI;

    /// The mirror image of a place along the rail, computed, is the
    /// mirrored receptance of the place before mid-bay: the head's 4 x 4
    /// in every direction (off the centre line, so that every cross term
    /// is there) within the quadrature's tolerance, the vertical to
    /// rounding.
    #[test]
    fn a_place_past_mid_bay_is_the_mirror_image_of_one_before_it() {
        let track = TrackConfig::default();
        let d = track.sleeper_spacing;
        let head = Discrete3::new(&track, 0.012);
        let vertical = DiscreteTrack::new(&track);
        for f in [120.0, 1070.0, 2500.0] {
            let w = 2.0 * PI * f;
            for p in [1usize, 3, 6] {
                let x = d * p as f64 / BAY_PLACES as f64;
                let a = head.heads(&[(x, x), (d - x, d - x)], w, true).unwrap();
                let image = mirror(&a[0], ALONG);
                let scale = a[1].iter().fold(0.0f64, |m, v| m.max(v.norm()));
                let err = a[1].iter().zip(image.iter()).fold(0.0f64, |m, (u, v)| m.max((u - v).norm()));
                eprintln!("{f} Hz, place {p}: mirror within {:.1e}", err / scale);
                // Measured 7e-11 (the quadrature's own tolerance is 1e-5).
                assert!(err < 1e-8 * scale, "{f} Hz, place {p}: {err:e} of {scale:e}");
                // The cross terms the mirror reverses are there.
                assert!(a[0][(0, 2)].norm() > 1e-6 * scale, "{f} Hz, place {p}: no x-z coupling");
                let v = vertical.vehicle_receptances(&[x, d - x], &[0.0], w);
                assert!((v[0][0] - v[1][0]).norm() < 1e-12 * v[0][0].norm(), "{f} Hz, place {p}: vertical");
            }
        }
    }
}
