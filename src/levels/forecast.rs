//! When a band reaches its limit: the wheel passages from a passage until
//! the band's level reaches the limit, and the same traffic in the
//! operator's units (million gross tonnes, days).
//!
//! A band's roughness grows two ways at once (book:
//! docs/src/theory/growth-spectrum.md): exponentially, at the
//! roughness-driven rate `r` of its level (dB per 1e5 wheel passages, the
//! change by the wear less the smooth rail's), and linearly, by the forced
//! pattern the smooth rail wears (`f`, m rms per wheel passage: the
//! sleeper passing, imposed loads). Per harmonic, `dR/dn = s R + F` gives
//! `R(n) = R0 e^(s n) + F (e^(s n) - 1) / s`; over a band's harmonics,
//! whose roughness and forced pattern have unrelated phases, the mean
//! squares add:
//!
//! ```text
//! A(n)^2 = A0^2 e^(2 s n) + f^2 ((e^(s n) - 1) / s)^2,   s = r ln(10) / (20 1e5)
//! ```
//!
//! (`A0 = r0 10^(L/20)` the band's rms now). The forecast is the first `n`
//! at which `A(n)` reaches the limit's rms: `(L_lim - L) / r 1e5` where
//! there is no forced pattern; 0 for a band at or above it; inf where the
//! band never reaches it (a decaying band whose forced pattern settles
//! below the limit, at `f / |s|`). A band that held no roughness of its
//! own at the start (below [`HELD_LEVEL`]) is driven by the others' wear
//! rather than grown from itself, however far they have raised it: its
//! roughness-driven change per passage counts as a forcing, not as an
//! exponential rate.
//!
//! This is the linear regime's forecast; a saturating band reaches its
//! limit later than it says.
//!
//! Traffic: one wheel passage of the rail is one axle passage of the
//! track, so `MGT = sum of axle loads (t) / 1e6` and `days = passages /
//! axles per day`.

use super::Band;

/// Wheel passages from a band at `level` (dB re 1 um) whose roughness
/// grows at `rate` (dB per 1e5 wheel passages) and by the forced pattern
/// `forced` (m rms per wheel passage) until it reaches `limit` (dB re 1
/// um; see the module doc).
pub fn passages_to_limit(level: f64, rate: f64, forced: f64, limit: f64) -> f64 {
    if level >= limit {
        return 0.0;
    }
    if forced.is_nan() || forced <= 0.0 || !limit.is_finite() {
        return if rate > 0.0 { (limit - level) / rate * 1e5 } else { f64::INFINITY };
    }
    let (a0, target) = (super::R0 * 10f64.powf(level / 20.0), super::R0 * 10f64.powf(limit / 20.0));
    let s = rate * std::f64::consts::LN_10 / 20.0 / 1e5;
    let amplitude = |n: f64| {
        let grown = if (s * n).abs() < 1e-8 { n } else { (s * n).exp_m1() / s };
        ((a0 * (s * n).exp()).powi(2) + (forced * grown).powi(2)).sqrt()
    };
    // The amplitude can fall first (a decaying band) and rise again.
    first_crossing(&amplitude, target)
}

/// The first traffic `n` (wheel passages, from 1 to 1e15) at which `value(n)`
/// reaches `target`: a scan by factors of 1.1 from one passage, then
/// bisection in the first bracket (a value that falls first and rises again
/// is caught at its rise); inf where it never does.
pub fn first_crossing(value: &dyn Fn(f64) -> f64, target: f64) -> f64 {
    let mut low = 0.0;
    let mut n = 1.0;
    while n <= 1e15 {
        if value(n) >= target {
            let mut high = n;
            for _ in 0..200 {
                let mid = 0.5 * (low + high);
                if value(mid) >= target {
                    high = mid
                } else {
                    low = mid
                }
                if high - low <= 1e-12 * high {
                    break;
                }
            }
            return high;
        }
        low = n;
        n *= 1.1;
    }
    f64::INFINITY
}

/// A band's roughness-driven rate and forcing for the forecast, from its
/// level `initial` before the study's first passage and its levels
/// `before` and `after` a passage of `scale` wheel passages (dB re 1 um),
/// the passage's roughness-driven `rate` (dB per 1e5 wheel passages) and
/// forced pattern `forced` (m rms per wheel passage). A band that held no
/// roughness of its own at the start (at or below [`HELD_LEVEL`]) and that
/// the others' wear raised is driven rather than grown from itself,
/// however high the others have raised it since (a band fed by its
/// neighbours through the sleepers rises at a rate that falls as its
/// level rises, and extrapolated as exponential growth it would cross any
/// limit): the rise per wheel passage counts as a forcing (added to
/// `forced` in mean square) and its exponential rate as 0. The
/// rise is `A_before (10^(rate scale / 20 1e5) - 1)`, or, from the floor
/// (no rate: an empty band), what of `A_after` the forced pattern does
/// not explain, `sqrt(A_after^2 - (scale forced)^2)`. A held band that
/// the wear lowers keeps its (decaying) rate (see the module doc).
pub fn driven(initial: f64, before: f64, after: f64, rate: f64, scale: f64, forced: f64) -> (f64, f64) {
    if initial > HELD_LEVEL || rate < 0.0 || scale.is_nan() || scale <= 0.0 {
        return (rate, forced);
    }
    let amplitude = |l: f64| super::R0 * 10f64.powf(l / 20.0);
    let rise = if before <= super::LEVEL_FLOOR {
        let new = amplitude(after);
        (new * new - (scale * forced).powi(2)).max(0.0).sqrt()
    } else {
        amplitude(before) * (10f64.powf(rate * scale / 20.0 / 1e5) - 1.0)
    };
    (0.0, forced.hypot(rise / scale))
}

/// The bands that reached their limit between the levels `before` and
/// `after` (dB): below it before, at or above it after.
pub fn crossed(before: &[f64], after: &[f64], limit: &[f64]) -> Vec<usize> {
    (0..limit.len()).filter(|&k| before[k] < limit[k] && after[k] >= limit[k]).collect()
}

/// Converts wheel passages of the rail into the operator's units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Units {
    /// Mean gross mass per wheel passage (t), where the axle loads are given.
    pub tonnes_per_passage: Option<f64>,
    /// Axles (wheel passages of the rail) per day, where given.
    pub axles_per_day: Option<f64>,
}

impl Units {
    /// The units of traffic classes of gross masses per axle `axle_loads`
    /// (kg, in class order; None: no tonnes) and `shares` (1, summing to 1;
    /// the mean axle load weighs the classes by them), `axles_per_day` over
    /// the rail (None: no days).
    pub fn new(axle_loads: Option<&[f64]>, axles_per_day: Option<f64>, shares: &[f64]) -> Self {
        let tonnes = axle_loads.map(|a| a.iter().zip(shares).map(|(m, s)| m * s).sum::<f64>() * 1e-3);
        Units { tonnes_per_passage: tonnes, axles_per_day }
    }

    /// Million gross tonnes of `passages` wheel passages.
    pub fn mgt(&self, passages: f64) -> Option<f64> {
        self.tonnes_per_passage.map(|t| passages * t * 1e-6)
    }

    /// Days of `passages` wheel passages.
    pub fn days(&self, passages: f64) -> Option<f64> {
        self.axles_per_day.map(|a| passages / a)
    }

    /// `passages` in words: "2.1 MGT, 140 days at 4000 axles per day (3.4e6
    /// wheel passages)".
    pub fn describe(&self, passages: f64) -> String {
        let mut parts = Vec::new();
        if let Some(m) = self.mgt(passages) {
            parts.push(format!("{} MGT", short(m)));
        }
        if let (Some(d), Some(a)) = (self.days(passages), self.axles_per_day) {
            let years = if d >= 365.25 { format!(" ({} years)", short(d / 365.25)) } else { String::new() };
            parts.push(format!("{} days{years} at {} axles per day", short(d), short(a)));
        }
        let count = format!("{passages:.2e} wheel passages");
        if parts.is_empty() { count } else { format!("{} ({count})", parts.join(", ")) }
    }
}

/// Cumulative million gross tonnes after each passage of `rows` ((class,
/// real passages it stood for)), with each class's axle load (kg).
pub fn cumulative_mgt(rows: &[(usize, f64)], axle_loads: &[f64]) -> Vec<f64> {
    let mut total = 0.0;
    rows.iter()
        .map(|(class, m)| {
            total += m * axle_loads.get(*class).copied().unwrap_or(0.0) * 1e-9;
            total
        })
        .collect()
}

/// A number as a person writes it: two significant digits below 100,
/// whole above.
fn short(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x.abs() >= 100.0 {
        return format!("{x:.0}");
    }
    let digits = if x == 0.0 { 0 } else { (1 - x.abs().log10().floor() as i32).max(0) as usize };
    format!("{x:.digits$}")
}

/// The level (dB re 1 um, 1 nm rms) below which a band counts as absent
/// from the initial roughness (the level of an empty band is -120 dB).
pub const HELD_LEVEL: f64 = -60.0;

/// Where a run stands against the limit after its last passage.
#[derive(Debug, Clone)]
pub struct Standing<'a> {
    /// The bands.
    pub bands: &'a [Band],
    /// Each band's limit (dB re 1 um; inf: none).
    pub limit: &'a [f64],
    /// The limit's name ("ISO 3095").
    pub limit_name: &'a str,
    /// Levels before the first passage (dB re 1 um).
    pub initial: &'a [f64],
    /// Levels after each passage (dB re 1 um).
    pub levels: &'a [Vec<f64>],
    /// Roughness-driven rates of each passage (dB per 1e5 wheel passages).
    pub rates: &'a [Vec<f64>],
    /// The forced pattern of each passage's class in each band (m rms per
    /// wheel passage; empty rows: none).
    pub forced: &'a [Vec<f64>],
    /// Real wheel passages represented after each passage.
    pub traffic: &'a [f64],
    /// The operator's units.
    pub units: Units,
}

/// Beyond this many times the traffic a study simulated, its forecast says
/// that it extrapolates.
const EXTRAPOLATION: f64 = 3.0;

/// The run's last lines about the limit: where a band first reached it,
/// which band reaches it next at the last passage's rates and when, and
/// which bands are above it.
pub fn outlook(s: &Standing) -> Vec<String> {
    let mut lines = Vec::new();
    let (Some(last), Some(rates), Some(&so_far)) = (s.levels.last(), s.rates.last(), s.traffic.last()) else {
        return lines;
    };
    if s.bands.is_empty() {
        return vec![
            "no one-third-octave band is resolved on this stretch (a band needs a quarter of its length)".into(),
        ];
    }
    let name = crate::levels::limit::limit_words(s.limit_name);
    let finite = s.limit.iter().any(|l| l.is_finite());
    if !finite {
        return lines;
    }
    // The first crossing during the run.
    let mut before = s.initial;
    for (p, after) in s.levels.iter().enumerate() {
        if let Some(&k) = crossed(before, after, s.limit).first() {
            lines.push(format!(
                "the {} band reached the {name} ({:.1} dB re 1 um) in passage {}, after {}",
                s.bands[k].label(),
                s.limit[k],
                p + 1,
                s.units.describe(s.traffic[p])
            ));
            break;
        }
        before = after;
    }
    let pass = s.levels.len();
    let forced = s.forced.last().map_or(&[][..], Vec::as_slice);
    let (first, scale) = match pass {
        1 => (s.initial, so_far),
        _ => (s.levels[pass - 2].as_slice(), so_far - s.traffic[pass - 2]),
    };
    let model =
        |k: usize| driven(s.initial[k], first[k], last[k], rates[k], scale, forced.get(k).copied().unwrap_or(0.0));
    let to_limit: Vec<f64> = (0..s.bands.len())
        .map(|k| {
            let (rate, f) = model(k);
            passages_to_limit(last[k], rate, f, s.limit[k])
        })
        .collect();
    let growing = |k: &usize| to_limit[*k] > 0.0 && to_limit[*k].is_finite();
    let next = (0..s.bands.len()).filter(growing).min_by(|&a, &b| to_limit[a].total_cmp(&to_limit[b]));
    match next {
        Some(k) => {
            let (rate, f) = model(k);
            let column: Vec<f64> = s.levels.iter().map(|l| l[k]).collect();
            let slower = power_law(&column, s.traffic, rate).filter(|_| f == 0.0).map_or_else(String::new, |p| {
                format!(
                    "; but its amplitude has grown as traffic^{p:.2} (not exponentially): at that pace it reaches the \
                     limit after {}",
                    s.units.describe(so_far * 10f64.powf((s.limit[k] - last[k]) / (20.0 * p)))
                )
            });
            let how = match (rate != 0.0, f > 0.0) {
                (true, true) => format!(
                    "growing at {rate:+.2} dB per 1e5 wheel passages from {:.1} dB and by the forced pattern's \
                     {:.3} um rms per 1e5 wheel passages",
                    last[k],
                    f * 1e5 * 1e6
                ),
                (false, true) => format!(
                    "worn in by the forced pattern's {:.3} um rms per 1e5 wheel passages from {:.1} dB",
                    f * 1e5 * 1e6,
                    last[k]
                ),
                _ => format!("{rate:+.2} dB per 1e5 wheel passages from {:.1} dB", last[k]),
            };
            let total = so_far + to_limit[k];
            let far = if total > EXTRAPOLATION * so_far {
                format!("; {:.0} times the traffic simulated: an extrapolation", total / so_far)
            } else {
                String::new()
            };
            lines.push(format!(
                "the {} band reaches the {name} ({:.1} dB re 1 um) after {} from the start, at passage \
                 {pass}'s rates ({how}){slower}{far}",
                s.bands[k].label(),
                s.limit[k],
                s.units.describe(total),
            ))
        }
        None => lines.push(format!("at passage {pass}'s rates no band below the {name} grows towards it")),
    }
    let above: Vec<usize> = (0..s.bands.len()).filter(|&k| to_limit[k] == 0.0).collect();
    if !above.is_empty() {
        let list: Vec<String> =
            above.iter().map(|&k| format!("{} (by {:.1} dB)", s.bands[k].label(), last[k] - s.limit[k])).collect();
        lines.push(format!("above the {name} after passage {pass}: {}", list.join(", ")));
    }
    if s.units.tonnes_per_passage.is_none() || s.units.axles_per_day.is_none() {
        lines.push("(traffic.axle_load and traffic.axles_per_day give these in million gross tonnes and days)".into());
    }
    lines
}

/// The exponent `p` of a band whose amplitude has grown as a power of the
/// traffic, `A ~ T^p` (its level as `20 p lg T`: wear that adds to the
/// profile without feeding back, `p = 1`, rather than the exponential
/// growth of the linear regime), if it has: over the second half of the
/// run in traffic (from the last passage at most half the final traffic)
/// the level rose by `20 p lg(T_n / T_h)` with `p` in [0.5, 2], and the last
/// rate agrees, `rate = 20 p / (ln 10 T_n) 1e5`, within 20 %. An
/// exponential growth fails the test: its rate is `x ln x / (x - 1)`
/// (1.39 at `x = T_n/T_h = 2`) times the power law's.
pub fn power_law(levels: &[f64], traffic: &[f64], rate: f64) -> Option<f64> {
    let (&t_n, &l_n) = (traffic.last()?, levels.last()?);
    let h = traffic.iter().rposition(|t| *t <= 0.5 * t_n)?;
    let (t_h, l_h) = (traffic[h], levels[h]);
    if !(t_h > 0.0 && l_h > super::LEVEL_FLOOR) {
        return None;
    }
    let p = (l_n - l_h) / (20.0 * (t_n / t_h).log10());
    let p_rate = rate * t_n / 1e5 * std::f64::consts::LN_10 / 20.0;
    ((0.5..=2.0).contains(&p) && (p_rate / p - 1.0).abs() < 0.2).then_some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passages_to_limit_follows_the_level_and_rate() {
        // No forced pattern: 5 dB below, 0.5 dB per 1e5: 1e6 passages.
        assert_eq!(passages_to_limit(10.0, 0.5, 0.0, 15.0), 1e6);
        assert_eq!(passages_to_limit(15.0, 0.5, 0.0, 15.0), 0.0);
        assert_eq!(passages_to_limit(16.0, -0.5, 0.0, 15.0), 0.0);
        assert_eq!(passages_to_limit(10.0, 0.0, 0.0, 15.0), f64::INFINITY);
        assert_eq!(passages_to_limit(10.0, -1.0, 0.0, 15.0), f64::INFINITY);
        assert_eq!(passages_to_limit(10.0, 1.0, 0.0, f64::INFINITY), f64::INFINITY);
        // Consistent: the level at the forecast traffic is the limit.
        let (l, r, lim) = (-3.7, 0.83, 2.9);
        let n = passages_to_limit(l, r, 0.0, lim);
        assert!((l + r * n / 1e5 - lim).abs() < 1e-12);
    }

    #[test]
    fn a_forced_pattern_adds_its_linear_growth_to_the_exponential_one() {
        let rms = |l: f64| 1e-6 * 10f64.powf(l / 20.0);
        // No exponential growth: A(n)^2 = A0^2 + (f n)^2, closed form.
        let (l, f, lim) = (-10.0, 2e-12, 0.0);
        let want = (rms(lim).powi(2) - rms(l).powi(2)).sqrt() / f;
        let n = passages_to_limit(l, 0.0, f, lim);
        assert!((n / want - 1.0).abs() < 1e-9, "{n} vs {want}");
        // From nothing (the floor): the forced pattern's own pace, A_lim / f.
        let n = passages_to_limit(-120.0, 0.0, f, lim);
        assert!((n / (rms(lim) / f) - 1.0).abs() < 1e-6, "{n}");
        // Growing and forced: sooner than either alone; the amplitude of
        // the model at the forecast is the limit's.
        let (l, r, f, lim) = (-6.0, 0.8, 1e-12, 3.0);
        let n = passages_to_limit(l, r, f, lim);
        assert!(n < passages_to_limit(l, r, 0.0, lim) && n < passages_to_limit(l, 0.0, f, lim));
        let s = r * std::f64::consts::LN_10 / 20.0 / 1e5;
        let a = ((rms(l) * (s * n).exp()).powi(2) + (f * (s * n).exp_m1() / s).powi(2)).sqrt();
        assert!((a / rms(lim) - 1.0).abs() < 1e-9, "{a} vs {}", rms(lim));
        // Decaying: the forced pattern settles at f / |s|: below the limit
        // never, above it at a finite traffic (after the decay's dip).
        let s = -0.5 * std::f64::consts::LN_10 / 20.0 / 1e5;
        assert_eq!(passages_to_limit(-6.0, -0.5, 0.5 * rms(0.0) * s.abs(), 0.0), f64::INFINITY);
        let n = passages_to_limit(-6.0, -0.5, 2.0 * rms(0.0) * s.abs(), 0.0);
        assert!(n.is_finite() && n > 0.0, "{n}");
        // A band holding no roughness of its own: its driven rise is a
        // forcing, not an exponential rate from 1 nm. 30 dB over a passage
        // of 1e3 wheel passages from -90 dB: A_before (10^1.5 - 1) / 1e3.
        let (rate, forced) = driven(-90.0, -90.0, -60.0, 30.0 * 1e5 / 1e3, 1e3, 0.0);
        assert_eq!(rate, 0.0);
        assert!((forced / (rms(-90.0) * (10f64.powf(1.5) - 1.0) / 1e3) - 1.0).abs() < 1e-12, "{forced}");
        // Its own roughness grows exponentially; a held band the wear
        // lowers decays at its rate.
        assert_eq!(driven(-20.0, -20.0, -19.0, 2.0, 1e3, 1e-12), (2.0, 1e-12));
        assert_eq!(driven(-80.0, -80.0, -81.0, -2.0, 1e3, 1e-12), (-2.0, 1e-12));
        // From the floor: what the forced pattern does not explain of the
        // new amplitude (3-4-5: the forced part 0.6 of it).
        let new = rms(-70.0);
        let (rate, forced) = driven(-120.0, -120.0, -70.0, 0.0, 1e3, 0.6 * new / 1e3);
        assert_eq!(rate, 0.0);
        assert!((forced / (new / 1e3) - 1.0).abs() < 1e-12, "{forced}");
        // A band empty at the start stays driven once the others have
        // raised it above the held level: its rise per passage is the
        // forcing (-42 -> -40.6 dB over 3.3e4 wheel passages, rate
        // +4 dB per 1e5), and it reaches -8.6 dB in proportion to the
        // traffic, not exponentially.
        let (b, a, scale) = (-42.0, -40.6, 3.3e4);
        let rate = (a - b) / scale * 1e5;
        let (r, f) = driven(-120.0, b, a, rate, scale, 0.0);
        assert_eq!(r, 0.0);
        assert!((f * scale / (rms(a) - rms(b)) - 1.0).abs() < 1e-12, "{f}");
        let n = passages_to_limit(a, r, f, -8.6);
        let want = (rms(-8.6).powi(2) - rms(a).powi(2)).sqrt() / f;
        assert!((n / want - 1.0).abs() < 1e-9, "{n} vs {want}");
        assert!(n > 10.0 * passages_to_limit(a, rate, 0.0, -8.6), "{n}");
    }

    #[test]
    fn a_power_law_is_told_from_exponential_growth() {
        // Amplitude proportional to traffic: L = 20 lg T + c, rate 20/(ln 10 T) 1e5.
        let traffic: Vec<f64> = (1..=20).map(|k| 1e4 * k as f64).collect();
        let linear: Vec<f64> = traffic.iter().map(|t| 20.0 * t.log10() - 100.0).collect();
        let rate = 20.0 / (std::f64::consts::LN_10 * 2e5) * 1e5;
        assert!((power_law(&linear, &traffic, rate).unwrap() - 1.0).abs() < 1e-9);
        // Exponential growth at 1 dB per 1e5: not a power law.
        let exponential: Vec<f64> = traffic.iter().map(|t| -30.0 + t / 1e5).collect();
        assert_eq!(power_law(&exponential, &traffic, 1.0), None);
        assert_eq!(power_law(&linear[..1], &traffic[..1], rate), None);
    }

    #[test]
    fn traffic_in_tonnes_and_days() {
        // 22.5 t and 17.5 t axles, 3 : 1; 4000 axles a day.
        let u = Units::new(Some(&[22.5e3, 17.5e3]), Some(4000.0), &[0.75, 0.25]);
        assert!((u.tonnes_per_passage.unwrap() - 21.25).abs() < 1e-12);
        assert!((u.mgt(1e5).unwrap() - 2.125).abs() < 1e-12);
        assert_eq!(u.days(1e5), Some(25.0));
        assert_eq!(u.describe(1e5), "2.1 MGT, 25 days at 4000 axles per day (1.00e5 wheel passages)");
        assert_eq!(Units::default().describe(3.4e6), "3.40e6 wheel passages");
        let long = Units { tonnes_per_passage: None, axles_per_day: Some(100.0) };
        assert_eq!(long.describe(1e5), "1000 days (2.7 years) at 100 axles per day (1.00e5 wheel passages)");
        let mgt = cumulative_mgt(&[(0, 1e4), (1, 2e4), (0, 1e4)], &[20e3, 10e3]);
        assert_eq!(mgt, vec![0.2, 0.4, 0.6000000000000001]);
    }

    #[test]
    fn the_outlook_names_the_crossing_and_the_next_band() {
        let bands = [Band::third_octave(15), Band::third_octave(16)];
        let limit = [15.0, 13.0];
        let levels = vec![vec![14.0, 9.0], vec![15.5, 10.0]];
        let rates = vec![vec![1.0, 0.5], vec![1.5, 1.0]];
        let units = Units { tonnes_per_passage: Some(20.0), axles_per_day: Some(1e4) };
        let s = Standing {
            bands: &bands,
            limit: &limit,
            limit_name: "ISO 3095",
            initial: &[13.0, 8.5],
            levels: &levels,
            rates: &rates,
            forced: &[],
            traffic: &[1e5, 2e5],
            units,
        };
        let lines = outlook(&s);
        assert_eq!(lines.len(), 3, "{lines:?}");
        assert!(lines[0].starts_with("the 31.5 mm band reached the ISO 3095 limit (15.0 dB re 1 um) in passage 2"));
        assert!(lines[0].ends_with("after 4.0 MGT, 20 days at 10000 axles per day (2.00e5 wheel passages)"));
        // 25 mm: 3 dB at 1 dB per 1e5: 3e5 more, 5e5 from the start.
        assert!(
            lines[1].starts_with("the 25 mm band reaches the ISO 3095 limit (13.0 dB re 1 um) after 10 MGT, 50 days")
        );
        assert!(
            lines[1].ends_with("at passage 2's rates (+1.00 dB per 1e5 wheel passages from 10.0 dB)"),
            "{}",
            lines[1]
        );
        assert!(lines[2].contains("31.5 mm (by 0.5 dB)"));
        // At 0.1 dB per 1e5 the 25 mm band needs 3e6 more: 16 times the
        // traffic simulated, said so.
        let slow = vec![vec![1.0, 0.5], vec![1.5, 0.1]];
        let lines = outlook(&Standing { rates: &slow, ..s });
        assert!(lines[1].ends_with("; 16 times the traffic simulated: an extrapolation"), "{}", lines[1]);
        // A band absent from the initial roughness that the forced pattern
        // wears in: forecast at the forced pattern's pace (no exponential
        // rate from nothing), and named first where it comes first.
        let bands = [Band::third_octave(15), Band::third_octave(16), Band::third_octave(22)];
        let limit = [15.0, 13.0, 5.0];
        let levels = vec![vec![14.0, 9.0, -120.0], vec![14.2, 10.0, -50.0]];
        let rates = vec![vec![0.2, 0.5, 0.0], vec![0.2, 1.0, 0.0]];
        let forced = vec![vec![0.0, 0.0, 1e-11], vec![0.0, 0.0, 1e-11]];
        let s = Standing {
            bands: &bands,
            limit: &limit,
            levels: &levels,
            rates: &rates,
            forced: &forced,
            initial: &[13.0, 8.5, -120.0],
            ..s
        };
        let lines = outlook(&s);
        // 5 dB = 1.78 um at 1e-11 m per passage: 1.78e5 passages from now.
        assert!(lines[0].starts_with("the 6.3 mm band reaches"), "{lines:?}");
        assert!(lines[0].contains("worn in by the forced pattern's 1.000 um rms per 1e5 wheel passages"), "{lines:?}");
        assert!(!lines.iter().any(|l| l.contains("left out")), "{lines:?}");
    }
}
