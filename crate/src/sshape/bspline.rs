//! Non-rational B-spline curves of any degree, evaluated by the Cox–de Boor recursion with exact
//! first and second derivatives (Chanal et al. 2022, Section 2.1).
//!
//! # Definition
//! A curve of degree `p` with control points `P_0 … P_n` (mm) and a non-decreasing knot vector
//! `u_0 … u_(n+p+1)` is `C(u) = Σ N_(i,p)(u)·P_i` with the basis functions
//!
//! ```text
//! N_(i,0)(u) = 1 if u_i ≤ u < u_(i+1), else 0
//! N_(i,a)(u) = (u − u_i)/(u_(i+a) − u_i)·N_(i,a−1)(u) + (u_(i+a+1) − u)/(u_(i+a+1) − u_(i+1))·N_(i+1,a−1)(u)
//! ```
//!
//! (a fraction with a zero denominator counts as zero). The paper prints the degree-0 function
//! with `u ≤ u_(i+1)` closed on both sides, which would count a point on an interior knot twice;
//! here the intervals are half-open and the last non-empty one is closed at its right end, so
//! that `C(u_(n+1)) = P_n` for a clamped knot vector.
//!
//! The derivatives are exact: `N'_(i,p) = p·(N_(i,p−1)/(u_(i+p) − u_i) − N_(i+1,p−1)/(u_(i+p+1) − u_(i+1)))`,
//! applied twice for the second derivative.
//!
//! The parameter is clamped to `[u_p, u_(n+1)]`, the curve's domain.

use crate::error::{Error, Result};
use nalgebra::Vector3;

/// Largest degree supported (the S-shape uses 3).
pub const MAX_DEGREE: usize = 5;

/// `num/den`, or 0 where `den` is 0 (the recursion's convention for a zero-length knot span).
#[inline(always)]
fn ratio(num: f64, den: f64) -> f64 {
    if den == 0.0 {
        0.0
    } else {
        num / den
    }
}

/// A B-spline curve in 3D (mm).
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Vector3<f64>>,
}

/// A point of a curve and its first two derivatives with respect to the parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// `C(u)`, mm.
    pub point: Vector3<f64>,
    /// `dC/du`, mm.
    pub d1: Vector3<f64>,
    /// `d²C/du²`, mm.
    pub d2: Vector3<f64>,
}

impl BSpline {
    /// A curve of degree `degree` (1..=5) through `points` with `knots` (`points.len() + degree + 1`
    /// non-decreasing finite values, with a non-empty domain `u_p < u_(n+1)`).
    pub fn new(degree: usize, knots: Vec<f64>, points: Vec<Vector3<f64>>) -> Result<Self> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(Error::field(
                "degree",
                format!("must be between 1 and {MAX_DEGREE}, got {degree}"),
            ));
        }
        if points.len() < degree + 1 {
            return Err(Error::field(
                "points",
                format!(
                    "a curve of degree {degree} needs at least {} control points, got {}",
                    degree + 1,
                    points.len()
                ),
            ));
        }
        if knots.len() != points.len() + degree + 1 {
            return Err(Error::field(
                "knots",
                format!(
                    "expected {} knots ({} control points, degree {degree}), got {}",
                    points.len() + degree + 1,
                    points.len(),
                    knots.len()
                ),
            ));
        }
        if knots.iter().any(|k| !k.is_finite())
            || points.iter().any(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(Error::field(
                "knots",
                "knots and control points must be finite",
            ));
        }
        if knots.windows(2).any(|w| w[1] < w[0]) {
            return Err(Error::field("knots", "must be non-decreasing"));
        }
        if knots[degree] >= knots[points.len()] {
            return Err(Error::field("knots", "the curve's domain is empty"));
        }
        Ok(Self {
            degree,
            knots,
            points,
        })
    }

    /// A clamped curve with uniform interior knots: `p + 1` zeros, `(k/m)` for `k = 1 … m−1`,
    /// `p + 1` ones, where `m = n − p + 1` (the knot vector of the S-shape, `m = 13`).
    pub fn clamped_uniform(degree: usize, points: Vec<Vector3<f64>>) -> Result<Self> {
        let n = points.len();
        if n < degree + 1 {
            return Self::new(degree, vec![], points);
        }
        let m = n - degree;
        let mut knots = vec![0.0; degree + 1];
        knots.extend((1..m).map(|k| k as f64 / m as f64));
        knots.extend(std::iter::repeat(1.0).take(degree + 1));
        Self::new(degree, knots, points)
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points, mm.
    pub fn points(&self) -> &[Vector3<f64>] {
        &self.points
    }

    /// The parameter domain `[u_p, u_(n+1)]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// The index `s` of the knot span `u_s ≤ u < u_(s+1)` holding `u` (clamped to the domain;
    /// the last non-empty span at the right end).
    pub fn span(&self, u: f64) -> usize {
        let p = self.degree;
        let n = self.points.len() - 1;
        let (a, b) = self.domain();
        let u = u.clamp(a, b);
        if u >= b {
            // The last span with u_s < u_(s+1).
            let mut s = n;
            while s > p && self.knots[s] >= self.knots[s + 1] {
                s -= 1;
            }
            return s;
        }
        // Binary search for u_s ≤ u < u_(s+1), s in [p, n].
        let (mut lo, mut hi) = (p, n + 1);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if u >= self.knots[mid] {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }

    /// The `p + 1` basis functions that are non-zero on span `s` at `u`, with their first and
    /// second derivatives: `(N, N', N'')`, entry `j` for `N_(s−p+j, p)`.
    pub fn basis(
        &self,
        s: usize,
        u: f64,
    ) -> (
        [f64; MAX_DEGREE + 1],
        [f64; MAX_DEGREE + 1],
        [f64; MAX_DEGREE + 1],
    ) {
        let p = self.degree;
        let t = &self.knots;
        // levels[d][j]: N_(s−p+j, d) for j in p−d ..= p (others zero).
        let mut levels = [[0.0; MAX_DEGREE + 1]; MAX_DEGREE + 1];
        levels[0][p] = 1.0;
        for d in 1..=p {
            for j in (p - d)..=p {
                let i = s + j - p; // global index
                                   // N_(i,d−1) and N_(i+1,d−1); entries outside p−d+1 ..= p are still zero.
                let left = levels[d - 1][j];
                let right = if j < p { levels[d - 1][j + 1] } else { 0.0 };
                levels[d][j] = ratio(u - t[i], t[i + d] - t[i]) * left
                    + ratio(t[i + d + 1] - u, t[i + d + 1] - t[i + 1]) * right;
            }
        }
        // Derivative of N_(i,d) from the degree d−1 values `lower` (entry j ↔ N_(s−p+j, d−1)).
        // A function always inlined rather than a closure: called 3(p + 1) times a point, a
        // call each costs more than its arithmetic, under WebAssembly most.
        #[inline(always)]
        fn derive(
            t: &[f64],
            s: usize,
            p: usize,
            d: usize,
            lower: &[f64; MAX_DEGREE + 1],
            j: usize,
        ) -> f64 {
            let i = s + j - p;
            let a = ratio(lower[j], t[i + d] - t[i]);
            let b = if j < p {
                ratio(lower[j + 1], t[i + d + 1] - t[i + 1])
            } else {
                0.0
            };
            d as f64 * (a - b)
        }
        let mut n = [0.0; MAX_DEGREE + 1];
        let mut d1 = [0.0; MAX_DEGREE + 1];
        let mut d2 = [0.0; MAX_DEGREE + 1];
        // First derivatives of degree p−1 functions (needed for the second derivative).
        let mut d1_lower = [0.0; MAX_DEGREE + 1];
        if p >= 2 {
            for (j, d) in d1_lower.iter_mut().enumerate().take(p + 1) {
                *d = derive(t, s, p, p - 1, &levels[p - 2], j);
            }
        }
        for j in 0..=p {
            n[j] = levels[p][j];
            d1[j] = derive(t, s, p, p, &levels[p - 1], j);
            d2[j] = if p >= 2 {
                derive(t, s, p, p, &d1_lower, j)
            } else {
                0.0
            };
        }
        (n, d1, d2)
    }

    /// `C(u)`, `C'(u)`, `C''(u)` (parameter clamped to the domain).
    pub fn eval(&self, u: f64) -> CurvePoint {
        let (a, b) = self.domain();
        let u = u.clamp(a, b);
        let s = self.span(u);
        let (n, d1, d2) = self.basis(s, u);
        let p = self.degree;
        let mut out = CurvePoint {
            point: Vector3::zeros(),
            d1: Vector3::zeros(),
            d2: Vector3::zeros(),
        };
        for j in 0..=p {
            let cp = &self.points[s - p + j];
            out.point += cp * n[j];
            out.d1 += cp * d1[j];
            out.d2 += cp * d2[j];
        }
        out
    }

    /// `C(u)` only.
    pub fn point(&self, u: f64) -> Vector3<f64> {
        self.eval(u).point
    }
}
