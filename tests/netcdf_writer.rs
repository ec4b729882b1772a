//! Tests of the netCDF-4 writer: round trips, dimension checks, atomic replacement.

use std::path::{Path, PathBuf};

use corrugation::output::netcdf::{NcError, NcGroup, read_attr_str, read_f64, read_i8, read_i64, write_atomically};
use ndarray::{Array, Array1, Array2, Array3, ArrayD, IxDyn};

fn f64_3d(a: usize, b: usize, c: usize, offset: f64) -> Array3<f64> {
    Array::from_shape_fn((a, b, c), |(i, j, k)| offset + i as f64 * 100.0 + j as f64 * 10.0 + k as f64 + 0.25)
}

/// Writes group `name` with dims step (unlimited) x elem x corner and 1-D/2-D/3-D variables
/// of every type; returns the 3-D arrays written.
fn write_group(root: &NcGroup, name: &str, n: (usize, usize, usize)) -> Result<(), NcError> {
    let g = root.group(name)?;
    g.attr_str("title", &format!("group {name}"))?;
    g.attr_f64("dt", 1.5e-4)?;
    g.attr_i64("passes", 7)?;
    let steps: Vec<i64> = (0..n.0 as i64).collect();
    let x: Vec<f64> = (0..n.1).map(|i| i as f64 * 0.5).collect();
    let corner: Vec<i64> = (0..n.2 as i64).collect();
    g.coord_i64("step", &steps, "1", "time step index", true)?;
    g.coord_f64("x", &x, "m", "position along the rail", false)?;
    g.coord_i64("corner", &corner, "1", "corner index", false)?;

    let a3 = f64_3d(n.0, n.1, n.2, 0.0);
    g.var_f64("f1", &["step"], a3.slice(ndarray::s![.., 0, 0]).into_dyn(), "N", "force")?;
    g.var_f64("f2", &["step", "x"], a3.slice(ndarray::s![.., .., 0]).into_dyn(), "m", "depth")?;
    g.var_f64("f3", &["step", "x", "corner"], a3.view().into_dyn(), "Pa", "pressure")?;
    let i3 = a3.mapv(|v| (v * 1000.0) as i64 - 5_000_000_000);
    g.var_i64("i1", &["x"], i3.slice(ndarray::s![0, .., 0]).into_dyn(), "1", "count")?;
    g.var_i64("i2", &["step", "corner"], i3.slice(ndarray::s![.., 0, ..]).into_dyn(), "1", "count")?;
    g.var_i64("i3", &["step", "x", "corner"], i3.view().into_dyn(), "1", "count")?;
    let b3 = a3.mapv(|v| if (v as i64) % 2 == 0 { 1i8 } else { -1 });
    g.var_i8("b1", &["corner"], b3.slice(ndarray::s![0, 0, ..]).into_dyn(), "1", "stick flag")?;
    g.var_i8("b2", &["x", "corner"], b3.slice(ndarray::s![0, .., ..]).into_dyn(), "1", "stick flag")?;
    g.var_i8("b3", &["step", "x", "corner"], b3.view().into_dyn(), "1", "stick flag")?;
    g.var_attr_str("b3", "flag_meanings", "slip stick")?;
    // A non-contiguous (transposed) view is accepted.
    let t = a3.slice(ndarray::s![.., .., 0]).to_owned();
    let tt = t.t().to_owned();
    g.var_f64("f2t", &["x", "step"], tt.t().t().into_dyn(), "m", "depth transposed")?;
    g.var_f64("scalar", &[], ndarray::arr0(2.5).into_dyn().view(), "s", "a scalar")?;
    Ok(())
}

fn check_group(path: &Path, name: &str, n: (usize, usize, usize)) {
    let a3 = f64_3d(n.0, n.1, n.2, 0.0);
    let i3 = a3.mapv(|v| (v * 1000.0) as i64 - 5_000_000_000);
    let b3 = a3.mapv(|v| if (v as i64) % 2 == 0 { 1i8 } else { -1 });
    assert_eq!(read_f64(path, name, "f1").unwrap(), a3.slice(ndarray::s![.., 0, 0]).into_dyn());
    assert_eq!(read_f64(path, name, "f2").unwrap(), a3.slice(ndarray::s![.., .., 0]).into_dyn());
    assert_eq!(read_f64(path, name, "f3").unwrap(), a3.clone().into_dyn());
    assert_eq!(read_i64(path, name, "i1").unwrap(), i3.slice(ndarray::s![0, .., 0]).into_dyn());
    assert_eq!(read_i64(path, name, "i2").unwrap(), i3.slice(ndarray::s![.., 0, ..]).into_dyn());
    assert_eq!(read_i64(path, name, "i3").unwrap(), i3.into_dyn());
    assert_eq!(read_i8(path, name, "b1").unwrap(), b3.slice(ndarray::s![0, 0, ..]).into_dyn());
    assert_eq!(read_i8(path, name, "b2").unwrap(), b3.slice(ndarray::s![0, .., ..]).into_dyn());
    assert_eq!(read_i8(path, name, "b3").unwrap(), b3.into_dyn());
    let t = a3.slice(ndarray::s![.., .., 0]).t().to_owned();
    assert_eq!(read_f64(path, name, "f2t").unwrap(), t.into_dyn());
    assert_eq!(read_f64(path, name, "scalar").unwrap(), ndarray::arr0(2.5).into_dyn());
    let x: Array1<f64> = (0..n.1).map(|i| i as f64 * 0.5).collect();
    assert_eq!(read_f64(path, name, "x").unwrap(), x.into_dyn());
    let steps: Array1<i64> = (0..n.0 as i64).collect();
    assert_eq!(read_i64(path, name, "step").unwrap(), steps.into_dyn());
    assert_eq!(read_attr_str(path, name, "title").unwrap(), format!("group {}", name.trim_start_matches('/')));
}

#[test]
fn round_trip_two_groups() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.nc");
    let config = "# a big TOML config\n".repeat(20_000); // ~400 KB, over the 64 KiB fixed limit
    write_atomically(&path, |root| {
        root.attr_str("config", &config)?;
        root.attr_str("unicode", "ε = 1 µm, ü")?;
        write_group(root, "g", (5, 4, 3))?;
        write_group(root, "h", (2, 6, 1))
    })
    .unwrap();
    check_group(&path, "g", (5, 4, 3));
    check_group(&path, "/h", (2, 6, 1));
    assert_eq!(read_attr_str(&path, "", "config").unwrap(), config);
    assert_eq!(read_attr_str(&path, "/", "unicode").unwrap(), "ε = 1 µm, ü");
    // Only the final file is left in the directory.
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, vec![std::ffi::OsString::from("out.nc")]);
}

#[test]
fn empty_unlimited_dimension_and_large_arrays() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.nc");
    let big = Array2::from_shape_fn((1000, 400), |(i, j)| (i * 400 + j) as f64 * 1e-3);
    write_atomically(&path, |root| {
        root.coord_i64("step", &[], "1", "step", true)?;
        root.coord_i64("empty", &[], "1", "fixed empty", false)?;
        root.coord_f64("elem", &vec![0.0; 400], "m", "element", false)?;
        root.var_f64("none", &["step", "elem"], Array2::zeros((0, 400)).view().into_dyn(), "m", "n")?;
        root.var_f64("nothing", &["elem", "empty"], Array2::zeros((400, 0)).view().into_dyn(), "m", "n")?;
        let g = root.group("run")?;
        let steps: Vec<i64> = (0..1000).collect();
        g.coord_i64("step", &steps, "1", "step", true)?;
        g.coord_i64("element", &(0..400).collect::<Vec<i64>>(), "1", "element", false)?;
        g.var_f64("w", &["step", "element"], big.view().into_dyn(), "m", "wear")
    })
    .unwrap();
    assert_eq!(read_f64(&path, "/", "none").unwrap().shape(), &[0, 400]);
    assert_eq!(read_f64(&path, "/", "nothing").unwrap().shape(), &[400, 0]);
    assert_eq!(read_f64(&path, "run", "w").unwrap(), big.into_dyn());
}

fn err_of(fill: impl FnOnce(&NcGroup) -> Result<(), NcError>) -> (String, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.nc");
    let err = write_atomically(&path, fill).unwrap_err().to_string();
    assert!(!path.exists(), "no file may be created on error");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "temporary file left behind");
    (err, path)
}

#[test]
fn dimension_errors_name_the_variable() {
    let setup = |g: &NcGroup| -> Result<(), NcError> {
        g.coord_i64("step", &[0, 1, 2], "1", "step", true)?;
        g.coord_f64("x", &[0.0, 1.0], "m", "x", false)
    };
    // Wrong length along a dimension.
    let (err, path) = err_of(|root| {
        let g = root.group("g")?;
        setup(&g)?;
        g.var_f64("depth", &["step", "x"], Array2::zeros((3, 5)).view().into_dyn(), "m", "d")
    });
    assert!(err.contains("\"/g/depth\"") && err.contains("\"x\"") && err.contains("length 5"), "{err}");
    assert!(err.contains(&path.display().to_string()), "{err}");
    // Unknown dimension.
    let (err, _) = err_of(|root| {
        setup(root)?;
        root.var_i8("stick", &["step", "y"], Array2::zeros((3, 2)).view().into_dyn(), "1", "s")
    });
    assert!(err.contains("\"/stick\"") && err.contains("unknown dimension \"y\""), "{err}");
    // Number of axes.
    let (err, _) = err_of(|root| {
        setup(root)?;
        let data = ArrayD::<i64>::zeros(IxDyn(&[3, 2, 1]));
        root.var_i64("count", &["step", "x"], data.view(), "1", "c")
    });
    assert!(err.contains("\"/count\"") && err.contains("3 axes"), "{err}");
    // Dimensions of another group are not visible.
    let (err, _) = err_of(|root| {
        setup(root)?;
        let g = root.group("child")?;
        g.var_f64("u", &["x"], Array1::zeros(2).view().into_dyn(), "m", "u")
    });
    assert!(err.contains("\"/child/u\"") && err.contains("unknown dimension \"x\""), "{err}");
    // Duplicate dimension and duplicate variable names.
    let (err, _) = err_of(|root| {
        setup(root)?;
        root.coord_f64("x", &[1.0], "m", "x again", false)
    });
    assert!(err.contains("\"/x\"") && err.contains("already exists"), "{err}");
    let (err, _) = err_of(|root| {
        setup(root)?;
        root.var_f64("u", &["x"], Array1::zeros(2).view().into_dyn(), "m", "u")?;
        root.var_f64("u", &["x"], Array1::zeros(2).view().into_dyn(), "m", "u")
    });
    assert!(err.contains("\"/u\""), "{err}");
}

#[test]
fn read_errors_name_file_group_and_variable() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.nc");
    write_atomically(&path, |root| {
        let g = root.group("g")?;
        g.coord_f64("x", &[1.0, 2.0], "m", "x", false)?;
        g.var_f64("u", &["x"], Array1::from(vec![3.0, 4.0]).view().into_dyn(), "m", "u")
    })
    .unwrap();
    let err = read_i64(&path, "g", "u").unwrap_err().to_string();
    assert!(err.contains("\"u\"") && err.contains("\"g\"") && err.contains("not i64"), "{err}");
    let err = read_f64(&path, "g", "missing").unwrap_err().to_string();
    assert!(err.contains("\"missing\"") && err.contains("r.nc"), "{err}");
    let err = read_f64(&path, "nogroup", "u").unwrap_err().to_string();
    assert!(err.contains("\"nogroup\""), "{err}");
    let err = read_attr_str(&dir.path().join("absent.nc"), "/", "config").unwrap_err().to_string();
    assert!(err.contains("absent.nc"), "{err}");
}

#[test]
fn failed_fill_leaves_existing_file_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("keep.nc");
    write_atomically(&path, |root| {
        root.attr_str("version", "old")?;
        root.coord_f64("x", &[1.0, 2.0, 3.0], "m", "x", false)
    })
    .unwrap();
    let before = std::fs::read(&path).unwrap();

    let err = write_atomically(&path, |root| {
        root.attr_str("version", "new")?;
        root.coord_f64("x", &[1.0], "m", "x", false)?;
        root.var_f64("u", &["x"], Array1::zeros(2).view().into_dyn(), "m", "u")
    });
    assert!(err.is_err());
    let panicked = std::panic::catch_unwind(|| {
        write_atomically(&path, |root| {
            root.attr_str("version", "new")?;
            panic!("fill panics");
        })
    });
    assert!(panicked.is_err());

    assert_eq!(std::fs::read(&path).unwrap(), before, "old file modified");
    assert_eq!(read_attr_str(&path, "/", "version").unwrap(), "old");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, vec![std::ffi::OsString::from("keep.nc")], "temporary file left behind");

    // A successful write replaces it.
    write_atomically(&path, |root| root.attr_str("version", "new")).unwrap();
    assert_eq!(read_attr_str(&path, "/", "version").unwrap(), "new");
}

#[test]
fn concurrent_writers_in_threads() {
    let dir = tempfile::tempdir().unwrap();
    std::thread::scope(|s| {
        for t in 0..4 {
            let path = dir.path().join(format!("t{t}.nc"));
            s.spawn(move || {
                for _ in 0..5 {
                    write_atomically(&path, |root| write_group(root, "g", (3, 4 + t, 2))).unwrap();
                    check_group(&path, "g", (3, 4 + t, 2));
                }
            });
        }
    });
}

/// Large variables are compressed chunk by chunk on all cores and stored
/// with `H5Dwrite_chunk`: HDF5 reads them back exactly through the
/// datasets' own filters (shuffle, deflate), also the padded last chunk
/// along the leading axis, for every number type.
#[test]
fn compressed_chunks_read_back_through_hdf5s_filters() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("chunks.nc");
    let f = Array3::from_shape_fn((333, 7, 211), |(i, j, k)| (i as f64 * 0.37 + j as f64).sin() * 1e3 + k as f64);
    let b = Array2::from_shape_fn((1001, 5000), |(i, j)| ((i * 7 + j * 3) % 5) as i8 - 2);
    let n = Array2::from_shape_fn((101, 3000), |(i, j)| (i as i64 - 50) * 1_000_003 + j as i64);
    write_atomically(&path, |root| {
        root.coord_i64("a", &(0..333).collect::<Vec<i64>>(), "1", "a", true)?;
        root.coord_i64("b", &(0..7).collect::<Vec<i64>>(), "1", "b", false)?;
        root.coord_i64("c", &(0..211).collect::<Vec<i64>>(), "1", "c", false)?;
        root.coord_i64("d", &(0..1001).collect::<Vec<i64>>(), "1", "d", false)?;
        root.coord_i64("e", &(0..5000).collect::<Vec<i64>>(), "1", "e", false)?;
        root.coord_i64("g", &(0..101).collect::<Vec<i64>>(), "1", "g", false)?;
        root.coord_i64("h", &(0..3000).collect::<Vec<i64>>(), "1", "h", false)?;
        root.var_f64("f", &["a", "b", "c"], f.view().into_dyn(), "m", "f")?;
        root.var_i8("flags", &["d", "e"], b.view().into_dyn(), "1", "flags")?;
        root.var_i64("counts", &["g", "h"], n.view().into_dyn(), "1", "counts")
    })
    .unwrap();
    assert_eq!(read_f64(&path, "/", "f").unwrap(), f.into_dyn());
    assert_eq!(read_i8(&path, "/", "flags").unwrap(), b.into_dyn());
    assert_eq!(read_i64(&path, "/", "counts").unwrap(), n.into_dyn());
    let file = hdf5::File::open(&path).unwrap();
    for (name, chunks) in [("f", vec![84, 7, 211]), ("flags", vec![126, 5000]), ("counts", vec![26, 3000])] {
        let ds = file.dataset(name).unwrap();
        assert_eq!(ds.chunk(), Some(chunks), "{name}");
        let filters = ds.filters();
        assert!(filters.contains(&hdf5::filters::Filter::Shuffle), "{name}: {filters:?}");
        assert!(filters.iter().any(|f| matches!(f, hdf5::filters::Filter::Deflate(1))), "{name}: {filters:?}");
    }
}
