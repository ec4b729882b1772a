//! The modes of the linearised update: eigenvalues and eigenvectors of each
//! Bloch class's growth matrix.
//!
//! Per wheel passage the roughness `R` (the class's complex amplitudes of
//! the contact-filtered lines) changes by `-J R` (`r <- r - W(r)`), so
//!
//! ```text
//! dR/dn = G R,   G = -J,   R(n) = sum_k a_k v_k exp(mu_k n)
//! ```
//!
//! with `(mu_k, v_k)` the eigenpairs of `G` (n counts wheel passages).
//! `Re mu` is the exponential growth rate, `20 lg(e) Re mu 1e5` dB per 1e5
//! wheel passages; `Im mu` turns the pattern's phase, so that a mode whose
//! largest harmonic has the signed wavenumber `q` drifts along the rail by
//! `-Im mu / q` per passage (the pattern `exp(Re mu n) cos(q X + Im mu n)`).
//! A class that is its own conjugate has its eigenvalues in conjugate pairs
//! (one real mode each); of a pair the one with `Im mu >= 0` is kept, and
//! a real eigenvalue (a standing pattern, locked in place) once.
//!
//! The shape along the stretch: a mode's pattern `v(X) = sum_s v_s exp(i
//! q_s X)` is a Bloch wave `exp(i kappa X) p(X)`; its local amplitude is
//! the envelope of its forward and backward parts, `sqrt(|sum_{s > 0}|^2 +
//! |sum_{s < 0}|^2)`, of period `L` (the stretch): deeper over the sleepers
//! or at mid-span on a one-bay stretch with a sleeper at its start.

use super::bloch::Class;
use faer::Mat;
use faer::c64;
use faer::linalg::solvers::DenseSolveCore;
use num_complex::Complex64;
use std::f64::consts::PI;

/// dB per neper: `20 lg(e)`.
pub const DB_PER_NEPER: f64 = 8.685_889_638_065_035;

/// One mode of the update.
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    /// The Bloch class (index into the classes).
    pub class: usize,
    /// Eigenvalue `mu` of `G = -J` (1 per wheel passage).
    pub eigenvalue: Complex64,
    /// Eigenvector on the class's basis, of unit norm, its largest
    /// component real and positive.
    pub vector: Vec<Complex64>,
    /// The basis entry of the largest component.
    pub dominant: usize,
    /// The dual (left) vector: the row of the inverse of the class's
    /// eigenvector matrix that belongs to this mode, scaled with `vector`,
    /// so that `sum_s dual_s R_s` is the mode's amplitude in any roughness
    /// `R` of the class (exactly `exp(mu n)` times its initial value in the
    /// linear regime, whatever the other modes do).
    pub dual: Vec<Complex64>,
}

/// Why the eigenproblem failed.
#[derive(Debug, thiserror::Error)]
#[error("the eigenvalues of Bloch class {class} ({size} harmonics) did not converge")]
pub struct EigenError {
    /// The class.
    pub class: usize,
    /// Its size.
    pub size: usize,
}

/// The modes of every class of `classes` whose matrices `J` (row major on
/// the class's basis) are `matrices`, sorted fastest growing first (ties:
/// the class, then the dominant harmonic's position in the basis).
pub fn modes(classes: &[Class], matrices: &[Vec<Complex64>]) -> Result<Vec<Mode>, EigenError> {
    let mut out = Vec::new();
    for (c, (class, j)) in classes.iter().zip(matrices).enumerate() {
        let n = class.basis.len();
        let g = Mat::<c64>::from_fn(n, n, |r, k| {
            let v = -j[r * n + k];
            c64::new(v.re, v.im)
        });
        let evd = g.eigen().map_err(|_| EigenError { class: c, size: n })?;
        let scale = (0..n).map(|k| evd.S()[k].norm()).fold(0.0f64, f64::max);
        // The duals: the rows of U^-1.
        let inverse = evd.U().partial_piv_lu().inverse();
        for k in 0..n {
            let mu = evd.S()[k];
            let mu = Complex64::new(mu.re, mu.im);
            if class.self_conjugate && mu.im < -1e-9 * scale {
                continue;
            }
            let mut v: Vec<Complex64> =
                (0..n).map(|r| Complex64::new(evd.U()[(r, k)].re, evd.U()[(r, k)].im)).collect();
            let norm = v.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt();
            let dominant = (0..n).max_by(|&a, &b| v[a].norm().total_cmp(&v[b].norm())).unwrap_or(0);
            let turn =
                if norm > 0.0 { v[dominant].conj() / (v[dominant].norm() * norm) } else { Complex64::new(1.0, 0.0) };
            v.iter_mut().for_each(|x| *x *= turn);
            // U's column k scaled by `turn`: its dual row by 1 / turn.
            let dual = (0..n).map(|r| Complex64::new(inverse[(k, r)].re, inverse[(k, r)].im) / turn).collect();
            out.push(Mode { class: c, eigenvalue: mu, vector: v, dominant, dual });
        }
    }
    out.sort_by(|a, b| {
        b.eigenvalue.re.total_cmp(&a.eigenvalue.re).then(a.class.cmp(&b.class)).then(a.dominant.cmp(&b.dominant))
    });
    Ok(out)
}

impl Mode {
    /// Growth rate (dB per 1e5 wheel passages).
    pub fn growth_rate(&self) -> f64 {
        DB_PER_NEPER * self.eigenvalue.re * 1e5
    }

    /// The signed wavenumber of the largest harmonic (1/m) on a supercell
    /// of length `supercell` (m).
    pub fn wavenumber(&self, class: &Class, supercell: f64) -> f64 {
        2.0 * PI * class.basis[self.dominant].index as f64 / supercell
    }

    /// Drift of the pattern along the rail (m per wheel passage, positive
    /// in the direction of travel).
    pub fn drift(&self, class: &Class, supercell: f64) -> f64 {
        -self.eigenvalue.im / self.wavenumber(class, supercell)
    }

    /// The mode's amplitude in the roughness whose coefficients on the
    /// class's basis are `roughness` (m): `sum_s dual_s R_s`.
    pub fn amplitude(&self, roughness: &[Complex64]) -> Complex64 {
        self.dual.iter().zip(roughness).map(|(d, r)| d * r).sum()
    }

    /// Share of the mode's energy in its largest harmonic (1).
    pub fn purity(&self) -> f64 {
        self.vector[self.dominant].norm_sqr()
    }

    /// Share of the mode's energy on rail `rail` (1).
    pub fn rail_share(&self, class: &Class, rail: usize) -> f64 {
        class.basis.iter().zip(&self.vector).filter(|(b, _)| b.rail == rail).map(|(_, v)| v.norm_sqr()).sum()
    }

    /// The envelope of the mode's pattern on rail `rail` at `positions`
    /// (m from the stretch's start) on a supercell of length `supercell`
    /// (m), normalised to rms 1 over the positions (zeros where the mode
    /// has nothing on the rail).
    pub fn envelope(&self, class: &Class, rail: usize, positions: &[f64], supercell: f64) -> Vec<f64> {
        let raw: Vec<f64> = positions
            .iter()
            .map(|&x| {
                let (mut forward, mut backward) = (Complex64::default(), Complex64::default());
                for (b, v) in class.basis.iter().zip(&self.vector).filter(|(b, _)| b.rail == rail) {
                    let term = v * Complex64::from_polar(1.0, 2.0 * PI * b.index as f64 * x / supercell);
                    if b.index > 0 { forward += term } else { backward += term }
                }
                (forward.norm_sqr() + backward.norm_sqr()).sqrt()
            })
            .collect();
        let rms = (raw.iter().map(|v| v * v).sum::<f64>() / raw.len().max(1) as f64).sqrt();
        if rms > 0.0 { raw.iter().map(|v| v / rms).collect() } else { raw }
    }
}

#[cfg(test)]
mod tests {
    use super::super::bloch::classes;
    use super::*;

    #[test]
    fn a_diagonal_map_gives_each_harmonic_its_own_rate_and_drift() {
        // J diagonal with J(s, s) = c_s, J(-s, -s) = conj c_s (a continuous
        // track): modes -c_s with the harmonic's wavelength; drift -Im(mu)/q.
        let all = classes(1, 2, 6, 1);
        let class = &all[0];
        let n = class.basis.len();
        let c = |s: i64| Complex64::new(1e-6 * s as f64 - 4e-6, 3e-7 * s as f64);
        let mut j = vec![Complex64::default(); n * n];
        for (k, b) in class.basis.iter().enumerate() {
            j[k * n + k] = if b.index > 0 { c(b.index) } else { c(-b.index).conj() };
        }
        let found = modes(&all, &[j]).unwrap();
        assert_eq!(found.len(), 5, "one mode per harmonic (conjugate pairs kept once)");
        // Fastest first: mu = -c_s, Re = 4e-6 - 1e-6 s: s = 2 fastest.
        for (m, s) in found.iter().zip(2..) {
            let b = class.basis[m.dominant];
            assert_eq!(b.index.abs(), s);
            let want = -if b.index > 0 { c(s) } else { c(s).conj() };
            assert!((m.eigenvalue - want).norm() < 1e-18, "{} vs {want}", m.eigenvalue);
            assert!((m.growth_rate() - DB_PER_NEPER * (4e-6 - 1e-6 * s as f64) * 1e5).abs() < 1e-9);
            assert!((m.purity() - 1.0).abs() < 1e-12);
            // The pattern exp(mu n) exp(i q X) moves by -Im mu / q.
            let q = 2.0 * PI * b.index as f64 / 1.0;
            assert!((m.drift(class, 1.0) - (-want.im / q)).abs() < 1e-18);
            assert!((m.drift(class, 1.0) - 3e-7 * s as f64 / (2.0 * PI * s as f64)).abs() < 1e-15);
            // The dual picks the mode's own harmonic.
            assert!((m.amplitude(&m.vector) - 1.0).norm() < 1e-12);
            let env = m.envelope(class, 0, &[0.0, 0.25, 0.5], 1.0);
            assert!(env.iter().all(|e| (e - 1.0).abs() < 1e-12), "a single harmonic has a flat envelope: {env:?}");
        }
    }

    #[test]
    fn a_coupled_pair_has_the_eigenvalues_of_its_two_by_two_block_and_a_modulated_envelope() {
        // Class 1 of a supercell of 4 stretches (length 1 m each) holds s =
        // 1, -3 and 5: couple 1 and 5 (wavenumbers 2 pi / 4 and 10 pi / 4,
        // one stretch's wavenumber apart). The eigenvalues are those of the
        // 2 x 2 block, and the pattern's envelope varies along the stretch
        // with the stretch's period.
        let all = classes(4, 1, 5, 1);
        let class = all.iter().find(|c| c.j == 1).unwrap();
        assert!(!class.self_conjugate);
        assert_eq!(class.basis.iter().map(|b| b.index).collect::<Vec<_>>(), vec![1, -3, 5]);
        let n = class.basis.len();
        let (a, b, d) = (Complex64::new(-2e-6, 1e-7), Complex64::new(5e-7, -2e-7), Complex64::new(-1e-6, 0.0));
        let mut j = vec![Complex64::default(); n * n];
        let at = |s: i64| class.basis.iter().position(|h| h.index == s).unwrap();
        j[at(1) * n + at(1)] = a;
        j[at(1) * n + at(5)] = b;
        j[at(5) * n + at(1)] = b;
        j[at(5) * n + at(5)] = d;
        j[at(-3) * n + at(-3)] = Complex64::new(1e-3, 0.0);
        let position = all.iter().position(|c| c.j == 1).unwrap();
        let found = modes(&all[position..position + 1], &[j]).unwrap();
        assert_eq!(found.len(), 3);
        // The 2 x 2 block's eigenvalues of G = -J, the fastest two modes.
        let (tr, det) = (-(a + d), a * d - b * b);
        let root = (tr * tr - 4.0 * det).sqrt();
        let mut want = [(tr + root) / 2.0, (tr - root) / 2.0];
        want.sort_by(|x, y| y.re.total_cmp(&x.re));
        for (m, w) in found.iter().zip(want) {
            assert!((m.eigenvalue - w).norm() < 1e-15, "{} vs {w}", m.eigenvalue);
        }
        // Duals and vectors are biorthogonal.
        for (a, m) in found.iter().enumerate() {
            for (b, o) in found.iter().enumerate() {
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((m.amplitude(&o.vector) - want).norm() < 1e-9, "{a}, {b}");
            }
        }
        let positions: Vec<f64> = (0..8).map(|k| k as f64 / 8.0).collect();
        let env = found[0].envelope(class, 0, &positions, 4.0);
        // The stretch's period (1 m): the envelope repeats after 1 m ...
        let later: Vec<f64> = positions.iter().map(|x| x + 1.0).collect();
        let again = found[0].envelope(class, 0, &later, 4.0);
        assert!(env.iter().zip(&again).all(|(x, y)| (x - y).abs() < 1e-9), "{env:?} vs {again:?}");
        // ... and varies within it (two harmonics beating).
        let spread = env.iter().cloned().fold(f64::MIN, f64::max) - env.iter().cloned().fold(f64::MAX, f64::min);
        assert!(spread > 0.1, "{env:?}");
    }
}
