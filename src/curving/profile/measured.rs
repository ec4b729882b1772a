//! A measured profile: points (lateral position, height) in mm from a text
//! or CSV file (a profile gauge's export), interpolated by a natural cubic
//! spline (continuous slope and curvature, which the contact's curvatures
//! need).

use super::ProfileError;
use std::path::Path;

/// A natural cubic spline through points with increasing abscissae.
#[derive(Debug, Clone, PartialEq)]
pub struct Spline {
    /// Abscissae (mm), increasing.
    x: Vec<f64>,
    /// Ordinates (mm).
    y: Vec<f64>,
    /// Second derivatives at the points (1/mm).
    m: Vec<f64>,
}

impl Spline {
    /// The spline through `x` (strictly increasing) and `y`; at least 4 points.
    pub fn new(x: Vec<f64>, y: Vec<f64>) -> Spline {
        let n = x.len();
        assert!(n >= 4 && y.len() == n);
        // Tridiagonal system for the interior second derivatives (natural ends).
        let mut m = vec![0.0; n];
        let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
        for i in 1..n - 1 {
            let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
            let rhs = 6.0 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
            let diag = 2.0 * (h0 + h1) - h0 * c[i - 1];
            c[i] = h1 / diag;
            d[i] = (rhs - h0 * d[i - 1]) / diag;
        }
        for i in (1..n - 1).rev() {
            m[i] = d[i] - c[i] * m[i + 1];
        }
        Spline { x, y, m }
    }

    /// The spline's value at `t`; None outside the points' range.
    pub fn value(&self, t: f64) -> Option<f64> {
        let (x, y, m) = (&self.x, &self.y, &self.m);
        if !(x[0]..=x[x.len() - 1]).contains(&t) {
            return None;
        }
        let i = x.partition_point(|&v| v <= t).clamp(1, x.len() - 1) - 1;
        let h = x[i + 1] - x[i];
        let (a, b) = ((x[i + 1] - t) / h, (t - x[i]) / h);
        Some(a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0)
    }

    /// The range of the abscissae (mm).
    pub fn range(&self) -> (f64, f64) {
        (self.x[0], self.x[self.x.len() - 1])
    }
}

/// Reads a profile file: one point per line, `lateral, height` (mm),
/// separated by a comma, semicolon, tab or spaces; lines starting with `#`
/// and a first line that is not numeric (a header) are skipped; the
/// lateral positions must increase strictly (a profile, not a closed
/// outline), between 4 and 100000 points.
pub fn read(path: &Path) -> Result<Spline, ProfileError> {
    let text = std::fs::read_to_string(path).map_err(|e| ProfileError::File {
        file: path.display().to_string(),
        line: 0,
        message: format!("cannot read: {e}"),
    })?;
    parse(&text, &path.display().to_string())
}

/// Parses a profile's text (`file` names it in errors).
pub fn parse(text: &str, file: &str) -> Result<Spline, ProfileError> {
    let err = |line: usize, message: String| ProfileError::File { file: file.to_string(), line, message };
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> =
            line.split(|c: char| c == ',' || c == ';' || c.is_whitespace()).filter(|f| !f.is_empty()).collect();
        let numbers: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        let Some(numbers) = numbers else {
            if x.is_empty() && k == 0 {
                continue; // a header
            }
            return Err(err(k + 1, format!("`{line}` is not two numbers (lateral position, height in mm)")));
        };
        if numbers.len() != 2 {
            return Err(err(
                k + 1,
                format!("has {} numbers; a point is two (lateral position, height in mm)", numbers.len()),
            ));
        }
        if numbers.iter().any(|v| !v.is_finite() || v.abs() > 1e3) {
            return Err(err(k + 1, "a coordinate is not finite or beyond 1000 mm (the file is in mm)".into()));
        }
        if let Some(&last) = x.last()
            && numbers[0] <= last
        {
            return Err(err(
                k + 1,
                format!(
                    "lateral position {} mm does not increase (after {last} mm): a profile is a height over increasing \
                     lateral positions",
                    numbers[0]
                ),
            ));
        }
        x.push(numbers[0]);
        y.push(numbers[1]);
        if x.len() > 100_000 {
            return Err(err(k + 1, "more than 100000 points".into()));
        }
    }
    if x.len() < 4 {
        return Err(err(0, format!("has {} points; a profile needs at least 4", x.len())));
    }
    Ok(Spline::new(x, y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spline_reproduces_a_line_exactly_and_a_circle_within_a_nanometre() {
        let x: Vec<f64> = (0..41).map(|i| -20.0 + i as f64).collect();
        let line: Vec<f64> = x.iter().map(|v| 0.5 - 0.05 * v).collect();
        let s = Spline::new(x.clone(), line);
        assert!((s.value(3.3).unwrap() - (0.5 - 0.05 * 3.3)).abs() < 1e-12);
        // A circle of radius 300 mm sampled every 1 mm: within 1e-6 mm between points.
        let circle: Vec<f64> = x.iter().map(|v| (300.0f64 * 300.0 - v * v).sqrt() - 300.0).collect();
        let s = Spline::new(x, circle);
        for t in [-10.5, 0.25, 7.75] {
            let exact = (300.0f64 * 300.0 - t * t).sqrt() - 300.0;
            assert!((s.value(t).unwrap() - exact).abs() < 1e-6, "{t}");
        }
        assert_eq!(s.value(20.5), None);
    }

    #[test]
    fn bad_files_name_the_line() {
        let e = parse("y,z\n0,0\n1,0\nx,3\n", "p.csv").unwrap_err().to_string();
        assert!(e.contains("p.csv") && e.contains("line 4"), "{e}");
        let e = parse("0 0\n2 0\n1 0\n3 0\n", "p.txt").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("does not increase"), "{e}");
        let e = parse("0 0 1\n", "p.txt").unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("3 numbers"), "{e}");
        assert!(parse("0 0\n1 0\n", "p").unwrap_err().to_string().contains("at least 4"));
        assert!(parse("0 0\n1 0\n2 1e9\n3 0\n", "p").unwrap_err().to_string().contains("in mm"));
    }
}
