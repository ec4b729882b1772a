//! Output: a generic netCDF-4 compatible HDF5 writer ([`netcdf`]) and the
//! run-file layout (book: docs/src/reference/run-file.md) ([`run_file`]).

pub mod checkpoint;
pub mod curve_file;
mod field_units;
pub mod forecast_group;
mod h5ds;
pub mod netcdf;
pub mod run_file;
mod run_record;
pub mod spectrum_file;
pub mod spectrum_part;
pub mod track_file;

use std::path::Path;

/// The folder a file at `path` is in (`.` for a bare file name).
pub fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Checks, before anything is computed, that a file can be written at
/// `path`: its folder exists and a file can be created in it (a probe file,
/// removed at once). An existing file at `path` is left untouched.
pub fn check_writable(path: &Path) -> std::io::Result<()> {
    let dir = folder_of(path);
    if !dir.is_dir() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("the folder {} does not exist", dir.display()),
        ));
    }
    if path.is_dir() {
        return Err(std::io::Error::new(std::io::ErrorKind::IsADirectory, "it is a folder"));
    }
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let probe = dir.join(format!(".{name}.probe-{}", std::process::id()));
    std::fs::File::create(&probe)?;
    std::fs::remove_file(&probe)
}

/// Removes the temporary files a killed writer left next to `path`
/// (`<name>.tmp-<pid>`, see [`netcdf::write_atomically`]), except this
/// process's own.
pub fn remove_stale_temporaries(path: &Path) {
    let Some(name) = path.file_name() else {
        return;
    };
    let dir = folder_of(path);
    let prefix = format!("{}{}", name.to_string_lossy(), netcdf::TEMPORARY_SUFFIX);
    let own = format!("{prefix}{}", std::process::id());
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let n = e.file_name().to_string_lossy().into_owned();
        if n.starts_with(&prefix) && n != own && n[prefix.len()..].chars().all(|c| c.is_ascii_digit()) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}
