//! The measurement of a linear growth spectrum: the passages over the
//! supercell (the base rail, the smooth rail, each round's perturbed rails)
//! and each perturbation's response on its class's basis
//! ([`super::bloch`]). A measurement can be split into parts (rounds `t`
//! with `t mod n = k`), each run on its own (a job array's task) and merged
//! ([`Responses::merge`]) before the classes' matrices are assembled.

use super::bloch::{self, Class, Harmonic, Slot};
use super::{Difference, Progress, SpectrumError, SpectrumParams, band, supercell};
use crate::build::study_grid;
use crate::growth::wear_map::WearMap;
use crate::growth::{contact_filtered_line, mean_patch};
use crate::params::Scene;
use ndarray::Array2;
use num_complex::Complex64;
use rustfft::FftPlanner;

/// What a measurement (or a part of one) found.
#[derive(Debug, Clone, PartialEq)]
pub struct Responses {
    /// The supercell's stretches `M`.
    pub cells: usize,
    /// Rails in the model.
    pub rails: usize,
    /// The classes measured.
    pub classes: Vec<Class>,
    /// Each class's perturbations ([`bloch::slots`]).
    pub plan: Vec<Vec<Slot>>,
    /// `columns[class][slot]`: the response to the slot's perturbation on
    /// the class's basis (share-weighted over the traffic classes), empty
    /// where this part did not measure it.
    pub columns: Vec<Vec<Vec<Complex64>>>,
    /// The smooth rail's contact-filtered wear on each rail, the stretch's
    /// harmonics n = 1 .. N/2 (complex amplitudes, m per wheel passage).
    pub forced: Vec<Vec<Complex64>>,
    /// The base rail's, the same way.
    pub base: Vec<Vec<Complex64>>,
    /// The smooth rail's mean wear per wheel passage on each rail (m).
    pub mean_wear: Vec<f64>,
    /// Whether the passages took the linear profile contact.
    pub linear_contact: bool,
    /// Supercell passages run.
    pub passages: usize,
    /// CPU seconds.
    pub cpu_seconds: f64,
    /// Wall-clock seconds.
    pub wall_seconds: f64,
    /// What the user must know.
    pub warnings: Vec<String>,
    /// The dynamics' resonances (label, Hz) of the first traffic class,
    /// for naming the modes.
    pub resonances: Vec<(String, f64)>,
}

/// A measurement's classes, each class's perturbations ([`bloch::slots`])
/// and the rounds they are run in ([`bloch::rounds`]).
pub type Layout = (Vec<Class>, Vec<Vec<Slot>>, Vec<Vec<Slot>>);

/// The classes and their perturbations of `params` on `scene` with
/// `rails` rails.
pub fn layout(scene: &Scene, params: &SpectrumParams, rails: usize) -> Result<Layout, SpectrumError> {
    let cell = study_grid(scene);
    let nodes = cell.nx * params.classes;
    let length = nodes as f64 * cell.dx;
    let (low, high) = band(params, nodes, length).ok_or(SpectrumError::EmptyBand {
        min: params.wavelength_min,
        max: params.wavelength_max,
        length,
        shortest: 2.0 * length / nodes as f64,
    })?;
    let classes = bloch::classes(params.classes, low, high, rails);
    let plan = bloch::slots(&classes);
    let rounds = bloch::rounds(&plan);
    Ok((classes, plan, rounds))
}

/// A measurement of `params` on `scene` with `rails` rails that has
/// measured nothing yet: its classes and plan, every column empty (what a
/// part file's responses are read into).
pub fn empty(scene: &Scene, params: &SpectrumParams, rails: usize) -> Result<Responses, SpectrumError> {
    let (classes, plan, _) = layout(scene, params, rails)?;
    Ok(Responses {
        cells: params.classes,
        rails,
        columns: plan.iter().map(|s| vec![Vec::new(); s.len()]).collect(),
        classes,
        plan,
        forced: Vec::new(),
        base: Vec::new(),
        mean_wear: Vec::new(),
        linear_contact: false,
        passages: 0,
        cpu_seconds: 0.0,
        wall_seconds: 0.0,
        warnings: Vec::new(),
        resonances: Vec::new(),
    })
}

/// Measures the responses of `scene`'s passage about `base` (m, each
/// rail's, on the study's grid) as `params` ask; with `part = Some((k,
/// n))` only the rounds `t` with `t mod n = k` (and the base and smooth
/// rails' passages, which every part runs). With `jobs` > 1 the rounds run
/// on that many threads, each with its own passage model (its own solver
/// and dynamics, built once per thread): the passages are independent, so
/// the responses are the same bit for bit whatever `jobs`.
pub fn measure(
    scene: &Scene,
    base: &[Array2<f64>],
    params: &SpectrumParams,
    part: Option<(usize, usize)>,
    jobs: usize,
    progress: &mut dyn FnMut(Progress),
) -> Result<Responses, SpectrumError> {
    let clock = cpu_time::ProcessTime::now();
    let wall = std::time::Instant::now();
    let cell = study_grid(scene);
    let cells = params.classes;
    let big = supercell(scene, cells);
    let traffic = scene.growth.as_ref().map(|g| g.classes.clone()).unwrap_or_default();
    let mut map = WearMap::new(&big, &traffic)?;
    let grid = map.grid().clone();
    let nodes = grid.nx;
    assert_eq!(nodes, cell.nx * cells, "the supercell's grid is {cells} copies of the stretch's");
    let rails = base.len();
    let (classes, plan, rounds) = layout(scene, params, rails)?;
    let resonances = map.dynamics(0).map(|d| d.describe_resonances()).unwrap_or_default();
    let mine: Vec<usize> = (0..rounds.len()).filter(|t| part.is_none_or(|(k, n)| t % n == k)).collect();
    // The base rails over the supercell.
    let tiled: Vec<Array2<f64>> =
        base.iter().map(|b| Array2::from_shape_fn((grid.ny, nodes), |(j, i)| b[[j, i % cell.nx]])).collect();
    let smooth = tiled.iter().all(|b| b.iter().all(|v| *v == 0.0));
    let b = mean_patch(scene, &map.derived().shape).1;
    let fft = FftPlanner::new().plan_fft_forward(nodes);
    let lines = Lines { grid: &grid, half_width: b, fft: fft.as_ref() };
    let per_round = match params.difference {
        Difference::Central => 2,
        Difference::Forward => 1,
    };
    let shares: Vec<f64> = if traffic.is_empty() { vec![1.0] } else { traffic.iter().map(|c| c.share).collect() };
    let total = shares.len() * (1 + usize::from(!smooth) + per_round * mine.len());
    let mut done = 0;
    let mut step = |done: &mut usize| {
        *done += 1;
        progress(Progress { done: *done, total });
    };
    let mut columns: Vec<Vec<Vec<Complex64>>> = plan.iter().map(|s| vec![Vec::new(); s.len()]).collect();
    let cell_harmonics = cell.nx / 2;
    let mut forced = vec![vec![Complex64::default(); cell_harmonics]; rails];
    let mut base_wear = vec![vec![Complex64::default(); cell_harmonics]; rails];
    let mut mean_wear = vec![0.0; rails];
    let mut warnings = Vec::new();
    // Per traffic class: whether its base passage took the linear contact,
    // and its base wear's lines (forward differences subtract them).
    let mut bases: Vec<(bool, Vec<Vec<f64>>)> = Vec::new();
    let on_cell = |coefficients: &[Complex64], into: &mut [Complex64], share: f64| {
        // The stretch's harmonic n is the supercell's n M.
        for (n, v) in into.iter_mut().enumerate() {
            *v += share * bloch::coefficient(coefficients, ((n + 1) * cells) as i64);
        }
    };
    let fail = |what: String| move |source| SpectrumError::Passage { what, source };
    for (c, share) in shares.iter().enumerate() {
        let refs: Vec<&Array2<f64>> = tiled.iter().collect();
        // The base passage: its wear, and which normal contact it took
        // (every perturbed passage of the class takes the same; the smooth
        // rail's passage chooses its own, as the study's does).
        map.unpin_normal();
        let g = map.passage(c, &refs, false, &mut |_, _| {}).map_err(fail("the base rail's passage".into()))?;
        step(&mut done);
        let base_lines: Vec<Vec<f64>> = g.rails.iter().map(|r| lines.filtered(&r.wear)).collect();
        for (r, line) in base_lines.iter().enumerate() {
            on_cell(&lines.dft(line), &mut base_wear[r], *share);
        }
        let smooth_lines = if smooth {
            base_lines.clone()
        } else {
            let zero = Array2::zeros((grid.ny, nodes));
            let z: Vec<&Array2<f64>> = vec![&zero; rails];
            let g = map.passage(c, &z, false, &mut |_, _| {}).map_err(fail("the smooth rail's passage".into()))?;
            step(&mut done);
            g.rails.iter().map(|r| lines.filtered(&r.wear)).collect()
        };
        for (r, line) in smooth_lines.iter().enumerate() {
            let spectrum = lines.dft(line);
            on_cell(&spectrum, &mut forced[r], *share);
            mean_wear[r] += share * bloch::coefficient(&spectrum, 0).re;
        }
        bases.push((g.linear_contact, base_lines));
    }
    let linear_contact = bases[0].0;
    let rounds_of = Rounds { classes: &classes, rounds: &rounds, tiled: &tiled, params, lines: &lines, bases: &bases };
    // Each traffic class's responses of the rounds, in round order.
    let measured: Vec<Vec<Measured>> = if jobs <= 1 || mine.len() <= 1 {
        (0..shares.len())
            .map(|c| {
                mine.iter()
                    .map(|&t| rounds_of.run(&mut map, c, t, &mut || step(&mut done)))
                    .collect::<Result<Vec<_>, _>>()
            })
            .collect::<Result<_, _>>()?
    } else {
        // Worker 0 is this thread, on the model the base passages ran on
        // (the others' progress reported between its passages); workers 1
        // .. jobs - 1 build their own. A worker that fails stops the others
        // at their next round.
        let jobs = jobs.min(mine.len());
        let stop = std::sync::atomic::AtomicBool::new(false);
        let (tx, rx) = std::sync::mpsc::channel::<()>();
        let work = |w: usize, map: &mut WearMap, tick: &mut dyn FnMut()| -> Result<WorkerRounds, SpectrumError> {
            let mut out = Vec::new();
            for c in 0..rounds_of.bases.len() {
                let mut class = Vec::new();
                for (i, &t) in mine.iter().enumerate().filter(|(i, _)| i % jobs == w) {
                    if stop.load(std::sync::atomic::Ordering::Relaxed) {
                        return Err(SpectrumError::Stopped);
                    }
                    let m = rounds_of.run(map, c, t, tick);
                    if m.is_err() {
                        stop.store(true, std::sync::atomic::Ordering::Relaxed);
                    }
                    class.push((i, m?));
                }
                out.push(class);
            }
            Ok(out)
        };
        let results: Vec<Result<WorkerRounds, SpectrumError>> = std::thread::scope(|s| {
            let handles: Vec<_> = (1..jobs)
                .map(|w| {
                    let (tx, big, traffic, work, stop) = (tx.clone(), &big, &traffic, &work, &stop);
                    s.spawn(move || {
                        let mut map = WearMap::new(big, traffic).inspect_err(|_| {
                            stop.store(true, std::sync::atomic::Ordering::Relaxed);
                        })?;
                        work(w, &mut map, &mut || {
                            let _ = tx.send(());
                        })
                    })
                })
                .collect();
            drop(tx);
            let own = work(0, &mut map, &mut || {
                step(&mut done);
                for () in rx.try_iter() {
                    step(&mut done);
                }
            });
            for () in rx {
                step(&mut done);
            }
            std::iter::once(own)
                .chain(handles.into_iter().map(|h| h.join().expect("a spectrum worker panicked")))
                .collect()
        });
        // The first failure that is not a stop (a passage's, a set-up's).
        let failed =
            |r: &Result<WorkerRounds, SpectrumError>| matches!(r, Err(e) if !matches!(e, SpectrumError::Stopped));
        if let Some(i) = results.iter().position(failed) {
            return Err(results.into_iter().nth(i).expect("found").expect_err("failed"));
        }
        let mut per_class: Vec<Vec<Option<Measured>>> = vec![vec![None; mine.len()]; shares.len()];
        for worker in results {
            for (c, class) in worker?.into_iter().enumerate() {
                for (i, m) in class {
                    per_class[c][i] = Some(m);
                }
            }
        }
        per_class.into_iter().map(|c| c.into_iter().map(|m| m.expect("every round measured")).collect()).collect()
    };
    // Accumulated in the traffic classes' order, round by round: the same
    // sums whatever the threads.
    for (c, share) in shares.iter().enumerate() {
        for (&t, m) in mine.iter().zip(&measured[c]) {
            warnings.extend(m.warnings.iter().cloned());
            for (slot, response) in rounds[t].iter().zip(&m.responses) {
                let column = &mut columns[slot.class][t];
                let weighted = response.iter().map(|v| share * *v);
                if column.is_empty() {
                    *column = weighted.collect();
                } else {
                    column.iter_mut().zip(weighted).for_each(|(a, b)| *a += b);
                }
            }
        }
    }
    Ok(Responses {
        cells,
        rails,
        classes,
        plan,
        columns,
        forced,
        base: base_wear,
        mean_wear,
        linear_contact,
        passages: done,
        cpu_seconds: clock.elapsed().as_secs_f64(),
        wall_seconds: wall.elapsed().as_secs_f64(),
        warnings,
        resonances,
    })
}

/// The contact-filtered line of a passage's wear and its spectrum.
struct Lines<'a> {
    grid: &'a crate::rail_grid::RailGrid,
    /// Half-width of the mean patch (m), the filter's.
    half_width: f64,
    fft: &'a dyn rustfft::Fft<f64>,
}

impl Lines<'_> {
    fn filtered(&self, w: &Array2<f64>) -> Vec<f64> {
        contact_filtered_line(w, self.grid, self.half_width)
    }

    fn dft(&self, line: &[f64]) -> Vec<Complex64> {
        let mut buf: Vec<Complex64> = line.iter().map(|v| Complex64::new(*v, 0.0)).collect();
        self.fft.process(&mut buf);
        buf
    }
}

/// One round's responses of one traffic class: per slot of the round, on
/// its class's basis (before the class's share), and what to warn of.
#[derive(Debug, Clone)]
struct Measured {
    responses: Vec<Vec<Complex64>>,
    warnings: Vec<String>,
}

/// A worker thread's rounds: per traffic class, (the round's place among
/// those measured, its responses).
type WorkerRounds = Vec<Vec<(usize, Measured)>>;

/// What a round's passages need.
struct Rounds<'a> {
    classes: &'a [Class],
    rounds: &'a [Vec<Slot>],
    tiled: &'a [Array2<f64>],
    params: &'a SpectrumParams,
    lines: &'a Lines<'a>,
    /// Per traffic class: its base passage's normal contact (linear or
    /// not) and wear lines.
    bases: &'a [(bool, Vec<Vec<f64>>)],
}

impl Rounds<'_> {
    /// Round `t`'s perturbed passages of traffic class `c` on `map`
    /// (`tick` after each passage) and their responses.
    fn run(&self, map: &mut WearMap, c: usize, t: usize, tick: &mut dyn FnMut()) -> Result<Measured, SpectrumError> {
        let round = &self.rounds[t];
        let (linear_contact, base_lines) = &self.bases[c];
        map.pin_normal(*linear_contact);
        let (ny, nodes) = self.tiled[0].dim();
        // A round carries one perturbation of each of its K classes: each
        // of amplitude eps / sqrt(K), so that the passage's perturbation is
        // the size of one harmonic of amplitude eps however many classes it
        // measures (its responses scaled back).
        let spread = if round.len() > 1 { (round.len() as f64).sqrt() } else { 1.0 };
        let perturbed = |sign: f64| -> Vec<Array2<f64>> {
            self.tiled
                .iter()
                .enumerate()
                .map(|(r, b)| {
                    let d = bloch::perturbation(round, r, nodes, sign * self.params.perturbation / spread);
                    Array2::from_shape_fn((ny, nodes), |(j, i)| b[[j, i]] + d[i])
                })
                .collect()
        };
        let mut warnings = Vec::new();
        let mut run = |profiles: Vec<Array2<f64>>, what: String| -> Result<Vec<Vec<f64>>, SpectrumError> {
            let refs: Vec<&Array2<f64>> = profiles.iter().collect();
            let g = map
                .passage(c, &refs, false, &mut |_, _| {})
                .map_err(|source| SpectrumError::Passage { what: what.clone(), source })?;
            tick();
            if g.linear_contact != *linear_contact || g.rerun.is_some() {
                warnings.push(format!("{what} took another normal contact than the base rail's"));
            }
            for (r, rail) in g.rails.iter().enumerate() {
                if rail.clipped_steps > 0 || rail.contact_loss_steps > 0 {
                    warnings.push(format!(
                        "{what}: rail {r} left the linear range ({} steps with the patch opened inside, {} without \
                         contact): lower spectrum.perturbation",
                        rail.clipped_steps, rail.contact_loss_steps
                    ));
                }
            }
            Ok(g.rails.iter().map(|r| self.lines.filtered(&r.wear)).collect())
        };
        let count = self.rounds.len();
        let plus = run(perturbed(1.0), format!("round {} of {count}, +", t + 1))?;
        let lines: Vec<Vec<f64>> = match self.params.difference {
            Difference::Central => {
                let minus = run(perturbed(-1.0), format!("round {} of {count}, -", t + 1))?;
                plus.iter().zip(&minus).map(|(p, m)| p.iter().zip(m).map(|(a, b)| 0.5 * (a - b)).collect()).collect()
            }
            Difference::Forward => {
                plus.iter().zip(base_lines).map(|(p, m)| p.iter().zip(m).map(|(a, b)| a - b).collect()).collect()
            }
        };
        let spectra: Vec<Vec<Complex64>> = lines.iter().map(|l| self.lines.dft(l)).collect();
        let responses = round
            .iter()
            .map(|slot| {
                self.classes[slot.class]
                    .basis
                    .iter()
                    .map(|h: &Harmonic| spread * bloch::coefficient(&spectra[h.rail], h.index))
                    .collect()
            })
            .collect();
        Ok(Measured { responses, warnings })
    }
}

impl Responses {
    /// The measurement of all `parts` (each a part of the same measurement:
    /// the same classes, the smooth and base rails' passages, disjoint
    /// rounds): their columns together, their passages and seconds summed.
    pub fn merge(parts: Vec<Responses>) -> Result<Responses, SpectrumError> {
        let mut iter = parts.into_iter();
        let Some(mut all) = iter.next() else {
            return Err(SpectrumError::Parts("no part to merge".into()));
        };
        for p in iter {
            if p.classes != all.classes || p.plan != all.plan || p.cells != all.cells || p.rails != all.rails {
                return Err(SpectrumError::Parts("the parts are of different measurements (classes, band)".into()));
            }
            if p.forced != all.forced || p.base != all.base {
                return Err(SpectrumError::Parts(
                    "the parts' smooth or base rail passages differ (another config or base rail)".into(),
                ));
            }
            for (mine, theirs) in all.columns.iter_mut().zip(p.columns) {
                for (a, b) in mine.iter_mut().zip(theirs) {
                    match (a.is_empty(), b.is_empty()) {
                        (true, false) => *a = b,
                        (false, false) => {
                            return Err(SpectrumError::Parts("two parts measured the same perturbation".into()));
                        }
                        _ => {}
                    }
                }
            }
            all.passages += p.passages;
            all.cpu_seconds += p.cpu_seconds;
            all.wall_seconds = all.wall_seconds.max(p.wall_seconds);
            all.warnings.extend(p.warnings);
        }
        Ok(all)
    }
}
