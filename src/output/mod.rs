//! Output: a generic netCDF-4 compatible HDF5 writer ([`netcdf`]) and the
//! run-file layout of DESIGN.md section 4 ([`run_file`]).

pub mod checkpoint;
mod h5ds;
pub mod netcdf;
pub mod run_file;
pub mod track_file;
