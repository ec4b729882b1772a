//! The creep forces' frequency response of a scene's contact
//! (`corrugation::dynamics::coupling::creep_response`), written as a CSV against the
//! reduced frequency `w a0 / V`.
//!
//! `cargo run --release --example creep_response -- CONFIG OUT.csv [KEY=VALUE ...]`
//!
//! Keys: `set=SECTION.KEY=VALUE` (a config override, repeatable),
//! `level` (the creepages' and spin's), `level_n` (the normal force's), `period` (patch lengths 2 a0), `run_in`, `lead` (patch
//! lengths), `max_reduced`, `step` (m, adapted mesh only), `inputs` (any of
//! `x`, `y`, `s`, `n`: the creepages, spin, normal force), `normal_force`,
//! `longitudinal_force` (N, the mean state; default the scene's). The
//! measurement's wall and CPU time go to stderr.

use corrugation::build::creep_response as scene;
use corrugation::dynamics::coupling::creep_response::Input;
use std::io::Write;
use std::time::Instant;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(args.len() >= 2, "usage: creep_response CONFIG OUT.csv [KEY=VALUE ...]");
    let mut sets = Vec::new();
    let mut opts = std::collections::BTreeMap::new();
    for a in &args[2..] {
        let (k, v) = a.split_once('=').ok_or_else(|| anyhow::anyhow!("{a}: expected KEY=VALUE"))?;
        if k == "set" {
            sets.push(v.to_string());
        } else {
            opts.insert(k.to_string(), v.to_string());
        }
    }
    let resolved = corrugation::config::load_file(std::path::Path::new(&args[0]), &sets)?;
    let sc = resolved.scene;
    let num = |k: &str| -> anyhow::Result<Option<f64>> {
        opts.get(k).map(|v| v.parse::<f64>()).transpose().map_err(Into::into)
    };
    let n0 = num("normal_force")?.unwrap_or(sc.loads.normal_force);
    let f0 = num("longitudinal_force")?.unwrap_or(sc.loads.longitudinal_force);
    let mean = scene::mean_state(&sc, n0, f0);
    let shape = scene::shape(&sc);
    let mut ex = scene::default_excitation(&sc, &shape, &mean)?;
    let two_a = 2.0 * shape.patch(n0)?.a;
    if let Some(v) = num("level")? {
        ex.level = [v, v, v, ex.level[3]];
    }
    if let Some(v) = num("level_n")? {
        ex.level[3] = v;
    }
    if let Some(v) = num("period")? {
        ex.period = v * two_a;
    }
    if let Some(v) = num("run_in")? {
        ex.run_in = v * two_a;
    }
    if let Some(v) = num("lead")? {
        ex.lead = v * two_a;
    }
    if let Some(v) = num("max_reduced")? {
        ex.max_reduced = v;
    }
    if let Some(v) = num("step")? {
        ex.step = v;
    }
    if let Some(v) = opts.get("inputs") {
        ex.inputs = ['x', 'y', 's', 'n'].map(|c| v.contains(c));
    }
    let (clock, cpu) = (Instant::now(), cpu_time::ProcessTime::now());
    let r = scene::response(&sc, &mean, &ex, &|| corrugation::build::build_solver(&sc, &scene::shape(&sc)))?;
    let (wall, cpu) = (clock.elapsed().as_secs_f64(), cpu.elapsed().as_secs_f64());
    eprintln!(
        "wall {wall:.3} s, cpu {cpu:.3} s; a0 = {:.4e} m, xi_x0 = {:.6e}, F0 = ({:.6e}, {:.6e}) N, {} points to w a0/V = {:.3}",
        r.semi_axis,
        r.creepage_x,
        r.force[0],
        r.force[1],
        r.reduced.len(),
        r.max_reduced()
    );
    let mut out = std::io::BufWriter::new(std::fs::File::create(&args[1])?);
    writeln!(out, "# creep response of {} (corrugation::dynamics::coupling::creep_response)", args[0])?;
    writeln!(
        out,
        "# N0 = {n0} N, mean longitudinal {:?}, xi_x0 = {:.8e}, V = {} m/s, a0 = {:.6e} m; H = dF/dq on the wheel, exp(+i w t)",
        mean.longitudinal, r.creepage_x, mean.speed, r.semi_axis
    )?;
    write!(out, "reduced_frequency,frequency_hz,wavelength_m")?;
    for row in ["fx", "fy"] {
        for i in Input::ALL {
            write!(out, ",{row}_{0}_re,{row}_{0}_im", i.name())?;
        }
    }
    writeln!(out)?;
    for (w, h) in r.reduced.iter().zip(&r.table) {
        let f = w * mean.speed / (2.0 * std::f64::consts::PI * r.semi_axis);
        let lambda = if *w > 0.0 { 2.0 * std::f64::consts::PI * r.semi_axis / w } else { f64::INFINITY };
        write!(out, "{w:.6},{f:.6},{lambda:.6e}")?;
        for row in h {
            for c in row {
                write!(out, ",{:.9e},{:.9e}", c.re, c.im)?;
            }
        }
        writeln!(out)?;
    }
    Ok(())
}
