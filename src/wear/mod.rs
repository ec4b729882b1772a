//! Rail wear: the Archard rate at the element centres ([`archard`]) and its
//! accumulation on the rail-surface grid ([`grid`], [`deposit`]).

pub mod archard;
pub mod deposit;
pub mod grid;

pub use archard::archard_rates;
pub use deposit::{PatchWear, WearDeposit};
pub use grid::RailGrid;
