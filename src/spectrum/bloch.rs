//! The Bloch (Floquet) classes of a periodic stretch, and the harmonics of
//! a supercell of `M` stretches that carry them.
//!
//! A passage over a stretch of length `L` that repeats (one sleeper bay,
//! or any periodic stretch) is invariant under the shift by `L`, so its
//! linearised wear map `J` (`W(r0 + d) = W(r0) + J d`) takes a Bloch wave
//! `exp(i kappa X) p(X)`, `p` of period `L`, to another with the same
//! `kappa`: `J` couples only the wavenumbers of one class,
//!
//! ```text
//! q = kappa + 2 pi n / L,   n integer,   kappa in [0, 2 pi / L)
//! ```
//!
//! (Floquet's theorem; for the track, Hempelmann and Knothe's coupling of
//! the harmonics `f + n V / d`). On a supercell of `M` stretches, length
//! `L_s = M L`, the harmonic of signed index `s` (wavenumber `2 pi s / L_s`)
//! belongs to class `j = s mod M`, `kappa_j = 2 pi j / L_s`. A real profile's
//! coefficients at `-s` are the conjugates of those at `s`, so class `M - j`
//! is the conjugate of class `j`: classes `0 <= j <= M / 2` hold every
//! mode once. Classes 0 and `M / 2` (`M` even) are their own conjugates.
//!
//! A class's basis is its signed indices `s` with `|s|` in the band
//! `[h_min, h_max]` (wavelengths `L_s / |s|`), on each rail. Its matrix is
//! measured by real perturbations `eps cos(2 pi h X / L_s + phi)`:
//!
//! * a class `j` that is not its own conjugate: the perturbation at the
//!   positive harmonic `h` (`h = s` or `-s`) puts `eps exp(+-i phi) / 2` on
//!   the class's index `s`; the response's coefficients on the class's
//!   indices are `J(., s)` times that (one passage per column);
//! * a class that is its own conjugate holds both `h` and `-h`: two
//!   perturbations at phases `phi` and `phi + pi / 2`, with responses `c1`,
//!   `c2`, give `J(., h) = (c1 - i c2) / (eps exp(i phi))` and `J(., -h) =
//!   (c1 + i c2) / (eps exp(-i phi))`.
//!
//! Different classes do not couple, so one passage carries one
//! perturbation of every class (a *round*), and every class's columns are
//! read off the same responses.

use num_complex::Complex64;
use std::f64::consts::PI;

/// One harmonic of a class's basis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Harmonic {
    /// The rail (0 the first, 1 the wheelset's second).
    pub rail: usize,
    /// Signed index on the supercell (wavenumber `2 pi index / L_s`).
    pub index: i64,
}

/// One Bloch class on the supercell.
#[derive(Debug, Clone, PartialEq)]
pub struct Class {
    /// Its number `j` (`kappa_j = 2 pi j / L_s`), `0 <= j <= M / 2`.
    pub j: usize,
    /// Whether it is its own conjugate (`j = 0` or `2 j = M`).
    pub self_conjugate: bool,
    /// Its basis, by rail then by increasing `|index|`, the positive index
    /// first.
    pub basis: Vec<Harmonic>,
}

/// One perturbation of a round.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slot {
    /// The class (index into the classes).
    pub class: usize,
    /// The rail perturbed.
    pub rail: usize,
    /// The positive harmonic perturbed (supercell index).
    pub h: usize,
    /// Its phase (rad).
    pub phase: f64,
    /// For a class that is its own conjugate: whether this is the second of
    /// the pair of phases (`phase` is then the first's plus `pi / 2`).
    pub second: bool,
}

/// The classes of a supercell of `cells` stretches with the harmonics
/// `h_min..=h_max` (positive supercell indices) on `rails` rails.
pub fn classes(cells: usize, h_min: usize, h_max: usize, rails: usize) -> Vec<Class> {
    let m = cells as i64;
    (0..=cells / 2)
        .map(|j| {
            let self_conjugate = j == 0 || 2 * j == cells;
            let mut indices: Vec<i64> = Vec::new();
            for h in h_min..=h_max {
                let h = h as i64;
                if h.rem_euclid(m) == j as i64 {
                    indices.push(h);
                }
                // -h is in class j where h is in class M - j (both, for a
                // class that is its own conjugate).
                if (-h).rem_euclid(m) == j as i64 {
                    indices.push(-h);
                }
            }
            indices.sort_by_key(|s| (s.abs(), -s.signum()));
            let basis =
                (0..rails).flat_map(|rail| indices.iter().map(move |&index| Harmonic { rail, index })).collect();
            Class { j, self_conjugate, basis }
        })
        .filter(|c: &Class| !c.basis.is_empty())
        .collect()
}

/// The perturbations of each class, in order: a class that is not its own
/// conjugate one per positive harmonic of its pair and rail, one that is
/// two (phases `phi`, `phi + pi / 2`). The phases follow the golden angle
/// from slot to slot and class to class, so that the perturbations of a
/// round do not peak together.
pub fn slots(classes: &[Class]) -> Vec<Vec<Slot>> {
    let golden = PI * (3.0 - 5f64.sqrt());
    classes
        .iter()
        .enumerate()
        .map(|(c, class)| {
            let mut out = Vec::new();
            let mut k = 0usize;
            for harmonic in &class.basis {
                let h = harmonic.index.unsigned_abs() as usize;
                // Each positive harmonic once: through its positive index in
                // a class that is its own conjugate, through whichever sign
                // the class holds otherwise.
                if class.self_conjugate && harmonic.index < 0 {
                    continue;
                }
                let phase = (golden * (k as f64 + 0.5 * c as f64)).rem_euclid(2.0 * PI);
                k += 1;
                out.push(Slot { class: c, rail: harmonic.rail, h, phase, second: false });
                if class.self_conjugate {
                    out.push(Slot { class: c, rail: harmonic.rail, h, phase: phase + 0.5 * PI, second: true });
                }
            }
            out
        })
        .collect()
}

/// The rounds: round `t` holds the `t`-th slot of every class that has one.
pub fn rounds(slots: &[Vec<Slot>]) -> Vec<Vec<Slot>> {
    let n = slots.iter().map(Vec::len).max().unwrap_or(0);
    (0..n).map(|t| slots.iter().filter_map(|s| s.get(t).copied()).collect()).collect()
}

/// A round's perturbation of rail `rail` (m, zero mean): the sum of `eps
/// cos(2 pi h X / L_s + phase)` over its slots on that rail, at the
/// supercell's `nodes` nodes `X = i L_s / nodes`.
pub fn perturbation(round: &[Slot], rail: usize, nodes: usize, eps: f64) -> Vec<f64> {
    let mut line = vec![0.0; nodes];
    for s in round.iter().filter(|s| s.rail == rail) {
        let k = 2.0 * PI * s.h as f64 / nodes as f64;
        for (i, v) in line.iter_mut().enumerate() {
            *v += eps * (k * i as f64 + s.phase).cos();
        }
    }
    line
}

/// The discrete Fourier transform of a real line of samples,
/// `sum_j line_j exp(-2 pi i j k / n)` for `k = 0 .. n - 1` (unnormalised,
/// as [`coefficient`] reads it).
pub fn dft(line: &[f64]) -> Vec<Complex64> {
    let mut buf: Vec<Complex64> = line.iter().map(|v| Complex64::new(*v, 0.0)).collect();
    rustfft::FftPlanner::new().plan_fft_forward(buf.len()).process(&mut buf);
    buf
}

/// The coefficient of the signed index `s` of a line whose forward DFT is
/// `dft` (rustfft's unnormalised transform of `nodes` samples): the line is
/// `sum_s c_s exp(2 pi i s X / L_s)`, `c_s = dft[s mod nodes] / nodes`.
pub fn coefficient(dft: &[Complex64], s: i64) -> Complex64 {
    let n = dft.len() as i64;
    dft[s.rem_euclid(n) as usize] / n as f64
}

/// Each class's matrix `J` (`J[class][(row, column)]` on its basis, row
/// major), from the responses to the slots: `response(slot, target)` the
/// coefficient of the basis harmonic `target` in the response to `slot`'s
/// perturbation of amplitude `eps` (see the module's doc).
pub fn assemble(
    classes: &[Class],
    slots: &[Vec<Slot>],
    eps: f64,
    response: impl Fn(&Slot, &Harmonic) -> Complex64,
) -> Vec<Vec<Complex64>> {
    classes
        .iter()
        .zip(slots)
        .map(|(class, slots)| {
            let n = class.basis.len();
            let mut j = vec![Complex64::default(); n * n];
            let column = |rail: usize, index: i64| {
                class.basis.iter().position(|b| b.rail == rail && b.index == index).expect("a basis harmonic")
            };
            let mut k = 0;
            while k < slots.len() {
                let slot = &slots[k];
                if class.self_conjugate {
                    let (first, second) = (slot, &slots[k + 1]);
                    let rot = Complex64::from_polar(eps, first.phase);
                    let (plus, minus) = (column(first.rail, first.h as i64), column(first.rail, -(first.h as i64)));
                    for (row, target) in class.basis.iter().enumerate() {
                        let (c1, c2) = (response(first, target), response(second, target));
                        let i = Complex64::i();
                        j[row * n + plus] = (c1 - i * c2) / rot;
                        if minus != plus {
                            j[row * n + minus] = (c1 + i * c2) / rot.conj();
                        }
                    }
                    k += 2;
                } else {
                    let h = slot.h as i64;
                    let m = class_of(class, h);
                    let (s, weight) = if m {
                        (h, Complex64::from_polar(0.5 * eps, slot.phase))
                    } else {
                        (-h, Complex64::from_polar(0.5 * eps, -slot.phase))
                    };
                    let col = column(slot.rail, s);
                    for (row, target) in class.basis.iter().enumerate() {
                        j[row * n + col] = response(slot, target) / weight;
                    }
                    k += 1;
                }
            }
            j
        })
        .collect()
}

/// Whether the positive harmonic `h` is in `class` with its positive sign.
fn class_of(class: &Class, h: i64) -> bool {
    class.basis.iter().any(|b| b.index == h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rustfft::FftPlanner;

    #[test]
    fn the_classes_hold_every_harmonic_of_the_band_once_with_its_conjugate() {
        // Every positive harmonic of the band appears in exactly one class
        // 0 <= j <= M/2, with its own sign or its conjugate's; the classes
        // that are their own conjugates hold both signs.
        for cells in [1, 2, 3, 4, 7] {
            let all = classes(cells, 3, 40, 1);
            for h in 3..=40i64 {
                let holders: Vec<&Class> = all.iter().filter(|c| c.basis.iter().any(|b| b.index.abs() == h)).collect();
                assert_eq!(holders.len(), 1, "M = {cells}, h = {h}");
                let class = holders[0];
                assert_eq!(class.self_conjugate, class.j == 0 || 2 * class.j == cells);
                let signs = class.basis.iter().filter(|b| b.index.abs() == h).count();
                assert_eq!(signs, if class.self_conjugate { 2 } else { 1 }, "M = {cells}, h = {h}");
                for b in &class.basis {
                    assert_eq!(b.index.rem_euclid(cells as i64), class.j as i64);
                }
            }
        }
    }

    /// A linear map on the harmonics of a supercell that couples each
    /// class's harmonics (a known, arbitrary matrix per class): the response
    /// line to a real line.
    fn known_map(line: &[f64], cells: usize, matrix: &dyn Fn(i64, i64) -> Complex64) -> Vec<f64> {
        let n = line.len();
        let input = dft(line);
        let mut out = vec![Complex64::default(); n];
        let half = (n / 2) as i64;
        for s in -half + 1..half {
            for t in -half + 1..half {
                if (s - t).rem_euclid(cells as i64) != 0 {
                    continue;
                }
                out[s.rem_euclid(n as i64) as usize] += matrix(s, t) * coefficient(&input, t);
            }
        }
        let mut buf = out;
        FftPlanner::new().plan_fft_inverse(n).process(&mut buf);
        buf.iter().map(|c| c.re).collect()
    }

    #[test]
    fn assembly_recovers_a_known_class_coupling_map() {
        // A real linear map (conjugate-symmetric: J(-s, -t) = conj J(s, t))
        // that couples the harmonics of each class; measured with rounds of
        // simultaneous perturbations, each class's matrix is recovered to
        // round-off.
        let (cells, nodes, eps) = (4usize, 256usize, 1e-3);
        let a = |s: i64, t: i64| -> Complex64 {
            let (x, y) = (s as f64, t as f64);
            Complex64::new(0.3 * (0.7 * x - 0.2 * y).sin() + if s == t { 1.0 } else { 0.0 }, 0.2 * (0.3 * x + y).cos())
        };
        let matrix = move |s: i64, t: i64| -> Complex64 {
            // Conjugate symmetry of a real map.
            if s > 0 || (s == 0 && t > 0) { a(s, t) } else { a(-s, -t).conj() }
        };
        let all = classes(cells, 2, 30, 1);
        let plan = slots(&all);
        let mut responses: Vec<Vec<Vec<Complex64>>> = plan.iter().map(|s| vec![Vec::new(); s.len()]).collect();
        for (t, round) in rounds(&plan).iter().enumerate() {
            let line = perturbation(round, 0, nodes, eps);
            let out = dft(&known_map(&line, cells, &matrix));
            for slot in round {
                let class = &all[slot.class];
                responses[slot.class][t] = class.basis.iter().map(|b| coefficient(&out, b.index)).collect();
            }
        }
        let found = assemble(&all, &plan, eps, |slot, target| {
            let class = &all[slot.class];
            let k = plan[slot.class].iter().position(|s| s == slot).unwrap();
            let row = class.basis.iter().position(|b| b == target).unwrap();
            responses[slot.class][k][row]
        });
        for (class, j) in all.iter().zip(&found) {
            let n = class.basis.len();
            for (r, row) in class.basis.iter().enumerate() {
                for (c, col) in class.basis.iter().enumerate() {
                    let want = matrix(row.index, col.index);
                    let got = j[r * n + c];
                    assert!(
                        (got - want).norm() < 1e-9,
                        "class {}: J({}, {}) = {got} vs {want}",
                        class.j,
                        row.index,
                        col.index
                    );
                }
            }
        }
    }
}
