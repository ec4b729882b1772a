//! The pressure of a step on the fixed grid, and the next step's computed
//! ahead on a second thread while this step's tangential problem is
//! solved.

use super::super::convolution::FftScratch;
use super::{FixedGrid, normal_reason};
use crate::contact::{ContactError, RailContact, StepInput};

/// A step's pressure.
#[derive(Debug, Clone)]
pub(super) struct Pressure {
    /// On every grid element (Pa).
    pub p3: Vec<f64>,
    /// Elements the linear contact clipped to zero.
    pub clipped: usize,
    /// Whether the load is symmetric about y = 0 (to rounding).
    pub symmetric: bool,
}

/// The next step's pressure, computed ahead, and the input it is for.
#[derive(Debug, Clone)]
pub(super) struct Ahead {
    pub key: [u64; 5],
    pub result: Result<Pressure, ContactError>,
}

impl Ahead {
    /// What a step's pressure depends on besides the warm start: the
    /// position, the normal force, the Hertz patch the linear contact
    /// starts from and (in its error report) the longitudinal force.
    pub fn key(input: &StepInput) -> [u64; 5] {
        let p = &input.patch;
        [input.position.to_bits(), p.normal_force.to_bits(), p.a.to_bits(), p.b.to_bits(), input.force_x.to_bits()]
    }
}

impl FixedGrid {
    /// The pressure of the step `input`: the linear profile contact's
    /// first-order pressure averaged over the elements, or the normal
    /// problem on the grid warm-started from `start` (the last step's).
    pub(super) fn pressure(
        &self,
        scratch: &mut FftScratch,
        input: &StepInput,
        start: Option<&[f64]>,
    ) -> Result<Pressure, ContactError> {
        match (&self.surface, &self.linear) {
            (Some(RailContact::Linear(surface)), Some(response)) => {
                let (xs, ys) = self.grid.centres();
                let centres: Vec<(f64, f64)> = xs.into_iter().zip(ys).collect();
                let half = (0.5 * self.grid.dx, 0.5 * self.grid.dy);
                let (p3, clipped) =
                    response.pressure_on_cells(surface, input.position, &input.patch, &centres, half)?;
                let symmetric = self.symmetric(&p3);
                Ok(Pressure { p3, clipped, symmetric })
            }
            _ => {
                let gap = self.gap_at(input.position);
                let n_force = input.patch.normal_force;
                let normal = self
                    .solve_normal(scratch, &gap, n_force, start)
                    .map_err(|e| ContactError::NoConvergence { force: input.force_x, reason: normal_reason(e) })?;
                let symmetric = self.surface.is_none() || self.symmetric(&gap);
                Ok(Pressure { p3: normal.pressure, clipped: 0, symmetric })
            }
        }
    }
}
