//! Minimal bindings to the HDF5 high-level dimension-scale API (`H5DS*` in `libhdf5_hl`).
//!
//! hdf5-metno has no wrapper for dimension scales, so the two functions needed to write
//! netCDF-4 dimensions are declared here. The `hl` feature of `hdf5-metno-sys` links
//! `hdf5_hl`. Every call runs under `hdf5::sync::sync`, the crate's global HDF5 lock, so it
//! serialises with hdf5-metno's own calls from other threads.

use std::ffi::{CString, c_char, c_uint};

use hdf5::Dataset;
use hdf5_sys::h5::herr_t;
use hdf5_sys::h5i::hid_t;

unsafe extern "C" {
    fn H5DSset_scale(dsid: hid_t, dimname: *const c_char) -> herr_t;
    fn H5DSattach_scale(did: hid_t, dsid: hid_t, idx: c_uint) -> herr_t;
}

/// Turn a negative HDF5 return code into the current HDF5 error stack.
fn check(rc: herr_t) -> hdf5::Result<()> {
    if rc < 0 { Err(hdf5::Error::query().unwrap_or_else(|e| e)) } else { Ok(()) }
}

/// Make `scale` a dimension scale named `name` (writes `CLASS="DIMENSION_SCALE"` and `NAME`
/// as the NULLTERM strings netCDF-C and h5py expect).
pub(crate) fn set_scale(scale: &Dataset, name: &str) -> hdf5::Result<()> {
    let cname = CString::new(name).map_err(|_| format!("dimension name {name:?} contains NUL"))?;
    hdf5::sync::sync(|| check(unsafe { H5DSset_scale(scale.id(), cname.as_ptr()) }))
}

/// Attach dimension scale `scale` to axis `axis` of `var` (writes `DIMENSION_LIST` on `var`
/// and `REFERENCE_LIST` on `scale`).
pub(crate) fn attach_scale(var: &Dataset, scale: &Dataset, axis: usize) -> hdf5::Result<()> {
    let idx = c_uint::try_from(axis).map_err(|_| format!("axis {axis} out of range"))?;
    hdf5::sync::sync(|| check(unsafe { H5DSattach_scale(var.id(), scale.id(), idx) }))
}
