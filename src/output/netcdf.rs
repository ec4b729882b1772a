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
use hdf5::types::{VarLenAscii, VarLenUnicode};
use hdf5::{Dataset, Extent, Extents, File, Group, H5Type, Location, SimpleExtents};
use ndarray::{ArrayD, ArrayView1, ArrayViewD};

use super::h5ds;

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

/// Target size of one chunk of a chunked (compressed or extendable) dataset. Kept at the size
/// of HDF5's default chunk cache so that partial reads (xarray's lazy slices) stay cheap.
const CHUNK_TARGET_BYTES: usize = 1 << 20;

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
        self.dims.borrow_mut().push(Dim { name: name.to_owned(), len: values.len(), unlimited, scale });
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
        self.check_name(name, &what)?;
        let defined = self.dims.borrow();
        if defined.iter().any(|d| d.name == name) {
            let msg = "the name is a dimension; write coordinates with coord_*".to_owned();
            return Err(self.invalid(what(), msg));
        }
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

/// Writes `data` into the new dataset `ds` (chunks of shape `chunk`,
/// shuffled and deflated at [`DEFLATE_LEVEL`]) chunk by chunk, the chunks
/// filtered here on all cores: HDF5 runs its filters on one thread (the
/// fields of paper_normal_30mm on the fixed grid, 92 MB, took 0.6 s of a
/// 2 s run). Each chunk (padded to the full chunk at the dataset's end, as
/// HDF5 stores it) goes through HDF5's shuffle filter's byte transposition
/// (byte `i` of element `j` to `i n + j`) and a zlib stream (flate2), then
/// `H5Dwrite_chunk` stores it as filtered by the dataset's own pipeline:
/// readers decode it as any chunk HDF5 wrote (tests/netcdf_writer.rs reads
/// it back with HDF5, postprocess's tests with h5py).
fn write_compressed<T: NcScalar>(ds: &Dataset, data: ArrayViewD<'_, T>, chunk: &[usize]) -> hdf5::Result<()> {
    use rayon::prelude::*;
    use std::io::Write;
    let shape = data.shape();
    let counts: Vec<usize> = shape.iter().zip(chunk).map(|(&n, &c)| n.div_ceil(c)).collect();
    let total: usize = counts.iter().product();
    let pad = data.first().cloned().ok_or_else(|| hdf5::Error::Internal("empty data".into()))?;
    let chunks: Vec<(Vec<u64>, Vec<u8>)> = (0..total)
        .into_par_iter()
        .map(|index| {
            // The chunk's first element along each axis (C order of chunks).
            let mut rest = index;
            let mut start = vec![0usize; shape.len()];
            for axis in (0..shape.len()).rev() {
                start[axis] = (rest % counts[axis]) * chunk[axis];
                rest /= counts[axis];
            }
            let mut block = ArrayD::from_elem(chunk.to_vec(), pad.clone());
            let within = |axis: usize| start[axis]..(start[axis] + chunk[axis]).min(shape[axis]);
            block
                .slice_each_axis_mut(|ax| {
                    let r = within(ax.axis.index());
                    ndarray::Slice::from(0..r.end - r.start)
                })
                .assign(&data.slice_each_axis(|ax| ndarray::Slice::from(within(ax.axis.index()))));
            let bytes = T::bytes(block.as_slice().expect("standard layout")).expect("a number type");
            let (size, n) = (size_of::<T>(), block.len());
            let mut shuffled = vec![0u8; bytes.len()];
            for (j, element) in bytes.chunks_exact(size).enumerate() {
                for (i, &b) in element.iter().enumerate() {
                    shuffled[i * n + j] = b;
                }
            }
            let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::new(DEFLATE_LEVEL.into()));
            z.write_all(&shuffled).and_then(|_| z.finish()).map(|out| (start.iter().map(|&v| v as u64).collect(), out))
        })
        .collect::<std::io::Result<_>>()
        .map_err(|e| hdf5::Error::Internal(format!("compressing a chunk: {e}")))?;
    for (start, bytes) in chunks {
        // SAFETY: `start` has one offset per dimension of `ds`, `bytes` is
        // a live buffer of the length passed.
        let status = hdf5::sync::sync(|| unsafe {
            hdf5_sys::h5d::H5Dwrite_chunk(
                ds.id(),
                hdf5_sys::h5p::H5P_DEFAULT,
                0,
                start.as_ptr(),
                bytes.len(),
                bytes.as_ptr().cast(),
            )
        });
        if status < 0 {
            return Err(hdf5::Error::Internal(format!("H5Dwrite_chunk failed at chunk {start:?}")));
        }
    }
    Ok(())
}

/// Chunk shape of about [`CHUNK_TARGET_BYTES`]: the full shape, with leading axes halved first
/// (so that chunks hold whole trailing rows, e.g. all elements of a few steps).
fn chunk_shape(shape: &[usize], elem_size: usize) -> Vec<usize> {
    let mut chunk: Vec<usize> = shape.iter().map(|&n| n.max(1)).collect();
    for axis in 0..chunk.len() {
        while chunk[axis] > 1 && chunk.iter().product::<usize>() * elem_size > CHUNK_TARGET_BYTES {
            chunk[axis] = chunk[axis].div_ceil(2);
        }
    }
    chunk
}

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

/// Opens the file at `path` for reading, as every reader of this module
/// does (HDF5 refuses to open a file a second time in one process with
/// other locking settings: open it with this while this module reads it).
pub fn open_file(path: &Path) -> Result<File, NcError> {
    File::with_options().with_fapl(|p| p.file_locking(false)).open(path).map_err(|source| NcError::Read {
        path: path.to_owned(),
        what: "file".into(),
        source,
    })
}

/// Open `group` (`""` or `"/"` = root) of the file at `path` for reading.
///
/// HDF5's own file locks are off for every file this module opens or
/// writes: a file is written whole under a temporary name and renamed, so a
/// reader never sees it half-written, and a lock would outlive the writer in
/// any child process started while the file was open (it inherits the
/// descriptor and, with it, the lock: a later reader of the renamed file was
/// refused with "unable to lock file, errno 11"). Sweep members have their
/// own lock files.
fn open_group(path: &Path, group: &str) -> Result<Group, NcError> {
    let read_err = |what: String, source| NcError::Read { path: path.to_owned(), what, source };
    let file = open_file(path)?;
    let gname = if group.is_empty() { "/" } else { group };
    file.group(gname).map_err(|e| read_err(format!("group {group:?}"), e))
}

fn read_var<T: NcScalar>(path: &Path, group: &str, var: &str) -> Result<ArrayD<T>, NcError> {
    let what = || format!("variable {var:?} in group {group:?}");
    let read_err = |source| NcError::Read { path: path.to_owned(), what: what(), source };
    let ds = open_group(path, group)?.dataset(var).map_err(read_err)?;
    let stored = ds.dtype().and_then(|t| t.to_descriptor()).map_err(read_err)?;
    if stored != T::type_descriptor() {
        let msg = format!("stored type is {stored}, not {}", T::NAME);
        return Err(NcError::Invalid { path: path.to_owned(), what: what(), msg });
    }
    ds.read_dyn::<T>().map_err(read_err)
}

/// Read the whole variable `var` of `group` (`""` or `"/"` = root) as `f64`. The stored
/// type must be `f64` (no silent conversion).
pub fn read_f64(path: &Path, group: &str, var: &str) -> Result<ArrayD<f64>, NcError> {
    read_var(path, group, var)
}

/// Read the whole variable `var` of `group` as `i64` (stored type must be `i64`).
pub fn read_i64(path: &Path, group: &str, var: &str) -> Result<ArrayD<i64>, NcError> {
    read_var(path, group, var)
}

/// Read the whole variable `var` of `group` as `i8` (stored type must be `i8`).
pub fn read_i8(path: &Path, group: &str, var: &str) -> Result<ArrayD<i8>, NcError> {
    read_var(path, group, var)
}

/// The attributes of one group of a file, opened once for several reads.
pub struct Attrs {
    path: PathBuf,
    group_name: String,
    group: Group,
}

impl Attrs {
    /// Opens `group` (`""` or `"/"` = root) of the file at `path`.
    pub fn open(path: &Path, group: &str) -> Result<Attrs, NcError> {
        Ok(Attrs { path: path.to_owned(), group_name: group.to_owned(), group: open_group(path, group)? })
    }

    fn read_err(&self, name: &str) -> impl Fn(hdf5::Error) -> NcError {
        let (path, what) = (self.path.clone(), format!("attribute {name:?} of group {:?}", self.group_name));
        move |source| NcError::Read { path: path.clone(), what: what.clone(), source }
    }

    /// The string attribute `name`: variable-length UTF-8 or ASCII (as
    /// written by [`NcGroup::attr_str`]).
    pub fn str(&self, name: &str) -> Result<String, NcError> {
        use hdf5::types::TypeDescriptor as TD;
        let read_err = self.read_err(name);
        let attr = self.group.attr(name).map_err(&read_err)?;
        match attr.dtype().and_then(|t| t.to_descriptor()).map_err(&read_err)? {
            TD::VarLenUnicode => Ok(attr.read_scalar::<VarLenUnicode>().map_err(&read_err)?.as_str().to_owned()),
            TD::VarLenAscii => Ok(attr.read_scalar::<VarLenAscii>().map_err(&read_err)?.as_str().to_owned()),
            other => Err(NcError::Invalid {
                path: self.path.clone(),
                what: format!("attribute {name:?} of group {:?}", self.group_name),
                msg: format!("stored type is {other}, not a variable-length string"),
            }),
        }
    }

    /// The scalar `i64` attribute `name` (as written by [`NcGroup::attr_i64`]).
    pub fn i64(&self, name: &str) -> Result<i64, NcError> {
        self.group.attr(name).and_then(|a| a.read_scalar::<i64>()).map_err(self.read_err(name))
    }
}

/// Read the string attribute `name` of `group` (`""` or `"/"` = root). Accepts
/// variable-length UTF-8 or ASCII strings (as written by [`NcGroup::attr_str`]).
pub fn read_attr_str(path: &Path, group: &str, name: &str) -> Result<String, NcError> {
    Attrs::open(path, group)?.str(name)
}
