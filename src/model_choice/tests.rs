use super::*;
use ContactModelKind::{ExactTransient, Fastsim, SimplifiedTransient};

/// Two wavelengths; FASTSIM cheap and poor, simplified in between, exact
/// converging at first order.
const MAP: &str = "model,mesh,wavelength,lambda_over_2a,wear_error,cpu_per_step
exact-transient,10,0.015,1.0,0.30,0.004
exact-transient,20,0.015,1.0,0.15,0.025
exact-transient,28,0.015,1.0,0.10,0.080
exact-transient,10,0.030,2.0,0.20,0.003
exact-transient,20,0.030,2.0,0.10,0.020
exact-transient,28,0.030,2.0,0.07,0.070
fastsim,20,0.015,1.0,0.90,0.001
fastsim,20,0.030,2.0,0.40,0.001
simplified-transient,20,0.015,1.0,0.40,0.002
simplified-transient,20,0.030,2.0,0.25,0.002
";

fn map() -> AccuracyMap {
    AccuracyMap::parse(MAP).unwrap()
}

#[test]
fn interpolates_in_log_ratio_and_clamps_above_the_map() {
    let m = map();
    let mid = m.predict(ExactTransient, false, 20, 2f64.sqrt()).unwrap();
    assert!((mid.wear_error - 0.125).abs() < 1e-12, "halfway in ln r: {}", mid.wear_error);
    assert!((mid.cpu_per_step - 0.0225).abs() < 1e-12);
    assert_eq!(m.predict(Fastsim, false, 20, 50.0).unwrap().wear_error, 0.40, "above: the top of the map");
    assert_eq!(m.predict(Fastsim, false, 20, f64::INFINITY).unwrap().wear_error, 0.40, "no wavelength");
    assert!(m.predict(Fastsim, false, 20, 0.9).is_none(), "below the map");
    assert!(m.predict(Fastsim, false, 40, 1.5).is_none(), "mesh not in the map");
}

#[test]
fn chooses_the_cheapest_within_the_tolerance() {
    let m = map();
    let c = m.choose(2.0, 0.5).unwrap();
    assert_eq!((c.chosen.model, c.chosen.mesh), (Fastsim, 20));
    let c = m.choose(2.0, 0.3).unwrap();
    assert_eq!((c.chosen.model, c.chosen.mesh), (SimplifiedTransient, 20));
    // The safety margin: exact 10 x 10 (0.20) does not meet 0.2, 20 x 20 does.
    let c = m.choose(2.0, 0.2).unwrap();
    assert_eq!((c.chosen.model, c.chosen.mesh), (ExactTransient, 20));
    let c = m.choose(2.0, 0.2 / SAFETY).unwrap();
    assert_eq!((c.chosen.model, c.chosen.mesh), (ExactTransient, 10));
    let c = m.choose(1.0, 0.12).unwrap();
    assert_eq!((c.chosen.model, c.chosen.mesh), (ExactTransient, 28));
    // Never slower than the exact model at the mesh that meets the tolerance.
    for r in [1.0, 1.3, 2.0, 10.0] {
        for tol in [0.1, 0.15, 0.2, 0.3, 0.5, 1.0] {
            if let Ok(c) = m.choose(r, tol) {
                let e = c.exact.expect("exact meets every tolerance this map allows");
                assert!(c.chosen.cpu_per_step <= e.cpu_per_step, "r {r} tol {tol}");
                assert!(c.chosen.wear_error <= SAFETY * tol);
            }
        }
    }
}

#[test]
fn refuses_outside_the_map_and_unreachable_tolerances() {
    let m = map();
    assert_eq!(m.choose(0.5, 0.5).unwrap_err(), ChoiceError::OutsideMap { lambda_over_2a: 0.5, min: 1.0 });
    let e = m.choose(1.0, 0.05).unwrap_err();
    assert!(
        matches!(&e, ChoiceError::Unreachable { best, label, .. } if *best == 0.10 && label == "exact-transient 28 x 28"),
        "{e:?}"
    );
    assert!(e.to_string().contains("exact-transient 28 x 28"), "{e}");
}

#[test]
fn fixed_grid_rows_are_candidates_of_their_own() {
    // The fixed grid at 0.2 mm (mesh in um): more accurate than exact 28 x 28
    // and cheaper; chosen where it is the cheapest within the tolerance.
    let text = format!("{MAP}exact-fixed,200,0.015,1.0,0.02,0.03\nexact-fixed,200,0.030,2.0,0.01,0.03\n");
    let m = AccuracyMap::parse(&text).unwrap();
    let c = m.choose(1.0, 0.05).unwrap();
    assert!(c.chosen.fixed && c.chosen.mesh == 200 && c.chosen.model == ExactTransient, "{c:?}");
    assert_eq!(c.chosen.label(), "exact-transient fixed grid 0.20 mm");
    assert_eq!(c.chosen.grid_dx(), Some(2e-4));
    assert_eq!(c.exact, Some(c.chosen), "the fixed grid is the exact model");
    // An adapted mesh of the same number is another candidate.
    assert!(!m.predict(ExactTransient, false, 20, 1.0).unwrap().fixed);
    assert!(m.predict(ExactTransient, true, 20, 1.0).is_none());
}

#[test]
fn bad_maps_are_refused_with_the_line() {
    assert!(AccuracyMap::parse("").is_err());
    let e = AccuracyMap::parse("model,mesh,lambda_over_2a,wear_error,cpu_per_step\nfoo,10,1,0.1,0.01").unwrap_err();
    assert!(e.contains("line 2") && e.contains("model"), "{e}");
    let e = AccuracyMap::parse("model,mesh,lambda_over_2a,wear_error\nfastsim,10,1,0.1").unwrap_err();
    assert!(e.contains("cpu_per_step"), "{e}");
    let e = AccuracyMap::parse("model,mesh,lambda_over_2a,wear_error,cpu_per_step\nfastsim,10,1,NaN,0.1").unwrap_err();
    assert!(e.contains("wear_error"), "{e}");
}
