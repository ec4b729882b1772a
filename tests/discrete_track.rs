//! The Timoshenko rail on discrete supports (src/dynamics/track/discrete.rs)
//! against closed forms: passivity, the pinned-pinned resonance of the
//! simply supported span, the static deflection of a closely supported
//! rail against the Winkler beam, and the continuous model when the
//! supports are smeared.
use corrugation::dynamics::receptance::winkler_point_receptance;
use corrugation::dynamics::track::TrackConfig;
use corrugation::dynamics::track::discrete::DiscreteTrack;
use num_complex::Complex64;
use std::f64::consts::PI;

fn uic60() -> DiscreteTrack {
    DiscreteTrack::new(&TrackConfig::default())
}

#[test]
fn passive_at_every_position_and_frequency() {
    // Im alpha <= 0 (exp(+i w t)): the track only absorbs energy. Every
    // sixteenth of the bay over the whole bay (both halves, and the next
    // sleeper), 61 frequencies log-spaced over 20-5000 Hz.
    let t = uic60();
    for p in 0..=16 {
        let x0 = 0.6 * p as f64 / 16.0;
        for k in 0..61 {
            let f = 20.0 * 250f64.powf(k as f64 / 60.0);
            let a = t.receptance(x0, 2.0 * PI * f);
            assert!(a.im <= 0.0 && a.norm().is_finite(), "x0 {x0} f {f}: {a}");
        }
    }
}

#[test]
fn pinned_pinned_resonance_at_the_simply_supported_span_frequency() {
    let t = uic60();
    let f_pp = t.pinned_pinned_frequency();
    // The mid-span receptance peaks there; above a sleeper it does not.
    let (mut best, mut at) = (0.0, 0.0);
    for k in 0..=120 {
        let f = 700.0 + 5.0 * k as f64;
        let m = t.receptance(0.3, 2.0 * PI * f).norm();
        if m > best {
            (best, at) = (m, f);
        }
    }
    eprintln!("pinned-pinned: simply supported span {f_pp:.1} Hz, mid-span peak {at:.1} Hz");
    assert!((1000.0..1100.0).contains(&f_pp), "{f_pp}");
    assert!((at - f_pp).abs() < 0.02 * f_pp, "peak {at} Hz vs {f_pp} Hz");
    let over = t.receptance(0.0, 2.0 * PI * at).norm();
    assert!(best > 3.0 * over, "mid-span {best:.3e} vs above a sleeper {over:.3e}");
}

/// A track whose per-support values are the default's smeared values times
/// `d`: the same track per length on supports `d` apart.
fn closely_supported(d: f64) -> DiscreteTrack {
    let base = TrackConfig::default();
    let s = base.smeared();
    let mut t = DiscreteTrack::new(&base);
    t.spacing = d;
    t.pad_stiffness = s.pad_stiffness * d;
    t.ballast_stiffness = s.ballast_stiffness * d;
    t.sleeper_mass = s.sleeper_mass * d;
    t
}

#[test]
fn close_supports_give_the_winkler_beam() {
    // Static: 1 / (8 EI beta^3), beta^4 = s / (4 EI), s pad and ballast in
    // series, for the Euler-Bernoulli rail of the Winkler beam (the
    // Timoshenko rail's shear adds 9 % here).
    let mut t = closely_supported(0.15);
    t.rail.shear_stiffness = 1e15;
    t.rail.rotary_inertia = 0.0;
    let s = TrackConfig::default().smeared();
    let kp = Complex64::new(s.pad_stiffness, s.pad_stiffness * s.pad_loss_factor);
    let kb = Complex64::new(s.ballast_stiffness, s.ballast_stiffness * s.ballast_loss_factor);
    let w = 2.0 * PI * 0.5;
    let winkler = winkler_point_receptance(s.bending_stiffness, kp * kb / (kp + kb) - s.rail_mass * w * w);
    for x0 in [0.0, 0.075] {
        let a = t.receptance(x0, w);
        eprintln!("static x0 {x0}: discrete {a:.4e}, Winkler {winkler:.4e}");
        assert!((a - winkler).norm() < 0.02 * winkler.norm(), "x0 {x0}: {a} vs {winkler}");
    }
}

#[test]
fn smeared_supports_give_the_continuous_model() {
    // The continuous model's rail (Euler-Bernoulli, no rail damping) on the
    // continuous support, against the discrete model with supports 0.1 m
    // apart, an Euler-Bernoulli rail and a light rail damping.
    let mut t = closely_supported(0.1);
    t.rail.shear_stiffness = 1e15;
    t.rail.rotary_inertia = 0.0;
    t.rail_loss_factor = 0.005;
    let s = TrackConfig::default().smeared();
    for f in [50.0, 150.0, 300.0, 600.0] {
        let w = 2.0 * PI * f;
        let c = s.rail_receptance(w);
        let a = t.receptance(0.05, w);
        eprintln!("{f} Hz: discrete {a:.4e}, continuous {c:.4e}");
        assert!((a - c).norm() < 0.03 * c.norm(), "{f} Hz: {a} vs {c}");
    }
}
