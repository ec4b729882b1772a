use super::*;
use crate::contact::friction::Characteristic;
use crate::contact::friction::STICK_SLIP_FACTOR;

/// Polach's dry law (A = 0.4, B = 0.6 s/m) and steeper laws, falling and
/// rising.
fn laws() -> [Characteristic; 4] {
    [
        Characteristic::Exponential { ratio: 0.4, speed: 1.0 / 0.6 },
        Characteristic::Exponential { ratio: 0.4, speed: 0.01 },
        Characteristic::Rational { ratio: 0.5, speed: 0.02 },
        Characteristic::Exponential { ratio: 1.3, speed: 0.05 },
    ]
}

/// `D = -dp/ds` against central differences of the traction, and the
/// Newton-Krylov solver's: the law's own where the characteristic rises,
/// else r(q) times the constant law's.
#[test]
fn jacobian_matches_differences() {
    let (mu_p3, eps) = (3e8, 1e-5);
    for ch in laws() {
        for s in [[3e-7, -1e-7], [2e-5, 1e-5], [0.004, -0.003], [0.3, 0.2], [-1.5, 0.1]] {
            let (_, d) = regularised_with(s, mu_p3, eps, ch);
            for c in 0..2 {
                let h = 1e-6 * (s[0].hypot(s[1]));
                let (mut a, mut b) = (s, s);
                a[c] += h;
                b[c] -= h;
                let (pa, pb) = (regularised_with(a, mu_p3, eps, ch).0, regularised_with(b, mu_p3, eps, ch).0);
                let col = [-(pa[0] - pb[0]) / (2.0 * h), -(pa[1] - pb[1]) / (2.0 * h)];
                let want = if c == 0 { [d[0], d[1]] } else { [d[1], d[2]] };
                let scale = d[0].abs().max(d[2].abs());
                for r in 0..2 {
                    assert!((col[r] - want[r]).abs() <= 1e-6 * scale, "{ch:?} s {s:?}: {col:?} vs {want:?}");
                }
            }
            let frozen = frozen_jacobian(s, mu_p3, eps, ch);
            let base = regularised(s, mu_p3, eps).1;
            let (r, rp) = ch.ratio(s[0].hypot(s[1]));
            let want = if rp >= 0.0 { d } else { base.map(|b| r * b) };
            for i in 0..3 {
                assert!((frozen[i] - want[i]).abs() <= 1e-12 * base[0].abs().max(base[2].abs()));
            }
        }
    }
}

/// The stick regime's inverse law: the slip of a traction gives it back.
#[test]
fn stick_inverse_is_the_law_inverted() {
    let (mu_p3, eps) = (3e8, 1e-5);
    for ch in laws() {
        for share in [1e-6, 0.3, 0.9] {
            let p = [share * mu_p3 * 0.8, -share * mu_p3 * 0.6];
            let s = regularised_slip_with(p, mu_p3, eps, ch);
            assert!(s[0].hypot(s[1]) < STICK_SLIP_FACTOR * eps);
            let back = regularised_with(s, mu_p3, eps, ch).0;
            assert!((back[0] - p[0]).abs() + (back[1] - p[1]).abs() <= 1e-12 * mu_p3, "{ch:?}");
        }
    }
}

/// The element's energy `1/2 (s - s0)^T K^-1 (s - s0) + phi(|s|)`.
fn energy(s: [f64; 2], s0: [f64; 2], k: [f64; 3], phi: &dyn Fn(f64) -> f64) -> f64 {
    let ki = symmetric_inverse(k);
    let d = [s[0] - s0[0], s[1] - s0[1]];
    0.5 * (ki[0] * d[0] * d[0] + 2.0 * ki[1] * d[0] * d[1] + ki[2] * d[1] * d[1]) + phi(s[0].hypot(s[1]))
}

/// Brute-force minimisation: a 201 x 201 grid on the box |s_i| <= 1.2 |s0|,
/// then five times a grid of the same size on a box a tenth as wide about
/// the best point.
fn brute_force(s0: [f64; 2], k: [f64; 3], phi: &dyn Fn(f64) -> f64) -> ([f64; 2], f64) {
    let q0 = s0[0].hypot(s0[1]);
    let (mut centre, mut half) = ([0.0, 0.0], 1.2 * q0);
    let mut best = ([0.0; 2], energy([0.0; 2], s0, k, phi));
    for _ in 0..6 {
        for i in 0..=200 {
            for j in 0..=200 {
                let s = [centre[0] + half * (i as f64 / 100.0 - 1.0), centre[1] + half * (j as f64 / 100.0 - 1.0)];
                let e = energy(s, s0, k, phi);
                if e < best.1 {
                    best = (s, e);
                }
            }
        }
        centre = best.0;
        half *= 0.1;
    }
    best
}

/// Coulomb with a falling law where stick and slip are both local minima:
/// the solver's state is the global minimum a brute-force search finds,
/// and the state switches from stick to slip where their energies cross.
#[test]
fn coulomb_element_is_the_global_minimum() {
    let (mu_p3, kk) = (1e8, 1e-8);
    let ch = Characteristic::Exponential { ratio: 0.4, speed: 0.01 };
    let phi = |q: f64| mu_p3 * ch.integral(q);
    let mut switched = None;
    for (n, k) in [[kk, 0.0, kk], [kk, 0.2 * kk, 1.4 * kk]].into_iter().enumerate() {
        let mut last_stick = true;
        for step in 0..=40 {
            let m = 0.3 + 0.02 * step as f64;
            let s0 = [m * 0.8, -m * 0.6];
            let (s, p) = coulomb_local_with(s0, k, mu_p3, ch);
            // The element equation s = s0 + K p and the law.
            let r = [s[0] - s0[0] - (k[0] * p[0] + k[1] * p[1]), s[1] - s0[1] - (k[1] * p[0] + k[2] * p[1])];
            assert!(r[0].hypot(r[1]) <= 1e-12 * m, "residual {r:?}");
            let (q, pm) = (s[0].hypot(s[1]), p[0].hypot(p[1]));
            if q > 0.0 {
                assert!((pm - mu_p3 * ch.ratio(q).0).abs() <= 1e-12 * mu_p3);
            } else {
                assert!(pm <= mu_p3 * (1.0 + 1e-12));
            }
            let (sb, eb) = brute_force(s0, k, &phi);
            let e = energy(s, s0, k, &phi);
            assert!(e <= eb + 1e-9 * eb.abs(), "K {k:?} |s0| {m}: energy {e} above the search's {eb}");
            assert!((s[0] - sb[0]).hypot(s[1] - sb[1]) <= 1e-4 * m, "K {k:?} |s0| {m}: {s:?} vs {sb:?}");
            let stick = q == 0.0;
            if n == 0 && last_stick && !stick {
                switched = Some(m);
            }
            assert!(!stick || last_stick, "slip then stick again at |s0| {m}");
            last_stick = stick;
        }
    }
    // Isotropic K: stick holds to |s0| = k mu p3 = 1 m/s, slip exists from
    // q + r(q) = |s0| on; their energies cross well before stick's limit.
    let m = switched.expect("stick and slip both occur");
    assert!(m > 0.4 && m < 1.0, "switched at {m}");
}

/// The regularised law with a falling characteristic in the non-convex
/// range: the solver's state is the global minimum of the element's
/// energy (phi by a fine trapezoid table, independent of the solver's
/// quadrature).
#[test]
fn regularised_element_is_the_global_minimum() {
    let (mu_p3, eps, kk) = (1e8, 1e-3, 1e-8);
    for ch in
        [Characteristic::Exponential { ratio: 0.4, speed: 0.01 }, Characteristic::Rational { ratio: 0.3, speed: 0.01 }]
    {
        let n = 400_000;
        let top = 2.0;
        let table: Vec<f64> = {
            let mut acc = vec![0.0; n + 1];
            let g = |q: f64| mu_p3 * ch.ratio(q).0 * 2.0 / PI * (q / eps).atan();
            for i in 1..=n {
                let (a, b) = (top * (i - 1) as f64 / n as f64, top * i as f64 / n as f64);
                acc[i] = acc[i - 1] + 0.5 * (b - a) * (g(a) + g(b));
            }
            acc
        };
        let phi = |q: f64| {
            let x = q / top * n as f64;
            let i = (x.floor() as usize).min(n - 1);
            table[i] + (x - i as f64) * (table[i + 1] - table[i])
        };
        for k in [[kk, 0.0, kk], [kk, -0.3 * kk, 0.8 * kk]] {
            for m in [0.2, 0.5, 0.7, 0.85, 1.2] {
                let s0 = [m * 0.6, m * 0.8];
                let (s, p) = local_solve_with(s0, k, mu_p3, eps, s0, ch);
                let r = [s[0] - s0[0] - (k[0] * p[0] + k[1] * p[1]), s[1] - s0[1] - (k[1] * p[0] + k[2] * p[1])];
                assert!(r[0].hypot(r[1]) <= 1e-11 * m, "residual {r:?}");
                let (_, eb) = brute_force(s0, k, &phi);
                let e = energy(s, s0, k, &phi);
                assert!(e <= eb + 1e-7 * eb.abs(), "{ch:?} K {k:?} |s0| {m}: energy {e} above {eb}");
            }
        }
    }
}

/// In the convex range the varying law's element problem is solved to
/// rounding from any start, as the constant law's.
#[test]
fn convex_element_problem_is_solved_to_rounding() {
    let (mu_p3, eps) = (5e8, 1e-5);
    let k = [2e-10, 3e-11, 2.6e-10];
    for ch in laws() {
        if mu_p3 * largest_eigenvalue(k) * ch.steepest_fall() >= 1.0 {
            continue;
        }
        for m in [1e-8, 1e-5, 1e-3, 0.05, 0.4, 3.0] {
            for start in [[0.0, 0.0], [m, -m], [1.0, 1.0]] {
                let s0 = [m * 0.28, -m * 0.96];
                let (s, p) = local_solve_with(s0, k, mu_p3, eps, start, ch);
                let r = [s[0] - s0[0] - (k[0] * p[0] + k[1] * p[1]), s[1] - s0[1] - (k[1] * p[0] + k[2] * p[1])];
                assert!(r[0].hypot(r[1]) <= 1e-13 * m.max(eps), "{ch:?} |s0| {m}: residual {r:?}");
                assert_eq!(regularised_with(s, mu_p3, eps, ch).0, p);
                let (sc, pc) = coulomb_local_with(s0, k, mu_p3, ch);
                let rc = [sc[0] - s0[0] - (k[0] * pc[0] + k[1] * pc[1]), sc[1] - s0[1] - (k[1] * pc[0] + k[2] * pc[1])];
                assert!(rc[0].hypot(rc[1]) <= 1e-12 * m, "Coulomb {ch:?} |s0| {m}: residual {rc:?}");
            }
        }
    }
}

/// A constant characteristic is the constant law bit for bit.
#[test]
fn constant_is_the_constant_law() {
    let ch = Characteristic::Exponential { ratio: 1.0, speed: 0.3 };
    let (s0, k) = ([1e-3, -2e-3], [2e-10, 1e-11, 3e-10]);
    assert_eq!(local_solve_with(s0, k, 3e8, 1e-5, s0, ch), local_solve(s0, k, 3e8, 1e-5, s0));
    assert_eq!(coulomb_local_with(s0, k, 3e8, ch), coulomb_local(s0, k, 3e8));
    assert_eq!(regularised_with(s0, 3e8, 1e-5, ch), regularised(s0, 3e8, 1e-5));
}
