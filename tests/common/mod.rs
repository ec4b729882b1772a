//! Shared fixtures of the integration tests: the source paper's parameters.
#![allow(dead_code)]

use corrugation::contact::friction::FrictionLaw;
use corrugation::contact::grid::spec::FixedGridSpec;
use corrugation::contact::grid::{FixedGrid, GridScheme, GridSolver};
use corrugation::creep_coefficients::{CreepCoefficients, creep_coefficients};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};

/// E = 210 GPa, nu = 0.3 (paper Table 1).
pub const STEEL: Elastic = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };

/// Paper Table 1 wheel/rail geometry; `concave` selects the sign of the
/// 0.409 m wheel-profile radius.
pub fn paper_shape(concave: bool) -> HertzShape {
    let r = if concave { -0.409 } else { 0.409 };
    HertzShape::new(Curvatures::wheel_on_rail(0.5, r, 0.3), STEEL).unwrap()
}

/// Kalker coefficients of the paper's patch.
pub fn paper_coefficients(concave: bool) -> CreepCoefficients {
    creep_coefficients(paper_shape(concave).aspect(), STEEL.poisson_ratio).unwrap()
}

/// Relative difference |x - y| / |y|.
pub fn rel(x: f64, y: f64) -> f64 {
    (x - y).abs() / y.abs()
}

/// Rows of a whitespace-separated table file, skipping `#` comments.
pub fn table(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(str::to_string).collect())
        .collect()
}

/// Peak |creepage| of a history after its first (Cattaneo) step, and the
/// rolled distance where it occurs (m), for steps of `step` m.
pub fn peak(history: &[f64], step: f64) -> (f64, f64) {
    history
        .iter()
        .enumerate()
        .skip(1)
        .fold((0.0, 0.0), |(m, at), (i, c)| if c.abs() > m { (c.abs(), i as f64 * step) } else { (m, at) })
}

/// Overrides that put `configs/growth_fastsim.toml` on one 0.6 m sleeper bay
/// of the discrete track, coarse (1 mm rail grid and step, 6 x 6 mesh).
pub const DISCRETE_BAY: [&str; 8] = [
    "dynamics.model=discrete",
    "rail.x_max=0.6",
    "passage.end=0.6",
    "rail.dx=1e-3",
    "rail.dy=1e-3",
    "passage.step_length=1e-3",
    "contact.elements_x=6",
    "contact.elements_y=6",
];

/// The paper's concave contact on a fixed grid of `dx x dy` sized for the
/// Hertz patch at `n_max` N times `length` along x and y (regularised
/// friction, eps = 1e-5 m/s, second-order difference, the solver `auto`).
pub fn paper_fixed_grid(dx: f64, dy: f64, length: f64, n_max: f64) -> FixedGrid {
    let patch = paper_shape(true).patch(n_max).unwrap();
    FixedGrid::new(FixedGridSpec::unaligned(
        (Curvatures::wheel_on_rail(0.5, -0.409, 0.3), STEEL),
        (dx, dy),
        (length * patch.a, length * patch.b),
        (FrictionLaw::Regularised, GridScheme::SecondOrder, 1e-5),
        GridSolver::Auto,
    ))
}

/// A fixed grid of `cell` elements for `curvatures` and `elastic`, sized
/// for the Hertz patch at `n_max` N, with the friction law, difference
/// scheme and eps of `model`, and `solver`.
pub fn fixed_grid(
    shape: &HertzShape,
    (curvatures, elastic): (Curvatures, Elastic),
    n_max: f64,
    cell: (f64, f64),
    (law, scheme, eps): (FrictionLaw, GridScheme, f64),
    solver: GridSolver,
) -> FixedGrid {
    let patch = shape.patch(n_max).unwrap();
    FixedGrid::new(FixedGridSpec::unaligned(
        (curvatures, elastic),
        cell,
        (patch.a, patch.b),
        (law, scheme, eps),
        solver,
    ))
}

/// The paper's convex contact (N up to 100 kN) on the 0.5 mm fixed grid,
/// regularised friction (eps = 1e-5 m/s), second-order difference, with
/// `solver`: the falling-friction and friction-memory tests' grid.
pub fn paper_convex_grid(solver: GridSolver) -> FixedGrid {
    fixed_grid(
        &paper_shape(false),
        (Curvatures::wheel_on_rail(0.5, 0.409, 0.3), STEEL),
        1e5,
        (0.5e-3, 0.5e-3),
        (FrictionLaw::Regularised, GridScheme::SecondOrder, 1e-5),
        solver,
    )
}

/// A profile of three harmonics (5th, 17th, 40th) of a periodic stretch of
/// `nodes` samples every `dx` (m), shifted in phase by `phase` (rad): 1,
/// 0.5 and 0.2 um.
pub fn three_harmonics(nodes: usize, dx: f64, phase: f64) -> Vec<f64> {
    let length = nodes as f64 * dx;
    (0..nodes)
        .map(|i| {
            let x = i as f64 * dx;
            [(5, 1e-6, 0.3), (17, 5e-7, 1.1), (40, 2e-7, 2.0)]
                .iter()
                .map(|(n, a, q)| a * (2.0 * std::f64::consts::PI * *n as f64 * x / length + q + phase).cos())
                .sum::<f64>()
        })
        .collect()
}

/// The largest magnitude of `a`.
pub fn largest(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// `max |a - s b| / max |b|`.
pub fn worst_scaled(a: &[f64], b: &[f64], s: f64) -> f64 {
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - s * y).abs())) / largest(b)
}

/// The DFT coefficient `sum_j v_j exp(-i 2 pi k j / N)` of harmonic `k`
/// of one period `v`, written out.
pub fn dft(v: &[f64], k: usize) -> num_complex::Complex64 {
    let n = v.len() as f64;
    v.iter()
        .enumerate()
        .map(|(j, x)| x * num_complex::Complex64::from_polar(1.0, -2.0 * std::f64::consts::PI * (k * j) as f64 / n))
        .sum()
}

/// The vehicle-track model in the configurations the dynamics tests
/// check: one wheel in every direction, one wheel vertically, and the
/// track bodies.
pub mod model {
    use corrugation::dynamics::ContactSignals;
    use corrugation::dynamics::coupling::contact_point::ContactLaw;
    use corrugation::dynamics::coupling::creep_response::CreepResponse;
    use corrugation::dynamics::model::{Directions, Track, VehicleTrack, Wheel};
    use corrugation::dynamics::track::TrackConfig;
    use corrugation::dynamics::track::continuous3::Continuous3;
    use corrugation::dynamics::track::discrete::DiscreteTrack;
    use corrugation::dynamics::track::discrete3::Discrete3;
    use corrugation::dynamics::wheelset::side::{Wheel3, WheelSide};

    /// The continuous track of `track` with its head in every direction
    /// at `offset` (m) from the centre line.
    pub fn continuous(track: &TrackConfig, offset: f64) -> Track {
        Track::Continuous { vertical: track.smeared(), head: Some(Continuous3::new(track, offset)) }
    }

    /// The discrete track of `track`, a sleeper at `sleeper_x0` (m), with
    /// its head in every direction at `offset` (m) where given.
    pub fn discrete(track: &TrackConfig, offset: Option<f64>, sleeper_x0: f64) -> Track {
        let head = offset.map(|o| Discrete3::new(track, o));
        let layout = corrugation::dynamics::track::layout::Layout::uniform(track);
        Track::Discrete { vertical: DiscreteTrack::new(track), head, sleeper_x0, layout }
    }

    /// One wheel's model with the single-profile calls of the tests.
    pub struct OneWheel(pub VehicleTrack);

    impl OneWheel {
        /// In every direction: the wheel `side` with its contact `law` (and
        /// creep `response`) at the mean load `mean_load` (N) on `track`.
        #[allow(clippy::too_many_arguments)]
        pub fn every(
            track: Track,
            side: WheelSide,
            law: ContactLaw,
            response: Option<CreepResponse>,
            mean_load: f64,
            nodes: usize,
            dx: f64,
            speed: f64,
        ) -> Self {
            let wheel = Wheel { behind: 0.0, rail: 0, side, law, response, mean_load };
            OneWheel(VehicleTrack::new(track, vec![wheel], Directions::All, nodes, dx, speed).unwrap())
        }

        /// Vertically: a rigid wheel of `mass` (kg) on a Hertz spring
        /// `stiffness` (N/m) at `mean_load` (N) on `track`.
        #[allow(clippy::too_many_arguments)]
        pub fn vertical(
            track: Track,
            mass: f64,
            stiffness: f64,
            mean_load: f64,
            nodes: usize,
            dx: f64,
            speed: f64,
        ) -> Self {
            let wheel = Wheel::vertical(0.0, Wheel3::new(mass, 0.46), stiffness, mean_load);
            OneWheel(VehicleTrack::new(track, vec![wheel], Directions::Vertical, nodes, dx, speed).unwrap())
        }

        /// The contact's variations from `profile`.
        pub fn signals(&self, profile: &[f64], dx: f64, speed: f64) -> ContactSignals {
            self.0.signals(std::slice::from_ref(&profile.to_vec()), dx, speed).remove(0)
        }

        /// The dynamic normal force (N) from `profile`.
        pub fn force_from_profile(&self, profile: &[f64], dx: f64, speed: f64) -> Vec<f64> {
            self.0.normal_forces(std::slice::from_ref(&profile.to_vec()), dx, speed).remove(0)
        }

        /// The wheel's parametric path (m).
        pub fn parametric_profile(&self) -> Vec<f64> {
            self.0.parametric_paths()[0].clone()
        }
    }
}
