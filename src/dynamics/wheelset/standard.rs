//! The default wheelset: a standard freight wheelset (0.5 m wheels of 350
//! kg, a solid axle, journals 2 m apart), its flexible modes from published
//! modal analyses and from documented simple models, on the rigid
//! wheelset's suspension modes ([`super::rigid`]).
//!
//! | mode (per family) | frequency | source of the frequency | participation from |
//! |---|---|---|---|
//! | torsion | `sqrt(2 k_t / J)`, 71.2 Hz | [`super::torsion`] (measured modes 40-100 Hz) | two wheels on the axle's torsional spring |
//! | first symmetric bending, vertical and horizontal plane | 87.0 Hz | Wu et al. 2020 | beam model (below) |
//! | first antisymmetric bending, both planes | 143.1 Hz | Wu et al. 2020 | beam model |
//! | umbrella (n = 0, axial), symmetric / antisymmetric | 450 / 563 Hz | Thompson 2009, ch. 5 | rim mass on the web's axial spring |
//! | n = 2, 3 axial (per wheel, a pair each) | 360, 1000 Hz | Thompson 2009, ch. 5 | half the rim's and a third of the web's mass |
//! | n = 2, 3 radial (per wheel, a pair each) | 1900, 2150 Hz | Thompson 2009, ch. 5 | half the rim's mass |
//!
//! Wu et al., *Key factors of the initiation and development
//! of polygonal wear in the wheels of a high-speed train*, Appl. Sci. 10
//! (2020) 5880, Fig. 8: the bending modes of a wheelset's FE model at 87,
//! 143, 284 and 576 Hz. Thompson, *Railway Noise and Vibration*, Elsevier
//! 2009, ch. 5: the modes of a railway wheel (the 920 mm freight wheel),
//! named by their nodal diameters `n`; the wheel's values here are typical
//! of such a wheel as that chapter describes them, rounded, and were not
//! read off its tables: for a real wheel give its FE analysis as a table
//! ([`super::table`]).
//!
//! **The beam model of the bending modes.** The axle is a free-free
//! Timoshenko beam (E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3, shear factor
//! `6 (1 + nu) / (7 + 6 nu)` of a solid circle) of 2.2 m: journals of 130
//! mm diameter (|y| > 0.90 m), 170 mm collars (0.82-0.90 m), 200 mm wheel
//! seats (0.68-0.82 m), a 180 mm body; the axle boxes (45 kg each) at the
//! journals' centres `y = +-1.0 m`; each wheel a rigid body of 350 kg on its
//! seat at `y = +-0.75 m` (under its contact), whose rim (diametral moment
//! of inertia 15 kg m^2, half the polar 30) tilts on the web's rotational
//! spring `k_w` relative to the seat's slope. Two numbers are fitted, the
//! rest is the geometry of a freight axle: the sections' bending stiffness
//! `EI` is scaled by 0.729 and `k_w = 1.83e7 N m/rad`, which put the first
//! symmetric and antisymmetric modes at Wu et al.'s 87 and 143 Hz (87.02 and
//! 143.09 Hz; the model's next two, 231 and 408 Hz, fall below their 284 and
//! 576 Hz and are left out). A mode's contact participations: the seat's
//! deflection (vertical in the vertical plane, longitudinal in the
//! horizontal one) and, in the vertical plane, the rim's tilt `a_x` times `r`
//! laterally (the contact, `r` below the axle, swings sideways when the
//! wheel tilts) and, in the horizontal plane, the rim's tilt about `z` as
//! the tread's rotation about the vertical; the rim's tilts couple the
//! planes by eq. 3 of [`super`].
//! The two planes' modes are the same free-free modes: the primary
//! suspension, three orders softer than the bending, acts on the rigid-body
//! modes only.
//!
//! **Wheel modes.** A wheel's mode with `n >= 1` nodal diameters, `cos n
//! phi` about the contact, normalised to a unit displacement at the contact
//! in its direction, has the modal mass of the moving ring's mass times the
//! mean of `cos^2`, 1/2: for the axial modes the rim (180 kg) and a third
//! of the web (110 kg; its displacement grows from the hub to the rim), 108
//! kg; for the radial modes the rim, 90 kg. Its `sin n phi` partner does not
//! move the contact axially or radially and enters through the rotation
//! (module [`super`], `beta = 1` axial, `(n^2 - 1) / (n^2 + 1)` radial)
//! and, for the axial modes, through the tread's rotation about the
//! vertical at the contact, the rim's slope `n / r` times the mode's
//! amplitude (what a wheel's axial vibration does to the spin creepage). The umbrella mode: each rim (216.7 kg) on the web's axial spring
//! at 450 Hz (hub held), the rest of the wheelset (767 kg) between: the
//! wheels in antiphase at 450 Hz, in phase (the axle against them) at 450
//! Hz `sqrt(1 + 2 m_r / m_c)` = 563 Hz. Damping (ratios): 1 % for the
//! bending modes (assumed), 0.1 % for the wheel's modes (Thompson 2009, ch.
//! 5: 1e-4 to 1e-3 for a free wheel).

use super::rigid::{RigidWheelset, TiltedMode, tilt_couplings};
use super::{Damping, Dir, Gyroscopic, Mode, WheelsetError, WheelsetModel, dof};
use nalgebra::{DMatrix, SymmetricEigen};
use std::f64::consts::PI;

/// Mass of the default wheelset with its axle boxes (kg): 1200 kg, the beam
/// model's axle (411 kg), two wheels of 350 kg and two axle boxes of 45 kg;
/// today's unsprung mass of 600 kg per wheel
/// ([`crate::dynamics::receptance::FREIGHT_UNSPRUNG_MASS`]).
pub const WHEELSET_MASS: f64 = 1200.0;
/// Roll and yaw moment of inertia of the default wheelset about its centre
/// (kg m^2): 660, the beam model's (wheels at 0.75 m, axle boxes at 1.0 m,
/// the axle, the rims' diametral inertia).
pub const WHEELSET_ROLL_INERTIA: f64 = 660.0;
/// Primary suspension, longitudinal stiffness per axle box (N/m): 31.4
/// MN/m, the Manchester benchmark vehicle's (Iwnicki, *Veh. Syst. Dyn.* 30
/// (1998) 295-313).
pub const SUSPENSION_STIFFNESS_X: f64 = 31.4e6;
/// Lateral stiffness per axle box (N/m): 3.88 MN/m (Manchester benchmark).
pub const SUSPENSION_STIFFNESS_Y: f64 = 3.88e6;
/// Vertical stiffness per axle box (N/m): 1.22 MN/m (Manchester benchmark).
pub const SUSPENSION_STIFFNESS_Z: f64 = 1.22e6;
/// Loss factor of the primary suspension (1): 0.1, assumed (springs with
/// friction and dampers; a dashpot's loss factor varies with frequency).
pub const SUSPENSION_LOSS_FACTOR: f64 = 0.1;
/// Distance between the axle boxes (journal centres) (m): 2.0 m, a
/// standard-gauge freight axle's.
pub const AXLE_BOX_SPACING: f64 = 2.0;
/// Distance between the two wheels' contact points (m): 1.5 m on standard
/// gauge (1435 mm plus the rail heads' half widths).
pub const CONTACT_SPACING: f64 = 1.5;
/// Damping ratio of the default bending modes (1): 1 %, assumed.
pub const BENDING_DAMPING: f64 = 0.01;
/// Damping ratio of the default wheel modes (1): 0.1 %; a free wheel's are
/// 1e-4 to 1e-3 (Thompson 2009, ch. 5).
pub const WHEEL_DAMPING: f64 = 1e-3;

/// Bending stiffness scale of the axle's sections and the web's rotational
/// stiffness (N m/rad): fitted to Wu et al.'s first two bending modes
/// (module docs).
const EI_SCALE: f64 = 0.729;
const WEB_TILT_STIFFNESS: f64 = 1.83e7;
const WHEEL_MASS: f64 = 350.0;
const RIM_DIAMETRAL_INERTIA: f64 = 15.0;
const AXLE_BOX_MASS: f64 = 45.0;
const SEAT: f64 = 0.75;
const JOURNAL: f64 = 1.0;
/// Nodes of the beam model along the axle (m), one half (mirrored).
const HALF_NODES: [f64; 10] = [0.0, 0.15, 0.3, 0.5, 0.68, 0.75, 0.82, 0.9, 1.0, 1.1];
/// The wheel's rim and web masses (kg) of the modal masses (module docs).
const RIM_MASS: f64 = 180.0;
const WEB_MASS: f64 = 110.0;
/// Clamped-hub umbrella frequency (Hz).
const UMBRELLA_FREQUENCY: f64 = 450.0;
/// (n, Hz) of the axial and the radial modes per wheel (module docs).
const AXIAL_MODES: [(u32, f64); 2] = [(2, 360.0), (3, 1000.0)];
const RADIAL_MODES: [(u32, f64); 2] = [(2, 1900.0), (3, 2150.0)];

/// The default design's parameters that the config sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Design {
    /// The rigid wheelset on its suspension (its `spin_inertia` is twice
    /// the torsion's polar inertia J per wheel).
    pub rigid: RigidWheelset,
    /// Axle torsional stiffness k_t (N m/rad).
    pub torsional_stiffness: f64,
    /// Loss factor of the torsion (1).
    pub torsional_loss_factor: f64,
    /// Damping ratio of the bending modes (1).
    pub bending_damping: f64,
    /// Damping ratio of the wheel's modes (1).
    pub wheel_damping: f64,
}

/// The rigid spin and the torsional mode of two wheels of polar inertia
/// `inertia` (kg m^2) on an axle of torsional stiffness `stiffness` (N
/// m/rad) with loss factor `loss_factor`, rolling radius `radius` (m)
/// (eq. 1 of [`super::torsion`] as modes).
pub fn torsion_modes(inertia: f64, stiffness: f64, loss_factor: f64, radius: f64) -> (Mode, Mode) {
    let s = 1.0 / (2.0 * inertia).sqrt();
    let mut spin = [0.0; super::DOFS];
    let mut twist = [0.0; super::DOFS];
    for (w, sign) in [(0, 1.0), (1, -1.0)] {
        spin[dof(w, Dir::Theta)] = s;
        spin[dof(w, Dir::X)] = -radius * s;
        twist[dof(w, Dir::Theta)] = sign * s;
        twist[dof(w, Dir::X)] = -radius * sign * s;
    }
    let f = (2.0 * stiffness / inertia).sqrt() / (2.0 * PI);
    (
        Mode { name: "rigid spin (free)".into(), frequency: 0.0, damping: Damping::LossFactor(0.0), shape: spin },
        Mode { name: "torsion".into(), frequency: f, damping: Damping::LossFactor(loss_factor), shape: twist },
    )
}

/// The default model: the rigid modes, then the torsion, the bending modes,
/// the umbrella modes and each wheel's diametral modes (module docs), with
/// their gyroscopic couplings.
pub fn default_model(d: &Design) -> Result<WheelsetModel, WheelsetError> {
    let r = d.rigid.radius;
    let polar = d.rigid.spin_inertia / 2.0;
    let mut tilted = d.rigid.modes();
    let (_, twist) = torsion_modes(polar, d.torsional_stiffness, d.torsional_loss_factor, r);
    tilted.push(TiltedMode { mode: twist, tilt: [[0.0; 2]; 2] });
    tilted.extend(bending_modes(r, d.bending_damping));
    tilted.extend(umbrella_modes(d.wheel_damping));
    let mut couplings = tilt_couplings(&tilted, 0, polar);
    let mut modes: Vec<Mode> = tilted.into_iter().map(|t| t.mode).collect();
    for w in 0..2 {
        for (family, list, dir) in [("axial", AXIAL_MODES, Dir::Y), ("radial", RADIAL_MODES, Dir::Z)] {
            for (n, f) in list {
                let n_f = f64::from(n);
                let (mass, beta) = match dir {
                    Dir::Y => ((RIM_MASS + WEB_MASS / 3.0) / 2.0, 1.0),
                    _ => (RIM_MASS / 2.0, (n_f * n_f - 1.0) / (n_f * n_f + 1.0)),
                };
                let mut shape = [0.0; super::DOFS];
                shape[dof(w, dir)] = 1.0 / mass.sqrt();
                // The sin partner's axial displacement a sin(n phi) is
                // still at the contact but slopes along the rim: the
                // tread turns about the vertical by -(n / r) a (phi
                // grows backwards from the contact, x = -r phi).
                let mut partner = [0.0; super::DOFS];
                if dir == Dir::Y {
                    partner[dof(w, Dir::Psi)] = -n_f / r / mass.sqrt();
                }
                let damping = Damping::Ratio(d.wheel_damping);
                let name = format!("wheel {w}: {n} nodal diameters, {family}");
                modes.push(Mode { name: format!("{name} (cos)"), frequency: f, damping, shape });
                modes.push(Mode {
                    name: format!("{name} (sin, still at the contact)"),
                    frequency: f,
                    damping,
                    shape: partner,
                });
                let c = modes.len() - 2;
                couplings.push(Gyroscopic { a: c, b: c + 1, coefficient: 2.0 * beta * n_f });
            }
        }
    }
    WheelsetModel::new(modes, couplings)
}

/// A model of the rigid wheelset `rigid` on its suspension and a user's
/// table of the free wheelset's flexible modes ([`super::table`]): the
/// rigid modes first, then the table's; the roll and yaw coupled by the
/// spin (eq. 3 of [`super`]), the table's modes by its own coefficients.
pub fn table_model(rigid: &RigidWheelset, table: &super::table::ModalTable) -> Result<WheelsetModel, WheelsetError> {
    let tilted = rigid.modes();
    let first = tilted.len();
    let mut couplings = tilt_couplings(&tilted, 0, rigid.spin_inertia / 2.0);
    couplings.extend(table.couplings.iter().map(|c| Gyroscopic { a: c.a + first, b: c.b + first, ..*c }));
    let modes = tilted.into_iter().map(|t| t.mode).chain(table.modes.iter().cloned()).collect();
    WheelsetModel::new(modes, couplings)
}

/// The free wheelset's first symmetric and antisymmetric bending modes in
/// the vertical and the horizontal plane (module docs), rolling radius `r`.
fn bending_modes(r: f64, damping: f64) -> Vec<TiltedMode> {
    let beam = default_beam();
    let seats = [beam.node(SEAT), beam.node(-SEAT)];
    let modes = beam.flexible_modes();
    let mut out = Vec::new();
    for (plane, deflection) in [("vertical", Dir::Z), ("horizontal", Dir::X)] {
        let mut count = [0usize; 2];
        for m in modes.iter().take(2) {
            // Wheel 0 is at y = +0.75 m: the beam's second wheel.
            let (w, tilt) = ([m.deflection[seats[0]], m.deflection[seats[1]]], [m.rim[1], m.rim[0]]);
            // Symmetric about the wheelset's centre: the rims tilt opposite ways.
            let symmetric = (tilt[0] + tilt[1]).abs() < (tilt[0] - tilt[1]).abs();
            count[usize::from(!symmetric)] += 1;
            let ordinal = ["first", "second", "third"][count[usize::from(!symmetric)] - 1];
            let kind = if symmetric { "symmetric" } else { "antisymmetric" };
            let mut shape = [0.0; super::DOFS];
            let mut tilts = [[0.0; 2]; 2];
            for wheel in 0..2 {
                shape[dof(wheel, deflection)] = w[wheel];
                if deflection == Dir::Z {
                    shape[dof(wheel, Dir::Y)] = r * tilt[wheel];
                    tilts[wheel][0] = tilt[wheel];
                } else {
                    tilts[wheel][1] = -tilt[wheel];
                    shape[dof(wheel, Dir::Psi)] = -tilt[wheel];
                }
            }
            out.push(TiltedMode {
                mode: Mode {
                    name: format!("{ordinal} {kind} bending ({plane} plane)"),
                    frequency: m.frequency,
                    damping: Damping::Ratio(damping),
                    shape,
                },
                tilt: tilts,
            });
        }
    }
    out
}

/// A free-free beam of circular sections with lumped masses and wheels
/// whose rims tilt on a rotational spring (module docs: the beam model).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Beam {
    /// Node positions along the beam (m), increasing.
    pub nodes: Vec<f64>,
    /// Each element's diameter (m).
    pub diameters: Vec<f64>,
    /// Young's modulus (Pa) and density (kg/m^3).
    pub young: f64,
    pub density: f64,
    /// Scale of the bending stiffness EI (1).
    pub ei_scale: f64,
    /// Timoshenko (shear) or Euler-Bernoulli elements.
    pub shear: bool,
    /// Point masses: (position (m), mass (kg)).
    pub masses: Vec<(f64, f64)>,
    /// Wheels: (position (m), mass (kg), rim's diametral inertia (kg m^2),
    /// web's rotational stiffness (N m/rad)).
    pub wheels: Vec<(f64, f64, f64, f64)>,
}

/// A flexible mode of a [`Beam`]: frequency (Hz), the deflection at each
/// node and each wheel rim's tilt (mass-normalised).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BeamMode {
    pub frequency: f64,
    pub deflection: Vec<f64>,
    pub rim: Vec<f64>,
}

impl Beam {
    /// The index of the node at `y` (m).
    pub fn node(&self, y: f64) -> usize {
        self.nodes.iter().position(|v| (v - y).abs() < 1e-9).expect("a node")
    }

    /// The flexible modes (above 1 Hz), ascending; each signed so that the
    /// larger of its rims' tilt sum and its deflections' sum is positive.
    /// Finite elements: cubic Hermite beam elements (Timoshenko's with
    /// `phi = 12 EI / (kappa G A l^2)`, consistent mass without rotary
    /// inertia), the generalised eigenproblem `K x = w^2 M x` by Cholesky.
    pub fn flexible_modes(&self) -> Vec<BeamMode> {
        let nu = 0.3;
        let (shear_modulus, kappa) = (self.young / (2.0 * (1.0 + nu)), 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu));
        let n = self.nodes.len();
        let size = 2 * n + self.wheels.len();
        let (mut k, mut m) = (DMatrix::<f64>::zeros(size, size), DMatrix::<f64>::zeros(size, size));
        for (e, d) in self.diameters.iter().enumerate() {
            let l = self.nodes[e + 1] - self.nodes[e];
            let (area, second) = (PI * d * d / 4.0, PI * d.powi(4) / 64.0);
            let ei = self.ei_scale * self.young * second;
            let phi = if self.shear { 12.0 * ei / (kappa * shear_modulus * area * l * l) } else { 0.0 };
            let ke = [
                [12.0, 6.0 * l, -12.0, 6.0 * l],
                [6.0 * l, (4.0 + phi) * l * l, -6.0 * l, (2.0 - phi) * l * l],
                [-12.0, -6.0 * l, 12.0, -6.0 * l],
                [6.0 * l, (2.0 - phi) * l * l, -6.0 * l, (4.0 + phi) * l * l],
            ];
            let me = [
                [156.0, 22.0 * l, 54.0, -13.0 * l],
                [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
                [54.0, 13.0 * l, 156.0, -22.0 * l],
                [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
            ];
            let (ks, ms) = (ei / (l.powi(3) * (1.0 + phi)), self.density * area * l / 420.0);
            for a in 0..4 {
                for b in 0..4 {
                    k[(2 * e + a, 2 * e + b)] += ks * ke[a][b];
                    m[(2 * e + a, 2 * e + b)] += ms * me[a][b];
                }
            }
        }
        for &(y, mass) in &self.masses {
            let j = self.node(y);
            m[(2 * j, 2 * j)] += mass;
        }
        for (s, &(y, mass, inertia, stiffness)) in self.wheels.iter().enumerate() {
            let (j, rim) = (self.node(y), 2 * n + s);
            m[(2 * j, 2 * j)] += mass;
            m[(rim, rim)] += inertia;
            let slope = 2 * j + 1;
            k[(slope, slope)] += stiffness;
            k[(rim, rim)] += stiffness;
            k[(slope, rim)] -= stiffness;
            k[(rim, slope)] -= stiffness;
        }
        // M = L L^T; L^-1 K L^-T x' = w^2 x', x = L^-T x'.
        let l = m.cholesky().expect("a positive mass matrix").l();
        let l_inv = l.try_inverse().expect("a regular Cholesky factor");
        let a = &l_inv * &k * l_inv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let eig = SymmetricEigen::new(a);
        let x = l_inv.transpose() * &eig.eigenvectors;
        let mut order: Vec<usize> = (0..size).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        order
            .into_iter()
            .filter(|&i| eig.eigenvalues[i] > (2.0 * PI).powi(2))
            .map(|i| {
                let v = x.column(i);
                let deflection: Vec<f64> = (0..n).map(|j| v[2 * j]).collect();
                let rim: Vec<f64> = (0..self.wheels.len()).map(|s| v[2 * n + s]).collect();
                let (ts, ds) = (rim.iter().sum::<f64>(), deflection.iter().sum::<f64>());
                let sign = if ts.abs() > ds.abs() { ts.signum() } else { ds.signum() };
                BeamMode {
                    frequency: eig.eigenvalues[i].sqrt() / (2.0 * PI),
                    deflection: deflection.iter().map(|v| sign * v).collect(),
                    rim: rim.iter().map(|v| sign * v).collect(),
                }
            })
            .collect()
    }
}

/// The default wheelset's beam model (module docs).
pub(crate) fn default_beam() -> Beam {
    let mut nodes: Vec<f64> = HALF_NODES.iter().rev().map(|y| -y).chain(HALF_NODES.iter().skip(1).copied()).collect();
    nodes.dedup();
    let diameters = nodes
        .windows(2)
        .map(|p| match (0.5 * (p[0] + p[1])).abs() {
            a if a < 0.68 => 0.18,
            a if a < 0.82 => 0.20,
            a if a < 0.90 => 0.17,
            _ => 0.13,
        })
        .collect();
    Beam {
        nodes,
        diameters,
        young: 210e9,
        density: 7850.0,
        ei_scale: EI_SCALE,
        shear: true,
        masses: vec![(-JOURNAL, AXLE_BOX_MASS), (JOURNAL, AXLE_BOX_MASS)],
        wheels: [-SEAT, SEAT].iter().map(|&y| (y, WHEEL_MASS, RIM_DIAMETRAL_INERTIA, WEB_TILT_STIFFNESS)).collect(),
    }
}

/// The umbrella modes (module docs): the two rims on the webs' axial
/// springs against the rest of the default wheelset.
fn umbrella_modes(damping: f64) -> Vec<TiltedMode> {
    let rim = RIM_MASS + WEB_MASS / 3.0;
    let core = WHEELSET_MASS - 2.0 * rim;
    let antiphase = 1.0 / (2.0 * rim).sqrt();
    let in_phase = 1.0 / (2.0 * rim * (1.0 + 2.0 * rim / core)).sqrt();
    let f_in = UMBRELLA_FREQUENCY * (1.0 + 2.0 * rim / core).sqrt();
    let mode = |name: &str, f: f64, a: [f64; 2]| {
        let mut shape = [0.0; super::DOFS];
        shape[dof(0, Dir::Y)] = a[0];
        shape[dof(1, Dir::Y)] = a[1];
        TiltedMode {
            mode: Mode { name: name.into(), frequency: f, damping: Damping::Ratio(damping), shape },
            tilt: [[0.0; 2]; 2],
        }
    };
    vec![
        mode(
            "umbrella (0 nodal diameters, axial), symmetric: both rims outwards",
            UMBRELLA_FREQUENCY,
            [antiphase, -antiphase],
        ),
        mode(
            "umbrella (0 nodal diameters, axial), antisymmetric: the axle against the rims",
            f_in,
            [in_phase, in_phase],
        ),
    ]
}
