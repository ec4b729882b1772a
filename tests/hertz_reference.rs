//! Hertz solution against the closed-form patches of the paper's scene (Baeza et al. 2008) and CONTACT's printed patches.
use crate::common;
use common::{STEEL, paper_shape, rel};
use corrugation::hertz::{Curvatures, Elastic, HertzShape};

#[test]
fn paper_patch_both_readings() {
    // The paper's scene (N = 100 kN): convex a = 8.07 mm, b = 3.99 mm,
    // p0 = 1483 MPa; concave a = 5.96 mm, b = 10.22 mm, p0 = 785 MPa.
    // CONTACT: cvx 8.067/3.991 mm, 1483 MPa, approach 0.1111 mm;
    //          ccv 5.957/10.22 mm, 784.5 MPa, approach 0.0818 mm.
    for (concave, a, b, p0, approach) in
        [(false, 8.067e-3, 3.991e-3, 1483e6, 0.1111e-3), (true, 5.957e-3, 10.22e-3, 784.5e6, 0.0818e-3)]
    {
        let p = paper_shape(concave).patch(1e5).unwrap();
        assert!(rel(p.a, a) < 1e-3, "a {} vs {a}", p.a);
        assert!(rel(p.b, b) < 1e-3, "b {} vs {b}", p.b);
        assert!(rel(p.p0, p0) < 1e-3, "p0 {} vs {p0}", p.p0);
        // CONTACT prints the approach to 3-4 digits.
        assert!(rel(p.approach, approach) < 2e-3, "approach {} vs {approach}", p.approach);
    }
}

#[test]
fn contact_cattaneo_example() {
    // CONTACT `cattaneo`: A = B = 10 /m, G = 200 MPa, nu = 0.42 -> a = 1 mm at N = 9.1954 N.
    let el = Elastic::from_shear(200e6, 0.42);
    let p = HertzShape::new(Curvatures { a: 10.0, b: 10.0 }, el).unwrap().patch(9.1954).unwrap();
    assert!(rel(p.a, 1e-3) < 1e-4 && rel(p.b, 1e-3) < 1e-4, "a = {}", p.a);
}

#[test]
fn scaling_with_force_and_swap_symmetry() {
    let s = paper_shape(true);
    let p1 = s.patch(1e5).unwrap();
    let p8 = s.patch(8e5).unwrap();
    assert!(rel(p8.a, 2.0 * p1.a) < 1e-12 && rel(p8.b, 2.0 * p1.b) < 1e-12);
    assert!(rel(p8.p0, 2.0 * p1.p0) < 1e-12 && rel(p8.approach, 4.0 * p1.approach) < 1e-12);
    // Swapping A and B swaps a and b.
    let c = Curvatures::wheel_on_rail(0.5, -0.409, 0.3);
    let q = HertzShape::new(Curvatures { a: c.b, b: c.a }, STEEL).unwrap().patch(1e5).unwrap();
    assert!(rel(q.a, p1.b) < 1e-9 && rel(q.b, p1.a) < 1e-9);
}

#[test]
fn strongly_elliptic_limit() {
    // For a/b -> 0 (A >> B): b/a -> large; force balance p0 = 3N/(2 pi a b) and
    // the shape equation must still hold; compare with the classic asymptotic
    // k'^2 ln(4/k') ~ B/A ... checked through the Johnson relation
    // B/A = ((a/b)^2 E - K)/(K - E) evaluated with series-free integrals.
    let el = STEEL;
    for ratio in [1e-4, 1e-2, 1e2, 1e4] {
        let s = HertzShape::new(Curvatures { a: 1.0, b: ratio }, el).unwrap();
        let p = s.patch(1e4).unwrap();
        let (long, short) = if p.a > p.b { (p.a, p.b) } else { (p.b, p.a) };
        let m = 1.0 - (short / long).powi(2);
        let k = ellip::ellipk(m).unwrap();
        let e = ellip::ellipe(m).unwrap();
        let c_ratio = ((long / short).powi(2) * e - k) / (k - e);
        let expected = if ratio > 1.0 { ratio } else { 1.0 / ratio };
        assert!(rel(c_ratio, expected) < 1e-8, "ratio {ratio}: {c_ratio}");
        assert!((p.pressure(0.0, 0.0) - p.p0).abs() < 1e-6 * p.p0);
    }
    assert!(HertzShape::new(Curvatures { a: 1.0, b: -1.0 }, el).is_err());
}
