//! The wear laws: the depth rate `w_dot` (m/s) of the rail at each element
//! of a contact solution, and the regime each element wears in.
//!
//! * Archard (J.F. Archard, J. Appl. Phys. 24 (1953) 981-988; Baeza et al.
//!   2008, Eq. 8): `w_dot = (k/H) p3 |s|`, one regime.
//! * The frictional-work law with regimes (the University of Sheffield's
//!   T-gamma/A law: Lewis & Dwyer-Joyce, Proc. IMechE J 218 (2004) 467-478;
//!   Braghin, Lewis, Dwyer-Joyce & Bruni, Wear 261 (2006) 1253-1264, for
//!   R8T wheel against UIC60 900A rail): with the local frictional power
//!   per unit area over the speed, `I = |p . s| / V` (Pa; the local `T
//!   gamma / A`), the mass worn per metre rolled and mm^2 of contact is
//!   `K(I)` (ug/(m mm^2)): `K = k1 I` below `I1` (mild), `K = K2` up to `I2`
//!   (severe), `K = k3 I - c3` beyond (catastrophic), with I in N/mm^2 and
//!   the published `k1 = 5.3`, `I1 = 10.4`, `K2 = 55.0`, `I2 = 77.2`, `k3 =
//!   61.9`, `c3 = 4778.7` (as published the catastrophic line starts near
//!   zero at `I2` and meets `K2` at 78.1 N/mm^2: `K` is taken as `max(0,
//!   .)`). Depth rate `w_dot = K 1e-3 V / rho` (ug/(m mm^2) = 1e-3
//!   kg/m^3).
//! * Archard's law with a wear map (Jendel, Wear 253 (2002) 89-99, after
//!   Olofsson & Telliskivi): `w_dot = k(p3, |s|) p3 |s| / H` with `k` by
//!   region: seizure where `p3 > 0.8 H`; below, mild for `|s| < 0.2 m/s`,
//!   severe for `0.2 <= |s| <= 0.7 m/s`, mild again beyond (the published
//!   ranges: 300-400, 1-10, 30-40, 1-10 x 1e-4).

use crate::contact::PatchSolution;

/// A wear regime: 0 where an element does not wear (no pressure or no
/// slip), else the law's regime number (1-based).
pub type Regime = i8;

/// The frictional-work law's coefficients (the published units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionalWork {
    /// `k1`, mild slope (ug/(m mm^2) per N/mm^2).
    pub mild_slope: f64,
    /// `I1`, mild-severe boundary (N/mm^2).
    pub mild_limit: f64,
    /// `K2`, severe rate (ug/(m mm^2)).
    pub severe_rate: f64,
    /// `I2`, severe-catastrophic boundary (N/mm^2).
    pub severe_limit: f64,
    /// `k3`, catastrophic slope (ug/(m mm^2) per N/mm^2).
    pub catastrophic_slope: f64,
    /// `c3`, catastrophic offset (ug/(m mm^2)).
    pub catastrophic_offset: f64,
    /// Rail steel's density rho (kg/m^3).
    pub density: f64,
}

impl FrictionalWork {
    /// Braghin et al. 2006's R8T/UIC60 900A coefficients, rho = 7850 kg/m^3.
    pub const SHEFFIELD: FrictionalWork = FrictionalWork {
        mild_slope: 5.3,
        mild_limit: 10.4,
        severe_rate: 55.0,
        severe_limit: 77.2,
        catastrophic_slope: 61.9,
        catastrophic_offset: 4778.7,
        density: 7850.0,
    };

    /// `K(I)` (ug/(m mm^2)) and the regime (1 mild, 2 severe, 3
    /// catastrophic) at the wear index `I` (N/mm^2).
    pub fn rate(&self, index: f64) -> (f64, Regime) {
        if index < self.mild_limit {
            (self.mild_slope * index, 1)
        } else if index <= self.severe_limit {
            (self.severe_rate, 2)
        } else {
            ((self.catastrophic_slope * index - self.catastrophic_offset).max(0.0), 3)
        }
    }
}

/// Jendel's wear map: Archard's coefficient by region of contact pressure
/// and slip speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WearMap {
    /// Hardness H of the rail (Pa).
    pub hardness: f64,
    /// k in seizure, `p3 > 0.8 H` (1).
    pub seizure: f64,
    /// k below `slow_limit` (1).
    pub mild: f64,
    /// k from `slow_limit` to `fast_limit` (1).
    pub severe: f64,
    /// k above `fast_limit` (1).
    pub fast: f64,
    /// Mild-severe boundary of the slip speed (m/s).
    pub slow_limit: f64,
    /// Severe-mild boundary (m/s).
    pub fast_limit: f64,
    /// The seizure boundary as a share of H (1).
    pub seizure_share: f64,
}

impl WearMap {
    /// k (1) and the region (1 seizure, 2 mild, 3 severe, 4 fast mild) at
    /// pressure `p3` (Pa) and slip speed `q` (m/s).
    pub fn coefficient(&self, p3: f64, q: f64) -> (f64, Regime) {
        if p3 > self.seizure_share * self.hardness {
            (self.seizure, 1)
        } else if q < self.slow_limit {
            (self.mild, 2)
        } else if q <= self.fast_limit {
            (self.severe, 3)
        } else {
            (self.fast, 4)
        }
    }
}

/// A wear law with its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WearLaw {
    /// Archard's, with `k/H` (m^2/N).
    Archard {
        /// k/H (m^2/N).
        k_over_h: f64,
    },
    /// The frictional-work (T-gamma/A) law with regimes.
    FrictionalWork(FrictionalWork),
    /// Archard's with Jendel's wear map.
    Map(WearMap),
}

impl WearLaw {
    /// The regimes' names, index = regime number - 1.
    pub fn regimes(&self) -> &'static [&'static str] {
        match self {
            WearLaw::Archard { .. } => &["archard"],
            WearLaw::FrictionalWork(_) => &["mild", "severe", "catastrophic"],
            WearLaw::Map(_) => &["seizure", "mild", "severe", "fast_mild"],
        }
    }

    /// The depth rate (m/s) and regime of every element of `sol` at rolling
    /// speed `speed` (m/s).
    pub fn rates(&self, sol: &PatchSolution, speed: f64) -> (Vec<f64>, Vec<Regime>) {
        let n = sol.pressure.len();
        let (mut rates, mut regimes) = (vec![0.0; n], vec![0; n]);
        for k in 0..n {
            let p3 = sol.pressure[k].max(0.0);
            let (sx, sy) = (sol.slip_x[k], sol.slip_y[k]);
            let q = sx.hypot(sy);
            let (rate, regime) = match self {
                WearLaw::Archard { k_over_h } => (k_over_h * p3 * q, 1),
                WearLaw::FrictionalWork(f) => {
                    // |p . s| / V in N/mm^2.
                    let index = (sol.traction_x[k] * sx + sol.traction_y[k] * sy).abs() / speed * 1e-6;
                    let (kk, regime) = f.rate(index);
                    (kk * 1e-3 * speed / f.density, regime)
                }
                WearLaw::Map(m) => {
                    let (kk, regime) = m.coefficient(p3, q);
                    (kk * p3 * q / m.hardness, regime)
                }
            };
            rates[k] = rate;
            regimes[k] = if rate > 0.0 { regime } else { 0 };
        }
        (rates, regimes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One element per (pressure Pa, traction x Pa, slip x m/s).
    fn solution(elements: &[(f64, f64, f64)]) -> PatchSolution {
        PatchSolution {
            pressure: elements.iter().map(|e| e.0).collect(),
            traction_x: elements.iter().map(|e| e.1).collect(),
            traction_y: vec![0.0; elements.len()],
            slip_x: elements.iter().map(|e| e.2).collect(),
            slip_y: vec![0.0; elements.len()],
            stick: vec![false; elements.len()],
            ..Default::default()
        }
    }

    /// Archard's law is the earlier kernel bit for bit.
    #[test]
    fn archard_is_the_earlier_kernel() {
        let sol = solution(&[(1e9, -2e8, 1e-3), (0.0, 0.0, 0.0), (5e8, 1e8, -0.2)]);
        let (rates, regimes) = WearLaw::Archard { k_over_h: 3.4e-14 }.rates(&sol, 30.0);
        assert_eq!(rates, crate::wear::archard_rates(3.4e-14, &sol));
        assert_eq!(regimes, vec![1, 0, 1]);
    }

    /// The frictional-work law on an element in each regime equals the
    /// regime's formula (index |p s| / V in N/mm^2; depth rate K 1e-3 V /
    /// rho); at the mild-severe boundary the published rates meet within
    /// 0.12 ug/(m mm^2) (5.3 x 10.4 = 55.12 against 55.0); at the
    /// severe-catastrophic boundary, as published, the rate drops to zero
    /// and regains 55 at 78.1 N/mm^2.
    #[test]
    fn frictional_work_regimes() {
        let (v, law) = (30.0, FrictionalWork::SHEFFIELD);
        // |p s| / V = I 1e6 Pa: traction 5e8 Pa, slip I 1e6 V / 5e8.
        let element = |index: f64| (1e9, -5e8, index * 1e6 * v / 5e8);
        let indices = [5.0, 40.0, 100.0];
        let sol = solution(&indices.map(element));
        let (rates, regimes) = WearLaw::FrictionalWork(law).rates(&sol, v);
        assert_eq!(regimes, vec![1, 2, 3]);
        let want = [5.3 * 5.0, 55.0, 61.9 * 100.0 - 4778.7];
        for k in 0..3 {
            let depth = want[k] * 1e-3 * v / 7850.0;
            assert!((rates[k] - depth).abs() <= 1e-12 * depth, "{k}: {} vs {depth}", rates[k]);
        }
        let below = law.rate(10.4 * (1.0 - 1e-12));
        let above = law.rate(10.4);
        assert_eq!((below.1, above.1), (1, 2));
        assert!((below.0 - above.0).abs() < 0.121);
        assert_eq!(law.rate(77.2).0, 55.0);
        assert!(law.rate(77.2 * (1.0 + 1e-12)).0 < 0.01);
        assert!((law.rate(4833.7 / 61.9).0 - 55.0).abs() < 1e-9);
        // No slip, no wear.
        assert_eq!(WearLaw::FrictionalWork(law).rates(&solution(&[(1e9, 1e8, 0.0)]), v).1, vec![0]);
    }

    /// Jendel's map: each region's k times p3 |s| / H, the seizure
    /// boundary at 0.8 H, the speed boundaries as published.
    #[test]
    fn map_regions() {
        let map = WearMap {
            hardness: 2.5e9,
            seizure: 350e-4,
            mild: 5.5e-4,
            severe: 35e-4,
            fast: 5.5e-4,
            slow_limit: 0.2,
            fast_limit: 0.7,
            seizure_share: 0.8,
        };
        let cases = [
            (2.1e9, 0.1, 350e-4, 1),
            (1e9, 0.1, 5.5e-4, 2),
            (1e9, 0.2, 35e-4, 3),
            (1e9, 0.7, 35e-4, 3),
            (1e9, 0.9, 5.5e-4, 4),
        ];
        let sol = solution(&cases.map(|c| (c.0, 0.0, c.1)));
        let (rates, regimes) = WearLaw::Map(map).rates(&sol, 30.0);
        for (k, c) in cases.iter().enumerate() {
            assert_eq!(regimes[k], c.3);
            assert!((rates[k] - c.2 * c.0 * c.1 / 2.5e9).abs() <= 1e-15 * rates[k]);
        }
        assert_eq!(map.coefficient(0.8 * 2.5e9, 0.1).1, 2);
    }
}
