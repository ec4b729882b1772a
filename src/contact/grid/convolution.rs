//! Influence coefficients on a uniform grid and their products.
//!
//! On a uniform grid the displacement difference at element I under uniform
//! traction on element J depends only on the index offset `(ix_I - ix_J,
//! iy_I - iy_J)`: the influence matrix is block-Toeplitz, `u_I = sum_J
//! K(I - J) p_J`, and one `(2 nx - 1) x (2 ny - 1)` table of coefficients per
//! component replaces the `N x N` matrix ([`ToeplitzKernel`]). The
//! coefficients are the closed-form rectangle integrals of
//! [`crate::contact::influence`] (Boussinesq for the normal, Cerruti for the
//! tangential displacement difference of two identical half-spaces).
//!
//! The product over the whole grid is a linear convolution, computed as a
//! circular one on a grid zero-padded to at least `(2 nx - 1) x (2 ny - 1)`
//! with 2-D FFTs ([`FftConvolution`]; rustfft along rows, then along
//! columns). The two tangential components travel in one complex transform
//! (`z = p_x + i p_y`, split by Hermitian symmetry), so a tangential product
//! costs two complex 2-D FFTs; the normal product, of one real field, runs
//! real-to-complex transforms along x (realfft) and the complex ones along
//! y on half the spectrum: about half of that.

use num_complex::{Complex, Complex64};
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_traits::{Float, FromPrimitive, ToPrimitive};
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

pub use super::kernel::ToeplitzKernel;

/// The padded transform length for `n` elements along an axis.
pub fn smooth_padding(n: usize) -> usize {
    smooth_length(2 * n - 1)
}

/// A length at least `n` whose prime factors are 2, 3 and 5 with at least
/// 2^2 and at most one 5: the symmetric products' lengths
/// ([`super::symmetric`]). rustfft's AVX transforms have fast butterflies
/// for these, realfft's real-to-complex transforms want even lengths. On
/// the 0.2 mm growth grid (109 x 74 elements) the symmetric normal product
/// takes 89 us on 240 x 160 points against 134 us on the smooth 225 x 150,
/// the single-precision tangential 110 against 147 us; on the default
/// 0.2 mm grid (67 x 45) 32 against 40 and 39 against 52 us (the
/// double-precision tangential 59 against 56, 41 against 47 at 0.4 mm).
pub(super) fn fast_length(n: usize) -> usize {
    (n.max(1)..)
        .find(|&m| {
            let (mut m, mut twos, mut fives) = (m, 0, 0);
            while m % 2 == 0 {
                m /= 2;
                twos += 1;
            }
            while m % 3 == 0 {
                m /= 3;
            }
            while m % 5 == 0 {
                m /= 5;
                fives += 1;
            }
            m == 1 && twos >= 2 && fives <= 1
        })
        .expect("such numbers are unbounded")
}

/// A length at least `n` whose prime factors are 2, 3 and 5 (fast for
/// rustfft's mixed-radix algorithms). (Lengths with at least 2^2 and at
/// most one 5, which single-precision transforms alone take faster, 1.5
/// times in criterion at 0.2 mm, made paper_normal_30mm no faster: 2 %
/// slower, median of 5, within this 2-vCPU machine's A/B noise of about
/// 5 %.)
fn smooth_length(n: usize) -> usize {
    (n..)
        .find(|&m| {
            let mut m = m;
            for p in [2, 3, 5] {
                while m % p == 0 {
                    m /= p;
                }
            }
            m == 1
        })
        .expect("smooth numbers are unbounded")
}

/// The floating-point types the products run in (`f64`; `f32` for the CG
/// solver's inner products).
pub trait Real: rustfft::FftNum + Float + FromPrimitive + ToPrimitive + Default {}
impl Real for f32 {}
impl Real for f64 {}

/// Zero-padded FFT products with the kernels of one [`ToeplitzKernel`].
#[derive(Clone)]
pub struct FftConvolution<T: Real = f64> {
    nx: usize,
    ny: usize,
    /// Padded lengths along x and y.
    mx: usize,
    my: usize,
    fwd_x: Arc<dyn Fft<T>>,
    fwd_y: Arc<dyn Fft<T>>,
    inv_x: Arc<dyn Fft<T>>,
    inv_y: Arc<dyn Fft<T>>,
    /// Real-to-complex and complex-to-real transforms along x (the normal
    /// product's real fields: half the spectrum, `mx/2 + 1` columns).
    real_x: Arc<dyn RealToComplex<T>>,
    real_inv_x: Arc<dyn ComplexToReal<T>>,
    /// Kernel spectra, transposed layout `kx my + ky`, including the
    /// `1/(mx my)` of the inverse transform: for the tangential kernel
    /// `(xx + yy)/2` and `(xx - yy)/2 + i xy`; for the normal kernel its
    /// first `mx/2 + 1` columns (the rest mirror them).
    spectra: Vec<Vec<Complex<T>>>,
}

impl<T: Real> std::fmt::Debug for FftConvolution<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "FftConvolution {{ {} x {} padded to {} x {} }}", self.nx, self.ny, self.mx, self.my)
    }
}

/// Work buffers of one product.
#[derive(Debug, Clone, Default)]
pub struct FftScratch<T: Real = f64> {
    rows: Vec<Complex<T>>,
    cols: Vec<Complex<T>>,
    /// The spectrum product of a tangential product (transposed layout).
    spectrum: Vec<Complex<T>>,
    /// The transforms' scratch.
    fft: Vec<Complex<T>>,
    /// One real row of a normal product and its half spectrum.
    real: Vec<T>,
    half: Vec<Complex<T>>,
}

/// Runs `fft` on every transform-length chunk of `data`. (Two parallel
/// halves per batch were measured slower on 2 cores: 28 s against 12 s
/// for paper_normal_30mm on the 0.2 mm grid, most of it the threads'
/// wake-ups.)
fn batch<T: Real>(fft: &Arc<dyn Fft<T>>, data: &mut [Complex<T>], scratch: &mut Vec<Complex<T>>) {
    let need = fft.get_inplace_scratch_len();
    if scratch.len() < need {
        scratch.resize(need, Complex::default());
    }
    fft.process_with_scratch(data, &mut scratch[..need]);
}

impl FftConvolution<f64> {
    /// Plans the transforms and the kernel spectra of `kernel`.
    pub fn new(kernel: &ToeplitzKernel) -> Self {
        let (nx, ny) = kernel.shape();
        Self::padded_to(kernel, (smooth_padding(nx), smooth_padding(ny)))
    }

    /// The same products in single precision (the CG solver's inner
    /// products, whose Newton systems are solved to a
    /// tenth of the residual: rounding of 1e-7 is far below that; the
    /// residual and the verdict stay in double precision).
    pub fn single(kernel: &ToeplitzKernel) -> FftConvolution<f32> {
        Self::new(kernel).to_single()
    }

    fn padded_to(kernel: &ToeplitzKernel, (mx, my): (usize, usize)) -> Self {
        let (nx, ny) = kernel.shape();
        let mut conv = FftConvolution::planned((nx, ny), (mx, my));
        conv.spectra = conv.padded_tables(kernel);
        conv.spectra = if kernel.components() == 3 {
            // The tangential product's combinations (see `tangential`).
            let (xx, xy, yy) = (&conv.spectra[0], &conv.spectra[1], &conv.spectra[2]);
            let sum = xx.iter().zip(yy).map(|(a, b)| (a + b) * 0.5).collect();
            let diff = xx.iter().zip(yy).zip(xy).map(|((a, b), c)| (a - b) * 0.5 + Complex64::i() * c).collect();
            vec![sum, diff]
        } else {
            vec![conv.spectra[0][..(mx / 2 + 1) * my].to_vec()]
        };
        conv
    }

    /// The inverse of the kernel's circulant approximation on a periodic
    /// grid of smooth lengths at least the grid's (no padding: a product
    /// with it costs about a third of one on the padded grid): the
    /// preconditioner of the tangential CG solver, `(u_x, u_y) -> (p_x,
    /// p_y)` (Pa/m) by [`FftConvolution::tangential`], and of the normal
    /// CG, `u -> p` by [`FftConvolution::normal`].
    ///
    /// The circulant is Strang's (each periodic offset takes the kernel at
    /// its nearest image, the mean of the two at half the period), the
    /// choice for Toeplitz systems of R. H. Chan & M. K. Ng, SIAM Review 38
    /// (1996) 427-482; Vollebregt's FFT-based preconditioner inverts the
    /// influence matrix on the grid the same way (J. Comput. Phys. 257
    /// (2014) 333-351). The tangential 2 x 2 symbol `[[K_xx, K_xy], [K_xy,
    /// K_yy]](k)` (the normal one, a scalar) is inverted at every
    /// wavenumber; a wavenumber whose symbol is not positive definite
    /// (none on the grids measured) takes the reciprocal of the mean
    /// diagonal.
    pub fn circulant_inverse(kernel: &ToeplitzKernel) -> Self {
        let (nx, ny) = kernel.shape();
        Self::circulant_inverse_on(kernel, (smooth_length(nx), smooth_length(ny)))
    }

    /// [`FftConvolution::circulant_inverse`] in single precision (the
    /// tangential CG's preconditioner).
    pub fn circulant_inverse_single(kernel: &ToeplitzKernel) -> FftConvolution<f32> {
        Self::circulant_inverse(kernel).to_single()
    }

    /// [`FftConvolution::circulant_inverse`] on the periodic lengths `(mx,
    /// my)`, at least the grid's.
    pub(super) fn circulant_inverse_on(kernel: &ToeplitzKernel, (mx, my): (usize, usize)) -> Self {
        let (nx, ny) = kernel.shape();
        let mut conv = FftConvolution::planned((nx, ny), (mx, my));
        let raw = conv.strang_tables(kernel);
        let scale = 1.0 / (mx * my) as f64;
        if kernel.components() == 1 {
            // The normal kernel's real, even symbol: its reciprocal, half
            // the spectrum for the real-to-complex product.
            let symbol = &raw[0][..(mx / 2 + 1) * my];
            let mean = symbol.iter().map(|v| v.re).sum::<f64>() / symbol.len() as f64;
            let inv = symbol
                .iter()
                .map(|v| Complex64::new(scale / if v.re > 1e-12 * mean { v.re } else { mean }, 0.0))
                .collect();
            conv.spectra = vec![inv];
            return conv;
        }
        let (xx, xy, yy) = (&raw[0], &raw[1], &raw[2]);
        let sum: Vec<Complex64> = xx.iter().zip(yy).map(|(a, b)| (a + b) * 0.5).collect();
        let diff: Vec<Complex64> =
            xx.iter().zip(yy).zip(xy).map(|((a, b), c)| (a - b) * 0.5 + Complex64::i() * c).collect();
        // W(k) = s(k) Z(k) + d(k) conj Z(-k) inverted: with the equation at
        // -k conjugated, Z(k) = (conj s(-k) W(k) - d(k) conj W(-k)) / det.
        let mean = sum.iter().map(|v| v.re).sum::<f64>() / sum.len() as f64;
        let (mut inv_sum, mut inv_diff) = (vec![Complex64::default(); mx * my], vec![Complex64::default(); mx * my]);
        for cx in 0..mx {
            for cy in 0..my {
                let k = cx * my + cy;
                let m = ((mx - cx) % mx) * my + (my - cy) % my;
                let det = sum[k] * sum[m].conj() - diff[k] * diff[m].conj();
                let (s, d) = (sum[k].re, diff[k].norm());
                if s - d > 1e-12 * mean && det.norm() > 0.0 {
                    inv_sum[k] = sum[m].conj() / det * scale;
                    inv_diff[k] = -diff[k] / det * scale;
                } else {
                    inv_sum[k] = Complex64::new(scale / mean, 0.0);
                }
            }
        }
        conv.spectra = vec![inv_sum, inv_diff];
        conv
    }

    /// The spectra (transposed layout) of the kernel's components
    /// zero-padded to the transform's lengths, with the `1/(mx my)` of the
    /// inverse transform.
    pub(super) fn padded_tables(&self, kernel: &ToeplitzKernel) -> Vec<Vec<Complex64>> {
        let (nx, ny, mx, my) = (self.nx, self.ny, self.mx, self.my);
        let scale = 1.0 / (mx * my) as f64;
        // The table zero-padded: an index's image within the table's
        // offsets, if any (at most one: the period holds 2 n - 1).
        let image = |i: usize, m: usize, n: usize| -> Option<isize> {
            [i as isize, i as isize - m as isize].into_iter().find(|d| d.unsigned_abs() < n)
        };
        self.spectra_of(kernel.components(), |c, i, j| match (image(i, mx, nx), image(j, my, ny)) {
            (Some(dix), Some(diy)) => kernel.at(c, dix, diy) * scale,
            _ => 0.0,
        })
    }

    /// The spectra (transposed layout) of the kernel's components as
    /// Strang's circulant on the transform's lengths (each periodic offset
    /// takes the kernel at its nearest image, the mean of the two at half
    /// the period), without the inverse transform's scale.
    pub(super) fn strang_tables(&self, kernel: &ToeplitzKernel) -> Vec<Vec<Complex64>> {
        let (mx, my) = (self.mx, self.my);
        // The nearest images of a periodic index, both at half the period.
        let images = |i: usize, m: usize| -> Vec<isize> {
            let (a, b) = (i as isize, i as isize - m as isize);
            match (2 * i).cmp(&m) {
                std::cmp::Ordering::Less => vec![a],
                std::cmp::Ordering::Equal => vec![a, b],
                std::cmp::Ordering::Greater => vec![b],
            }
        };
        self.spectra_of(kernel.components(), |c, i, j| {
            let (xs, ys) = (images(i, mx), images(j, my));
            let mut v = 0.0;
            for &dix in &xs {
                for &diy in &ys {
                    v += kernel.at(c, dix, diy);
                }
            }
            v / (xs.len() * ys.len()) as f64
        })
    }

    /// The spectra (transposed layout) of `components` periodic tables on
    /// the transform's points, `value(c, i, j)` at column `i`, row `j`.
    fn spectra_of(&self, components: usize, value: impl Fn(usize, usize, usize) -> f64) -> Vec<Vec<Complex64>> {
        let (mx, my) = (self.mx, self.my);
        let mut scratch = FftScratch::default();
        (0..components)
            .map(|c| {
                scratch.rows.clear();
                scratch.rows.extend(
                    (0..my)
                        .flat_map(|j| (0..mx).map(move |i| (i, j)))
                        .map(|(i, j)| Complex64::new(value(c, i, j), 0.0)),
                );
                self.forward(&mut scratch, my);
                scratch.cols.clone()
            })
            .collect()
    }

    /// The same products in single precision.
    pub fn to_single(&self) -> FftConvolution<f32> {
        let mut single = FftConvolution::planned((self.nx, self.ny), (self.mx, self.my));
        single.spectra =
            self.spectra.iter().map(|sp| sp.iter().map(|v| Complex::new(v.re as f32, v.im as f32)).collect()).collect();
        single
    }
}

impl<T: Real> FftConvolution<T> {
    /// The transforms of an `nx x ny` grid on `mx x my` points, no
    /// spectra yet.
    pub(super) fn planned((nx, ny): (usize, usize), (mx, my): (usize, usize)) -> Self {
        let mut planner = FftPlanner::<T>::new();
        let mut real = RealFftPlanner::<T>::new();
        FftConvolution {
            nx,
            ny,
            mx,
            my,
            fwd_x: planner.plan_fft_forward(mx),
            fwd_y: planner.plan_fft_forward(my),
            inv_x: planner.plan_fft_inverse(mx),
            inv_y: planner.plan_fft_inverse(my),
            real_x: real.plan_fft_forward(mx),
            real_inv_x: real.plan_fft_inverse(mx),
            spectra: Vec::new(),
        }
    }

    /// Grid columns and rows (nx, ny).
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Padded transform size (mx, my).
    pub fn padded(&self) -> (usize, usize) {
        (self.mx, self.my)
    }

    /// 2-D forward transform of `s.rows` (row-major, `my` rows of `mx`, only
    /// the first `rows_nonzero` rows used: the rest are zero) into `s.cols`
    /// (transposed).
    fn forward(&self, s: &mut FftScratch<T>, rows_nonzero: usize) {
        let (mx, my) = (self.mx, self.my);
        batch(&self.fwd_x, &mut s.rows[..rows_nonzero * mx], &mut s.fft);
        s.cols.resize(mx * my, Complex::default());
        for (c, col) in s.cols.chunks_exact_mut(my).enumerate() {
            for (r, v) in col[..rows_nonzero].iter_mut().enumerate() {
                *v = s.rows[r * mx + c];
            }
            col[rows_nonzero..].fill(Complex::default());
        }
        batch(&self.fwd_y, &mut s.cols, &mut s.fft);
    }

    /// 2-D inverse transform of `s.cols` (transposed) into the first
    /// `rows_needed` rows of `s.rows`.
    fn inverse(&self, s: &mut FftScratch<T>, rows_needed: usize) {
        let (mx, my) = (self.mx, self.my);
        batch(&self.inv_y, &mut s.cols, &mut s.fft);
        s.rows.resize(mx * my, Complex::default());
        for r in 0..rows_needed {
            for (c, v) in s.rows[r * mx..(r + 1) * mx].iter_mut().enumerate() {
                *v = s.cols[c * my + r];
            }
        }
        batch(&self.inv_x, &mut s.rows[..rows_needed * mx], &mut s.fft);
    }

    /// Loads two real fields given on the grid, as the real and imaginary
    /// parts, into the first `ny` padded rows.
    fn load(&self, s: &mut FftScratch<T>, re: &[f64], im: &[f64]) {
        let (nx, mx) = (self.nx, self.mx);
        s.rows.resize(mx * self.my, Complex::default());
        for r in 0..self.ny {
            let row = &mut s.rows[r * mx..(r + 1) * mx];
            for (c, v) in row[..nx].iter_mut().enumerate() {
                let k = r * nx + c;
                *v = Complex::new(T::from_f64(re[k]).unwrap_or_else(T::nan), T::from_f64(im[k]).unwrap_or_else(T::nan));
            }
            row[nx..].fill(Complex::default());
        }
    }

    /// Normal product `u = K_n p` on the whole grid: the field is real, so
    /// along x a real-to-complex transform gives the `mx/2 + 1` columns of
    /// half the spectrum (the rest is their conjugate mirror), the complex
    /// transforms along y run on those only, and a complex-to-real
    /// transform returns each row: half the work of the complex product.
    pub fn normal(&self, s: &mut FftScratch<T>, p: &[f64], u: &mut [f64]) {
        let (nx, ny, mx, my) = (self.nx, self.ny, self.mx, self.my);
        let hx = mx / 2 + 1;
        s.real.resize(mx, T::zero());
        s.half.resize(hx, Complex::default());
        let need = self.real_x.get_scratch_len().max(self.real_inv_x.get_scratch_len());
        if s.fft.len() < need {
            s.fft.resize(need, Complex::default());
        }
        s.cols.resize(hx * my, Complex::default());
        for r in 0..ny {
            for (v, pk) in s.real[..nx].iter_mut().zip(&p[r * nx..(r + 1) * nx]) {
                *v = T::from_f64(*pk).unwrap_or_else(T::nan);
            }
            s.real[nx..].fill(T::zero());
            self.real_x
                .process_with_scratch(&mut s.real, &mut s.half, &mut s.fft[..need])
                .expect("buffers of the planned lengths");
            for (c, v) in s.half.iter().enumerate() {
                s.cols[c * my + r] = *v;
            }
        }
        for col in s.cols.chunks_exact_mut(my) {
            col[ny..].fill(Complex::default());
        }
        batch(&self.fwd_y, &mut s.cols, &mut s.fft);
        for (z, k) in s.cols.iter_mut().zip(&self.spectra[0]) {
            *z = *z * k;
        }
        batch(&self.inv_y, &mut s.cols, &mut s.fft);
        for r in 0..ny {
            for (c, v) in s.half.iter_mut().enumerate() {
                *v = s.cols[c * my + r];
            }
            // The product is real: the zero and Nyquist bins' imaginary
            // parts are rounding.
            s.half[0].im = T::zero();
            if mx % 2 == 0 {
                s.half[hx - 1].im = T::zero();
            }
            self.real_inv_x
                .process_with_scratch(&mut s.half, &mut s.real, &mut s.fft[..need])
                .expect("buffers of the planned lengths");
            for (uk, v) in u[r * nx..(r + 1) * nx].iter_mut().zip(&s.real[..nx]) {
                *uk = v.to_f64().unwrap_or(f64::NAN);
            }
        }
    }

    /// Tangential product `(u_x, u_y) = K (p_x, p_y)` on the whole grid.
    pub fn tangential(&self, s: &mut FftScratch<T>, (px, py): (&[f64], &[f64]), (ux, uy): (&mut [f64], &mut [f64])) {
        let (mx, my) = (self.mx, self.my);
        self.load(s, px, py);
        self.forward(s, self.ny);
        // Z = P_x + i P_y; P_x(k) = (Z(k) + conj Z(-k)) / 2,
        // P_y(k) = (Z(k) - conj Z(-k)) / 2i; W = U_x + i U_y
        // = (K_xx + K_yy)/2 Z(k) + ((K_xx - K_yy)/2 + i K_xy) conj Z(-k).
        let z = &s.cols;
        let w = &mut s.spectrum;
        w.resize(mx * my, Complex::default());
        let (sum, diff) = (&self.spectra[0], &self.spectra[1]);
        for cx in 0..mx {
            let mcx = (mx - cx) % mx;
            let (row, mirror) = (&z[cx * my..(cx + 1) * my], &z[mcx * my..(mcx + 1) * my]);
            let (srow, drow) = (&sum[cx * my..(cx + 1) * my], &diff[cx * my..(cx + 1) * my]);
            let out = &mut w[cx * my..(cx + 1) * my];
            out[0] = srow[0] * row[0] + drow[0] * mirror[0].conj();
            for cy in 1..my {
                out[cy] = srow[cy] * row[cy] + drow[cy] * mirror[my - cy].conj();
            }
        }
        std::mem::swap(&mut s.cols, &mut s.spectrum);
        self.inverse(s, self.ny);
        for r in 0..self.ny {
            for c in 0..self.nx {
                let v = s.rows[r * mx + c];
                ux[r * self.nx + c] = v.re.to_f64().unwrap_or(f64::NAN);
                uy[r * self.nx + c] = v.im.to_f64().unwrap_or(f64::NAN);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::PotentialGrid;
    use super::*;

    fn field(n: usize, seed: f64) -> Vec<f64> {
        (0..n).map(|k| ((k as f64 * 0.731 + seed).sin() * 1e8).max(0.0)).collect()
    }

    #[test]
    fn fft_products_equal_direct_summation() {
        // Odd and even sizes, a non-square element.
        for (nx, ny) in [(7, 5), (12, 9), (1, 4)] {
            let grid = PotentialGrid { nx, ny, dx: 2e-4, dy: 5e-4, x_front: 0.0, y_low: 0.0 };
            let (g, nu) = (8.08e10, 0.3);
            let n = grid.len();
            let kn = ToeplitzKernel::normal(&grid, g, nu);
            let fn_ = FftConvolution::new(&kn);
            let p = field(n, 0.3);
            let (mut direct, mut fast) = (vec![0.0; n], vec![0.0; n]);
            kn.normal_direct(&p, &mut direct);
            let mut s = FftScratch::default();
            fn_.normal(&mut s, &p, &mut fast);
            let scale = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (d, f) in direct.iter().zip(&fast) {
                assert!((d - f).abs() < 1e-12 * scale, "normal {nx}x{ny}: {d} vs {f}");
            }
            let kt = ToeplitzKernel::tangential(&grid, g, nu);
            let ft = FftConvolution::new(&kt);
            let (px, py) = (field(n, 0.1), field(n, 1.7).iter().map(|v| v - 3e7).collect::<Vec<_>>());
            let (mut dx_, mut dy_) = (vec![0.0; n], vec![0.0; n]);
            kt.tangential_direct((&px, &py), (&mut dx_, &mut dy_));
            let (mut fx, mut fy) = (vec![0.0; n], vec![0.0; n]);
            ft.tangential(&mut s, (&px, &py), (&mut fx, &mut fy));
            let scale = dx_.iter().chain(&dy_).fold(0.0f64, |m, v| m.max(v.abs()));
            for k in 0..n {
                assert!((dx_[k] - fx[k]).abs() < 1e-12 * scale, "ux {nx}x{ny} at {k}");
                assert!((dy_[k] - fy[k]).abs() < 1e-12 * scale, "uy {nx}x{ny} at {k}");
            }
        }
    }

    #[test]
    fn circulant_inverse_is_symmetric_positive_and_inverts_the_kernel() {
        // The preconditioners: symmetric positive definite (what CG
        // needs), and an approximate inverse of the Toeplitz product: a
        // smooth traction in the middle of the grid comes back from its
        // displacement within 3 % (normal; measured 1.5 %) and 5 %
        // (tangential; 2.9 %) on its support (the displacement known on the
        // grid only, the periodic inverse sees its truncation at the edges).
        let grid = PotentialGrid { nx: 40, ny: 24, dx: 2e-4, dy: 5e-4, x_front: 0.0, y_low: 0.0 };
        let (g, nu) = (8.08e10, 0.3);
        let n = grid.len();
        let bump: Vec<f64> = (0..n)
            .map(|k| {
                let (x, y) = ((k % 40) as f64 / 39.0 - 0.5, (k / 40) as f64 / 23.0 - 0.5);
                1e8 * (1.0 - 9.0 * (x * x + y * y)).max(0.0).powi(2)
            })
            .collect();
        let mut s = FftScratch::default();
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let (a, b) = (field(n, 0.4), field(n, 2.9).iter().map(|v| v - 4e7).collect::<Vec<_>>());
        // Normal.
        let kn = ToeplitzKernel::normal(&grid, g, nu);
        let (prod, inv) = (FftConvolution::new(&kn), FftConvolution::circulant_inverse(&kn));
        let (mut ia, mut ib) = (vec![0.0; n], vec![0.0; n]);
        inv.normal(&mut s, &a, &mut ia);
        inv.normal(&mut s, &b, &mut ib);
        assert!((dot(&a, &ib) - dot(&ia, &b)).abs() < 1e-10 * dot(&a, &ia).abs());
        assert!(dot(&a, &ia) > 0.0 && dot(&b, &ib) > 0.0);
        let (mut u, mut back) = (vec![0.0; n], vec![0.0; n]);
        prod.normal(&mut s, &bump, &mut u);
        inv.normal(&mut s, &u, &mut back);
        let inner = |k: usize| bump[k] > 0.0;
        let err = (0..n).filter(|&k| inner(k)).fold(0.0f64, |m, k| m.max((back[k] - bump[k]).abs())) / 1e8;
        assert!(err < 0.03, "normal: {err}");
        // Tangential, both components.
        let kt = ToeplitzKernel::tangential(&grid, g, nu);
        let (prod, inv) = (FftConvolution::new(&kt), FftConvolution::circulant_inverse(&kt));
        let (mut iax, mut iay, mut ibx, mut iby) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        inv.tangential(&mut s, (&a, &b), (&mut iax, &mut iay));
        inv.tangential(&mut s, (&b, &a), (&mut ibx, &mut iby));
        let (ab, ba) = (dot(&a, &ibx) + dot(&b, &iby), dot(&iax, &b) + dot(&iay, &a));
        assert!((ab - ba).abs() < 1e-10 * ab.abs(), "{ab} vs {ba}");
        assert!(dot(&a, &iax) + dot(&b, &iay) > 0.0);
        let half: Vec<f64> = bump.iter().map(|v| -0.5 * v).collect();
        let (mut ux, mut uy, mut px, mut py) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        prod.tangential(&mut s, (&bump, &half), (&mut ux, &mut uy));
        inv.tangential(&mut s, (&ux, &uy), (&mut px, &mut py));
        let err = (0..n)
            .filter(|&k| inner(k))
            .fold(0.0f64, |m, k| m.max((px[k] - bump[k]).abs()).max((py[k] - half[k]).abs()))
            / 1e8;
        assert!(err < 0.05, "tangential: {err}");
    }

    #[test]
    fn smooth_lengths() {
        assert_eq!(smooth_length(1), 1);
        assert_eq!(smooth_length(7), 8);
        assert_eq!(smooth_length(97), 100);
        assert_eq!(smooth_length(121), 125);
        // At least 2^2, at most one 5.
        for (n, m) in [(1, 4), (89, 96), (133, 144), (147, 160), (217, 240)] {
            assert_eq!(fast_length(n), m, "{n}");
        }
    }
}
