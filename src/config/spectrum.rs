//! Section `[spectrum]`: what `corrugation spectrum` measures of a growth
//! study's passage ([`crate::spectrum`]). Only with a `[growth]` section
//! (the spectrum linearises its passage); without `[spectrum]` the command
//! takes the defaults.

use super::ConfigError;
use super::reader::{Range, Section};
use crate::spectrum::{Base, DEFAULT_PERTURBATION, Difference, SpectrumParams};
use toml::{Table, Value};

/// Most Bloch classes (`spectrum.classes`): a supercell of this many
/// stretches.
pub const MAX_CLASSES: usize = 256;

/// Reads `[spectrum]`; `None` where it is absent or invalid (the errors
/// recorded). `stretch` is the growth study's stretch (m), where valid.
pub fn read(
    root: &mut Table,
    resolved: &mut Table,
    growth: bool,
    stretch: Option<f64>,
    errors: &mut Vec<ConfigError>,
) -> Option<SpectrumParams> {
    if !root.contains_key("spectrum") {
        return None;
    }
    if !growth {
        root.remove("spectrum");
        errors.push(ConfigError::new(
            "spectrum",
            "is only allowed with a [growth] section (the spectrum linearises a growth study's passage)".into(),
        ));
        return None;
    }
    let d = SpectrumParams::default();
    let mut s = Section::new(root, "", "spectrum", errors);
    let min = s.f64("wavelength_min", Some(d.wavelength_min), Range::OpenClosed(0.0, 10.0));
    let max = s.f64("wavelength_max", Some(d.wavelength_max), Range::OpenClosed(0.0, 10.0));
    // The classes, given or from the resolution asked at the longest
    // wavelength: a supercell of M stretches L spaces the wavenumbers
    // 2 pi / (M L), the wavelengths about lambda^2 / (M L) apart.
    let classes = match (s.has("classes"), s.has("resolution")) {
        (true, true) => {
            s.usize("classes", None, 1, MAX_CLASSES);
            s.f64("resolution", None, Range::OpenClosed(0.0, 10.0));
            s.error("resolution", "and spectrum.classes both set the Bloch classes: give one of them".into());
            None
        }
        (_, true) => match (s.f64("resolution", None, Range::OpenClosed(0.0, 10.0)), max, stretch) {
            (Some(r), Some(max), Some(l)) => {
                let m = (max * max / (r * l) - 1e-9).ceil().max(1.0) as usize;
                if m > MAX_CLASSES {
                    s.error(
                        "resolution",
                        format!(
                            "= {r} m at spectrum.wavelength_max = {max} m needs {m} Bloch classes on the {l} m \
                             stretch; at most {MAX_CLASSES} (a coarser resolution or a shorter wavelength_max)"
                        ),
                    );
                    None
                } else {
                    Some(m)
                }
            }
            _ => None,
        },
        _ => s.usize("classes", Some(d.classes), 1, MAX_CLASSES),
    };
    let perturbation = s.f64("perturbation", Some(DEFAULT_PERTURBATION), Range::Closed(1e-10, 1e-5));
    let difference = s.choice("difference", Some("central"), &["central", "forward"]);
    let base = s.choice("base", Some("smooth"), &["smooth", "roughness"]);
    if let (Some(a), Some(b)) = (min, max)
        && a >= b
    {
        s.error("wavelength_max", format!("= {b} m must be > spectrum.wavelength_min = {a} m"));
    }
    let table = s.finish();
    resolved.insert("spectrum".into(), Value::Table(table));
    let (Some(min), Some(max), Some(classes), Some(perturbation), Some(difference), Some(base)) =
        (min, max, classes, perturbation, difference, base)
    else {
        return None;
    };
    (min < max).then(|| SpectrumParams {
        wavelength_min: min,
        wavelength_max: max,
        classes,
        perturbation,
        difference: difference.parse().unwrap_or(Difference::Central),
        base: if base == "roughness" { Base::Roughness } else { Base::Smooth },
    })
}
