//! `corrugation`: prediction of rail corrugation with a non-stationary
//! wheel-rail contact model (Baeza, Vila, Roda, Fayos, Wear 265 (2008)
//! 1156-1162), closing the loop from transient contact to long-term growth.
//!
//! Model chain of one wheel passage: imposed loads along the rail
//! ([`loads`]) -> Hertz normal contact ([`hertz`]) -> tangential contact
//! ([`contact`]) -> Archard wear on the rail surface ([`wear`]), driven by
//! [`passage`]. [`config`] turns TOML into validated [`params`]; [`output`]
//! writes netCDF-4 compatible HDF5.

pub mod build;
pub mod config;
pub mod contact;
pub mod cost;
pub mod creep_coefficients;
pub mod curving;
pub mod dynamics;
pub mod growth;
pub mod harmonics;
pub mod hertz;
pub mod levels;
pub mod loads;
pub mod metrics;
pub mod model_choice;
pub mod numerics;
pub mod output;
pub mod params;
pub mod passage;
pub mod quadrature;
pub mod rail_grid;
pub mod run;
pub mod spectrum;
pub mod sweep;
pub mod wear;
