//! Paul-Hashemi discretisation of the elliptic contact patch.
//!
//! The ellipse `(x/a)^2 + (y/b)^2 <= 1` is cut into `ny` strips of equal width
//! parallel to the rolling direction x; every strip is split into the same
//! number `nx` of equal elements across its chord (Paul and Hashemi,
//! *Numerical determination of contact pressures between closely conforming
//! wheels and rails*, Report, Brown University 1977; Baeza et al., Wear 265
//! (2008), Fig. 2). In normalised coordinates `xi = x/a`, `eta = y/b` the mesh
//! is the same for every patch size, so it moves and rescales with N.
//!
//! Element order: strip by strip (eta increasing), within a strip from the
//! leading edge (xi > 0, where rail material enters when rolling in +x) to the
//! trailing edge.

/// The normalised mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct EllipseMesh {
    /// Elements per strip along x.
    pub nx: usize,
    /// Number of strips along y.
    pub ny: usize,
    /// Element centres xi = x/a (1), length nx*ny.
    pub xi: Vec<f64>,
    /// Element centres eta = y/b (1), length nx*ny.
    pub eta: Vec<f64>,
    /// Normalised half-chord of each strip at its centre line (1), length ny.
    pub half_chord: Vec<f64>,
    /// Normalised element length along x of each strip (1), length ny.
    pub d_xi: Vec<f64>,
    /// Normalised strip width (1).
    pub d_eta: f64,
}

impl EllipseMesh {
    /// A mesh with `nx` elements per strip and `ny` strips (both >= 1).
    pub fn new(nx: usize, ny: usize) -> Self {
        assert!(nx >= 1 && ny >= 1, "mesh needs at least one element");
        let d_eta = 2.0 / ny as f64;
        let mut xi = Vec::with_capacity(nx * ny);
        let mut eta = Vec::with_capacity(nx * ny);
        let mut half_chord = Vec::with_capacity(ny);
        let mut d_xi = Vec::with_capacity(ny);
        for j in 0..ny {
            let e = -1.0 + (j as f64 + 0.5) * d_eta;
            let c = (1.0 - e * e).sqrt();
            let dx = 2.0 * c / nx as f64;
            half_chord.push(c);
            d_xi.push(dx);
            for i in 0..nx {
                xi.push(c - (i as f64 + 0.5) * dx);
                eta.push(e);
            }
        }
        EllipseMesh { nx, ny, xi, eta, half_chord, d_xi, d_eta }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a mesh has at least one element.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Strip index of element `k`.
    pub fn strip(&self, k: usize) -> usize {
        k / self.nx
    }

    /// Normalised area of element `k` (multiply by a*b for m^2).
    pub fn area(&self, k: usize) -> f64 {
        self.d_xi[self.strip(k)] * self.d_eta
    }

    /// Sum of `values[k] * area_k * a * b` over the patch (value * m^2).
    pub fn integrate(&self, values: &[f64], a: f64, b: f64) -> f64 {
        let mut sum = 0.0;
        for j in 0..self.ny {
            let strip: f64 = values[j * self.nx..(j + 1) * self.nx].iter().sum();
            sum += strip * self.d_xi[j];
        }
        sum * self.d_eta * a * b
    }
}

/// Normal pressure distribution assumed over the patch.
/// Named as FASTSIM's traction bound (`contact.fastsim_bound`):
/// "parabolic", "elliptic".
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "lowercase")]
pub enum PressureShape {
    /// Kalker's parabolic distribution of FASTSIM: p3 proportional to
    /// 1 - xi^2 - eta^2.
    Parabolic,
    /// Hertz: p3 proportional to sqrt(1 - xi^2 - eta^2).
    #[strum(serialize = "elliptic")]
    Hertz,
}

/// Pressure at the element centres (Pa), scaled so that its discrete
/// integral over the mesh equals the normal force `n` (N) exactly: the
/// discrete force balance then holds to round-off.
pub fn pressure_on_mesh(mesh: &EllipseMesh, shape: PressureShape, n: f64, a: f64, b: f64) -> Vec<f64> {
    let mut p: Vec<f64> = mesh
        .xi
        .iter()
        .zip(&mesh.eta)
        .map(|(x, e)| {
            let r = (1.0 - x * x - e * e).max(0.0);
            match shape {
                PressureShape::Hertz => r.sqrt(),
                PressureShape::Parabolic => r,
            }
        })
        .collect();
    let scale = n / mesh.integrate(&p, a, b);
    p.iter_mut().for_each(|v| *v *= scale);
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn areas_converge_to_ellipse() {
        let m = EllipseMesh::new(10, 200);
        let area: f64 = (0..m.len()).map(|k| m.area(k)).sum();
        assert!((area - std::f64::consts::PI).abs() < 1e-3);
    }

    #[test]
    fn pressure_balances_force_and_approaches_hertz_p0() {
        let m = EllipseMesh::new(60, 60);
        let (n, a, b) = (1e5, 6e-3, 1e-2);
        let p = pressure_on_mesh(&m, PressureShape::Hertz, n, a, b);
        assert!((m.integrate(&p, a, b) - n).abs() < 1e-9 * n);
        let p0 = 3.0 * n / (2.0 * std::f64::consts::PI * a * b);
        let pmax = p.iter().cloned().fold(0.0, f64::max);
        assert!((pmax - p0).abs() / p0 < 5e-3, "{pmax} vs {p0}");
    }

    #[test]
    fn leading_edge_first_and_symmetric() {
        let m = EllipseMesh::new(4, 3);
        assert!(m.xi[0] > 0.0 && m.xi[3] < 0.0);
        assert!((m.xi[0] + m.xi[3]).abs() < 1e-15);
        assert!((m.eta[0] + m.eta[11]).abs() < 1e-15);
    }
}
