//! The distributions the decisions need, written from their definitions (no statistics crate):
//! Student's t (two-sided p-values and quantiles) and the χ² upper tail.
//!
//! * `ln Γ(x)` by Stirling's series `(x − ½)·ln x − x + ½·ln 2π + 1/(12x) − 1/(360x³) +
//!   1/(1260x⁵) − 1/(1680x⁷)`, taken at `x + n ≥ 10` and brought back by `Γ(x + 1) = x·Γ(x)`
//!   (error below 1e-12).
//! * The regularized incomplete beta `I_x(a, b)` by its continued fraction (modified Lentz),
//!   using the symmetry `I_x(a, b) = 1 − I_{1−x}(b, a)` where `x > (a + 1)/(a + b + 2)`.
//!   Two-sided p of Student's t with ν degrees of freedom: `I_{ν/(ν+t²)}(ν/2, ½)`.
//! * The regularized upper incomplete gamma `Q(a, x)` by its series below `x < a + 1` and its
//!   continued fraction above. χ² upper tail with k degrees of freedom: `Q(k/2, x/2)`.
//!
//! Checked against closed forms in `crate/tests/identify/stats.rs`: t with 1 and 2 degrees of
//! freedom (`1 − 2·atan|t|/π`, `1 − |t|/√(t² + 2)`), χ² with 2 (`e^(−x/2)`), and the normal limit.

use std::f64::consts::PI;

const EPS: f64 = 1e-15;
const MAX_ITER: usize = 10_000;

/// `ln Γ(x)` for `x > 0`.
pub fn ln_gamma(x: f64) -> f64 {
    // Γ(x) = Γ(x + n)/(x(x + 1)…(x + n − 1)): the product taken once through one logarithm.
    let mut product = 1.0;
    let mut z = x;
    while z < 10.0 {
        product *= z;
        z += 1.0;
    }
    let shift = product.ln();
    let z2 = z * z;
    let series = 1.0 / (12.0 * z) - 1.0 / (360.0 * z * z2) + 1.0 / (1260.0 * z * z2 * z2)
        - 1.0 / (1680.0 * z * z2 * z2 * z2);
    (z - 0.5) * z.ln() - z + 0.5 * (2.0 * PI).ln() + series - shift
}

/// Continued fraction of the incomplete beta (modified Lentz).
fn beta_fraction(a: f64, b: f64, x: f64) -> f64 {
    let tiny = 1e-300;
    let mut c = 1.0;
    let mut d = 1.0 - (a + b) * x / (a + 1.0);
    if d.abs() < tiny {
        d = tiny;
    }
    d = 1.0 / d;
    let mut h = d;
    for m in 1..MAX_ITER {
        let m = m as f64;
        let m2 = 2.0 * m;
        let aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
        d = 1.0 + aa * d;
        d = if d.abs() < tiny { tiny } else { d };
        c = 1.0 + aa / c;
        c = if c.abs() < tiny { tiny } else { c };
        d = 1.0 / d;
        h *= d * c;
        let aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
        d = 1.0 + aa * d;
        d = if d.abs() < tiny { tiny } else { d };
        c = 1.0 + aa / c;
        c = if c.abs() < tiny { tiny } else { c };
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < EPS {
            break;
        }
    }
    h
}

/// The regularized incomplete beta `I_x(a, b)`, `0 ≤ x ≤ 1`, `a, b > 0`.
pub fn beta_inc(a: f64, b: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    let ln_front = ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln();
    if x < (a + 1.0) / (a + b + 2.0) {
        ln_front.exp() * beta_fraction(a, b, x) / a
    } else {
        1.0 - ln_front.exp() * beta_fraction(b, a, 1.0 - x) / b
    }
}

/// Two-sided p-value of Student's t: `P(|T_ν| ≥ |t|)`. `ν ≥ 1`.
pub fn t_two_sided(t: f64, dof: f64) -> f64 {
    if !t.is_finite() {
        return 0.0;
    }
    beta_inc(dof / 2.0, 0.5, dof / (dof + t * t)).clamp(0.0, 1.0)
}

/// The two-sided quantile: the `t ≥ 0` with `P(|T_ν| ≥ t) = p`, `0 < p < 1`: Newton's method on
/// [`t_two_sided`] (its derivative is `−2·f(t)`, `f` the density
/// `Γ((ν+1)/2)/(√(νπ)·Γ(ν/2))·(1 + t²/ν)^(−(ν+1)/2)`), kept inside a bracket that it narrows, with
/// a bisection step where Newton would leave it; to 1e-13 relative.
pub fn t_quantile_two_sided(p: f64, dof: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    while t_two_sided(hi, dof) > p {
        lo = hi;
        hi *= 2.0;
        if hi > 1e12 {
            return hi;
        }
    }
    let ln_c = ln_gamma((dof + 1.0) / 2.0) - ln_gamma(dof / 2.0) - 0.5 * (dof * PI).ln();
    let mut t = 0.5 * (lo + hi);
    for _ in 0..200 {
        let f = t_two_sided(t, dof) - p; // decreasing in t
        if f > 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let density = (ln_c - (dof + 1.0) / 2.0 * (1.0 + t * t / dof).ln()).exp();
        let mut next = t + f / (2.0 * density);
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - t).abs() <= 1e-13 * next.abs() || hi - lo <= 1e-13 * hi {
            return next;
        }
        t = next;
    }
    t
}

/// The regularized upper incomplete gamma `Q(a, x) = Γ(a, x)/Γ(a)`.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let ln_front = -x + a * x.ln() - ln_gamma(a);
    if x < a + 1.0 {
        // P(a, x) by its series Σ xⁿ/(a(a+1)…(a+n)).
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..MAX_ITER {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * EPS {
                break;
            }
        }
        (1.0 - sum * ln_front.exp()).clamp(0.0, 1.0)
    } else {
        // Q(a, x) by its continued fraction (modified Lentz).
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..MAX_ITER {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            d = if d.abs() < tiny { tiny } else { d };
            c = b + an / c;
            c = if c.abs() < tiny { tiny } else { c };
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < EPS {
                break;
            }
        }
        (ln_front.exp() * h).clamp(0.0, 1.0)
    }
}

/// χ² upper tail `P(X ≥ x)` with `k` degrees of freedom.
pub fn chi2_upper(x: f64, k: f64) -> f64 {
    gamma_q(k / 2.0, x / 2.0)
}
