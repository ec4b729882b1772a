//! Rail wear: the Archard rate at the element centres ([`archard`]) and its
//! accumulation on the rail-surface grid ([`crate::rail_grid`], [`deposit`]).

pub mod archard;
pub mod cell_deposit;
pub mod deposit;
pub mod law;

pub use archard::archard_rates;
pub use cell_deposit::CellDeposit;
pub use deposit::{PatchWear, WearDeposit, WearKernel};
pub use law::WearLaw;
