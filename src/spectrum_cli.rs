//! `corrugation spectrum CONFIG.toml -o SPECTRUM.h5`: the linear growth
//! spectrum of a growth study's passage ([`corrugation::spectrum`]),
//! written to one file, with the fastest modes printed.

use corrugation::config::Resolved;
use corrugation::growth::study::initial_state;
use corrugation::spectrum::{Base, Progress, Spectrum, linear_spectrum};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// Modes printed at the end.
const PRINTED: usize = 8;

/// The rail a run file's study holds: its profile after the passages
/// stored, or with `pass` (from 1) that passage's stored snapshot; each
/// rail's.
pub fn stored_rail(file: &Path, resolved: &Resolved, pass: Option<usize>) -> Result<Vec<ndarray::Array2<f64>>, String> {
    let state = corrugation::run::stored_state(file, resolved).map_err(|e| e.to_string())?;
    let pick = |s: &corrugation::growth::state::RunState| match pass {
        None => Ok(s.profile.clone()),
        Some(p) => s.rail.iter().find(|r| r.index as usize + 1 == p).map(|r| r.profile.clone()).ok_or_else(|| {
            let kept: Vec<String> = s.rail.iter().map(|r| (r.index + 1).to_string()).collect();
            format!(
                "{}: passage {p} is not stored (rail snapshots of passages {}; growth.store_every sets them)",
                file.display(),
                kept.join(", ")
            )
        }),
    };
    std::iter::once(&state).chain(state.second_rail.as_deref()).map(pick).collect()
}

/// Measures and writes the spectrum of `resolved` to `out`, about `stored`
/// (a run file's rail) or the config's `spectrum.base`.
pub fn spectrum(resolved: &Resolved, stored: Option<Vec<ndarray::Array2<f64>>>, out: &Path) -> ExitCode {
    let scene = &resolved.scene;
    if scene.growth.is_none() {
        say!(
            "error: corrugation spectrum linearises a growth study's passage: the config needs a [growth] section \
             (with its [dynamics], [track] and [roughness])"
        );
        return ExitCode::from(2);
    }
    let params = scene.spectrum.unwrap_or_default();
    let state = initial_state(scene);
    let base: Vec<ndarray::Array2<f64>> = match (stored, params.base) {
        (Some(rails), _) => rails,
        (None, Base::Smooth) => {
            let z = ndarray::Array2::zeros(state.profile.raw_dim());
            vec![z; 1 + usize::from(state.second_rail.is_some())]
        }
        (None, Base::Roughness) => std::iter::once(state.profile.clone())
            .chain(state.second_rail.as_ref().map(|s| s.profile.clone()))
            .collect(),
    };
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = ProgressBar::new(1);
        b.set_style(
            ProgressStyle::with_template("spectrum [{bar:20}] {pos}/{len} passages, {elapsed}, ETA {eta}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        b
    });
    let start = Instant::now();
    let mut last = Instant::now();
    let mut report = |p: Progress| match &bar {
        Some(b) => {
            b.set_length(p.total as u64);
            b.set_position(p.done as u64);
        }
        None if p.done == p.total || last.elapsed().as_secs_f64() >= 10.0 => {
            last = Instant::now();
            let secs = start.elapsed().as_secs_f64();
            say!("spectrum: {}/{} passages ({secs:.0} s)", p.done, p.total);
        }
        None => {}
    };
    let result = linear_spectrum(scene, &base, &params, &mut report);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let s = match result {
        Ok(s) => s,
        Err(e) => {
            say!("error: {e}");
            say!("{} was not written", out.display());
            return ExitCode::from(1);
        }
    };
    for w in &s.warnings {
        say!("warning: {w}");
    }
    if let Err(e) = corrugation::output::spectrum_file::write_spectrum_file(out, &s, &params, &resolved.toml) {
        say!("error: {e}");
        return ExitCode::from(1);
    }
    summary(&s, out);
    ExitCode::SUCCESS
}

/// The fastest modes, the forced pattern's deepest harmonics and the cost.
fn summary(s: &Spectrum, out: &Path) {
    say!(
        "wrote {}: {} modes of {} Bloch class(es) on the {} m stretch ({} harmonics perturbed), {:.0} passage \
         equivalents, {:.1} s CPU, {:.1} s wall",
        out.display(),
        s.modes.len(),
        s.classes.len(),
        s.stretch,
        s.classes.iter().map(|c| c.basis.len()).sum::<usize>(),
        s.passage_equivalents,
        s.cpu_seconds,
        s.wall_seconds,
    );
    say!("fastest modes (dB per 1e5 wheel passages; drift in mm per 1e5 wheel passages):");
    say!("  rate      wavelength  frequency  drift     purity  sleeper/mid-span");
    for k in 0..s.modes.len().min(PRINTED) {
        let m = &s.modes[k];
        let class = s.class_of(k);
        let env = m.envelope(class, 0, &[0.0, 0.5 * s.stretch], s.supercell());
        say!(
            "  {:+8.3}  {:7.2} mm  {:7.1} Hz  {:+8.3}  {:5.2}   {:5.2}",
            m.growth_rate(),
            s.wavelength(k) * 1e3,
            s.frequency(k),
            m.drift(class, s.supercell()) * 1e5 * 1e3,
            m.purity(),
            if env[1] > 0.0 { env[0] / env[1] } else { f64::NAN },
        );
    }
    let forced = &s.forced_wear[0];
    let mut order: Vec<usize> = (0..forced.len()).collect();
    order.sort_by(|a, b| forced[*b].total_cmp(&forced[*a]));
    // Harmonics below 1e-6 of the mean wear are the round-off of a uniform
    // wear along the stretch.
    if forced.iter().any(|f| *f > 1e-6 * s.mean_wear[0]) {
        let top: Vec<String> = order
            .iter()
            .take(4)
            .map(|&k| format!("{:.1} mm {:.3} nm", s.wavelengths[k] * 1e3, forced[k] * 1e5 * 1e9))
            .collect();
        say!(
            "forced pattern (the smooth rail's wear per 1e5 wheel passages, of {:.3} um in all): {}",
            s.mean_wear[0] * 1e5 * 1e6,
            top.join(", ")
        );
    } else {
        say!("forced pattern: none (the smooth rail wears uniformly along the stretch)");
    }
}
