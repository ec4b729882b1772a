//! Mixed traffic: the classes of wheel that pass over the rail, and the
//! order in which a growth study simulates them.
//!
//! Real traffic mixes vehicles: each class `c` has its own speed, mean
//! loads and unsprung mass, and a share `s_c` of the wheel passages. The
//! real profile evolves as
//!
//! ```text
//! dr/dn = - sum_c s_c W_c(r),
//! ```
//!
//! n counting real passages of all classes. A growth study simulates one
//! class per passage and lets it stand for `m` real passages of that class
//! (`r <- r - m W_c(r)`): a splitting of the sum whose classes take turns.
//! The turn goes to the class furthest behind its share of the real traffic
//! so far ([`next_class`]), whatever `m` each passage takes (the adaptive
//! controller may give classes different `m`). The deficits `s_c T - T_c`
//! sum to zero and the chosen one is the largest, so at least zero; it
//! falls by at most one `m`: no class runs more than the largest `m` ahead
//! of its share, nor more than `K - 1` times it behind (K classes). With the same
//! `m` for every passage it is smooth weighted round robin: shares 0.7 / 0.3
//! simulate `A B A A B A A B A A`, 7 to 3 in every ten.

/// The class of the next simulated passage: the one whose real traffic
/// `tally[c]` is furthest below its share `shares[c]` (summing to 1) of the
/// total, `s_c T - T_c`; ties go to the larger share, then the lower index.
pub fn next_class(shares: &[f64], tally: &[f64]) -> usize {
    assert_eq!(shares.len(), tally.len(), "one tally per class");
    let total: f64 = tally.iter().sum();
    let deficit = |c: usize| shares[c] * total - tally[c];
    (0..shares.len())
        .reduce(|best, c| {
            let (d, e) = (deficit(c), deficit(best));
            // Deficits equal up to rounding count as a tie.
            let tol = 1e-9 * total.max(1.0);
            if d > e + tol || ((d - e).abs() <= tol && shares[c] > shares[best]) { c } else { best }
        })
        .expect("at least one class")
}

/// Real traffic of each of `classes` classes in rows of (class, real
/// passages of the row).
pub fn tally(classes: usize, rows: impl IntoIterator<Item = (usize, f64)>) -> Vec<f64> {
    let mut t = vec![0.0; classes];
    for (c, m) in rows {
        t[c] += m;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn sequence(shares: &[f64], scales: impl Fn(usize, usize) -> f64, n: usize) -> (Vec<usize>, Vec<f64>) {
        let mut t = vec![0.0; shares.len()];
        let mut seq = Vec::new();
        for k in 0..n {
            let c = next_class(shares, &t);
            t[c] += scales(k, c);
            seq.push(c);
        }
        (seq, t)
    }

    #[test]
    fn equal_scales_give_smooth_weighted_round_robin() {
        let (seq, _) = sequence(&[0.7, 0.3], |_, _| 1.0, 10);
        assert_eq!(seq, [0, 1, 0, 0, 1, 0, 0, 1, 0, 0]);
        // A single class always gets the turn.
        assert_eq!(sequence(&[1.0], |_, _| 3.0, 4).0, [0, 0, 0, 0]);
        // Equal shares alternate, the lower index first.
        assert_eq!(sequence(&[0.5, 0.5], |_, _| 1.0, 4).0, [0, 1, 0, 1]);
    }

    #[test]
    fn a_class_with_a_smaller_scale_gets_more_turns() {
        // Class 1 stands for a quarter of class 0's passages per turn: it
        // needs four times the turns for the same share.
        let (seq, t) = sequence(&[0.5, 0.5], |_, c| if c == 0 { 4.0 } else { 1.0 }, 50);
        assert_eq!(seq.iter().filter(|c| **c == 1).count(), 40);
        assert!((t[0] - t[1]).abs() <= 4.0);
    }

    proptest! {
        #[test]
        fn each_class_stays_within_its_bound_of_its_share(
            weights in proptest::collection::vec(0.01f64..1.0, 1..5),
            scale_seed in proptest::collection::vec(1.0f64..1e4, 1..5),
            n in 1usize..300,
        ) {
            let total: f64 = weights.iter().sum();
            let shares: Vec<f64> = weights.iter().map(|w| w / total).collect();
            // Each class's own m, varying along the run.
            let scales = |k: usize, c: usize| scale_seed[c % scale_seed.len()] * (1.0 + (k % 7) as f64 / 7.0);
            let (_, t) = sequence(&shares, scales, n);
            let sum: f64 = t.iter().sum();
            let m_max = scale_seed.iter().cloned().fold(0.0, f64::max) * 2.0;
            let behind = (shares.len() - 1).max(1) as f64 * m_max;
            for (c, s) in shares.iter().enumerate() {
                let deficit = s * sum - t[c];
                // (Ties are decided within 1e-9 of the total.)
                let slack = 1e-8 * sum;
                prop_assert!(deficit >= -m_max - slack, "class {c} ahead by {}", -deficit);
                prop_assert!(deficit <= behind + slack, "class {c} behind by {deficit}");
            }
        }
    }
}
