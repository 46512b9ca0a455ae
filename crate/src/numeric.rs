//! Small numerical helpers shared by the studies.

/// Maximises a unimodal `f` on `[a, b]` by golden-section search to 1e-13: each step keeps
/// `(√5 − 1)/2` of the bracket, so a bracket of width `w` takes `⌈ln(w/1e-13)/ln φ⌉` steps.
/// At most [`GOLDEN_STEPS`]: where doubles lie further apart than 1e-13 (`|x| ≥ 512`) the
/// bracket cannot shrink to it, and the search stops with the bracket as narrow as it gets.
pub(crate) fn golden_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    let mut steps = 0;
    while b - a > 1e-13 && steps < GOLDEN_STEPS {
        steps += 1;
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

/// The most steps of [`golden_max`]: enough for a bracket of 10¹⁰ (129 steps).
const GOLDEN_STEPS: usize = 200;

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
/// or every parameter by less than 1e-8 of its difference step, or when no damping lowers the
/// sum of squares; fails after `max_iter` iterations without stopping. The covariance is the usual linearised one (`s²(JᵀJ)⁻¹`, Jacobian at the
/// minimum), on which confidence intervals `x ± t·√C_jj` rest. Where the residuals do not
/// vanish at the minimum, the point found is where the forward-difference Jacobian is orthogonal
/// to them: within O(step) of the true minimum (a test: 2.4e-6 relative with a step of 1e-3,
/// under 1e-8 with 1e-6).
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

/// The helpers against closed forms (found by cargo-mutants, scope `numeric`: the module had no
/// tests of its own; the studies' tests reach it only through their results).
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn golden_section_finds_the_maximum_of_unimodal_functions_to_1e_12() {
        // A parabola with its top anywhere in the bracket, at the ends included.
        for top in [-2.0, -1.3, 0.0, 0.37, 1.999_999, 2.0] {
            let x = golden_max(|x| -(x - top) * (x - top), -2.0, 2.0);
            assert!((x - top).abs() < 1e-12, "top {top}: {x}");
        }
        // An asymmetric one: x·e^(−x) is largest at x = 1.
        let x = golden_max(|x| x * (-x).exp(), 0.0, 7.0);
        assert!((x - 1.0).abs() < 1e-7, "{x}"); // flat top: f'' = −1/e, f to 1e-16
                                                // Far from zero, where doubles lie 1.1e-13 apart: the bracket never gets under 1e-13,
                                                // and the search still ends, as close as doubles allow.
        let x = golden_max(|x| -(x - 1_000.123_456).abs(), 1000.1, 1000.2);
        assert!((x - 1_000.123_456).abs() < 1e-12, "{x}");
    }

    #[test]
    fn golden_section_takes_the_golden_ratio_s_number_of_evaluations() {
        // Each step keeps 0.618… of the bracket: from 4 to 1e-13, ⌈ln(4e13)/ln φ⌉ = 66 steps,
        // one evaluation each, after the first two.
        let count = std::cell::Cell::new(0);
        golden_max(
            |x| {
                count.set(count.get() + 1);
                -x * x
            },
            -2.0,
            2.0,
        );
        let phi = (1.0 + 5f64.sqrt()) / 2.0;
        let steps = ((4.0 / 1e-13_f64).ln() / phi.ln()).ceil() as usize;
        assert!(
            (steps + 1..=steps + 3).contains(&count.get()),
            "{} evaluations, {steps} steps expected",
            count.get()
        );
    }

    /// A straight line `y = a + b·t` fitted to `(t, y)` by the normal equations: `(a, b)`,
    /// `s²` and the covariance `s²·(AᵀA)⁻¹` in closed form.
    fn line(t: &[f64], y: &[f64]) -> ([f64; 2], f64, [f64; 4]) {
        let n = t.len() as f64;
        let (st, sy) = (t.iter().sum::<f64>(), y.iter().sum::<f64>());
        let stt = t.iter().map(|v| v * v).sum::<f64>();
        let sty = t.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
        let det = n * stt - st * st;
        let b = (n * sty - st * sy) / det;
        let a = (sy - b * st) / n;
        let ss = t
            .iter()
            .zip(y)
            .map(|(t, y)| (y - a - b * t).powi(2))
            .sum::<f64>();
        let s2 = ss / (n - 2.0);
        (
            [a, b],
            s2,
            [s2 * stt / det, -s2 * st / det, -s2 * st / det, s2 * n / det],
        )
    }

    fn data() -> (Vec<f64>, Vec<f64>) {
        let t: Vec<f64> = (0..12).map(|i| i as f64 * 0.5).collect();
        // y = 2 − 0.7 t with a fixed ±0.05 scatter.
        let y = t
            .iter()
            .enumerate()
            .map(|(i, t)| 2.0 - 0.7 * t + 0.05 * [1.0, -1.0, 0.5, -0.3][i % 4])
            .collect();
        (t, y)
    }

    #[test]
    fn least_squares_of_a_line_are_the_normal_equations() {
        let (t, y) = data();
        let model = |x: &[f64]| Ok(t.iter().zip(&y).map(|(t, y)| y - x[0] - x[1] * t).collect());
        let fit = levenberg_marquardt(model, &[0.0, 0.0], &[1e-6, 1e-6], 50).unwrap();
        let (x, s2, cov) = line(&t, &y);
        for (got, want) in fit.x.iter().zip(x) {
            assert!((got - want).abs() < 1e-8, "x {got} vs {want}");
        }
        assert!(
            (fit.sigma - s2.sqrt()).abs() < 1e-9 * s2.sqrt(),
            "{} {}",
            fit.sigma,
            s2.sqrt()
        );
        for (got, want) in fit.covariance.iter().zip(cov) {
            assert!(
                (got - want).abs() < 1e-6 * want.abs(),
                "cov {got} vs {want}"
            );
        }
        // The residuals returned are those at the minimum.
        for (i, r) in fit.residuals.iter().enumerate() {
            assert!((r - (y[i] - x[0] - x[1] * t[i])).abs() < 1e-8);
        }
        assert!(
            fit.iterations >= 1 && fit.iterations < 50,
            "{}",
            fit.iterations
        );
    }

    #[test]
    fn least_squares_reach_a_nonlinear_minimum_from_afar_and_stop_there() {
        // y = a·e^(−b·t) exactly: the fit recovers (a, b) and a zero scatter.
        let t: Vec<f64> = (0..20).map(|i| i as f64 * 0.25).collect();
        let y: Vec<f64> = t.iter().map(|t| 3.0 * (-0.8 * t).exp()).collect();
        let model = |x: &[f64]| {
            Ok(t.iter()
                .zip(&y)
                .map(|(t, y)| y - x[0] * (-x[1] * t).exp())
                .collect())
        };
        let fit = levenberg_marquardt(model, &[1.0, 0.1], &[1e-7, 1e-7], 100).unwrap();
        assert!(
            (fit.x[0] - 3.0).abs() < 1e-7 && (fit.x[1] - 0.8).abs() < 1e-7,
            "{:?}",
            fit.x
        );
        assert!(fit.sigma < 1e-7, "{}", fit.sigma);
        // `max_iter` caps the iterations: as many as the fit took are enough, one fewer not.
        let n = fit.iterations;
        assert!(n > 2, "{n}");
        assert_eq!(
            levenberg_marquardt(model, &[1.0, 0.1], &[1e-7, 1e-7], n)
                .unwrap()
                .iterations,
            n
        );
        assert_eq!(
            levenberg_marquardt(model, &[1.0, 0.1], &[1e-7, 1e-7], n - 1).unwrap_err(),
            LsqFailure::NoConvergence
        );
        // One iteration is not enough from there.
        assert_eq!(
            levenberg_marquardt(model, &[1.0, 0.1], &[1e-7, 1e-7], 1).unwrap_err(),
            LsqFailure::NoConvergence
        );
    }

    #[test]
    fn least_squares_damp_a_step_that_overshoots_or_leaves_the_model_s_domain() {
        // y = e^(x·t), x = 1, started at x = −2: the Gauss–Newton step from there (the model's
        // slope is small) lands far beyond the minimum, where the sum of squares is larger;
        // Marquardt's damping must grow until a step goes downhill.
        let t: Vec<f64> = (0..21).map(|i| 0.1 * i as f64).collect();
        let y: Vec<f64> = t.iter().map(|t| t.exp()).collect();
        let model = |x: &[f64]| -> crate::Result<Vec<f64>> {
            Ok(t.iter()
                .zip(&y)
                .map(|(t, y)| y - (x[0] * t).exp())
                .collect())
        };
        let ss = |x: f64| {
            model(&[x])
                .unwrap()
                .iter()
                .map(|r: &f64| r * r)
                .sum::<f64>()
        };
        let (jr, jj) = t.iter().zip(&y).fold((0.0, 0.0), |(a, b), (t, y)| {
            let (f, d) = ((-2.0 * t).exp(), t * (-2.0 * t).exp());
            (a + d * (y - f), b + d * d)
        });
        assert!(
            ss(-2.0 + jr / jj) > ss(-2.0),
            "the undamped step must overshoot"
        );
        let fit = levenberg_marquardt(model, &[-2.0], &[1e-7], 100).unwrap();
        assert!((fit.x[0] - 1.0).abs() < 1e-9, "{:?}", fit.x);
        // The same where the model cannot be computed beyond x = 1.5 (an error there): the
        // damping grows until the step stays inside.
        let bounded = |x: &[f64]| {
            if x[0] > 1.5 {
                Err(crate::Error::field("x", "outside the model's domain"))
            } else {
                model(x)
            }
        };
        let fit = levenberg_marquardt(bounded, &[-2.0], &[1e-7], 100).unwrap();
        assert!((fit.x[0] - 1.0).abs() < 1e-9, "{:?}", fit.x);
    }

    #[test]
    fn least_squares_stop_at_the_minimum_not_at_a_step_the_size_of_the_difference_step() {
        // Scattered data (the residuals do not vanish: Gauss–Newton converges linearly) and a
        // coarse difference step of 1e-3: the fit must still reach the minimum of the sum of
        // squares, found here by the golden section on it.
        let t: Vec<f64> = (0..21).map(|i| 0.1 * i as f64).collect();
        let y: Vec<f64> = t
            .iter()
            .enumerate()
            .map(|(i, t)| t.exp() * (1.0 + 0.2 * [1.0, -1.0, 0.6, -0.4, 0.1][i % 5]))
            .collect();
        let model = |x: &[f64]| -> crate::Result<Vec<f64>> {
            Ok(t.iter()
                .zip(&y)
                .map(|(t, y)| y - (x[0] * t).exp())
                .collect())
        };
        let ss = |x: f64| model(&[x]).unwrap().iter().map(|r| r * r).sum::<f64>();
        let best = golden_max(|x| -ss(x), 0.5, 1.5);
        let fit = levenberg_marquardt(model, &[0.3], &[1e-6], 100).unwrap();
        assert!((fit.x[0] - best).abs() < 1e-7, "{} vs {best}", fit.x[0]);
    }

    #[test]
    fn least_squares_do_not_depend_on_a_parameter_s_unit() {
        // Marquardt's damping scales with diag(JᵀJ): the same fit with b in thousandths (and
        // its difference step with it) takes the same iterations to the same minimum.
        let t: Vec<f64> = (0..20).map(|i| i as f64 * 0.25).collect();
        let y: Vec<f64> = t.iter().map(|t| 3.0 * (-0.8 * t).exp()).collect();
        let fit_in = |unit: f64| {
            let model = |x: &[f64]| -> crate::Result<Vec<f64>> {
                Ok(t.iter()
                    .zip(&y)
                    .map(|(t, y)| y - x[0] * (-x[1] * unit * t).exp())
                    .collect())
            };
            levenberg_marquardt(model, &[1.0, 0.1 / unit], &[1e-7, 1e-7 / unit], 100).unwrap()
        };
        let (one, milli) = (fit_in(1.0), fit_in(1e-3));
        assert_eq!(one.iterations, milli.iterations);
        assert!(
            (milli.x[1] * 1e-3 - one.x[1]).abs() < 1e-9,
            "{:?} {:?}",
            one.x,
            milli.x
        );
        assert!((milli.x[0] - one.x[0]).abs() < 1e-9);
    }

    #[test]
    fn least_squares_refuse_what_the_data_cannot_determine() {
        let (t, y) = data();
        // Fewer data than parameters + 1.
        let two = |x: &[f64]| Ok(vec![1.0 - x[0], 2.0 - x[1]]);
        assert_eq!(
            levenberg_marquardt(two, &[0.0, 0.0], &[1e-6; 2], 20).unwrap_err(),
            LsqFailure::TooFewData
        );
        // A parameter the model ignores: that one is named.
        let ignores = |x: &[f64]| Ok(t.iter().zip(&y).map(|(t, y)| y - x[0] - x[2] * t).collect());
        assert_eq!(
            levenberg_marquardt(ignores, &[0.0; 3], &[1e-6; 3], 50).unwrap_err(),
            LsqFailure::Undetermined(1)
        );
        // Two parameters with the same effect (only their sum is seen): undetermined, the
        // index one of the two.
        let sum = |x: &[f64]| {
            Ok(t.iter()
                .zip(&y)
                .map(|(t, y)| y - x[0] - x[1] - x[2] * t)
                .collect())
        };
        let e = levenberg_marquardt(sum, &[0.0; 3], &[1e-6; 3], 50).unwrap_err();
        assert!(matches!(e, LsqFailure::Undetermined(0 | 1)), "{e:?}");
        // The model's own error is passed on.
        let fails = |_: &[f64]| Err(crate::Error::field("model", "broken"));
        assert_eq!(
            levenberg_marquardt(fails, &[0.0], &[1e-6], 5).unwrap_err(),
            LsqFailure::Model(crate::Error::field("model", "broken"))
        );
    }
}
