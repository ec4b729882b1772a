//! The `[wear]` section: the wear law and its parameters
//! ([`crate::wear::WearLaw`]), and the deposit's sub-steps.

use super::reader::{Range, Section};
use crate::wear::law::{FrictionalWork, WearLaw, WearMap};

/// The names of `wear.law`.
pub const LAWS: [&str; 3] = ["archard", "frictional-work", "map"];

/// Jendel's map (Wear 253 (2002) 89-99): the middle of each published
/// range of k (seizure 300-400, mild 1-10, severe 30-40, fast mild 1-10 x
/// 1e-4).
pub const JENDEL_K: [f64; 4] = [350e-4, 5.5e-4, 35e-4, 5.5e-4];

/// Rail steel R260's hardness, 260 HB (Pa).
pub const R260_HARDNESS: f64 = 260.0 * 9.806_65e6;

/// Reads the law (None when invalid; errors recorded).
pub(super) fn read(s: &mut Section) -> Option<WearLaw> {
    let law = s.choice("law", Some("archard"), &LAWS);
    let archard = law.as_deref() == Some("archard");
    // k/H: Archard's own; checked and kept, unused, with the other laws.
    let k_over_h = if archard || s.has("k_over_h") { s.f64("k_over_h", None, Range::NonNegative) } else { Some(0.0) };
    let f = FrictionalWork::SHEFFIELD;
    let work = [f.mild_slope, f.mild_limit, f.severe_rate, f.severe_limit, f.catastrophic_slope, f.catastrophic_offset];
    let uses = |name: &str| law.as_deref() == Some(name);
    let read_if = |s: &mut Section, used: bool, key: &str, read: &dyn Fn(&mut Section) -> Option<Vec<f64>>| {
        if used || s.has(key) { read(s) } else { Some(Vec::new()) }
    };
    let coefficients = read_if(s, uses("frictional-work"), "work_coefficients", &|s| {
        s.f64_list("work_coefficients", work.to_vec(), Range::NonNegative, 6)
    });
    let density = if uses("frictional-work") || s.has("density") {
        s.f64("density", Some(f.density), Range::Positive)
    } else {
        Some(f.density)
    };
    let map = read_if(s, uses("map"), "map_coefficients", &|s| {
        s.f64_list("map_coefficients", JENDEL_K.to_vec(), Range::NonNegative, 4)
    });
    let speeds =
        read_if(s, uses("map"), "map_speeds", &|s| s.f64_list("map_speeds", vec![0.2, 0.7], Range::Positive, 2));
    let hardness = if uses("map") || s.has("hardness") {
        s.f64("hardness", Some(R260_HARDNESS), Range::Positive)
    } else {
        Some(R260_HARDNESS)
    };
    let (law, k_over_h, coefficients, density, map, speeds, hardness) =
        (law?, k_over_h?, coefficients?, density?, map?, speeds?, hardness?);
    match law.as_str() {
        "frictional-work" => {
            let [k1, i1, k2, i2, k3, c3] = coefficients[..] else {
                s.error(
                    "work_coefficients",
                    format!("has {} numbers; expected 6: k1, I1, K2, I2, k3, c3", coefficients.len()),
                );
                return None;
            };
            if i1 > i2 {
                s.error("work_coefficients", format!("the mild limit I1 = {i1} exceeds the severe limit I2 = {i2}"));
                return None;
            }
            Some(WearLaw::FrictionalWork(FrictionalWork {
                mild_slope: k1,
                mild_limit: i1,
                severe_rate: k2,
                severe_limit: i2,
                catastrophic_slope: k3,
                catastrophic_offset: c3,
                density,
            }))
        }
        "map" => {
            let (&[seizure, mild, severe, fast], &[slow_limit, fast_limit]) = (&map[..], &speeds[..]) else {
                let message = format!(
                    "expected 4 coefficients (seizure, mild, severe, fast mild) and 2 speeds, got {} and {}",
                    map.len(),
                    speeds.len()
                );
                s.error("map_coefficients", message);
                return None;
            };
            if slow_limit >= fast_limit {
                s.error("map_speeds", format!("[{slow_limit}, {fast_limit}] must increase"));
                return None;
            }
            Some(WearLaw::Map(WearMap {
                hardness,
                seizure,
                mild,
                severe,
                fast,
                slow_limit,
                fast_limit,
                seizure_share: 0.8,
            }))
        }
        _ => Some(WearLaw::Archard { k_over_h }),
    }
}
