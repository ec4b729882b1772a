//! A user's modal table (`[wheelset] modes = "FILE.csv"`): the free
//! wheelset's flexible modes as a finite element modal analysis gives them.
//!
//! # Format
//!
//! Comma-separated text, `#` starts a comment line, blank lines are skipped,
//! fields may be quoted. The first other line is the header: column names,
//! in any order, each once:
//!
//! | column | unit | meaning |
//! |---|---|---|
//! | `name` | | the mode's name, unique (e.g. `first symmetric bending (vertical)`) |
//! | `frequency` | Hz | natural frequency of the non-rotating free wheelset, >= 1 Hz |
//! | `damping_ratio` or `loss_factor` | 1 | one of the two columns (or both, one value per row): viscous ratio in (0, 1), loss factor > 0 |
//! | `x0`, `y0`, `z0`, `theta0` | 1/sqrt(kg); rad/(m sqrt(kg)) | the mass-normalised mode (unit modal mass, 1 kg) at wheel 0's contact (`+y` side): longitudinal (with the rotation's `-r theta`), lateral, vertical displacement, rotation about the axle |
//! | `psi0` (optional) | rad/(m sqrt(kg)) | wheel 0's tread's rotation about the vertical (`+z`) at the contact (0 where absent) |
//! | `x1`, `y1`, `z1`, `theta1`, `psi1` | same | at wheel 1's contact (`-y` side) |
//! | `partner` (optional) | | the name of a mode this one is coupled to by the rotation, or empty |
//! | `coefficient` (optional) | 1 | `G_ab` of eq. 1 of [`super`] (this mode `a`, the partner `b`); the partner's row may give the same coupling as `-G_ab` |
//!
//! Directions and signs are those of [`super`] (`x` forwards, `z` up, `y`
//! to the left; the rotation in the rolling spin's sense). The rigid-body
//! modes (the wheelset on its primary suspension, the free spin) are not
//! in the table: the `[wheelset]` keys give them.
//!
//! Example (the default's torsion and its first symmetric bending in the
//! vertical plane, and a wheel's 2-diameter axial pair split by the spin):
//!
//! ```text
//! name,frequency,damping_ratio,loss_factor,x0,y0,z0,theta0,x1,y1,z1,theta1,partner,coefficient
//! torsion,71.18,,0.02,-0.0645,0,0,0.129,0.0645,0,0,-0.129,,
//! first symmetric bending,87.0,0.01,,0,0.0694,-0.0041,0,0,-0.0694,-0.0041,0,,
//! wheel 0 n=2 axial cos,360,0.001,,0,0.0962,0,0,0,0,0,0,wheel 0 n=2 axial sin,4
//! wheel 0 n=2 axial sin,360,0.001,,0,0,0,0,0,0,0,0,,
//! ```

use super::{DOFS, Damping, Gyroscopic, Mode};
use std::fmt;

/// The participation columns, in the order of [`super::dof`].
pub const SHAPE_COLUMNS: [&str; DOFS] = ["x0", "y0", "z0", "theta0", "psi0", "x1", "y1", "z1", "theta1", "psi1"];

/// The participation columns a table may leave out (0 where absent).
const OPTIONAL_COLUMNS: [&str; 2] = ["psi0", "psi1"];

/// Why a mode needs damping.
const UNDAMPED: &str = " (an undamped mode's receptance is infinite at its frequency: give the structure's damping)";

/// A problem in a table, at a line (1-based; 0: the whole table).
#[derive(Debug, Clone, PartialEq)]
pub struct TableError {
    /// Line number (1-based), 0 for the table as a whole.
    pub line: u64,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 { write!(f, "{}", self.message) } else { write!(f, "line {}: {}", self.line, self.message) }
    }
}

impl std::error::Error for TableError {}

/// The modes of a table and their couplings (indices into `modes`).
#[derive(Debug, Clone, PartialEq)]
pub struct ModalTable {
    /// The modes, in the table's order.
    pub modes: Vec<Mode>,
    /// The gyroscopic couplings between them.
    pub couplings: Vec<Gyroscopic>,
}

/// Reads a table from `text` (module docs).
pub fn parse(text: &str) -> Result<ModalTable, TableError> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .flexible(false)
        .has_headers(true)
        .from_reader(text.as_bytes());
    let at = |line: u64, message: String| TableError { line, message };
    let headers = reader.headers().map_err(|e| at(csv_line(&e), format!("cannot read the header: {e}")))?.clone();
    let header_line = headers.position().map_or(1, |p| p.line());
    let column = |name: &str| headers.iter().position(|h| h == name);
    let known: Vec<&str> = ["name", "frequency", "damping_ratio", "loss_factor", "partner", "coefficient"]
        .into_iter()
        .chain(SHAPE_COLUMNS)
        .collect();
    for (i, h) in headers.iter().enumerate() {
        if !known.contains(&h) {
            return Err(at(header_line, format!("unknown column `{h}`; the columns are {}", known.join(", "))));
        }
        if headers.iter().take(i).any(|g| g == h) {
            return Err(at(header_line, format!("column `{h}` given twice")));
        }
    }
    let need = |name: &str| {
        column(name).ok_or_else(|| at(header_line, format!("missing column `{name}` (columns: {})", known.join(", "))))
    };
    let (name_col, freq_col) = (need("name")?, need("frequency")?);
    let shape_cols: Vec<Option<usize>> = SHAPE_COLUMNS
        .iter()
        .map(|c| if OPTIONAL_COLUMNS.contains(c) { Ok(column(c)) } else { need(c).map(Some) })
        .collect::<Result<_, _>>()?;
    let (ratio_col, loss_col) = (column("damping_ratio"), column("loss_factor"));
    if ratio_col.is_none() && loss_col.is_none() {
        return Err(at(header_line, "missing a damping column: `damping_ratio` or `loss_factor`".into()));
    }
    let (partner_col, coeff_col) = (column("partner"), column("coefficient"));
    if partner_col.is_some() != coeff_col.is_some() {
        return Err(at(header_line, "the columns `partner` and `coefficient` go together".into()));
    }

    let mut modes = Vec::new();
    let mut lines = Vec::new();
    let mut declared: Vec<(usize, String, f64, u64)> = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| at(csv_line(&e), e.to_string()))?;
        let line = record.position().map_or(0, |p| p.line());
        let field = |c: usize| record.get(c).unwrap_or("");
        let number = |c: usize, what: &str| -> Result<Option<f64>, TableError> {
            let s = field(c);
            if s.is_empty() {
                return Ok(None);
            }
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(v)),
                _ => Err(at(line, format!("{what} `{s}` is not a finite number"))),
            }
        };
        let name = field(name_col).to_string();
        if name.is_empty() {
            return Err(at(line, "the mode has no name".into()));
        }
        if modes.iter().any(|m: &Mode| m.name == name) {
            return Err(at(line, format!("mode `{name}` is named twice")));
        }
        let frequency = number(freq_col, "frequency")?.ok_or_else(|| at(line, "frequency missing".into()))?;
        if frequency < 1.0 {
            return Err(at(
                line,
                format!(
                    "frequency = {frequency} Hz must be >= 1 Hz: the table holds the free wheelset's flexible modes \
                     (the [wheelset] keys give the rigid-body modes)"
                ),
            ));
        }
        let ratio = ratio_col.map(|c| number(c, "damping_ratio")).transpose()?.flatten();
        let loss = loss_col.map(|c| number(c, "loss_factor")).transpose()?.flatten();
        let damping = match (ratio, loss) {
            (Some(z), None) if z > 0.0 && z < 1.0 => Damping::Ratio(z),
            (Some(z), None) => return Err(at(line, format!("damping_ratio = {z} must be in (0, 1){UNDAMPED}"))),
            (None, Some(e)) if e > 0.0 => Damping::LossFactor(e),
            (None, Some(e)) => return Err(at(line, format!("loss_factor = {e} must be > 0{UNDAMPED}"))),
            _ => return Err(at(line, "give exactly one of damping_ratio and loss_factor".into())),
        };
        let mut shape = [0.0; DOFS];
        for (k, c) in shape_cols.iter().enumerate() {
            let Some(c) = *c else { continue };
            shape[k] = number(c, SHAPE_COLUMNS[k])?
                .ok_or_else(|| at(line, format!("{} missing (0 where the mode does not move)", SHAPE_COLUMNS[k])))?;
        }
        if let (Some(pc), Some(cc)) = (partner_col, coeff_col) {
            let partner = field(pc).to_string();
            let coefficient = number(cc, "coefficient")?;
            match (partner.is_empty(), coefficient) {
                (true, None) => {}
                (false, Some(g)) => declared.push((modes.len(), partner, g, line)),
                _ => return Err(at(line, "give both partner and coefficient, or neither".into())),
            }
        }
        modes.push(Mode { name, frequency, damping, shape });
        lines.push(line);
    }
    if modes.is_empty() {
        return Err(at(0, "the table has no mode".into()));
    }
    let mut couplings: Vec<Gyroscopic> = Vec::new();
    for (a, partner, g, line) in declared {
        let b = modes
            .iter()
            .position(|m| m.name == partner)
            .ok_or_else(|| at(line, format!("partner `{partner}` is not a mode of the table")))?;
        if b == a {
            return Err(at(line, "a mode cannot be its own partner".into()));
        }
        match couplings.iter().find(|c| c.a == b && c.b == a) {
            Some(c) if (c.coefficient + g).abs() <= 1e-9 * g.abs().max(c.coefficient.abs()) => {}
            Some(c) => {
                return Err(at(
                    line,
                    format!(
                        "coefficient {g} contradicts line {}'s {} (G is skew: G_ba = -G_ab)",
                        lines[b], c.coefficient
                    ),
                ));
            }
            None => couplings.push(Gyroscopic { a, b, coefficient: g }),
        }
    }
    Ok(ModalTable { modes, couplings })
}

fn csv_line(e: &csv::Error) -> u64 {
    e.position().map_or(0, |p| p.line())
}
