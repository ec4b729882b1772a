//! Reading variables and attributes of the files this module writes.

use std::path::{Path, PathBuf};

use hdf5::types::{VarLenAscii, VarLenUnicode};
use hdf5::{File, Group};
use ndarray::ArrayD;

use super::{NcError, NcScalar};

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
