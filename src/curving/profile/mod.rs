//! Wheel and rail profiles: the standard S1002 wheel (EN 13715), the 60E1
//! rail (EN 13674-1) and measured profiles from a file, each a height over
//! a lateral coordinate (SI units outside this module's submodules, which
//! keep the standards' mm).
//!
//! - A wheel profile's height is its radius less the radius at the tape
//!   circle (m), over the lateral coordinate from the tape circle (m),
//!   positive towards the field side (the flange at negative values).
//! - A rail profile's height is the head's height above its crown (m,
//!   zero or negative), over the lateral coordinate from the rail's axis
//!   (m), positive towards the field side (the gauge face at negative
//!   values).

pub mod cone;
pub mod measured;
pub mod rail60e1;
pub mod s1002;

use std::path::Path;
use std::sync::Arc;

/// A profile that cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// A profile file that is not a profile (`line` 0: the whole file).
    #[error("{file}{}: {message}", if *line > 0 { format!(", line {line}") } else { String::new() })]
    File {
        /// The file.
        file: String,
        /// Its line (1-based), 0 for the whole file.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// What a profile is made of.
#[derive(Debug, Clone, PartialEq)]
enum Shape {
    S1002,
    /// A cone of this slope on S1002's flange.
    Cone(f64),
    Rail60E1,
    Measured(Arc<measured::Spline>),
}

/// A profile: a height over a lateral coordinate (both m).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    shape: Shape,
    name: String,
}

impl Profile {
    /// The S1002 wheel.
    pub fn s1002() -> Profile {
        Profile { shape: Shape::S1002, name: "S1002".into() }
    }

    /// A conical wheel of tread slope `slope` (1) on S1002's flange (see
    /// [`cone`]).
    pub fn cone(slope: f64) -> Profile {
        Profile { shape: Shape::Cone(slope), name: format!("cone 1:{}", crate::numerics::round_sig(1.0 / slope, 4)) }
    }

    /// The 60E1 (UIC60) rail head.
    pub fn rail_60e1() -> Profile {
        Profile { shape: Shape::Rail60E1, name: "60E1".into() }
    }

    /// A measured profile from a file (points in mm; see [`measured::parse`]).
    pub fn measured(path: &Path) -> Result<Profile, ProfileError> {
        Ok(Profile { shape: Shape::Measured(Arc::new(measured::read(path)?)), name: path.display().to_string() })
    }

    /// A measured profile from points already read (mm).
    pub fn from_spline(spline: measured::Spline, name: &str) -> Profile {
        Profile { shape: Shape::Measured(Arc::new(spline)), name: name.into() }
    }

    /// The profile's name ("S1002", "60E1" or the file).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The height (m) at lateral coordinate `u` (m); None outside the
    /// profile.
    pub fn height(&self, u: f64) -> Option<f64> {
        let mm = u * 1e3;
        let h = match &self.shape {
            Shape::S1002 => s1002::height_mm(mm),
            Shape::Cone(slope) => cone::height_mm(*slope, mm),
            Shape::Rail60E1 => rail60e1::height_mm(mm),
            Shape::Measured(s) => s.value(mm),
        };
        h.map(|v| v * 1e-3)
    }

    /// The lateral range the profile covers (m).
    pub fn range(&self) -> (f64, f64) {
        let (a, b) = match &self.shape {
            Shape::S1002 | Shape::Cone(_) => (s1002::BOUNDS[0], s1002::BOUNDS[8]),
            Shape::Rail60E1 => {
                let (u, _) = rail60e1::flank_start();
                let reach = u + 1.0; // 20 mm down the 1:20 flank
                (-reach, reach)
            }
            Shape::Measured(s) => s.range(),
        };
        (a * 1e-3, b * 1e-3)
    }
}
