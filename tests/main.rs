//! The integration tests, built as one test binary: each file of
//! `tests/` is a module here (one link instead of one per file; the files
//! keep their names and paths). `cargo test --test integration spectrum::`
//! runs one file's tests, `cargo nextest run -E 'test(/^spectrum::/)'` with
//! nextest.
mod common;

mod auto_model;
mod cli_run;
mod config_errors;
mod config_reference;
mod contact_dynamics;
mod contact_vehicle;
mod creep_response;
mod creepage_control;
mod curving;
mod discrete_dynamics;
mod discrete_track;
mod falling_friction;
mod fastsim_reference;
mod field_units;
mod fixed_grid;
mod friction_memory;
mod grid_cg;
mod growth;
mod hertz_reference;
mod imports;
mod linear_contact;
mod measured_record;
mod netcdf_writer;
mod profile_contact;
mod rail_head;
mod receptance;
mod resume;
mod spectrum;
mod sweep;
mod torsion;
mod track_config;
mod track_layout;
mod traffic_mix;
mod transient_passage;
mod transient_reference;
mod two_rails;
mod units_input;
mod vehicle;
mod wear_deposit;
mod wheelset_modal;
