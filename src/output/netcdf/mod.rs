//! A small writer of netCDF-4-compatible HDF5 files.
//!
//! Files written here open in `xarray` (engines `h5netcdf` and `netcdf4`) and in netCDF-C
//! with named dimensions and coordinates:
//!
//! * a dimension is a 1-D coordinate dataset named like the dimension and made an HDF5
//!   dimension scale (`H5DSset_scale`), with a file-wide `_Netcdf4Dimid` attribute as netCDF-C
//!   and h5netcdf write it;
//! * a data variable has every axis attached to the dimension scale of its dimension
//!   (`H5DSattach_scale`);
//! * every variable carries `units` and `long_name` (variable-length UTF-8 strings);
//! * link and attribute creation order is tracked and indexed on the file, the groups and the
//!   datasets, so variables and attributes list in the order they were written.
//!
//! Files are only ever written whole through [`write_atomically`] (temporary file, fsync,
//! rename), which survives a crash at any point with either the old or the new file in place.
//! The module knows nothing about what the numbers mean.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicI32, Ordering};

use hdf5::file::FileCloseDegree;
use hdf5::plist::file_create::{AttrCreationOrder, LinkCreationOrder};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Extent, Extents, File, Group, H5Type, Location, SimpleExtents};
use ndarray::{ArrayD, ArrayView1, ArrayViewD};

use super::h5ds;
use chunks::{chunk_shape, write_compressed};
pub use read::{Attrs, open_file, read_attr_str, read_f64, read_i8, read_i64};

mod chunks;
mod read;

/// Errors of the netCDF writer and readers. Messages name the file and the object involved.
#[derive(Debug, thiserror::Error)]
pub enum NcError {
    /// HDF5 failed while writing `what` (a group, variable or attribute).
    #[error("HDF5 error writing {what} in {path}: {source}")]
    Write {
        /// The file being written (the final path, not the temporary one).
        path: PathBuf,
        /// The object being written, e.g. `variable "/g/u"`.
        what: String,
        /// The HDF5 error stack.
        source: hdf5::Error,
    },
    /// HDF5 failed while reading `what`.
    #[error("HDF5 error reading {what} from {path}: {source}")]
    Read {
        /// The file being read.
        path: PathBuf,
        /// The object being read, e.g. `variable "u" in group "g"`.
        what: String,
        /// The HDF5 error stack.
        source: hdf5::Error,
    },
    /// A file-system operation (fsync, rename, ...) failed.
    #[error("I/O error ({what}) on {path}: {source}")]
    Io {
        /// The file or directory concerned.
        path: PathBuf,
        /// The operation, e.g. `fsync of the temporary file`.
        what: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// The request is inconsistent: unknown dimension, shape mismatch, bad name, wrong type.
    #[error("invalid {what} in {path}: {msg}")]
    Invalid {
        /// The file concerned.
        path: PathBuf,
        /// The object concerned, e.g. `variable "/g/u"`.
        what: String,
        /// What is wrong.
        msg: String,
    },
}

/// Element types a variable can hold (`f64`, `i64`, `i8`). Sealed: only used to share one
/// generic implementation among the typed public functions.
trait NcScalar: H5Type + Clone + Send + Sync {
    /// Name used in error messages.
    const NAME: &'static str;
    /// Whether large data of the type are deflate-compressed (HDF5 filters
    /// do not apply to variable-length strings).
    const COMPRESS: bool = true;
    /// The values' bytes in memory (the file's layout: native numbers), for
    /// chunks compressed here.
    fn bytes(values: &[Self]) -> Option<&[u8]> {
        let _ = values;
        None
    }
}
impl NcScalar for f64 {
    const NAME: &'static str = "f64";
    fn bytes(values: &[Self]) -> Option<&[u8]> {
        Some(bytemuck::cast_slice(values))
    }
}
impl NcScalar for i64 {
    const NAME: &'static str = "i64";
    fn bytes(values: &[Self]) -> Option<&[u8]> {
        Some(bytemuck::cast_slice(values))
    }
}
impl NcScalar for i8 {
    const NAME: &'static str = "i8";
    fn bytes(values: &[Self]) -> Option<&[u8]> {
        Some(bytemuck::cast_slice(values))
    }
}
impl NcScalar for VarLenUnicode {
    const NAME: &'static str = "string";
    const COMPRESS: bool = false;
}

/// Compression level of data variables (zlib); low levels are several times faster than the
/// default 6 at nearly the same ratio on simulation output.
const DEFLATE_LEVEL: u8 = 1;

/// Data variables smaller than this are stored contiguous and uncompressed.
const MIN_COMPRESS_BYTES: usize = 4096;

/// State shared by all groups of one file.
struct FileCtx {
    /// Final path of the file, for error messages.
    path: PathBuf,
    /// Next `_Netcdf4Dimid`; netCDF dimension ids are unique across the whole file.
    next_dimid: AtomicI32,
}

/// A dimension defined in a group: its coordinate variable is the dimension scale.
struct Dim {
    name: String,
    len: usize,
    unlimited: bool,
    scale: Dataset,
    /// Whether it has a coordinate variable (else a dimension alone, [`NcGroup::dim`]).
    coordinate: bool,
}

/// A netCDF group being written: wraps an [`hdf5::Group`] and remembers the dimensions it
/// defines (name, length, unlimited) so that data variables can be checked and attached.
///
/// Obtained as the root group in the closure of [`write_atomically`], or from
/// [`NcGroup::group`].
pub struct NcGroup {
    group: Group,
    /// Absolute HDF5 path of the group: `/` or `/a/b`.
    name: String,
    ctx: Arc<FileCtx>,
    dims: RefCell<Vec<Dim>>,
}

impl NcGroup {
    /// Create a child group `name` (a single path component) and return it.
    pub fn group(&self, name: &str) -> Result<NcGroup, NcError> {
        let full = self.child_path(name);
        let what = || format!("group {full:?}");
        self.check_name(name, &what)?;
        let group = self
            .group
            .create_group_builder()
            .create_intermediate_group(false)
            .with_gcpl(|p| {
                p.link_creation_order(LinkCreationOrder::Indexed).attr_creation_order(AttrCreationOrder::Indexed)
            })
            .create(name)
            .map_err(|e| self.write_err(what(), e))?;
        Ok(NcGroup { group, name: full.clone(), ctx: Arc::clone(&self.ctx), dims: RefCell::default() })
    }

    /// Write a variable-length UTF-8 string attribute on the group (any length; a whole TOML
    /// configuration is fine).
    pub fn attr_str(&self, name: &str, value: &str) -> Result<(), NcError> {
        let what = || format!("attribute {name:?} of group {:?}", self.name);
        write_str_attr(&self.group, name, value).map_err(|e| self.write_err(what(), e))
    }

    /// Write a scalar `f64` attribute on the group.
    pub fn attr_f64(&self, name: &str, value: f64) -> Result<(), NcError> {
        let what = || format!("attribute {name:?} of group {:?}", self.name);
        write_attr(&self.group, name, &value).map_err(|e| self.write_err(what(), e))
    }

    /// Write a scalar `i64` attribute on the group.
    pub fn attr_i64(&self, name: &str, value: i64) -> Result<(), NcError> {
        let what = || format!("attribute {name:?} of group {:?}", self.name);
        write_attr(&self.group, name, &value).map_err(|e| self.write_err(what(), e))
    }

    /// Define dimension `name` of length `values.len()` together with its coordinate variable
    /// (a dataset named like the dimension, made a dimension scale) holding `values`.
    /// `unlimited` makes the dimension extendable (chunked, maximum size unlimited), which
    /// netCDF readers report as an unlimited dimension. Note that netCDF has no fixed
    /// dimensions of length 0: netCDF-C reports an empty dimension as unlimited either way
    /// (h5netcdf keeps it fixed).
    pub fn coord_f64(
        &self,
        name: &str,
        values: &[f64],
        units: &str,
        long_name: &str,
        unlimited: bool,
    ) -> Result<(), NcError> {
        self.coord(name, values, units, long_name, unlimited)
    }

    /// Define dimension `name` of length `len` without a coordinate variable, as netCDF-C
    /// writes one: a dimension scale of that name whose `NAME` says it is "a netCDF dimension
    /// but not a netCDF variable". A data variable of the same name on other dimensions may
    /// then be written ([`NcGroup::var_f64`] stores it as netCDF-C does, under the name
    /// `_nc4_non_coord_<name>`, which netCDF readers and xarray show as `name`).
    pub fn dim(&self, name: &str, len: usize) -> Result<(), NcError> {
        let full = self.child_path(name);
        let what = || format!("dimension {full:?}");
        self.check_name(name, &what)?;
        let zeros = vec![0i64; len];
        let data = ArrayView1::from(&zeros).into_dyn();
        let dimid = self.ctx.next_dimid.fetch_add(1, Ordering::Relaxed);
        let scale = (|| {
            let ds = self.create_dataset(name, data, &[false], false)?;
            h5ds::set_scale(&ds, &format!("{DIMENSION_WITHOUT_VARIABLE}{len:10}"))?;
            write_attr(&ds, "_Netcdf4Dimid", &dimid)?;
            Ok(ds)
        })()
        .map_err(|e| self.write_err(what(), e))?;
        self.dims.borrow_mut().push(Dim { name: name.to_owned(), len, unlimited: false, scale, coordinate: false });
        Ok(())
    }

    /// Like [`NcGroup::coord_f64`] with an `i64` coordinate (e.g. step or element indices).
    pub fn coord_i64(
        &self,
        name: &str,
        values: &[i64],
        units: &str,
        long_name: &str,
        unlimited: bool,
    ) -> Result<(), NcError> {
        self.coord(name, values, units, long_name, unlimited)
    }

    /// Write data variable `name` on dimensions `dims` (in axis order; all defined in THIS
    /// group by `coord_*`, each axis of `data` as long as its dimension), attach the dimension
    /// scales and write `units` and `long_name`. An empty `dims` with a 0-d array gives a
    /// scalar variable. Data of 4 KiB or more are chunked (about 1 MiB per chunk, whole
    /// trailing rows), shuffled and deflate-compressed (level 1) when the HDF5 library provides
    /// deflate. `data` may be any view (non-contiguous views are copied first).
    pub fn var_f64(
        &self,
        name: &str,
        dims: &[&str],
        data: ArrayViewD<'_, f64>,
        units: &str,
        long_name: &str,
    ) -> Result<(), NcError> {
        self.var(name, dims, data, units, long_name)
    }

    /// Like [`NcGroup::var_f64`] for `i64` data.
    pub fn var_i64(
        &self,
        name: &str,
        dims: &[&str],
        data: ArrayViewD<'_, i64>,
        units: &str,
        long_name: &str,
    ) -> Result<(), NcError> {
        self.var(name, dims, data, units, long_name)
    }

    /// Like [`NcGroup::var_f64`] for `i8` data (flags such as stick = 1 / slip = 0).
    pub fn var_i8(
        &self,
        name: &str,
        dims: &[&str],
        data: ArrayViewD<'_, i8>,
        units: &str,
        long_name: &str,
    ) -> Result<(), NcError> {
        self.var(name, dims, data, units, long_name)
    }

    /// Like [`NcGroup::coord_f64`] with a string coordinate (netCDF-4
    /// `string`, variable-length UTF-8), e.g. the values of a sweep axis.
    pub fn coord_str(&self, name: &str, values: &[String], units: &str, long_name: &str) -> Result<(), NcError> {
        let v = self.strings(name, values.iter().map(String::as_str))?;
        self.coord(name, &v, units, long_name, false)
    }

    /// Like [`NcGroup::var_f64`] for strings (netCDF-4 `string`,
    /// variable-length UTF-8; stored uncompressed).
    pub fn var_str(
        &self,
        name: &str,
        dims: &[&str],
        data: ArrayViewD<'_, String>,
        units: &str,
        long_name: &str,
    ) -> Result<(), NcError> {
        let v = self.strings(name, data.iter().map(String::as_str))?;
        let a = ArrayD::from_shape_vec(ndarray::IxDyn(data.shape()), v).expect("same shape");
        self.var(name, dims, a.view(), units, long_name)
    }

    fn strings<'s>(
        &self,
        name: &str,
        values: impl IntoIterator<Item = &'s str>,
    ) -> Result<Vec<VarLenUnicode>, NcError> {
        values
            .into_iter()
            .map(|s| {
                s.parse::<VarLenUnicode>()
                    .map_err(|e| self.invalid(self.child_path(name), format!("string {s:?}: {e}")))
            })
            .collect()
    }

    /// Write an extra string attribute (e.g. `flag_meanings`, `comment`) on the existing
    /// variable or coordinate `var` of this group. An attribute of the same name must not
    /// exist yet.
    pub fn var_attr_str(&self, var: &str, name: &str, value: &str) -> Result<(), NcError> {
        let what = || format!("attribute {name:?} of variable {:?}", self.child_path(var));
        let ds = self.group.dataset(var).map_err(|e| self.write_err(what(), e))?;
        write_str_attr(&ds, name, value).map_err(|e| self.write_err(what(), e))
    }

    // ----- private helpers -----

    fn coord<T: NcScalar>(
        &self,
        name: &str,
        values: &[T],
        units: &str,
        long_name: &str,
        unlimited: bool,
    ) -> Result<(), NcError> {
        let full = self.child_path(name);
        let what = || format!("coordinate {full:?}");
        self.check_name(name, &what)?;
        let data = ArrayView1::from(values).into_dyn();
        let dimid = self.ctx.next_dimid.fetch_add(1, Ordering::Relaxed);
        let scale = (|| {
            let ds = self.create_dataset(name, data, &[unlimited], false)?;
            h5ds::set_scale(&ds, name)?;
            write_attr(&ds, "_Netcdf4Dimid", &dimid)?;
            write_str_attr(&ds, "units", units)?;
            write_str_attr(&ds, "long_name", long_name)?;
            Ok(ds)
        })()
        .map_err(|e| self.write_err(what(), e))?;
        self.dims.borrow_mut().push(Dim {
            name: name.to_owned(),
            len: values.len(),
            unlimited,
            scale,
            coordinate: true,
        });
        Ok(())
    }

    fn var<T: NcScalar>(
        &self,
        name: &str,
        dims: &[&str],
        data: ArrayViewD<'_, T>,
        units: &str,
        long_name: &str,
    ) -> Result<(), NcError> {
        let full = self.child_path(name);
        let what = || format!("variable {full:?}");
        let defined = self.dims.borrow();
        // A variable named like a dimension of this group (one without a
        // coordinate variable, on other dimensions) is stored as netCDF-C
        // stores it.
        let stored = match defined.iter().find(|d| d.name == name) {
            Some(_) if dims.contains(&name) => {
                let msg = "the name is a dimension of the variable; write coordinates with coord_*".to_owned();
                return Err(self.invalid(what(), msg));
            }
            Some(d) if d.coordinate => {
                let msg = "the name is a dimension with a coordinate variable".to_owned();
                return Err(self.invalid(what(), msg));
            }
            Some(_) => format!("{NON_COORD_PREFIX}{name}"),
            None => name.to_owned(),
        };
        let name = stored.as_str();
        self.check_name(name, &what)?;
        if dims.len() != data.ndim() {
            let msg = format!(
                "data has {} axes (shape {:?}) but {} dimensions {dims:?} were given",
                data.ndim(),
                data.shape(),
                dims.len()
            );
            return Err(self.invalid(what(), msg));
        }
        let mut used: Vec<&Dim> = Vec::with_capacity(dims.len());
        for (axis, &dname) in dims.iter().enumerate() {
            let Some(dim) = defined.iter().find(|d| d.name == dname) else {
                let known: Vec<&str> = defined.iter().map(|d| d.name.as_str()).collect();
                let msg =
                    format!("unknown dimension {dname:?}; dimensions defined in group {:?}: {known:?}", self.name);
                return Err(self.invalid(what(), msg));
            };
            if used.iter().any(|d| d.name == dname) {
                return Err(self.invalid(what(), format!("dimension {dname:?} used twice")));
            }
            if data.shape()[axis] != dim.len {
                let msg = format!(
                    "axis {axis} has length {} but dimension {dname:?} has length {} (data shape {:?}, dimensions {dims:?})",
                    data.shape()[axis],
                    dim.len,
                    data.shape()
                );
                return Err(self.invalid(what(), msg));
            }
            used.push(dim);
        }
        let unlimited: Vec<bool> = used.iter().map(|d| d.unlimited).collect();
        (|| {
            let ds = self.create_dataset(name, data, &unlimited, true)?;
            for (axis, dim) in used.iter().enumerate() {
                h5ds::attach_scale(&ds, &dim.scale, axis)?;
            }
            write_str_attr(&ds, "units", units)?;
            write_str_attr(&ds, "long_name", long_name)
        })()
        .map_err(|e| self.write_err(what(), e))
    }

    /// Create dataset `name` holding `data`. Axes flagged in `unlimited` get an unlimited
    /// maximum size. The dataset is chunked when it must be (unlimited axis) or when it is
    /// compressed (`compress`, deflate available, non-empty data).
    fn create_dataset<T: NcScalar>(
        &self,
        name: &str,
        data: ArrayViewD<'_, T>,
        unlimited: &[bool],
        compress: bool,
    ) -> hdf5::Result<Dataset> {
        let shape = data.shape().to_vec();
        let nbytes = data.len() * size_of::<T>();
        let compress = compress && T::COMPRESS && nbytes >= MIN_COMPRESS_BYTES && hdf5::filters::deflate_available();
        let chunked = compress || unlimited.iter().any(|&u| u);
        let extents = if shape.is_empty() {
            Extents::Scalar
        } else {
            // A fixed axis of length 0 cannot be chunked (chunk sizes are >= 1 and may not
            // exceed a fixed size), so it is made extendable in the dataset; the dimension
            // itself stays fixed (readers take that from the dimension scale).
            let ext = shape
                .iter()
                .zip(unlimited)
                .map(|(&n, &u)| if u || (chunked && n == 0) { Extent::resizable(n) } else { Extent::fixed(n) });
            Extents::Simple(SimpleExtents::from_vec(ext.collect()))
        };
        let mut builder = self
            .group
            .new_dataset::<T>()
            .attr_creation_order(AttrCreationOrder::Indexed)
            .create_intermediate_group(false);
        if shape.is_empty() {
            // Scalar: contiguous (HDF5 cannot chunk 0-d datasets).
        } else if chunked {
            builder = builder.chunk(chunk_shape(&shape, size_of::<T>()));
            if compress {
                builder = builder.shuffle().deflate(DEFLATE_LEVEL);
            }
        } else {
            // Contiguous, also when empty (hdf5-metno would otherwise chunk empty datasets).
            builder = builder.no_chunk();
        }
        let ds = builder.shape(extents).create(name)?;
        if compress && !shape.is_empty() && !data.is_empty() {
            write_compressed(&ds, data, &chunk_shape(&shape, size_of::<T>()))?;
        } else if !data.is_empty() {
            ds.write(data.as_standard_layout().view())?;
        }
        Ok(ds)
    }

    fn child_path(&self, name: &str) -> String {
        if self.name == "/" { format!("/{name}") } else { format!("{}/{name}", self.name) }
    }

    fn check_name(&self, name: &str, what: &dyn Fn() -> String) -> Result<(), NcError> {
        if name.is_empty() || name.contains('/') || name.contains('\0') || name == "." {
            let msg = "names must be non-empty, not \".\", without '/' or NUL".to_owned();
            return Err(self.invalid(what(), msg));
        }
        // HDF5 reports a duplicate name with an empty error stack; say it plainly.
        if self.group.link_exists(name) {
            let msg = format!("an object named {name:?} already exists in group {:?}", self.name);
            return Err(self.invalid(what(), msg));
        }
        Ok(())
    }

    fn write_err(&self, what: String, source: hdf5::Error) -> NcError {
        NcError::Write { path: self.ctx.path.clone(), what, source }
    }

    fn invalid(&self, what: String, msg: String) -> NcError {
        NcError::Invalid { path: self.ctx.path.clone(), what, msg }
    }
}

/// The `NAME` of a dimension scale that is not a netCDF variable (netCDF-C's
/// `DIM_WITHOUT_VARIABLE`; the dimension's length follows, right-aligned in 10 characters).
const DIMENSION_WITHOUT_VARIABLE: &str = "This is a netCDF dimension but not a netCDF variable.";

/// netCDF-C's prefix of a variable stored under another name because a dimension without a
/// coordinate variable has its name.
const NON_COORD_PREFIX: &str = "_nc4_non_coord_";

fn write_attr<T: H5Type>(loc: &Location, name: &str, value: &T) -> hdf5::Result<()> {
    loc.new_attr::<T>().create(name)?.write_scalar(value)
}

fn write_str_attr(loc: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    let value: VarLenUnicode =
        value.parse().map_err(|e| hdf5::Error::from(format!("string for attribute {name:?}: {e}")))?;
    write_attr(loc, name, &value)
}

/// A file being written atomically is `<name><TEMPORARY_SUFFIX><pid>`.
pub const TEMPORARY_SUFFIX: &str = ".tmp-";

/// Removes the temporary file on drop (error or panic) unless disarmed after the rename.
struct TempFile {
    path: PathBuf,
    armed: bool,
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if self.armed {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// Write a whole file atomically: create `<path>.tmp-<pid>` in the same directory, call
/// `fill` with the root group, close the file, fsync it, rename it over `path`, fsync the
/// directory. On any error (or a panic in `fill`) the temporary file is removed and an
/// existing file at `path` is left untouched; after a crash either the old or the new file
/// is at `path` (a stale `*.tmp-<pid>` may remain next to it).
pub fn write_atomically<F>(path: &Path, fill: F) -> Result<(), NcError>
where
    F: FnOnce(&NcGroup) -> Result<(), NcError>,
{
    let io_err = |p: &Path, what: &str, source| NcError::Io { path: p.to_owned(), what: what.into(), source };
    let Some(file_name) = path.file_name() else {
        let msg = "not a file path".to_owned();
        return Err(NcError::Invalid { path: path.to_owned(), what: "output path".into(), msg });
    };
    let dir = super::folder_of(path).to_path_buf();
    let mut tmp_name = file_name.to_os_string();
    tmp_name.push(format!("{TEMPORARY_SUFFIX}{}", std::process::id()));
    let tmp = dir.join(tmp_name);
    let ctx = Arc::new(FileCtx { path: path.to_owned(), next_dimid: AtomicI32::new(0) });
    let write_err = |what: &str, source| NcError::Write { path: path.to_owned(), what: what.into(), source };

    // Declared before the file so that it drops after it; armed once the file is ours.
    let mut guard = TempFile { path: tmp.clone(), armed: false };
    let file = File::with_options()
        .with_fcpl(|p| {
            p.link_creation_order(LinkCreationOrder::Indexed).attr_creation_order(AttrCreationOrder::Indexed)
        })
        .with_fapl(|p| p.fclose_degree(FileCloseDegree::Strong).file_locking(false))
        .create(&tmp)
        .map_err(|e| write_err(&format!("temporary file {}", tmp.display()), e))?;
    guard.armed = true;
    let root_group = file.group("/").map_err(|e| write_err("root group", e))?;
    let root = NcGroup { group: root_group, name: "/".into(), ctx, dims: RefCell::default() };
    fill(&root)?;
    drop(root);
    file.close().map_err(|e| write_err("file (closing)", e))?;

    std::fs::File::open(&tmp).and_then(|f| f.sync_all()).map_err(|e| io_err(&tmp, "fsync of the temporary file", e))?;
    std::fs::rename(&tmp, path).map_err(|e| io_err(path, "rename of the temporary file", e))?;
    guard.armed = false;
    #[cfg(unix)]
    std::fs::File::open(&dir).and_then(|d| d.sync_all()).map_err(|e| io_err(&dir, "fsync of the directory", e))?;
    Ok(())
}
