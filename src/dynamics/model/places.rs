//! The leading wheel's tabulated places on the discrete track: every
//! support interval of the layout's period divided into [`BAY_PLACES`]
//! (one bay: every `d / 16`), and the place a wheel stands at.

use super::BAY_PLACES;
use crate::dynamics::track::layout::Layout;

/// The places of a layout whose first support stands at `x0` along the
/// stretch.
#[derive(Debug, Clone, PartialEq)]
pub struct Places {
    /// The supports' positions from the first (m), and the period's end.
    bounds: Vec<f64>,
    /// The first support's position along the stretch (m).
    x0: f64,
}

impl Places {
    /// The places of `layout` with its first support at `x0` (m).
    pub fn new(layout: &Layout, x0: f64) -> Places {
        Places { bounds: layout.bounds(), x0 }
    }

    /// The number of places.
    pub fn len(&self) -> usize {
        BAY_PLACES * (self.bounds.len() - 1)
    }

    /// Whether there is none (never).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The first support's position along the stretch (m).
    pub fn start(&self) -> f64 {
        self.x0
    }

    /// The places (m from the first support).
    pub fn positions(&self) -> Vec<f64> {
        self.bounds
            .windows(2)
            .flat_map(|w| (0..BAY_PLACES).map(move |p| w[0] + (w[1] - w[0]) * p as f64 / BAY_PLACES as f64))
            .collect()
    }

    /// The place before `x` (m along the stretch), the one after
    /// (periodic), and the weight of the one after.
    pub fn locate(&self, x: f64) -> (usize, usize, f64) {
        let period = *self.bounds.last().expect("a period");
        let r = (x - self.x0).rem_euclid(period);
        let m = self.bounds.partition_point(|&b| b <= r).clamp(1, self.bounds.len() - 1) - 1;
        let (start, end) = (self.bounds[m], self.bounds[m + 1]);
        let u = (r - start) / (end - start) * BAY_PLACES as f64;
        let p = (u.floor() as usize).min(BAY_PLACES - 1);
        let i = m * BAY_PLACES + p;
        (i, (i + 1) % self.len(), u - p as f64)
    }
}

/// The (load, watched) places (m) of every pair of wheels `[j n + l]`
/// (wheel `j` watched, `l` loaded; `behind` the leading wheel, m) with the
/// leading wheel at each of `positions` (m).
pub fn load_and_watched(positions: &[f64], behind: &[f64]) -> Vec<(f64, f64)> {
    let n = behind.len();
    positions.iter().flat_map(|x| (0..n * n).map(move |q| (x - behind[q % n], x - behind[q / n]))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::track::TrackConfig;

    #[test]
    fn places_divide_each_support_interval() {
        let t = TrackConfig::default();
        let layout = Layout::at_positions(&t, 1.8, &[0.0, 0.5, 1.2]).unwrap();
        let places = Places::new(&layout, 0.1);
        let x = places.positions();
        assert_eq!(x.len(), 48);
        assert!((x[16] - 0.5).abs() < 1e-15 && (x[8] - 0.25).abs() < 1e-15 && (x[40] - 1.5).abs() < 1e-15);
        // A wheel a quarter into the second interval, a period later.
        let (p, q, t) = places.locate(0.1 + 1.8 + 0.5 + 0.7 / 4.0 + 1e-9);
        assert_eq!((p, q), (20, 21));
        assert!(t < 1e-6);
        // The period's last place wraps to the first.
        let (p, q, _) = places.locate(0.1 + 1.79);
        assert_eq!((p, q), (47, 0));
    }
}
