//! The rail on a layout of supports ([`super::layout`]) by its waves'
//! scattering: the infinite periodic track's response to a point load
//! from each support's reflection and transmission of the free rail's
//! waves, with the semi-infinite track on either side of every place by
//! doubling. Exact (no integral over the Bloch wavenumber, no truncated
//! sum), and linear in the period's supports: each support's matrices are
//! built once per frequency, and a load's response travels only the
//! supports between the load and the watched place.
//!
//! # Equations
//! The free rail's Green's matrix is a sum of waves with rank-one residues,
//! `G(x) = sum_w phi_w psi_w^T exp(i lambda_w x)` for `x >= 0` and `G(-x) =
//! G(x)^T` ([`super::waves`] eq. 1; the vertical Timoshenko rail's two
//! waves, [`super::discrete`] eq. 5). Forces `f_y` at places `y` (the
//! load, the supports' reactions) give the rail's displacement
//! ```text
//! u(x) = Phi a(x) + Psi b(x),   a_w(x) = sum_{y <= x} exp(i lambda_w (x - y)) psi_w^T f_y,   b_w(x) = sum_{y > x} exp(i lambda_w (y - x)) phi_w^T f_y   (1)
//! ```
//! (`Phi = [phi_w]`, `Psi = [psi_w]`): `a` the waves travelling in `+x`,
//! `b` those in `-x`, each a scalar per wave. Over a span `d` free of
//! forces `a` and `b` each decay by `E = diag(exp(i lambda_w d))`. A
//! support of dynamic stiffness `K` at `x_s` reacts `f = -C (Phi a^- + Psi
//! b^+)`, `C = (I + K G(0))^-1 K`, and scatters the waves:
//! ```text
//! a^+ = t a^- + r' b^+,   b^- = r a^- + t' b^+,   r = -Phi^T C Phi,  t = I - Psi^T C Phi,  t' = I - Phi^T C Psi,  r' = -Psi^T C Psi   (2)
//! ```
//! Segments join by Redheffer's star product; the track to the right of a
//! place reflects `b = R a`, that to its left `a = L b`. The period's
//! scattering matrix doubled `2^k` times converges to the semi-infinite
//! track's on either side (the waves decay through the periods: the rail's
//! and the supports' damping); sweeping the period's supports backwards
//! gives `R` at each, forwards `L`:
//! ```text
//! R^- = r + t' R^+ (I - r' R^+)^-1 t,   L^+ = r' + t L^- (I - r L^-)^-1 t',   R(x - d) = E R(x) E,   L(x + d) = E L(x) E   (3)
//! ```
//! A unit load `B` at `x0` emits `p = Psi^T B` and `q = Phi^T B`, so that
//! `a^+ = a^- + p`, `b^- = b^+ + q`, `a^- = L b^-`, `b^+ = R a^+`:
//! ```text
//! (I - L R) a^- = L (R p + q),   B^T G(x0; x0) B = B^T (Phi a^+ + Psi R a^+)   (4)
//! ```
//! and the waves carry the response to `x1`: ahead of the load `a` crosses
//! each support as `a^+ = (I - r' R^+)^-1 t a^-`, behind it `b^- = (I - r
//! L^-)^-1 t' b^+`, each span as `E`; `B^T G(x1; x0) B = B^T (Phi a + Psi
//! b)` there. A place at a support is taken just after it (the support in
//! the track to its left).

use nalgebra::{DMatrix, SMatrix, SVector};
use num_complex::Complex64;

/// The free rail's waves in `Q` freedoms at one frequency: `G(x) = sum_w
/// phi_w psi_w^T exp(i lambda_w x)` for `x >= 0`, `G(-x) = G(x)^T` (eq. 1).
pub trait RailWaves<const Q: usize> {
    /// The wavenumbers `lambda_w` (rad/m, `Im > 0`).
    fn wavenumbers(&self) -> Vec<Complex64>;
    /// Each wave's residue's factors `(phi_w, psi_w)`.
    fn factors(&self) -> Vec<(SVector<Complex64, Q>, SVector<Complex64, Q>)>;

    /// The residues `M_w = phi_w psi_w^T`.
    fn residues(&self) -> Vec<SMatrix<Complex64, Q, Q>> {
        self.factors().iter().map(|(phi, psi)| phi * psi.transpose()).collect()
    }

    /// `G(x)`: the response at `x` (m) to a unit load at 0.
    fn green(&self, x: f64) -> SMatrix<Complex64, Q, Q> {
        let mut g = SMatrix::<Complex64, Q, Q>::zeros();
        for (l, m) in self.wavenumbers().iter().zip(self.residues()) {
            g += m * (Complex64::i() * l * x.abs()).exp();
        }
        if x < 0.0 { g.transpose() } else { g }
    }
}

/// A support of the period: its position (m from the period's start) and
/// dynamic stiffness in the rail's freedoms (N/m for the displacements,
/// N m/rad for the rotations).
pub type Supported<const Q: usize> = (f64, SMatrix<Complex64, Q, Q>);

/// The semi-infinite track did not converge: the waves do not decay
/// through the periods (an undamped track).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "the semi-infinite track by doubling: the reflection still changed by {change:.3e} after 2^{doublings} periods"
)]
pub struct ScatteringError {
    /// Doublings made.
    pub doublings: usize,
    /// The reflection's last relative change.
    pub change: f64,
}

/// The most doublings of the period (`2^60` periods).
const MAX_DOUBLINGS: usize = 60;

/// The reflections' relative change per doubling at which the
/// semi-infinite track has converged (the transmission through the
/// periods below rounding).
const CONVERGED: f64 = 1e-15;

type Mat = DMatrix<Complex64>;

/// A segment's scattering matrix (eq. 2): `b^- = r a^- + t' b^+`, `a^+ = t
/// a^- + r' b^+` between its left and right ends.
#[derive(Debug, Clone)]
struct Scattering {
    r: Mat,
    t: Mat,
    t_back: Mat,
    r_back: Mat,
}

impl Scattering {
    /// A free span: the waves decay by `e` (diagonal).
    fn span(e: Mat) -> Scattering {
        let w = e.nrows();
        Scattering { r: Mat::zeros(w, w), t: e.clone(), t_back: e, r_back: Mat::zeros(w, w) }
    }

    /// Redheffer's star product: `self` then `next` along `+x`.
    fn then(&self, next: &Scattering) -> Scattering {
        let w = self.r.nrows();
        let id = Mat::identity(w, w);
        // Waves between the two: a = D (t a^- + r' t'_next b^+).
        let d = inverse(&(&id - &self.r_back * &next.r));
        let d2 = inverse(&(&id - &next.r * &self.r_back));
        Scattering {
            r: &self.r + &self.t_back * &next.r * &d * &self.t,
            t: &next.t * &d * &self.t,
            t_back: &self.t_back * &d2 * &next.t_back,
            r_back: &next.r_back + &next.t * &d * &self.r_back * &next.t_back,
        }
    }
}

/// `diag(exp(i lambda_w d))` over `d` (m).
fn decay(lambda: &[Complex64], d: f64) -> Mat {
    Mat::from_diagonal(&nalgebra::DVector::from_iterator(
        lambda.len(),
        lambda.iter().map(|l| (Complex64::i() * l * d).exp()),
    ))
}

fn inverse(m: &Mat) -> Mat {
    m.clone().lu().try_inverse().expect("a passive track's scattering is regular")
}

/// Each support's matrices and the reflections about it (eq. 3).
struct Site {
    /// The track to the right reflects, just before the support (the
    /// support with it).
    before: Mat,
    /// The track to the left (with the support) reflects, just after it.
    left: Mat,
    /// `a` across the support ahead of a load: `(I - r' R^+)^-1 t`.
    ahead: Mat,
    /// `b` across the support behind a load: `(I - r L^-)^-1 t'`.
    behind: Mat,
}

/// The periodic track's waves at one frequency: its supports' sites.
struct Track<'a> {
    lambda: Vec<Complex64>,
    x: Vec<f64>,
    period: f64,
    sites: Vec<Site>,
    phi: &'a Mat,
    psi: &'a Mat,
}

impl Track<'_> {
    /// `E = diag(exp(i lambda_w d))` over `d` (m).
    fn diagonal(&self, d: f64) -> Mat {
        decay(&self.lambda, d)
    }

    /// The support before `x` (m, any period; taken just after a support
    /// at `x`): its index over all periods.
    fn locate(&self, x: f64) -> i64 {
        let m = self.x.len() as i64;
        let cells = (x / self.period).floor();
        let xr = (x - cells * self.period).clamp(0.0, self.period);
        let s = self.x.partition_point(|&v| v <= xr).max(1) as i64 - 1;
        cells as i64 * m + s
    }

    /// Support `g`'s (over all periods) position (m) and site.
    fn at(&self, g: i64) -> (f64, &Site) {
        let m = self.x.len() as i64;
        let s = g.rem_euclid(m) as usize;
        (self.x[s] + g.div_euclid(m) as f64 * self.period, &self.sites[s])
    }

    /// The reflections `(R, L)` at `x` (m) within the interval after
    /// support `g`.
    fn reflections(&self, x: f64, g: i64) -> (Mat, Mat) {
        let (xs, site) = self.at(g);
        let (next, next_site) = self.at(g + 1);
        let ahead = self.diagonal(next - x);
        let behind = self.diagonal(x - xs);
        (&ahead * &next_site.before * &ahead, &behind * &site.left * &behind)
    }

    /// `B^T G(x1; x0) B` with `p = Psi^T B`, `q = Phi^T B` (eq. 4 and the
    /// waves carried to `x1`), as the rail's displacement `Phi a + Psi b`
    /// (to be projected).
    fn response(&self, (x0, x1): (f64, f64), (p, q): (&Mat, &Mat)) -> Mat {
        let g0 = self.locate(x0);
        let (r, l) = self.reflections(x0, g0);
        let w = self.lambda.len();
        let id = Mat::identity(w, w);
        let a_minus = inverse(&(&id - &l * &r)) * &l * (&r * p + q);
        let a_plus = &a_minus + p;
        let g1 = self.locate(x1);
        if x1 >= x0 {
            // Ahead: a carried over the spans and supports.
            let mut a = a_plus;
            let (mut g, mut x) = (g0, x0);
            while g < g1 {
                let (next, site) = self.at(g + 1);
                a = &site.ahead * self.diagonal(next - x) * a;
                (g, x) = (g + 1, next);
            }
            a = self.diagonal(x1 - x) * a;
            let (r1, _) = self.reflections(x1, g1);
            self.phi * &a + self.psi * (r1 * a)
        } else {
            // Behind: b carried back.
            let mut b = &r * &a_plus + q;
            let (mut g, mut x) = (g0, x0);
            while g > g1 {
                let (xs, site) = self.at(g);
                b = &site.behind * self.diagonal(x - xs) * b;
                (g, x) = (g - 1, xs);
            }
            // At x0, or just before the support after x1's.
            b = self.diagonal(x - x1) * b;
            let (_, l1) = self.reflections(x1, g1);
            self.phi * (l1 * &b) + self.psi * b
        }
    }
}

/// `B^T G(x1; x0) B` (the rail's freedoms mapped by `b` to the loads'
/// `N`) for each pair `(x0, x1)` of `pairs` (m: the load's place and the
/// watched place) on the supports `supports` (ascending, the first at 0)
/// repeated every `period` (m), eqs. 1-4.
///
/// # Errors
/// Where the semi-infinite track does not converge (an undamped track).
///
/// # Panics
/// If a support's or the track's scattering is singular (a passive
/// track's is not).
pub fn response<const Q: usize, const N: usize>(
    waves: &impl RailWaves<Q>,
    supports: &[Supported<Q>],
    period: f64,
    b: &SMatrix<Complex64, Q, N>,
    pairs: &[(f64, f64)],
) -> Result<Vec<SMatrix<Complex64, N, N>>, ScatteringError> {
    debug_assert!(supports.first().is_some_and(|s| s.0 == 0.0), "the first support at the period's start");
    let lambda = waves.wavenumbers();
    let factors = waves.factors();
    let w = lambda.len();
    let phi = Mat::from_fn(Q, w, |i, k| factors[k].0[i]);
    let psi = Mat::from_fn(Q, w, |i, k| factors[k].1[i]);
    let g0 = &phi * psi.transpose();
    // Each support's scattering (eq. 2).
    let id_q = Mat::identity(Q, Q);
    let id = Mat::identity(w, w);
    let scatter: Vec<Scattering> = supports
        .iter()
        .map(|(_, k)| {
            let k = Mat::from_fn(Q, Q, |i, j| k[(i, j)]);
            let c = inverse(&(&id_q + &k * &g0)) * k;
            Scattering {
                r: -(phi.transpose() * &c * &phi),
                t: &id - psi.transpose() * &c * &phi,
                t_back: &id - phi.transpose() * &c * &psi,
                r_back: -(psi.transpose() * &c * &psi),
            }
        })
        .collect();
    let m = supports.len();
    let spans: Vec<f64> =
        (0..m).map(|s| if s + 1 < m { supports[s + 1].0 - supports[s].0 } else { period - supports[s].0 }).collect();
    // The period from just before support 0, doubled to the semi-infinite
    // track (eq. 3's fixed points).
    let mut whole = Scattering::span(Mat::identity(w, w));
    for (sc, &d) in scatter.iter().zip(&spans) {
        whole = whole.then(sc).then(&Scattering::span(decay(&lambda, d)));
    }
    let mut doublings = 0;
    loop {
        let next = whole.then(&whole);
        let moved = |a: &Mat, b: &Mat| (a - b).norm() / b.norm().max(f64::MIN_POSITIVE);
        let change = moved(&next.r, &whole.r).max(moved(&next.r_back, &whole.r_back));
        (whole, doublings) = (next, doublings + 1);
        if change <= CONVERGED {
            break;
        }
        if doublings == MAX_DOUBLINGS || !change.is_finite() {
            return Err(ScatteringError { doublings, change });
        }
    }
    // R just before support 0 and L there; the sweeps (eq. 3).
    // Backwards: R just after each support, the support's `ahead`, R
    // just before it.
    let mut after: Vec<(Mat, Mat)> = Vec::with_capacity(m);
    let mut r_before = whole.r.clone();
    for (sc, &d) in scatter.iter().zip(&spans).rev() {
        let e = decay(&lambda, d);
        let right = &e * &r_before * &e;
        let ahead = inverse(&(&id - &sc.r_back * &right)) * &sc.t;
        r_before = &sc.r + &sc.t_back * &right * &ahead;
        after.push((ahead, r_before.clone()));
    }
    after.reverse();
    // Forwards: L just after each support, the support's `behind`.
    let mut sites = Vec::with_capacity(m);
    let mut l_before = whole.r_back.clone();
    for ((sc, &d), (ahead, before)) in scatter.into_iter().zip(&spans).zip(after) {
        let behind = inverse(&(&id - &sc.r * &l_before)) * &sc.t_back;
        let left = &sc.r_back + &sc.t * &l_before * &behind;
        let e = decay(&lambda, d);
        l_before = &e * &left * &e;
        sites.push(Site { before, left, ahead, behind });
    }
    let track = Track { lambda, x: supports.iter().map(|s| s.0).collect(), period, sites, phi: &phi, psi: &psi };
    let bm = Mat::from_fn(Q, N, |i, j| b[(i, j)]);
    let (p, q) = (psi.transpose() * &bm, phi.transpose() * &bm);
    Ok(pairs
        .iter()
        .map(|&pair| {
            let u = bm.transpose() * track.response(pair, (&p, &q));
            SMatrix::<Complex64, N, N>::from_fn(|r, c| u[(r, c)])
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::super::TrackConfig;
    use super::super::discrete::DiscreteTrack;
    use super::super::discrete3::Discrete3;
    use super::super::floquet;
    use super::super::layout::Layout;
    use super::super::section::{Mat4, Mat6, translations};
    use super::*;
    use std::f64::consts::PI;

    const HZ: [f64; 4] = [150.0, 600.0, 1500.0, 3000.0];

    fn omega(hz: f64) -> f64 {
        2.0 * PI * hz
    }

    /// An irregular layout of three bays: spacings 0.55, 0.70 and 0.55 m,
    /// the second pad twice as stiff, the third sleeper lighter.
    fn irregular(t: &TrackConfig) -> Layout {
        let mut l = Layout::at_positions(t, 1.8, &[0.0, 0.55, 1.25]).unwrap();
        l.supports[1].pad_stiffness *= 2.0;
        l.supports[2].sleeper_mass *= 0.7;
        l
    }

    fn relative(a: Complex64, b: Complex64) -> f64 {
        (a - b).norm() / b.norm()
    }

    #[test]
    fn one_support_per_period_is_the_discrete_track() {
        // Vertically against the lattice sums of discrete.rs (their own
        // truncation and midpoint rule); in every direction against
        // discrete3.rs's one-support integral.
        let t = TrackConfig::default();
        let layout = Layout::uniform(&t);
        let vertical = DiscreteTrack::new(&t);
        let head = Discrete3::new(&t, 0.01);
        let pairs = [(0.0, 0.0), (0.15, 0.15), (0.3, 0.3), (0.1, 0.45)];
        let (mut ev, mut eh) = (0.0f64, 0.0f64);
        for hz in HZ {
            let w = omega(hz);
            let lay = vertical.layout_receptances(&layout, &pairs, w).unwrap();
            let own: Vec<Complex64> =
                pairs.iter().map(|&(x0, x1)| vertical.transfer_receptances(x0, &[x1 - x0], w)[0]).collect();
            for (a, b) in lay.iter().zip(&own) {
                ev = ev.max(relative(*a, *b));
            }
            let lay = head.layout_heads(&layout, &pairs, w, true).unwrap();
            let own = head.heads(&pairs, w, true).unwrap();
            for (a, b) in lay.iter().zip(&own) {
                eh = eh.max((a - b).norm() / b.norm());
            }
        }
        // Vertically 1.5e-4: the lattice sums' truncation (a few 1e-4 of
        // the receptance, discrete.rs); in every direction 2.8e-10, the
        // one-support integral's tolerance.
        assert!(ev < 1e-3, "vertical: {ev:e}");
        assert!(eh < 1e-8, "every direction: {eh:e}");
    }

    #[test]
    fn identical_bays_are_one_bay() {
        let t = TrackConfig::default();
        let three = Layout::at_positions(&t, 1.8, &[0.0, 0.6, 1.2]).unwrap();
        let one = Layout::uniform(&t);
        let vertical = DiscreteTrack::new(&t);
        let head = Discrete3::new(&t, 0.01);
        // The same places seen from another bay of the three.
        let pairs = [(0.1, 0.1), (0.2, 0.5), (0.3, 1.0)];
        let shifted: Vec<(f64, f64)> = pairs.iter().map(|&(a, b)| (a + 0.6, b + 0.6)).collect();
        let (mut ev, mut eh) = (0.0f64, 0.0f64);
        for hz in HZ {
            let w = omega(hz);
            let a = vertical.layout_receptances(&three, &shifted, w).unwrap();
            let b = vertical.layout_receptances(&one, &pairs, w).unwrap();
            for (a, b) in a.iter().zip(&b) {
                ev = ev.max(relative(*a, *b));
            }
            let a = head.layout_heads(&three, &shifted, w, false).unwrap();
            let b = head.layout_heads(&one, &pairs, w, false).unwrap();
            for (a, b) in a.iter().zip(&b) {
                eh = eh.max((a - b).norm() / b.norm());
            }
        }
        // Measured 1.7e-15 and 5.4e-15: the same waves through other
        // supports' matrices, to rounding.
        assert!(ev < 1e-12 && eh < 1e-12, "vertical {ev:e}, every direction {eh:e}");
    }

    /// The rail's response on `periods` copies each side of the layout's
    /// supports, solved in space: `w_s + sum_t G(p_s - p_t) K_t w_t = G(p_s
    /// - x0)`, the response at `x1` `G(x1 - x0) - sum_t G(x1 - p_t) K_t w_t`.
    fn in_space<const Q: usize>(
        waves: &impl RailWaves<Q>,
        supports: &[Supported<Q>],
        period: f64,
        periods: i32,
        (x0, x1): (f64, f64),
    ) -> SMatrix<Complex64, Q, Q> {
        let all: Vec<&Supported<Q>> = (-periods..=periods).flat_map(|_| supports.iter()).collect();
        let place: Vec<f64> =
            (-periods..=periods).flat_map(|n| supports.iter().map(move |(x, _)| x + n as f64 * period)).collect();
        let n = all.len();
        let mut a = Mat::identity(Q * n, Q * n);
        let mut rhs = Mat::zeros(Q * n, Q);
        for s in 0..n {
            for t in 0..n {
                let block = waves.green(place[s] - place[t]) * all[t].1;
                let mut v = a.view_mut((Q * s, Q * t), (Q, Q));
                v += block;
            }
            rhs.view_mut((Q * s, 0), (Q, Q)).copy_from(&waves.green(place[s] - x0));
        }
        let w = a.lu().solve(&rhs).unwrap();
        let mut g = waves.green(x1 - x0);
        for t in 0..n {
            let wt = SMatrix::<Complex64, Q, Q>::from_fn(|r, c| w[(Q * t + r, c)]);
            g -= waves.green(x1 - place[t]) * all[t].1 * wt;
        }
        g
    }

    #[test]
    fn an_irregular_layout_against_its_supports_solved_in_space() {
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let vertical = DiscreteTrack::new(&t);
        let pairs = [(0.0, 0.0), (0.3, 0.3), (0.9, 0.9), (0.2, 1.4)];
        let mut e = 0.0f64;
        for hz in HZ {
            let w = omega(hz);
            let waves = vertical.waves(w);
            let supports = vertical.layout_supports(&layout, w);
            let scattered = vertical.layout_receptances(&layout, &pairs, w).unwrap();
            for (p, f) in pairs.iter().zip(&scattered) {
                let s = in_space(&waves, &supports, layout.period, 60, *p)[(0, 0)];
                e = e.max(relative(*f, s));
            }
        }
        // Measured 1.6e-10: the sum in space's 60 periods.
        assert!(e < 1e-8, "vertical: {e:e}");
    }

    #[test]
    fn an_irregular_layout_in_every_direction_against_its_supports_solved_in_space() {
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let head = Discrete3::new(&t, 0.01);
        // The lateral and longitudinal waves carry little damping: the
        // sum in space converges slowly with its length (7.0e-3, 1.2e-3,
        // 5.6e-4 at 10, 20, 30 periods each side).
        let pairs = [(0.3, 0.3), (0.2, 1.4)];
        let mut e = 0.0f64;
        for hz in [600.0, 1500.0] {
            let w = omega(hz);
            let waves = head.free_waves(w).unwrap();
            let supports = head.layout_supports(&layout, w);
            let scattered = head.layout_heads(&layout, &pairs, w, false).unwrap();
            for (p, f) in pairs.iter().zip(&scattered) {
                let g: Mat6 = in_space(&waves, &supports, layout.period, 30, *p);
                let s = head.section.head(&g);
                e = e.max((translations(f) - s).norm() / s.norm());
            }
        }
        assert!(e < 1e-3, "every direction: {e:e}");
    }

    #[test]
    fn an_irregular_layout_is_reciprocal_and_passive_in_every_direction() {
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let head = Discrete3::new(&t, 0.01);
        let places = [0.0, 0.2, 0.55, 0.9, 1.6];
        for hz in HZ {
            let w = omega(hz);
            let pairs: Vec<(f64, f64)> = places.iter().flat_map(|&a| places.iter().map(move |&b| (a, b))).collect();
            let g = head.layout_heads(&layout, &pairs, w, true).unwrap();
            let n = places.len();
            for i in 0..n {
                for j in 0..n {
                    let (a, b) = (&g[i * n + j], &g[j * n + i]);
                    let e = (a - b.transpose()).norm() / a.norm();
                    assert!(e < 1e-9, "{hz} Hz, places {i}, {j}: G(x1; x0) - G(x0; x1)^T at {e:e}");
                }
                // Passive (exp(+i w t)): (A - A^H) / 2i is negative
                // semidefinite at a point.
                let a: &Mat4 = &g[i * n + i];
                let h = (a - a.adjoint()) / Complex64::new(0.0, 2.0);
                let top = h.map(|v| v.re).symmetric_eigenvalues().max();
                assert!(top <= 1e-9 * a.norm(), "{hz} Hz at {} m: the dissipation's eigenvalue {top:e}", places[i]);
            }
        }
    }

    #[test]
    fn the_scattering_is_the_floquet_integral() {
        // Two independent methods: eq. 1 of floquet.rs integrated over the
        // Bloch wavenumber to 1e-10, against the waves' scattering; loads
        // and watched places across periods, on either side, at supports.
        let t = TrackConfig::default();
        let layout = irregular(&t);
        let vertical = DiscreteTrack::new(&t);
        let head = Discrete3::new(&t, 0.01);
        let pairs = [(0.0, 0.0), (0.55, 0.55), (0.3, 2.9), (1.7, -0.4), (-0.2, 0.35), (1.25, 0.1)];
        let limits = (1e-10, 1_000_000);
        let one = SMatrix::<Complex64, 1, 1>::from_element(Complex64::new(1.0, 0.0));
        let (mut ev, mut eh) = (0.0f64, 0.0f64);
        for hz in HZ {
            let w = omega(hz);
            let supports = vertical.layout_supports(&layout, w);
            let f = floquet::response(&vertical.waves(w), &supports, layout.period, &one, &pairs, limits).unwrap();
            let s = vertical.layout_receptances(&layout, &pairs, w).unwrap();
            for (a, b) in s.iter().zip(&f) {
                ev = ev.max(relative(*a, b[(0, 0)]));
            }
            let waves = head.free_waves(w).unwrap();
            let supports = head.layout_supports(&layout, w);
            let map = head.section.head_map();
            let f = floquet::response(&waves, &supports, layout.period, &map, &pairs, limits).unwrap();
            let s = response(&waves, &supports, layout.period, &map, &pairs).unwrap();
            for (a, b) in s.iter().zip(&f) {
                eh = eh.max((a - b).norm() / b.norm());
            }
        }
        // Measured 1.9e-14 and 9.4e-13: the integral's tolerance.
        assert!(ev < 1e-10 && eh < 1e-10, "vertical {ev:e}, every direction {eh:e}");
    }
}
