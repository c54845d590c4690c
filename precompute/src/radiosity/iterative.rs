//! Iterative solvers of the radiosity equation `M = M0 + R F M` for one band, the methods a
//! basis is compared with in `eigenrad-bench update`: Gauss–Seidel sweeps and Southwell
//! iteration (progressive refinement, shooting the patch with the most unshot flux).

/// The radiosity system of one band in the form the iterative methods use.
pub struct BandSystem<'a> {
    n: usize,
    /// Row `i` of `G` (= column `i`, G symmetric), m².
    g: &'a [f64],
    area: &'a [f64],
    rho: &'a [f64],
}

impl<'a> BandSystem<'a> {
    /// The system with `g` the rows of `G = A F` (row-major, n × n, m²), patch areas `area`
    /// (m²) and reflectances `rho`, all of length n.
    pub fn new(g: &'a [f64], area: &'a [f64], rho: &'a [f64]) -> Self {
        assert_eq!(g.len(), area.len() * area.len(), "G must be n × n");
        assert_eq!(rho.len(), area.len(), "one reflectance per patch");
        BandSystem {
            n: area.len(),
            g,
            area,
            rho,
        }
    }
}

impl BandSystem<'_> {
    fn g_row(&self, i: usize) -> &[f64] {
        self.g.get(i * self.n..(i + 1) * self.n).unwrap_or(&[])
    }

    fn norm(&self, x: &[f64]) -> f64 {
        self.area
            .iter()
            .zip(x)
            .map(|(a, v)| a * v * v)
            .sum::<f64>()
            .sqrt()
    }

    /// Relative residual `‖M0 + R F M − M‖ / ‖M‖` (area-weighted 2-norms).
    pub fn residual(&self, m0: &[f64], m: &[f64]) -> f64 {
        let r: Vec<f64> = (0..self.n)
            .map(|i| {
                let gm: f64 = self.g_row(i).iter().zip(m).map(|(g, x)| g * x).sum();
                m0[i] + self.rho[i] / self.area[i] * gm - m[i]
            })
            .collect();
        self.norm(&r) / self.norm(m).max(f64::MIN_POSITIVE)
    }

    /// Gauss–Seidel sweeps `M_i ← M0_i + ρ_i Σ_j F_ij M_j` until the relative residual is at
    /// most `tol` (checked after every sweep). Returns the solution and the sweep count.
    pub fn gauss_seidel(&self, m0: &[f64], tol: f64) -> (Vec<f64>, usize) {
        let mut m = m0.to_vec();
        for sweep in 1..=10_000 {
            for i in 0..self.n {
                if self.rho[i] == 0.0 {
                    continue;
                }
                let gm: f64 = self.g_row(i).iter().zip(&m).map(|(g, x)| g * x).sum();
                m[i] = m0[i] + self.rho[i] / self.area[i] * gm;
            }
            if self.residual(m0, &m) <= tol {
                return (m, sweep);
            }
        }
        (m, 10_000)
    }

    /// Southwell iteration (progressive refinement): repeatedly shoot the patch with the most
    /// unshot flux `A_i |U_i|`, until the unshot exitance is at most `tol` of the exitance
    /// (area-weighted 2-norms; the true residual is `R F U`, smaller). Returns the solution
    /// and the number of shots.
    pub fn southwell(&self, m0: &[f64], tol: f64) -> (Vec<f64>, usize) {
        let n = self.n;
        let mut m = m0.to_vec();
        let mut unshot = m0.to_vec();
        let (mut sum_u, mut sum_m) = (0.0, 0.0);
        let mut best = (0usize, 0.0f64);
        for i in 0..n {
            sum_u += self.area[i] * unshot[i] * unshot[i];
            sum_m += self.area[i] * m[i] * m[i];
            let flux = self.area[i] * unshot[i].abs();
            if flux > best.1 {
                best = (i, flux);
            }
        }
        let mut shots = 0;
        while sum_u > tol * tol * sum_m && shots < 100 * n {
            let i = best.0;
            let u = unshot[i];
            unshot[i] = 0.0;
            shots += 1;
            let row = self.g_row(i);
            sum_u = 0.0;
            sum_m = 0.0;
            best = (0, 0.0);
            for j in 0..n {
                let d = self.rho[j] / self.area[j] * row[j] * u;
                unshot[j] += d;
                m[j] += d;
                sum_u += self.area[j] * unshot[j] * unshot[j];
                sum_m += self.area[j] * m[j] * m[j];
                let flux = self.area[j] * unshot[j].abs();
                if flux > best.1 {
                    best = (j, flux);
                }
            }
        }
        (m, shots)
    }
}
