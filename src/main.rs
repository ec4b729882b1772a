//! Command line of `corrugation` (DESIGN.md section 4).
//!
//! Exit codes: 0 success, 1 the run failed (solver or output), 2 bad input
//! (command line or config).

/// A line on stderr. A closed stderr (`... 2>&1 | head`) must not stop a
/// run: write errors are ignored. Defined before the modules that use it.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// [`say!`] without the newline.
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($arg)*);
    }};
}

mod progress;

use clap::{Parser, Subcommand};
use corrugation::config::{self, Resolved};
use corrugation::contact::transient::StepSolver;
use corrugation::dynamics::TrackDynamics;
use corrugation::growth::traffic::TrafficScaling;
use corrugation::loads::LoadQuantity;
use corrugation::model_choice::{AccuracyMap, AutoChoice, Candidate, SAFETY, departures};
use corrugation::params::{ContactModelKind, DynamicsKind};
use corrugation::run::{ResumeError, RunSummary, derive, periodic_grid, run_scene, track_dynamics};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Rail corrugation: transient wheel-rail contact, Archard wear, growth.
#[derive(Parser)]
#[command(name = "corrugation", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene and write one HDF5 run file.
    Run {
        /// Scene config (TOML).
        config: PathBuf,
        /// Output file (default: the config's name with .h5, in the current directory).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Override a config key, e.g. --set contact.elements_x=30 (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
    },
    /// Continue a growth study from its run file (a checkpoint or a finished
    /// run), bit for bit as if it had never stopped.
    Resume {
        /// Run file written by `corrugation run` (rewritten atomically).
        file: PathBuf,
        /// Run this many passages more than the file holds (default: up to
        /// the stored growth.passes); extends a finished study.
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
        passes: Option<u32>,
        /// Write the continued run here instead of rewriting FILE.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Validate a config and print derived quantities.
    Check {
        /// Scene config (TOML).
        config: PathBuf,
        /// Override a config key (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        set: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { config, set } => {
            // `check` only prints: end quietly, as other Unix tools do, when
            // the reader of stdout has gone (`corrugation check f | head`).
            reset_sigpipe();
            match load(&config, &set) {
                Ok(r) => {
                    print_check(&r);
                    ExitCode::SUCCESS
                }
                Err(code) => code,
            }
        }
        Command::Run { config, output, set } => {
            let resolved = match load(&config, &set) {
                Ok(r) => r,
                Err(code) => return code,
            };
            let out = output.unwrap_or_else(|| default_output(&config));
            run(&resolved, &out)
        }
        Command::Resume { file, passes, output } => resume(&file, passes.map(|n| n as usize), output.as_deref()),
    }
}

/// Restores the default action of SIGPIPE (end the process), which Rust's
/// runtime sets to ignore, so that printing to a closed pipe ends `check`
/// instead of panicking.
fn reset_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called before any other thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn load(path: &Path, set: &[String]) -> Result<Resolved, ExitCode> {
    config::load_file(path, set).map_err(|e| {
        say_raw!("error: {e}");
        ExitCode::from(2)
    })
}

fn default_output(config: &Path) -> PathBuf {
    let stem = config.file_stem().map(|s| s.to_os_string()).unwrap_or_else(|| "run".into());
    PathBuf::from(stem).with_extension("h5")
}

fn run(resolved: &Resolved, out: &Path) -> ExitCode {
    let passes = resolved.scene.growth.as_ref().map_or(1, |g| g.passes);
    let label = if passes == 1 { "passage".to_string() } else { format!("{passes} passages") };
    let mut bar = progress::Progress::new(&label, resolved.scene.growth.is_some());
    let result = run_scene(resolved, out, &mut |e| bar.event(e));
    bar.finish();
    match result {
        Ok(s) => {
            report(&s, out);
            ExitCode::SUCCESS
        }
        Err(e) => {
            say!("error: {e}");
            say!("{} was not written (or holds the last checkpoint of a growth study)", out.display());
            ExitCode::from(1)
        }
    }
}

fn resume(file: &Path, passes: Option<usize>, output: Option<&Path>) -> ExitCode {
    let mut bar = progress::Progress::new("resume", true);
    let result = corrugation::run::resume(file, passes, output, &mut |e| bar.event(e));
    bar.finish();
    let out = output.unwrap_or(file);
    match result {
        Ok(s) => {
            report(&s, out);
            ExitCode::SUCCESS
        }
        Err(ResumeError::Run(e)) => {
            say!("error: {e}");
            say!("{} holds the last checkpoint", out.display());
            ExitCode::from(1)
        }
        Err(e) => {
            say!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn report(s: &RunSummary, out: &Path) {
    say!(
        "wrote {}: {} passage(s) ({} computed now, {:.3} s CPU), traffic {:.4e}; last passage: max wear {:.4e} m, \
         removed volume {:.4e} m^3; rms corrugation {:.4e} m",
        out.display(),
        s.passes,
        s.computed,
        s.cpu_seconds,
        s.traffic,
        s.max_wear,
        s.removed_volume,
        s.rms_corrugation,
    );
    let (q, pass) = s.max_update_ratio;
    if q > s.update_bound * (1.0 + 1e-9) {
        let effect = if q <= 1.0 {
            format!("growth rates are off by about {:.0} % for standing patterns, more for travelling ones", 50.0 * q)
        } else {
            "harmonics can change sign between updates: growth is spurious".to_string()
        };
        say!(
            "warning: traffic scaling too coarse: the update of passage {pass} changed the corrugation by {q:.3} of \
             its amplitude (bound {}); {effect}. Lower growth.traffic_scale or set growth.adaptive = true.",
            s.update_bound
        );
    }
}

/// What contact.model = "auto" chose and why.
fn print_auto(a: &AutoChoice) {
    let ms = |c: &Candidate| c.cpu_per_step * 1e3;
    println!(
        "auto               tolerance {} (relative centre-line wear error); shortest wavelength {:.4} mm, \
         lambda / 2a_max = {:.3}",
        a.tolerance,
        a.wavelength * 1e3,
        a.lambda_over_2a
    );
    let c = &a.chosen;
    println!(
        "auto choice        {} {} x {}: predicted error {:.4}, {:.3} ms CPU per step (the cheapest within the tolerance)",
        c.model.name(),
        c.mesh,
        c.mesh,
        c.wear_error,
        ms(c)
    );
    if let Some(e) = &a.exact {
        println!(
            "auto exact         exact-transient would need {} x {}: predicted error {:.4}, {:.3} ms CPU per step",
            e.mesh,
            e.mesh,
            e.wear_error,
            ms(e)
        );
    }
    let list: Vec<String> = AccuracyMap::builtin()
        .candidates(a.lambda_over_2a)
        .iter()
        .map(|c| {
            let mark = if c.wear_error <= SAFETY * a.tolerance { "ok" } else { "no" };
            format!("{} {}: {:.3} in {:.2} ms {mark}", c.model.name(), c.mesh, c.wear_error, ms(c))
        })
        .collect();
    println!("auto candidates    (cheapest first) {}", list.join("; "));
}

fn print_check(r: &Resolved) {
    let s = &r.scene;
    let d = derive(s);
    let mm = |v: f64| v * 1e3;
    println!("config OK");
    let by = if s.contact.auto.is_some() { " (chosen by contact.model = \"auto\")" } else { "" };
    println!("contact model      {}{by}", s.contact.model.name());
    if let Some(a) = &s.contact.auto {
        print_auto(a);
        for note in departures(s) {
            println!("note               outside the map's conditions: {note}");
        }
    }
    println!("Hertz a/b          {:.4}", d.shape.aspect());
    if d.patch_min.is_none() {
        println!(
            "contact loss       N <= 0 on part of the stretch (min N = {:.4e} N): no patch there",
            s.loads.min_normal_force()
        );
    }
    for (label, p) in [("mean", Some(d.patch_mean)), ("min", d.patch_min), ("max", Some(d.patch_max))] {
        let Some(p) = p else { continue };
        println!(
            "Hertz at {label:<4} N   N = {:.4e} N: a = {:.4} mm, b = {:.4} mm, p0 = {:.1} MPa, approach = {:.4} mm",
            p.normal_force,
            mm(p.a),
            mm(p.b),
            p.p0 / 1e6,
            mm(p.approach)
        );
    }
    let el = 2.0 * d.patch_mean.a / s.contact.elements_x as f64;
    println!(
        "mesh               {} x {} = {} elements; element length {:.4} mm at mean N",
        s.contact.elements_x,
        s.contact.elements_y,
        s.contact.elements_x * s.contact.elements_y,
        mm(el)
    );
    let p = &d.passage;
    println!(
        "passage            X from {:.4} to {:.4} mm, {} steps of {:.4} mm (dt = {:.4e} s), {} wear sub-steps",
        mm(p.start),
        mm(p.end),
        p.n_steps(),
        mm(p.dt() * p.speed),
        p.dt(),
        p.substeps
    );
    let g = if s.growth.is_some() { periodic_grid(s) } else { d.grid.clone() };
    let periodic = if s.growth.is_some() { " (periodic)" } else { "" };
    println!(
        "rail grid          {} x {} nodes{periodic}, dx = {:.4} mm, dy = {:.4} mm",
        g.nx,
        g.ny,
        mm(g.dx),
        mm(g.dy)
    );
    // Cost model from measurements on 2 cores (README, Performance), per
    // step: wear ~ 20 ns per node visit; FASTSIM ~ 18 ns per element and
    // solve, 25 solves; simplified-transient ~ 3 us per element; the exact
    // model with constant N ~ 60 ms at 400 elements, growing as N^3 (dense
    // LU); with a varying N (harmonics or track dynamics) 2.5 ms at 100 and
    // 175 ms at 400 elements, both fitted by 2.7e-9 N^3 s. The Gauss-Seidel
    // solver (scripts/solver_scaling.sh, wall): 2.4 ms at 100 and 11.8 ms at
    // 400 elements (~N^1.15 while C fits in cache), ~N^2.2 beyond. Measured
    // on the old AMD development machine; the newer Intel one (README,
    // Performance) takes 0.45-0.6 of these times: an upper estimate.
    let n_el = (s.contact.elements_x * s.contact.elements_y) as f64;
    let nodes = std::f64::consts::PI * d.patch_max.a * d.patch_max.b / (g.dx * g.dy);
    let contact = match s.contact.model {
        ContactModelKind::Fastsim => 25.0 * 18e-9 * n_el,
        ContactModelKind::SimplifiedTransient => 3e-6 * n_el,
        ContactModelKind::ExactTransient if s.contact.solver == StepSolver::GaussSeidel => {
            if n_el <= 400.0 {
                2.4e-3 * (n_el / 100.0).powf(1.15)
            } else {
                11.8e-3 * (n_el / 400.0).powf(2.2)
            }
        }
        ContactModelKind::ExactTransient => {
            let varying = s.loads.harmonics.iter().any(|h| h.quantity == LoadQuantity::NormalForce)
                || s.growth.as_ref().is_some_and(|g| g.dynamics != DynamicsKind::Imposed);
            if varying { 2.7e-9 * n_el.powi(3) } else { 0.06 * (n_el / 400.0).powi(3) }
        }
    };
    // With "auto", the map's own measurement of the chosen model.
    let contact = s.contact.auto.map_or(contact, |a| a.chosen.cpu_per_step);
    let secs = p.n_steps() as f64 * (contact + p.substeps as f64 * nodes * 20e-9);
    let passes = s.growth.as_ref().map_or(1, |g| g.passes);
    if let Some(g) = &s.growth {
        match g.traffic {
            TrafficScaling::Fixed { scale, .. } => println!(
                "growth             {} passages x traffic scale {scale} = {:.4e} real passages; dynamics {:?}",
                g.passes,
                g.passes as f64 * scale,
                g.dynamics
            ),
            TrafficScaling::Adaptive { initial, max, max_update_ratio } => println!(
                "growth             {} passages, adaptive traffic scale from {initial} up to {max} (update ratio <= \
                 {max_update_ratio}); dynamics {:?}",
                g.passes, g.dynamics
            ),
        }
        println!("checkpoints        every {} passages; rail stored every {}", g.checkpoint_every, g.store_every);
        if let Some(t) = track_dynamics(s, &d) {
            for (label, f) in t.describe_resonances() {
                println!("resonance          {f:8.1} Hz  {label}");
            }
        }
    }
    println!("estimated cost     {:.1} s on 2 cores (rough, from the benchmarks)", secs * passes as f64);
}
