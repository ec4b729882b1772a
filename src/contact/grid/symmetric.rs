//! Tangential products of fields symmetric about the grid's centre line
//! at about half the cost of [`FftConvolution::tangential`].
//!
//! A problem symmetric about y = 0 (no lateral creepage, no spin, a
//! symmetric gap) has `p_x` even and `p_y` odd in y. Along y such fields
//! are cosine and sine series: with the grid's rows placed on the period
//! `m_y` so that the centre line sits at index -1/2 (an even number of
//! rows; at 0 for odd), an even real column has the spectrum
//! `phi(k) R(k)` and an odd one `-i phi(k) S(k)`, `R`, `S` real and
//! `phi(k) = exp(i pi k delta / m_y)` (`delta` = 1 for an even number of
//! rows, 0 for odd). The two fields' y spectra are thus one complex row
//! `R + i S` per wavenumber `k_y = 0 ..= m_y / 2`, transformed along x as
//! one complex field `Z`. The kernels' symbols `a` (xx), `b` (yy), both
//! even, and `c` (xy, odd in k_x and in k_y), all real, act on it as
//!
//! ```text
//! W(k_x) = ((a + b)/2 - c) Z(k_x) + (a - b)/2 conj Z(-k_x)
//! ```
//!
//! (`Z = A + i B`: `U_x = phi (a A - i c B)`, `U_y = -i phi (i c A + b B)`),
//! back along x, then along y as the even and odd columns they are. The y
//! transforms run on the grid's `n_x` columns only (the x padding is still
//! zero there), the x transforms on `m_y / 2 + 1` rows: two thirds of the
//! full product's transform work, half its spectral product (the
//! convolution theorem for symmetric sequences, S. A. Martucci, IEEE
//! Trans. Signal Process. 42 (1994) 1038-1051).

use super::convolution::{FftConvolution, Real, ToeplitzKernel, fast_length};
use num_complex::{Complex, Complex64};
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Symmetric tangential products with one kernel (the zero-padded
/// influence kernel, or the inverse of its circulant).
#[derive(Clone)]
pub struct SymmetricConvolution<T: Real = f64> {
    nx: usize,
    ny: usize,
    /// Transform lengths along x and y.
    mx: usize,
    my: usize,
    fwd_x: Arc<dyn Fft<T>>,
    inv_x: Arc<dyn Fft<T>>,
    fwd_y: Arc<dyn Fft<T>>,
    inv_y: Arc<dyn Fft<T>>,
    /// `phi(k)`, `k = 0 ..= my / 2`.
    phase: Vec<Complex<T>>,
    /// Periodic index of each row and of its mirror image ([`places`]).
    place: Vec<(usize, usize)>,
    /// `(a + b)/2 - c` and `(a - b)/2` at `k_y mx + k_x`, with the
    /// `1/(mx my)` of the inverse transforms.
    sigma: Vec<T>,
    delta: Vec<T>,
}

impl<T: Real> std::fmt::Debug for SymmetricConvolution<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SymmetricConvolution {{ {} x {} on {} x {} }}", self.nx, self.ny, self.mx, self.my)
    }
}

/// Work buffers of one symmetric product.
#[derive(Debug, Clone, Default)]
pub struct SymmetricScratch<T: Real = f64> {
    /// Columns (`nx` of `my`).
    cols: Vec<Complex<T>>,
    /// Rows `k_y` of `mx`: `Z`, then `W`.
    z: Vec<Complex<T>>,
    w: Vec<Complex<T>>,
    fft: Vec<Complex<T>>,
}

impl SymmetricConvolution<f64> {
    /// The zero-padded tangential kernel (the product of
    /// [`FftConvolution::new`] on symmetric fields).
    pub fn padded(kernel: &ToeplitzKernel) -> Self {
        let (nx, ny) = kernel.shape();
        Self::padded_on(kernel, (fast_length(2 * nx - 1), fast_length(2 * ny - 1)))
    }

    /// [`SymmetricConvolution::padded`] on the transform lengths `(mx, my)`, at
    /// least `2 n - 1` each.
    pub fn padded_on(kernel: &ToeplitzKernel, lengths: (usize, usize)) -> Self {
        Self::with_symbols(kernel, lengths, |a, b, c| (a, b, c), padded_spectra(kernel, lengths))
    }

    /// The inverse of the kernel's circulant on the periods
    /// `fast_length(n)` (the product of [`FftConvolution::circulant_inverse`]
    /// on those periods, for symmetric fields): the 2 x 2 symbol `[[a, c], [c, b]]` inverted at every wavenumber; one not
    /// positive definite takes the reciprocal of the mean diagonal.
    pub fn circulant_inverse(kernel: &ToeplitzKernel) -> Self {
        let (lengths, raw, scale) = strang_spectra(kernel);
        let mean = raw[0].iter().zip(&raw[2]).map(|(a, b)| 0.5 * (a.re + b.re)).sum::<f64>() / raw[0].len() as f64;
        let invert = |a: f64, b: f64, c: f64| {
            let (s, d) = (0.5 * (a + b), (0.25 * (a - b) * (a - b) + c * c).sqrt());
            let det = a * b - c * c;
            if s - d > 1e-12 * mean && det > 0.0 {
                (b * scale / det, a * scale / det, -c * scale / det)
            } else {
                (scale / mean, scale / mean, 0.0)
            }
        };
        Self::with_symbols(kernel, lengths, invert, raw)
    }

    /// Builds the products from the kernel's three spectra `raw`
    /// (transposed layout `k_x my + k_y`), `map(a, b, c)` giving the
    /// symbol to apply.
    fn with_symbols(
        kernel: &ToeplitzKernel,
        (mx, my): (usize, usize),
        map: impl Fn(f64, f64, f64) -> (f64, f64, f64),
        raw: Vec<Vec<Complex64>>,
    ) -> Self {
        let (nx, ny) = kernel.shape();
        let hy = my / 2 + 1;
        let (mut sigma, mut delta) = (vec![0.0; hy * mx], vec![0.0; hy * mx]);
        for ky in 0..hy {
            for kx in 0..mx {
                let t = kx * my + ky;
                let (a, b, c) = map(raw[0][t].re, raw[2][t].re, raw[1][t].re);
                sigma[ky * mx + kx] = 0.5 * (a + b) - c;
                delta[ky * mx + kx] = 0.5 * (a - b);
            }
        }
        Self::planned((nx, ny), (mx, my), sigma, delta)
    }

    /// The same products in single precision.
    pub fn to_single(&self) -> SymmetricConvolution<f32> {
        let cast = |v: &[f64]| v.iter().map(|&x| x as f32).collect();
        SymmetricConvolution::planned((self.nx, self.ny), (self.mx, self.my), cast(&self.sigma), cast(&self.delta))
    }
}

impl<T: Real> SymmetricConvolution<T> {
    fn planned((nx, ny): (usize, usize), (mx, my): (usize, usize), sigma: Vec<T>, delta: Vec<T>) -> Self {
        let mut planner = FftPlanner::<T>::new();
        let phase = phases(ny, my);
        SymmetricConvolution {
            nx,
            ny,
            mx,
            my,
            fwd_x: planner.plan_fft_forward(mx),
            inv_x: planner.plan_fft_inverse(mx),
            fwd_y: planner.plan_fft_forward(my),
            inv_y: planner.plan_fft_inverse(my),
            phase,
            place: (0..ny).map(|r| places(ny, my, r)).collect(),
            sigma,
            delta,
        }
    }

    /// `(u_x, u_y) = K (p_x, p_y)` on the whole grid for the fields
    /// `p_x` even and `p_y` odd about the centre line, read from the lower
    /// half of the rows (`r < ny / 2`; on an odd grid the middle row's
    /// `p_x` too, its `p_y` being zero).
    pub fn tangential(
        &self,
        s: &mut SymmetricScratch<T>,
        (px, py): (&[f64], &[f64]),
        (ux, uy): (&mut [f64], &mut [f64]),
    ) {
        let rows = self.ny.div_ceil(2);
        let (ix, iy): (Vec<usize>, Vec<usize>) = (0..rows * self.nx).map(|k| (k % self.nx, k / self.nx)).unzip();
        self.product_on(s, (&ix, &iy), |c| (px[c], py[c]), |_, _, _| ());
        self.whole_grid(s, (ux, uy));
    }

    /// The product of the symmetric fields given at the grid elements in
    /// columns `ix` and rows `iy` of the lower half (`field(c)` = `(p_x,
    /// p_y)` of the `c`-th; zero elsewhere), handed back at the same
    /// elements (`out(c, u_x, u_y)`). The whole field stays in `s` for
    /// [`SymmetricConvolution::whole_grid`].
    pub fn product_on(
        &self,
        s: &mut SymmetricScratch<T>,
        (ix, iy): (&[usize], &[usize]),
        field: impl Fn(usize) -> (f64, f64),
        mut out: impl FnMut(usize, f64, f64),
    ) {
        let (nx, my) = (self.nx, self.my);
        let t = |v: f64| T::from_f64(v).unwrap_or_else(T::nan);
        // The columns, each field with its mirror image.
        s.cols.clear();
        s.cols.resize(nx * my, Complex::default());
        for (c, (&x, &r)) in ix.iter().zip(iy).enumerate() {
            let (fx, fy) = field(c);
            let (j, m) = self.place[r];
            let col = &mut s.cols[x * my..];
            if j == m {
                col[j] = Complex::new(t(fx), T::zero());
            } else {
                col[j] = Complex::new(t(fx), t(fy));
                col[m] = Complex::new(t(fx), -t(fy));
            }
        }
        self.transform(s);
        for (c, (&x, &r)) in ix.iter().zip(iy).enumerate() {
            let v = s.cols[x * my + self.place[r].0];
            out(c, v.re.to_f64().unwrap_or(f64::NAN), v.im.to_f64().unwrap_or(f64::NAN));
        }
    }

    /// The last product of [`SymmetricConvolution::product_on`] on the
    /// whole grid.
    pub fn whole_grid(&self, s: &SymmetricScratch<T>, (ux, uy): (&mut [f64], &mut [f64])) {
        let (nx, my) = (self.nx, self.my);
        for (r, &(j, _)) in self.place.iter().enumerate() {
            for x in 0..nx {
                let v = s.cols[x * my + j];
                ux[r * nx + x] = v.re.to_f64().unwrap_or(f64::NAN);
                uy[r * nx + x] = v.im.to_f64().unwrap_or(f64::NAN);
            }
        }
    }

    /// The loaded columns `s.cols` to the product's columns.
    fn transform(&self, s: &mut SymmetricScratch<T>) {
        let (nx, mx, my) = (self.nx, self.mx, self.my);
        let hy = my / 2 + 1;
        batch(&self.fwd_y, &mut s.cols, &mut s.fft);
        // R + i S of each column into the rows k_y.
        let half = T::from_f64(0.5).unwrap_or_else(T::nan);
        s.z.clear();
        s.z.resize(hy * mx, Complex::default());
        for x in 0..nx {
            let col = &s.cols[x * my..(x + 1) * my];
            for (ky, phase) in self.phase.iter().enumerate() {
                let (zk, zm) = (col[ky], col[if ky == 0 { 0 } else { my - ky }].conj());
                let (even, odd) = (zk + zm, zk - zm);
                // R = Re(conj phi X_p), S = -Im(conj phi X_q), X_p = even /
                // 2, X_q = odd / 2i.
                let r = half * (phase.re * even.re + phase.im * even.im);
                let sv = half * (phase.re * odd.re + phase.im * odd.im);
                s.z[ky * mx + x] = Complex::new(r, sv);
            }
        }
        batch(&self.fwd_x, &mut s.z, &mut s.fft);
        s.w.resize(hy * mx, Complex::default());
        for ky in 0..hy {
            let (z, w) = (&s.z[ky * mx..(ky + 1) * mx], &mut s.w[ky * mx..(ky + 1) * mx]);
            let (sg, dl) = (&self.sigma[ky * mx..(ky + 1) * mx], &self.delta[ky * mx..(ky + 1) * mx]);
            spectral_row(z, (sg, dl), w);
        }
        batch(&self.inv_x, &mut s.w, &mut s.fft);
        // Back along y: U_x = phi R_u, U_y = -i phi S_u, both real
        // columns (their Hermitian halves), in one complex transform.
        for x in 0..nx {
            let col = &mut s.cols[x * my..(x + 1) * my];
            for (ky, phase) in self.phase.iter().enumerate() {
                let v = s.w[ky * mx + x];
                // a = phi R_u, b = -i phi S_u; the column a + i b at k_y
                // and conj a + i conj b at -k_y.
                let (a_re, a_im) = (phase.re * v.re, phase.im * v.re);
                let (b_re, b_im) = (phase.im * v.im, -phase.re * v.im);
                if ky == 0 || 2 * ky == my {
                    col[ky] = Complex::new(a_re, b_re);
                } else {
                    col[ky] = Complex::new(a_re - b_im, a_im + b_re);
                    col[my - ky] = Complex::new(a_re + b_im, b_re - a_im);
                }
            }
        }
        batch(&self.inv_y, &mut s.cols, &mut s.fft);
    }
}

/// Normal products of a pressure symmetric about the centre line, by the
/// same transforms as [`SymmetricConvolution`]: pairs of columns travel in
/// one complex transform along y (the real and imaginary parts, split by
/// Hermitian symmetry), each column's real cosine coefficients `R(k_y)`
/// then, row by row, through real-to-complex transforms along x, where the
/// kernel's symbol is real. About two thirds of the transform work of
/// [`FftConvolution::normal`].
#[derive(Clone)]
pub struct SymmetricNormal {
    nx: usize,
    ny: usize,
    mx: usize,
    my: usize,
    real_x: Arc<dyn RealToComplex<f64>>,
    real_inv_x: Arc<dyn ComplexToReal<f64>>,
    fwd_y: Arc<dyn Fft<f64>>,
    inv_y: Arc<dyn Fft<f64>>,
    phase: Vec<Complex64>,
    /// Periodic index of each row and of its mirror image ([`places`]).
    place: Vec<(usize, usize)>,
    /// The real symbol at `k_y (mx / 2 + 1) + k_x`, with the `1/(mx my)` of
    /// the inverse transforms.
    symbol: Vec<f64>,
}

impl std::fmt::Debug for SymmetricNormal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SymmetricNormal {{ {} x {} on {} x {} }}", self.nx, self.ny, self.mx, self.my)
    }
}

/// Work buffers of one symmetric normal product.
#[derive(Debug, Clone, Default)]
pub struct NormalScratch {
    /// Pairs of columns (`(nx + 1) / 2` of `my`).
    cols: Vec<Complex64>,
    /// Rows `k_y` of `mx` reals, and their half spectra.
    rows: Vec<f64>,
    half: Vec<Complex64>,
    fft: Vec<Complex64>,
}

impl SymmetricNormal {
    /// The zero-padded normal kernel (the product of
    /// [`FftConvolution::new`] on symmetric fields).
    pub fn padded(kernel: &ToeplitzKernel) -> Self {
        let (nx, ny) = kernel.shape();
        Self::padded_on(kernel, (fast_length(2 * nx - 1), fast_length(2 * ny - 1)))
    }

    /// [`SymmetricNormal::padded`] on the transform lengths `(mx, my)`, at
    /// least `2 n - 1` each.
    pub fn padded_on(kernel: &ToeplitzKernel, lengths: (usize, usize)) -> Self {
        Self::with_symbol(kernel, lengths, |a| a, &padded_spectra(kernel, lengths)[0])
    }

    /// The inverse of the kernel's circulant on the periods
    /// `fast_length(n)` (the preconditioner of
    /// [`FftConvolution::circulant_inverse`] on those periods, for
    /// symmetric fields); a wavenumber whose symbol is not positive takes the reciprocal of the
    /// mean.
    pub fn circulant_inverse(kernel: &ToeplitzKernel) -> Self {
        let (lengths, raw, scale) = strang_spectra(kernel);
        let mean = raw[0].iter().map(|v| v.re).sum::<f64>() / raw[0].len() as f64;
        Self::with_symbol(kernel, lengths, |a| scale / if a > 1e-12 * mean { a } else { mean }, &raw[0])
    }

    fn with_symbol(
        kernel: &ToeplitzKernel,
        (mx, my): (usize, usize),
        map: impl Fn(f64) -> f64,
        raw: &[Complex64],
    ) -> Self {
        let (nx, ny) = kernel.shape();
        let (hx, hy) = (mx / 2 + 1, my / 2 + 1);
        let symbol = (0..hy * hx).map(|t| map(raw[(t % hx) * my + t / hx].re)).collect();
        let mut planner = FftPlanner::new();
        let mut real = RealFftPlanner::new();
        SymmetricNormal {
            nx,
            ny,
            mx,
            my,
            real_x: real.plan_fft_forward(mx),
            real_inv_x: real.plan_fft_inverse(mx),
            fwd_y: planner.plan_fft_forward(my),
            inv_y: planner.plan_fft_inverse(my),
            phase: phases(ny, my),
            place: (0..ny).map(|r| places(ny, my, r)).collect(),
            symbol,
        }
    }

    /// Makes `p` on the whole grid symmetric about the centre line (each
    /// element and its mirror image take their mean).
    pub fn symmetrize(&self, p: &mut [f64]) {
        symmetrize(p, (self.nx, self.ny));
    }

    /// The weights of the lower half's elements (the first `(ny + 1) / 2`
    /// rows) in sums over the whole grid of a symmetric field: 2 for an
    /// element and its mirror image, 1 on the middle row of an odd grid.
    pub fn lower_half_weights(&self) -> Vec<f64> {
        let (nx, ny) = (self.nx, self.ny);
        (0..ny.div_ceil(2) * nx).map(|k| if 2 * (k / nx) + 1 == ny { 1.0 } else { 2.0 }).collect()
    }

    /// Copies the lower half of `p` onto its mirror image.
    pub fn mirror_lower(&self, p: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        for r in 0..ny / 2 {
            let m = ny - 1 - r;
            let (low, high) = p.split_at_mut(m * nx);
            high[..nx].copy_from_slice(&low[r * nx..(r + 1) * nx]);
        }
    }

    /// `u = K_n p` on the whole grid for a pressure symmetric about the
    /// centre line, read from the lower half of the rows (`r <
    /// (ny + 1) / 2`).
    pub fn normal(&self, s: &mut NormalScratch, p: &[f64], u: &mut [f64]) {
        self.product(s, p, u, self.ny);
    }

    /// [`SymmetricNormal::normal`] written on the lower half of the rows
    /// only (the normal solve's loops run there).
    pub fn normal_lower(&self, s: &mut NormalScratch, p: &[f64], u: &mut [f64]) {
        self.product(s, p, u, self.ny.div_ceil(2));
    }

    /// `u = K_n p` on the first `rows` rows.
    fn product(&self, s: &mut NormalScratch, p: &[f64], u: &mut [f64], rows: usize) {
        let (nx, ny, mx, my) = (self.nx, self.ny, self.mx, self.my);
        let (hx, hy, pairs) = (mx / 2 + 1, my / 2 + 1, nx.div_ceil(2));
        let place = &self.place;
        // Columns 2q and 2q + 1 as the real and imaginary parts of column q.
        s.cols.clear();
        s.cols.resize(pairs * my, Complex::default());
        for (q, col) in s.cols.chunks_exact_mut(my).enumerate() {
            let (x, odd) = (2 * q, 2 * q + 1 < nx);
            for (r, &(j, m)) in place[..ny.div_ceil(2)].iter().enumerate() {
                let v = Complex::new(p[r * nx + x], if odd { p[r * nx + x + 1] } else { 0.0 });
                (col[j], col[m]) = (v, v);
            }
        }
        batch(&self.fwd_y, &mut s.cols, &mut s.fft);
        // Each column's cosine coefficients R(k_y): row k_y of `rows`.
        s.rows.clear();
        s.rows.resize(hy * mx, 0.0);
        for (q, col) in s.cols.chunks_exact(my).enumerate() {
            for (ky, ph) in self.phase.iter().enumerate() {
                let (zk, zm) = (col[ky], col[if ky == 0 { 0 } else { my - ky }].conj());
                let (even, odd) = (zk + zm, zk - zm);
                // Column 2q + 1 lies in the padding where nx is odd; its
                // coefficients are zero.
                s.rows[ky * mx + 2 * q] = 0.5 * (ph.re * even.re + ph.im * even.im);
                s.rows[ky * mx + 2 * q + 1] = 0.5 * (ph.re * odd.im - ph.im * odd.re);
            }
        }
        for ky in 0..hy {
            s.rows[ky * mx + nx..(ky + 1) * mx].fill(0.0);
        }
        let need = self.real_x.get_scratch_len().max(self.real_inv_x.get_scratch_len());
        if s.fft.len() < need {
            s.fft.resize(need, Complex::default());
        }
        s.half.resize(hx, Complex::default());
        for (row, symbol) in s.rows.chunks_exact_mut(mx).zip(self.symbol.chunks_exact(hx)) {
            self.real_x.process_with_scratch(row, &mut s.half, &mut s.fft[..need]).expect("planned lengths");
            for (h, k) in s.half.iter_mut().zip(symbol) {
                *h *= *k;
            }
            // The product is real: the zero and Nyquist bins' imaginary
            // parts are rounding.
            s.half[0].im = 0.0;
            if mx % 2 == 0 {
                s.half[hx - 1].im = 0.0;
            }
            self.real_inv_x.process_with_scratch(&mut s.half, row, &mut s.fft[..need]).expect("planned lengths");
        }
        // Back along y: U(k_y) = phi R_u(k_y), two columns per transform.
        for (q, col) in s.cols.chunks_exact_mut(my).enumerate() {
            for (ky, ph) in self.phase.iter().enumerate() {
                let (ra, rb) = (s.rows[ky * mx + 2 * q], s.rows[ky * mx + 2 * q + 1]);
                let (a_re, a_im, b_re, b_im) = (ph.re * ra, ph.im * ra, ph.re * rb, ph.im * rb);
                if ky == 0 || 2 * ky == my {
                    col[ky] = Complex::new(a_re, b_re);
                } else {
                    col[ky] = Complex::new(a_re - b_im, a_im + b_re);
                    col[my - ky] = Complex::new(a_re + b_im, b_re - a_im);
                }
            }
        }
        batch(&self.inv_y, &mut s.cols, &mut s.fft);
        for (r, &(j, _)) in place[..rows].iter().enumerate() {
            let row = &mut u[r * nx..(r + 1) * nx];
            for (pair, col) in row.chunks_mut(2).zip(s.cols.chunks_exact(my)) {
                pair[0] = col[j].re;
                if let Some(v) = pair.get_mut(1) {
                    *v = col[j].im;
                }
            }
        }
    }
}

/// One row of the spectral product, `w(k) = sigma(k) z(k) + delta(k)
/// conj z(-k)` with real `sigma`, `delta` (the mirror wavenumber's run
/// reversed, so that the loop vectorises).
fn spectral_row<T: Real>(z: &[Complex<T>], (sigma, delta): (&[T], &[T]), w: &mut [Complex<T>]) {
    w[0] = Complex::new((sigma[0] + delta[0]) * z[0].re, (sigma[0] - delta[0]) * z[0].im);
    let terms = w[1..].iter_mut().zip(&z[1..]).zip(z[1..].iter().rev()).zip(sigma[1..].iter().zip(&delta[1..]));
    for (((w, a), b), (&s, &d)) in terms {
        *w = Complex::new(s * a.re + d * b.re, s * a.im - d * b.im);
    }
}

/// The kernel's spectra zero-padded on the transform lengths `(mx, my)`,
/// at least `2 n - 1` each (transposed layout `k_x my + k_y`).
fn padded_spectra(kernel: &ToeplitzKernel, lengths: (usize, usize)) -> Vec<Vec<Complex64>> {
    let (nx, ny) = kernel.shape();
    assert!(lengths.0 > 2 * nx - 2 && lengths.1 > 2 * ny - 2, "zero padding of at least 2 n - 1");
    FftConvolution::planned((nx, ny), lengths).padded_tables(kernel)
}

/// The spectra of the kernel's Strang circulant on the periods
/// `fast_length(n)`, those periods and the inverse transforms' `1/(mx
/// my)`.
fn strang_spectra(kernel: &ToeplitzKernel) -> ((usize, usize), Vec<Vec<Complex64>>, f64) {
    let (nx, ny) = kernel.shape();
    let lengths = (fast_length(nx), fast_length(ny));
    let raw = FftConvolution::planned((nx, ny), lengths).strang_tables(kernel);
    (lengths, raw, 1.0 / (lengths.0 * lengths.1) as f64)
}

/// Makes `p` on a grid of `nx x ny` elements symmetric about the centre
/// line: each element and its mirror image take their mean.
pub fn symmetrize(p: &mut [f64], (nx, ny): (usize, usize)) {
    for r in 0..ny / 2 {
        let m = ny - 1 - r;
        for x in 0..nx {
            let v = 0.5 * (p[r * nx + x] + p[m * nx + x]);
            (p[r * nx + x], p[m * nx + x]) = (v, v);
        }
    }
}

/// `phi(k) = exp(i pi k delta / my)`, `k = 0 ..= my / 2`: the half-sample
/// shift of a grid of `ny` rows (`delta` = 1 for even `ny`, 0 for odd).
fn phases<T: Real>(ny: usize, my: usize) -> Vec<Complex<T>> {
    let shift = if ny.is_multiple_of(2) { 1.0 } else { 0.0 };
    (0..=my / 2)
        .map(|k| {
            let t = std::f64::consts::PI * k as f64 * shift / my as f64;
            Complex::new(T::from_f64(t.cos()).unwrap_or_else(T::nan), T::from_f64(t.sin()).unwrap_or_else(T::nan))
        })
        .collect()
}

/// Periodic index, on a period of `my`, of row `r` of `ny` and of its
/// mirror image: the centre line at -1/2 (even `ny`) or 0 (odd).
fn places(ny: usize, my: usize, r: usize) -> (usize, usize) {
    let (ny, my) = (ny as isize, my as isize);
    let j = r as isize - ny / 2;
    let m = if ny % 2 == 0 { -1 - j } else { -j };
    (j.rem_euclid(my) as usize, m.rem_euclid(my) as usize)
}

/// Runs `fft` on every transform-length chunk of `data`.
fn batch<T: Real>(fft: &Arc<dyn Fft<T>>, data: &mut [Complex<T>], scratch: &mut Vec<Complex<T>>) {
    let need = fft.get_inplace_scratch_len();
    if scratch.len() < need {
        scratch.resize(need, Complex::default());
    }
    fft.process_with_scratch(data, &mut scratch[..need]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::grid::PotentialGrid;
    use crate::contact::grid::convolution::FftScratch;

    /// A symmetric pair of fields (x even, y odd about the centre line).
    fn symmetric_fields(nx: usize, ny: usize, seed: f64) -> (Vec<f64>, Vec<f64>) {
        let (mut px, mut py) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        for r in 0..ny.div_ceil(2) {
            let m = ny - 1 - r;
            for x in 0..nx {
                let v = ((r * nx + x) as f64 * 0.731 + seed).sin();
                let w = ((r * nx + x) as f64 * 1.37 + 2.0 * seed).cos();
                (px[r * nx + x], px[m * nx + x]) = (v, v);
                if m != r {
                    (py[r * nx + x], py[m * nx + x]) = (w, -w);
                }
            }
        }
        (px, py)
    }

    /// The symmetric normal product equals the full one on a symmetric
    /// pressure, for odd and even column and row counts, padded and as the
    /// circulant inverse.
    #[test]
    fn normal_equals_the_full_product_on_symmetric_fields() {
        for (nx, ny) in [(13, 8), (12, 9), (20, 14), (7, 5), (6, 6)] {
            let kernel = ToeplitzKernel::normal(&grid(nx, ny), 8.1e10, 0.28);
            let (p, _) = symmetric_fields(nx, ny, 0.7);
            let n = nx * ny;
            for (name, full, sym) in [
                ("padded", FftConvolution::new(&kernel), SymmetricNormal::padded(&kernel)),
                (
                    "inverse",
                    FftConvolution::circulant_inverse_on(&kernel, (fast_length(nx), fast_length(ny))),
                    SymmetricNormal::circulant_inverse(&kernel),
                ),
            ] {
                let mut u = vec![0.0; n];
                full.normal(&mut FftScratch::default(), &p, &mut u);
                let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let mut v = vec![f64::NAN; n];
                sym.normal(&mut NormalScratch::default(), &p, &mut v);
                let err = u.iter().zip(&v).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
                assert!(err < 1e-12, "{name} {nx} x {ny}: {err:e}");
            }
        }
    }

    fn grid(nx: usize, ny: usize) -> PotentialGrid {
        PotentialGrid { nx, ny, dx: 2e-4, dy: 5e-4, x_front: 0.5 * nx as f64 * 2e-4, y_low: -0.5 * ny as f64 * 5e-4 }
    }

    /// The symmetric product equals the full one on symmetric fields, on
    /// grids with an even and an odd number of rows, for the padded kernel
    /// and the circulant inverse, in both precisions.
    #[test]
    fn equals_the_full_product_on_symmetric_fields() {
        for (nx, ny) in [(13, 8), (12, 9), (20, 14), (7, 5)] {
            let kernel = ToeplitzKernel::tangential(&grid(nx, ny), 8.1e10, 0.28);
            let (px, py) = symmetric_fields(nx, ny, 0.3);
            let n = nx * ny;
            for (name, full, sym) in [
                ("padded", FftConvolution::new(&kernel), SymmetricConvolution::padded(&kernel)),
                (
                    "inverse",
                    FftConvolution::circulant_inverse_on(&kernel, (fast_length(nx), fast_length(ny))),
                    SymmetricConvolution::circulant_inverse(&kernel),
                ),
            ] {
                let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
                full.tangential(&mut FftScratch::default(), (&px, &py), (&mut ux, &mut uy));
                let scale = ux.iter().chain(&uy).fold(0.0f64, |m, v| m.max(v.abs()));
                let (mut vx, mut vy) = (vec![f64::NAN; n], vec![f64::NAN; n]);
                sym.tangential(&mut SymmetricScratch::default(), (&px, &py), (&mut vx, &mut vy));
                let err =
                    |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
                let (ex, ey) = (err(&ux, &vx), err(&uy, &vy));
                assert!(ex < 1e-12 && ey < 1e-12, "{name} {nx} x {ny}: {ex:e} {ey:e}");
                let single = sym.to_single();
                single.tangential(&mut SymmetricScratch::default(), (&px, &py), (&mut vx, &mut vy));
                let (ex, ey) = (err(&ux, &vx), err(&uy, &vy));
                assert!(ex < 1e-5 && ey < 1e-5, "{name} single {nx} x {ny}: {ex:e} {ey:e}");
            }
        }
    }
}
