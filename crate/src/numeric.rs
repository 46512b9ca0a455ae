//! Small numerical helpers shared by the studies.

/// Maximises a unimodal `f` on `[a, b]` by golden-section search to 1e-13.
pub(crate) fn golden_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > 1e-13 {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

/// A nonlinear least-squares fit by [`levenberg_marquardt`].
#[derive(Debug, Clone)]
pub(crate) struct LeastSquares {
    /// The parameters at the minimum.
    pub x: Vec<f64>,
    /// The residuals there (data − model).
    pub residuals: Vec<f64>,
    /// The covariance of `x` from the linearised model, `s²·(JᵀJ)⁻¹`, row-major `p × p`, with
    /// `s² = Σr²/(n − p)` the residual variance.
    pub covariance: Vec<f64>,
    /// `s`, the residuals' standard deviation (`n − p` degrees of freedom).
    pub sigma: f64,
    /// Iterations taken.
    pub iterations: usize,
}

/// Why a least-squares fit failed.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LsqFailure {
    /// The model failed at some parameters (its own message).
    Model(crate::Error),
    /// `JᵀJ` is singular: the parameter with this index (and others) is not determined by the
    /// data (relative singular value below 1e-10).
    Undetermined(usize),
    /// No decrease of the sum of squares within the iterations allowed.
    NoConvergence,
    /// Fewer data than parameters + 1.
    TooFewData,
}

/// Minimises `Σ r_i(x)²` by Levenberg–Marquardt (Marquardt's scaling by `diag(JᵀJ)`), with the
/// Jacobian from forward differences of step `steps[j]` in parameter `j`. `residuals(x)` returns
/// `data − model(x)`. Stops when a step changes the sum of squares by less than 1e-10 relatively
/// and every parameter by less than 1e-8 of its difference step, or after `max_iter`
/// iterations. The covariance is the usual linearised one (`s²(JᵀJ)⁻¹`, Jacobian at the
/// minimum), on which confidence intervals `x ± t·√C_jj` rest.
pub(crate) fn levenberg_marquardt(
    mut residuals: impl FnMut(&[f64]) -> crate::Result<Vec<f64>>,
    x0: &[f64],
    steps: &[f64],
    max_iter: usize,
) -> Result<LeastSquares, LsqFailure> {
    use nalgebra::{DMatrix, DVector};
    let p = x0.len();
    let mut x = x0.to_vec();
    let mut r = residuals(&x).map_err(LsqFailure::Model)?;
    let n = r.len();
    if n <= p {
        return Err(LsqFailure::TooFewData);
    }
    let ss = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let mut s = ss(&r);
    let jacobian = |x: &[f64], r: &[f64], f: &mut dyn FnMut(&[f64]) -> crate::Result<Vec<f64>>| {
        let mut j = DMatrix::<f64>::zeros(n, p);
        for k in 0..p {
            let mut xk = x.to_vec();
            xk[k] += steps[k];
            let rk = f(&xk)?;
            for i in 0..n {
                // J of the model = −∂r/∂x.
                j[(i, k)] = (r[i] - rk[i]) / steps[k];
            }
        }
        Ok::<_, crate::Error>(j)
    };
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let mut converged = false;
    while iterations < max_iter {
        iterations += 1;
        let j = jacobian(&x, &r, &mut residuals).map_err(LsqFailure::Model)?;
        let jtj = j.transpose() * &j;
        let jtr = j.transpose() * DVector::from_column_slice(&r);
        let mut improved = false;
        for _ in 0..30 {
            let mut a = jtj.clone();
            for k in 0..p {
                a[(k, k)] += lambda * jtj[(k, k)].max(1e-300);
            }
            let Some(dx) = a.cholesky().map(|c| c.solve(&jtr)) else {
                lambda *= 10.0;
                continue;
            };
            let xn: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
            let rn = match residuals(&xn) {
                Ok(v) => v,
                Err(_) => {
                    lambda *= 10.0;
                    continue;
                }
            };
            let sn = ss(&rn);
            if sn <= s {
                let small_step = dx.iter().zip(steps).all(|(d, h)| d.abs() < 1e-8 * h.abs());
                let small_change = s - sn <= 1e-10 * s;
                x = xn;
                r = rn;
                s = sn;
                lambda = (lambda / 10.0).max(1e-12);
                improved = true;
                converged = small_step || small_change;
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            // No step lowers the sum of squares: at the minimum to working precision.
            converged = true;
        }
        if converged {
            break;
        }
    }
    if !converged {
        return Err(LsqFailure::NoConvergence);
    }
    let j = jacobian(&x, &r, &mut residuals).map_err(LsqFailure::Model)?;
    // Column scaling so that the singular-value test is about the data, not the units.
    let norms: Vec<f64> = (0..p).map(|k| j.column(k).norm()).collect();
    if let Some(k) = norms.iter().position(|v| *v == 0.0 || !v.is_finite()) {
        return Err(LsqFailure::Undetermined(k));
    }
    let mut js = j.clone();
    for (k, nk) in norms.iter().enumerate() {
        js.column_mut(k).scale_mut(1.0 / nk);
    }
    let svd = js.clone().svd(false, true);
    let smax = svd.singular_values.max();
    if let Some(i) = svd.singular_values.iter().position(|v| *v < 1e-10 * smax) {
        let v_t = svd
            .v_t
            .as_ref()
            .map(|v| v.row(i).iter().map(|x| x.abs()).collect::<Vec<_>>());
        let k = v_t.map_or(0, |row| {
            row.iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .map_or(0, |(k, _)| k)
        });
        return Err(LsqFailure::Undetermined(k));
    }
    let inv = (js.transpose() * &js)
        .try_inverse()
        .ok_or(LsqFailure::Undetermined(0))?;
    let s2 = s / (n - p) as f64;
    let mut covariance = vec![0.0; p * p];
    for a in 0..p {
        for b in 0..p {
            covariance[a * p + b] = s2 * inv[(a, b)] / (norms[a] * norms[b]);
        }
    }
    Ok(LeastSquares {
        x,
        residuals: r,
        covariance,
        sigma: s2.sqrt(),
        iterations,
    })
}
