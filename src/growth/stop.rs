//! When a growth study has reached saturation (`growth.stop =
//! "saturation"`): the corrugation stops growing when its wear no longer
//! deepens the troughs faster than it wears the crests, and the linear
//! track model stops being valid when the wheel leaves the rail.

use super::state::RunState;
use crate::levels::{BandLevels, forecast::crossed};
use crate::params::{GrowthParams, Scene, StopRule};

/// Passages over which the rms growth rate is measured.
pub const SATURATION_WINDOW: usize = 10;

/// The rms growth rate over the last [`SATURATION_WINDOW`] passages (dB per
/// 1e5 real passages): `20 log10(rms_n / rms_{n-W}) / (T_n - T_{n-W}) 1e5`
/// from the rms (m) and the traffic (real passages) after each passage;
/// None before the window is full.
pub fn rms_growth_rate(rms: &[f64], traffic: &[f64]) -> Option<f64> {
    let n = rms.len();
    if n <= SATURATION_WINDOW || traffic.len() != n {
        return None;
    }
    let (r0, r1) = (rms[n - 1 - SATURATION_WINDOW], rms[n - 1]);
    let dt = traffic[n - 1] - traffic[n - 1 - SATURATION_WINDOW];
    if !(r0 > 0.0 && r1 > 0.0 && dt > 0.0) {
        return None;
    }
    Some(20.0 * (r1 / r0).log10() / dt * 1e5)
}

/// Why the study stops after the last passage, if it does: contact lost in
/// that passage (`contact_loss_steps` > 0), or the rms growth rate below
/// `rate` (dB per 1e5 passages).
pub fn saturation(rms: &[f64], traffic: &[f64], contact_loss_steps: f64, rate: f64) -> Option<String> {
    if contact_loss_steps > 0.0 {
        return Some(format!(
            "contact loss: the wheel left the rail at {contact_loss_steps} steps of the stretch (the linear track model ends there)"
        ));
    }
    let g = rms_growth_rate(rms, traffic)?;
    (g < rate).then(|| {
        format!(
            "saturation: the rms grew by {g:.3} dB per 1e5 passages over the last {SATURATION_WINDOW} passages (< growth.saturation_rate = {rate})"
        )
    })
}

/// Why a growth study of `scene` stops after the last row of `state`: the
/// first rail's reason, or where the wheelset has a second rail, the first
/// rail's or the second's, named.
pub(super) fn rails_stop_reason(scene: &Scene, state: &RunState, levels: &BandLevels, limit: &[f64]) -> Option<String> {
    let growth = scene.growth.as_ref();
    let name = &scene.levels.limit.name;
    let first = stop_reason(growth, state, levels, limit, name);
    match (state.second_rail.as_deref(), scene.second_rail.as_ref()) {
        (Some(second), Some(r)) => first
            .map(|why| format!("{}: {why}", r.names[0]))
            .or_else(|| stop_reason(growth, second, levels, limit, name).map(|why| format!("{}: {why}", r.names[1]))),
        _ => first,
    }
}

/// Why a growth study stops after the last row of `state`, by its
/// `growth.stop` rule.
fn stop_reason(
    growth: Option<&GrowthParams>,
    state: &RunState,
    levels: &BandLevels,
    limit: &[f64],
    limit_name: &str,
) -> Option<String> {
    let rows = &state.rows;
    let last = rows.last()?;
    match growth?.stop {
        StopRule::Never => None,
        StopRule::Saturation { rate } => {
            let rms: Vec<f64> = rows.iter().map(|r| r.rms_corrugation).collect();
            let traffic: Vec<f64> = rows.iter().map(|r| r.traffic).collect();
            saturation(&rms, &traffic, last.contact_loss_steps, rate)
        }
        StopRule::Limit => {
            let before = match rows.len() {
                1 => &state.initial_level,
                n => &rows[n - 2].roughness_level,
            };
            let &k = crossed(before, &last.roughness_level, limit).first()?;
            Some(format!(
                "limit: the {} band reached the {} ({:.1} dB re 1 um) in passage {}",
                levels.bands()[k].label(),
                crate::levels::limit::limit_words(limit_name),
                limit[k],
                rows.len()
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn growth_rate_over_the_window() {
        // rms doubling (6.02 dB) over 1e5 passages in 10 passages.
        let traffic: Vec<f64> = (0..11).map(|k| 1e4 * k as f64).collect();
        let rms: Vec<f64> = (0..11).map(|k| 2f64.powf(k as f64 / 10.0)).collect();
        let g = rms_growth_rate(&rms, &traffic).unwrap();
        assert!((g - 20.0 * 2f64.log10()).abs() < 1e-9, "{g}");
        assert!(rms_growth_rate(&rms[..10], &traffic[..10]).is_none());
        assert!(saturation(&rms, &traffic, 0.0, 0.1).is_none());
        let flat = vec![1.0; 11];
        assert!(saturation(&flat, &traffic, 0.0, 0.1).unwrap().starts_with("saturation"));
        assert!(saturation(&rms[..3], &traffic[..3], 2.0, 0.1).unwrap().starts_with("contact loss"));
    }
}
