//! Nonlinear error of rotary-axis interpolation (Geng, Wu & Qiu 2018, Sections 3 and 4).
//!
//! # The model
//! A move takes the rotary axes from `(θk0, θm0)` to `(θk1, θm1)` with the angles interpolated
//! linearly (eq 10): `θ(u) = (1-u)·θ0 + u·θ1`, `u ∈ [0, 1]`. The tool orientation follows
//! `P(u) = V(θk(u), θm(u))` (eq 9), while the ideal orientation moves on the great circle
//! through `V0 = P(0)` and `V1 = P(1)`: `Q(u)` (eqs 11-16). The nonlinear error is the distance of
//! the tool point from the plane of that great circle (eqs 19-21):
//!
//! ```text
//! δ(u) = L · |P(u) · n|,   n = (V0 × V1) / |V0 × V1|,   δ = max over u of δ(u)
//! ```
//!
//! `L` (mm) is the tool length for a head, or the distance from the rotary centre to the tool
//! point for a table. `δ` is in mm. For a unit `P`, `|P·n|` is the sine of the angle between
//! `P(u)` and the plane; eq 19's chord `|Q(u) - P(u)|` is the same to first order.
//!
//! # Degenerate moves (no unique plane)
//! * **Coincident** ends (`V0 = V1`, e.g. a full turn of K, or no move at all): the ideal
//!   orientation does not move, `Q(u) = V0`, and the error is eq 19's chord
//!   `δ(u) = L·|P(u) - V0|`.
//! * **Opposite** ends (`V1 = -V0`): every plane through `±V0` is a great circle joining them;
//!   the reference is the least-squares plane through `±V0` fitted to the path (sampled at
//!   [`FIT_SAMPLES`] equal steps of u), then `δ(u) = L·|P(u)·n|` as usual.
//!
//! The ends count as coincident or opposite when `|V0 × V1| <` [`DEGENERATE_SINE`]. Close to that,
//! the plane is ill-conditioned (a tiny change of the end moves it a lot); `plane_sine` reports
//! `|V0 × V1|` so a caller can warn.
//!
//! # Exact maximum
//! `g(u) = P(u)·w` (`w = n`, or `-V0` for the chord) is smooth with analytic derivatives (see
//! [`RotaryType::tool_vector_jet`]). [`Deviation::peak`] takes the maximum of `|g|` (of `g` for
//! the chord) over `u ∈ [0, 1]` in one of three ways; each counts its orientation evaluations
//! ([`Deviation::peak_counted`]).
//!
//! **Dense (the reference, [`Deviation::peak_dense`]; every move).** `g` is sampled at
//! `16 + 4·(|Δθk| + |Δθm|)` steps (Δ in radians, so that no extremum hides between samples), each
//! local maximum of the objective is refined by safeguarded Newton steps on `g' = 0` inside its
//! bracket (golden-section search where the bracket does not change sign), to `u` within 1e-13.
//! At least 17 + ~6 evaluations (about 30 for short moves), and hundreds where `g` is flat to
//! rounding (a move of M alone: every sample is then a local maximum to refine).
//!
//! The other two apply to planes. Both start from one evaluation at `u = 1/2` with `g'''`, and
//! both compare the interior extremum with the ends `|V0·n|`, `|V1·n|` (zero but for rounding;
//! `V0`, `V1` are those of [`Deviation::new`], not evaluated again).
//!
//! **A move of one axis (Δθk = 0 or Δθm = 0): one evaluation.** The tool turns about a fixed
//! axis at rate `d`, so `g(u) = C + a·cos(d(u - ½)) + b·sin(d(u - ½))` exactly, with
//! `a = -g''(½)/d²`, `b = g'(½)/d`, `C = g(½) - a`: the extrema are `C ± hypot(a, b)` at known
//! `u`.
//!
//! **Both axes, `g''` of one sign: a handful of evaluations.** Let `S = |Δθk| + |Δθm|`.
//! *Lemma:* `|V⁽ⁿ⁾(u)| ≤ Sⁿ`. With `V = R_K(θk) R_M(θm) e_H`, `d/du` acts as
//! `Δθk·[e_K×]` on the left of `R_K` plus `Δθm·[e_M×]` between `R_K` and `R_M` (each cross
//! product commutes with the rotation about its own axis), so
//! `V⁽ⁿ⁾ = Σ_j C(n,j) Δθkʲ Δθm⁽ⁿ⁻ʲ⁾ [e_K×]ʲ R_K [e_M×]ⁿ⁻ʲ R_M e_H`; rotations have norm 1 and
//! `[e×]` norm ≤ 1, so `|V⁽ⁿ⁾| ≤ Σ_j C(n,j)|Δθk|ʲ|Δθm|ⁿ⁻ʲ = Sⁿ`. Hence `|g⁽ⁿ⁾| ≤ Sⁿ` for the
//! unit `w`. Over `[0, 1]`, `|g''(u) - g''(½)| ≤ min(S³/2, |g'''(½)|/2 + S⁴/8)` (by `|g'''| ≤ S³`,
//! or by Taylor at `½` with `|g''''| ≤ S⁴`; the second is far smaller for short moves close to a
//! great circle, where `g'''` lies nearly in the plane). If `|g''(½)|` exceeds that bound (plus a
//! rounding allowance), `g''` keeps one sign on `[0, 1]`: `g` is strictly convex or concave, `g'`
//! strictly monotone with at most one root, and `|g|` has no interior local maximum but at that
//! root (a convex `g`'s maximum is at an end; `-g`'s is at the root or an end). So the maximum
//! of `|g|` is the largest of `|g(0)|`, `|g(1)|` and `|g(u*)|`, `g'(u*) = 0`. The root is found
//! by Newton from `½`, kept inside a bracket that the bounds `m ≤ |g''| ≤ big` also narrow
//! (`u* ∈ [u - f/m, u - f/big]` for `f = ±g'(u) > 0`, which also tells when there is no root in
//! `(0, 1)`). Newton from `u` lands within `max|g'''|·e²/(2m)` of `u*` when `|u - u*| ≤ e`
//! (`e = |g'(u)|/m`); when that is below 1e-13 the Newton point is taken with `g` from its
//! Taylor series (remainder `≤ max|g'''|·|step|³/6`), without evaluating there.
//!
//! Otherwise (the test fails, near the pole for instance, or coincident or opposite ends) the
//! dense method answers. Both fast paths agree with it to rounding: `δ` to 1e-12 relative or
//! ~1e-15 absolute (the rounding of `g` itself: an ulp of the angles, the dot product), `u` to
//! 1e-9 where the maximum is well defined (crate/tests/nonlinear/fast_peak.rs). Short moves (under 5°)
//! take 2 to 5 evaluations on average instead of about 30 (examples/bench.rs); the dense
//! fallback is left mostly to moves whose `g''` changes sign, e.g. a Group I tool crossing the
//! plane perpendicular to K (θm = ±90°) with both axes moving, where `|g|` has two maxima.

mod inputs;
pub use inputs::{
    analyze_move, compare_types, grid, sweep_k, sweep_m, swing_length, AngleSpan, MoveEnd,
    MoveStart, NonlinearCase, NonlinearGridInput, NonlinearMoveInput, SweepKInput, SweepMInput,
    TypeCompareInput,
};

use crate::error::{check_count, check_positive, check_range, Result};
use crate::geometry::angle_between;
use crate::rotary::{Group, Pose, RotaryType};
use nalgebra::Vector3;
use serde::Serialize;
use std::cell::Cell;
use std::f64::consts::PI;

/// Below this value of `|V0 × V1|` the ends count as coincident or opposite.
pub const DEGENERATE_SINE: f64 = 1e-9;
/// Samples of the path used to fit the reference plane of an opposite-ends move.
pub const FIT_SAMPLES: usize = 257;
/// Distance in `u` within which the fast path locates the root of `g'` (the dense method's
/// Newton stops on steps below 1e-14).
const ROOT_TOL: f64 = 1e-13;
/// Rounding allowance of the fast path's bounds, per unit of the angles' size (a generous
/// multiple of the machine epsilon; see `Deviation::convex_extremum`).
const ROUNDING: f64 = 4.0 * f64::EPSILON;
/// Iteration cap of the fast path's safeguarded Newton (it needs a handful).
const MAX_NEWTON: usize = 100;
/// Largest accepted angle, degrees or radians equivalent (ten turns).
pub const MAX_ANGLE_DEG: f64 = 3600.0;
/// Largest accepted tool length / pivot distance, mm.
pub const MAX_LENGTH_MM: f64 = 1.0e5;

/// How the reference plane of a move was defined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "lowercase")]
pub enum Reference {
    /// The plane of `V0` and `V1` (the normal case).
    Plane,
    /// `V0 = V1`: chord distance from the fixed ideal orientation.
    Coincident,
    /// `V1 = -V0`: least-squares plane through `±V0`.
    Opposite,
}

/// A move of the two rotary axes of one type, angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    /// The machine's rotary-axis type.
    pub rtype: RotaryType,
    /// Start pose.
    pub start: Pose,
    /// End pose.
    pub end: Pose,
}

impl Move {
    /// A move from `start` to `end`.
    pub fn new(rtype: RotaryType, start: Pose, end: Pose) -> Self {
        Self { rtype, start, end }
    }

    /// Checks the angles: finite and within ±[`MAX_ANGLE_DEG`] (inputs are in radians here,
    /// messages in degrees).
    pub fn validate(&self) -> Result<()> {
        let lim = MAX_ANGLE_DEG;
        for (name, v) in [
            ("start.k", self.start.k),
            ("start.m", self.start.m),
            ("end.k", self.end.k),
            ("end.m", self.end.m),
        ] {
            check_range(name, v.to_degrees(), -lim, lim, "degrees")?;
        }
        Ok(())
    }

    /// The pose at parameter `u` by linear interpolation of the angles (eq 10).
    pub fn pose_at(&self, u: f64) -> Pose {
        Pose::new(
            self.start.k + u * (self.end.k - self.start.k),
            self.start.m + u * (self.end.m - self.start.m),
        )
    }

    /// `P(u)`, the tool orientation at `u` (eq 9).
    pub fn orientation(&self, u: f64) -> Vector3<f64> {
        self.rtype.tool_vector(self.pose_at(u))
    }

    fn increments(&self) -> (f64, f64) {
        (self.end.k - self.start.k, self.end.m - self.start.m)
    }
}

/// The deviation function of one move: the reference plane (or chord) and how to evaluate it.
#[derive(Debug, Clone, Copy)]
pub struct Deviation {
    mv: Move,
    dk: f64,
    dm: f64,
    /// `n` for a plane, `-V0` for the chord form.
    w: Vector3<f64>,
    reference: Reference,
    plane_sine: f64,
    v0: Vector3<f64>,
    v1: Vector3<f64>,
}

/// Where along the move the error is largest.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    /// Parameter `u ∈ [0, 1]` of the maximum.
    pub u: f64,
    /// The error there, as a fraction of `L` (multiply by `L` for mm).
    pub value: f64,
}

impl Deviation {
    /// Sets up the reference for `mv` (see the module docs for the degenerate cases).
    pub fn new(mv: Move) -> Self {
        let (dk, dm) = mv.increments();
        let v0 = mv.orientation(0.0);
        let v1 = mv.orientation(1.0);
        let cross = v0.cross(&v1);
        let plane_sine = cross.norm();
        let (reference, w) = if plane_sine >= DEGENERATE_SINE {
            (Reference::Plane, cross / plane_sine)
        } else if v0.dot(&v1) > 0.0 {
            (Reference::Coincident, -v0)
        } else {
            (Reference::Opposite, best_fit_normal(&mv, &v0))
        };
        Self {
            mv,
            dk,
            dm,
            w,
            reference,
            plane_sine,
            v0,
            v1,
        }
    }

    /// How the reference was defined.
    pub fn reference(&self) -> Reference {
        self.reference
    }

    /// `|V0 × V1|`, the sine of the angle between the end orientations.
    pub fn plane_sine(&self) -> f64 {
        self.plane_sine
    }

    /// Unit normal of the reference plane (for the coincident case: `-V0`).
    pub fn normal(&self) -> Vector3<f64> {
        self.w
    }

    /// Start and end tool orientations `V0`, `V1`.
    pub fn ends(&self) -> (Vector3<f64>, Vector3<f64>) {
        (self.v0, self.v1)
    }

    /// `g(u) = P(u)·w` and its first two derivatives in `u`.
    fn g(&self, u: f64) -> (f64, f64, f64) {
        let (p, d1, d2) =
            self.mv
                .rtype
                .tool_vector_derivatives(self.mv.pose_at(u), self.dk, self.dm);
        (p.dot(&self.w), d1.dot(&self.w), d2.dot(&self.w))
    }

    /// The deviation at `u` as a fraction of `L`: `|P(u)·n|`, or `|P(u) - V0|` for coincident ends.
    pub fn at(&self, u: f64) -> f64 {
        self.value_of(self.g(u).0)
    }

    fn value_of(&self, g: f64) -> f64 {
        match self.reference {
            // |P - V0| = sqrt(2 - 2 P·V0) = sqrt(2 + 2 g) with g = -P·V0.
            Reference::Coincident => (2.0 + 2.0 * g).max(0.0).sqrt(),
            _ => g.abs(),
        }
    }

    /// The objective maximised: `|g|` for planes, `g` for the chord (monotone in the chord).
    fn objective(&self, g: f64) -> f64 {
        match self.reference {
            Reference::Coincident => g,
            _ => g.abs(),
        }
    }

    /// The exact maximum of the deviation over `u ∈ [0, 1]` and where it occurs: a fast path where
    /// the shape of `g` is provable (see the module docs, "Exact maximum"), else
    /// [`Self::peak_dense`].
    pub fn peak(&self) -> Peak {
        self.peak_counted().0
    }

    /// [`Self::peak`] and the number of orientation evaluations it took (one evaluation of `P(u)`
    /// with its derivatives at one `u`). The end orientations `V0`, `V1`, computed once by
    /// [`Self::new`], are not counted.
    pub fn peak_counted(&self) -> (Peak, usize) {
        let count = Cell::new(0);
        let peak = match self.peak_fast(&count) {
            Some(p) => p,
            None => self.dense(&count),
        };
        (peak, count.get())
    }

    /// The reference method, valid for every move: `g` sampled at `16 + 4·(|Δθk| + |Δθm|)` equal
    /// steps, each local maximum of the objective refined by safeguarded Newton (module docs).
    /// [`Self::peak`] gives the same result (to rounding) with far fewer evaluations when it can
    /// prove where the extremum is, and falls back to this otherwise.
    pub fn peak_dense(&self) -> Peak {
        self.dense(&Cell::new(0))
    }

    /// `g(u)` and its derivatives, counting one orientation evaluation.
    fn g_counted(&self, u: f64, count: &Cell<usize>) -> (f64, f64, f64) {
        count.set(count.get() + 1);
        self.g(u)
    }

    /// The objective at the ends from the stored `V0`, `V1` (the same numbers as `g(0)`, `g(1)`:
    /// `V1` is computed at `pose_at(1.0)` too), without evaluating the orientation again.
    fn end_values(&self) -> (f64, f64) {
        (self.v0.dot(&self.w), self.v1.dot(&self.w))
    }

    /// The fast paths (planes only): one evaluation at `u = 1/2` with `g'''`, then the closed form
    /// of a move of one axis, or Newton where `g''` provably keeps one sign. `None` when neither
    /// applies (the caller then samples densely).
    fn peak_fast(&self, count: &Cell<usize>) -> Option<Peak> {
        if self.reference != Reference::Plane {
            return None;
        }
        let mid = self.mv.pose_at(0.5);
        count.set(count.get() + 1);
        let jet = self.mv.rtype.tool_vector_jet(mid, self.dk, self.dm);
        let g = jet.map(|v| v.dot(&self.w));
        let interior = if self.dk == 0.0 || self.dm == 0.0 {
            self.single_axis_extremum(g)
        } else {
            self.convex_extremum(mid, g, count)?
        };
        // The largest |g| of the ends and the interior extremum (ties to the earlier, as dense).
        let (e0, e1) = self.end_values();
        let mut best = Peak {
            u: 0.0,
            value: e0.abs(),
        };
        if e1.abs() > best.value {
            best = Peak {
                u: 1.0,
                value: e1.abs(),
            };
        }
        if let Some((u, g)) = interior {
            if g.abs() > best.value {
                best = Peak { u, value: g.abs() };
            }
        }
        Some(best)
    }

    /// A move of one axis at rate `d` turns the tool about a fixed axis, so
    /// `g(u) = C + a·cos(d(u - 1/2)) + b·sin(d(u - 1/2))` exactly; the jet at `1/2` gives
    /// `a = -g''/d²`, `b = g'/d`, `C = g - a`. With `R = hypot(a, b)`, `φ = atan2(b, a)`, the
    /// interior extrema are `C + R·(-1)^j` at `d(u - 1/2) = φ + jπ`. Returns the one of largest
    /// `|g|` (the earliest of equal ones) as `(u, g)`, `None` when there is none inside.
    fn single_axis_extremum(&self, [g0, g1, g2, _]: [f64; 4]) -> Option<(f64, f64)> {
        let d = self.dk + self.dm;
        let a = -g2 / (d * d);
        let b = g1 / d;
        let c = g0 - a;
        let (r, phi) = (a.hypot(b), b.atan2(a));
        // d(u - 1/2) ∈ (-|d|/2, |d|/2) for u ∈ (0, 1).
        let half = 0.5 * d.abs();
        let first = ((-half - phi) / PI).ceil() as i64;
        let last = ((half - phi) / PI).floor() as i64;
        let mut best: Option<(f64, f64)> = None;
        for j in first..=last {
            let u = 0.5 + (phi + j as f64 * PI) / d;
            if !(u > 0.0 && u < 1.0) {
                continue;
            }
            let v = if j % 2 == 0 { c + r } else { c - r };
            best = match best {
                Some((bu, bv)) if bv.abs() > v.abs() || (bv.abs() == v.abs() && bu < u) => {
                    Some((bu, bv))
                }
                _ => Some((u, v)),
            };
        }
        best
    }

    /// Two axes: `None` unless `g''` provably keeps one sign on `[0, 1]`; then `Some(interior)`,
    /// the root of `g'` inside `(0, 1)` and `g` there, if any.
    ///
    /// The jet at `1/2` (`g = [g, g', g'', g''']` there) gives bounds `m ≤ |g''| ≤ big` and
    /// `|g'''| ≤ m3` over `[0, 1]` (module docs). Then `f = σ·g'` (`σ` the sign of `g''`) is
    /// strictly increasing with `m ≤ f' ≤ big`: at any `u` its root lies in `[u - f/m, u - f/big]`
    /// (for `f > 0`; mirrored for `f < 0`), and a Newton step from `u` lands within `m3·e²/(2m)`
    /// of it when `e` bounds the distance of `u` from the root.
    fn convex_extremum(
        &self,
        mid: Pose,
        [g0, g1, g2, g3]: [f64; 4],
        count: &Cell<usize>,
    ) -> Option<Option<(f64, f64)>> {
        let s = self.dk.abs() + self.dm.abs();
        let (s2, s3, s4) = (s * s, s * s * s, s * s * s * s);
        // Rounding allowance, relative to the scale S^n of the n-th derivative: the evaluation
        // itself (a few ulps) and the pose rounded off the line (an ulp of the angles).
        let r = ROUNDING * (32.0 + mid.k.abs() + mid.m.abs());
        // |g''(u) - g''(1/2)| over [0, 1]: by |g'''| ≤ S³, or by Taylor at 1/2 with |g''''| ≤ S⁴.
        let spread = (0.5 * s3).min(0.5 * (g3.abs() + r * s3) + 0.125 * s4) * (1.0 + r);
        let m = g2.abs() - r * s2 - spread;
        if m.is_nan() || m <= 0.0 {
            return None;
        }
        let big = g2.abs() + r * s2 + spread;
        let m3 = s3.min(g3.abs() + r * s3 + 0.5 * s4) * (1.0 + r);
        let sigma = g2.signum();

        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        let (mut u, mut g, mut d1, mut d2) = (0.5, g0, g1, g2);
        for _ in 0..MAX_NEWTON {
            let f = sigma * d1;
            if f.abs() <= m * ROOT_TOL {
                return Some(Some((u, g)));
            }
            // The root is in [u - f/m, u - f/big] (f > 0) or [u - f/big, u - f/m] (f < 0).
            if f > 0.0 {
                if u - f / big <= 0.0 {
                    return Some(None); // g' > 0 on (0, 1]: the maximum is at an end.
                }
                hi = hi.min(u - f / big);
                lo = lo.max(u - f / m);
            } else {
                if u - f / big >= 1.0 {
                    return Some(None); // g' < 0 on [0, 1).
                }
                lo = lo.max(u - f / big);
                hi = hi.min(u - f / m);
            }
            let step = -d1 / d2;
            let next = u + step;
            if next > lo && next < hi {
                let err = f.abs() / m;
                if 0.5 * m3 / m * err * err <= ROOT_TOL {
                    // The Newton point is within ROOT_TOL of the root: take it, with g from the
                    // Taylor series (remainder ≤ m3·|step|³/6).
                    return Some(Some((next, g + step * (d1 + 0.5 * step * d2))));
                }
                u = next;
            } else {
                u = 0.5 * (lo + hi);
            }
            if hi - lo <= ROOT_TOL {
                return Some(Some((u, self.g_counted(u, count).0)));
            }
            (g, d1, d2) = self.g_counted(u, count);
        }
        // Not settled within MAX_NEWTON steps (not expected): the caller samples densely.
        None
    }

    /// See [`Self::peak_dense`].
    fn dense(&self, count: &Cell<usize>) -> Peak {
        let span = self.dk.abs() + self.dm.abs();
        let n = (16.0 + (4.0 * span).ceil()).min(20_000.0) as usize;
        let h = 1.0 / n as f64;
        let samples: Vec<(f64, f64, f64)> = (0..=n)
            .map(|i| self.g_counted(i as f64 * h, count))
            .collect();
        let obj: Vec<f64> = samples.iter().map(|s| self.objective(s.0)).collect();
        let mut best_u = 0.0;
        let mut best_obj = obj[0];
        if obj[n] > best_obj {
            best_u = 1.0;
            best_obj = obj[n];
        }
        for i in 1..n {
            if obj[i] < obj[i - 1] || obj[i] < obj[i + 1] {
                continue;
            }
            let sign = match self.reference {
                Reference::Coincident => 1.0,
                _ => {
                    if samples[i].0 >= 0.0 {
                        1.0
                    } else {
                        -1.0
                    }
                }
            };
            let (u, o) = self.refine(
                (i - 1) as f64 * h,
                (i + 1) as f64 * h,
                sign,
                i as f64 * h,
                count,
            );
            if o > best_obj {
                best_obj = o;
                best_u = u;
            }
        }
        // For planes the objective is |g| itself; for the chord it is g, which value_of maps.
        Peak {
            u: best_u,
            value: self.value_of(best_obj),
        }
    }

    /// Maximises `sign·g` on `[a, b]` starting near `u0`: Newton on `g' = 0` kept inside a
    /// bracket, golden-section search when `g'` does not change sign over the bracket.
    /// Returns `(u, objective)`.
    fn refine(&self, a: f64, b: f64, sign: f64, u0: f64, count: &Cell<usize>) -> (f64, f64) {
        let h = |u: f64| {
            let (g, d1, d2) = self.g_counted(u, count);
            (sign * g, sign * d1, sign * d2)
        };
        let (_, ha, _) = h(a);
        let (_, hb, _) = h(b);
        let result_u = if ha > 0.0 && hb < 0.0 {
            // Bracketed root of the derivative: safeguarded Newton.
            let (mut lo, mut hi) = (a, b);
            let mut u = u0;
            for _ in 0..60 {
                let (_, d1, d2) = h(u);
                if d1 > 0.0 {
                    lo = u;
                } else {
                    hi = u;
                }
                let newton = if d2 < 0.0 { u - d1 / d2 } else { f64::NAN };
                let next = if newton.is_finite() && newton > lo && newton < hi {
                    newton
                } else {
                    0.5 * (lo + hi)
                };
                if (next - u).abs() < 1e-14 || hi - lo < 1e-14 {
                    u = next;
                    break;
                }
                u = next;
            }
            u
        } else {
            crate::numeric::golden_max(|u| h(u).0, a, b)
        };
        let u = result_u.clamp(0.0, 1.0);
        (u, self.objective(self.g_counted(u, count).0))
    }
}

/// Least-squares plane through `±v0` fitted to the sampled path: the normal is `v0 × d`, `d` the
/// principal direction of the path's projection onto the plane perpendicular to `v0`.
fn best_fit_normal(mv: &Move, v0: &Vector3<f64>) -> Vector3<f64> {
    // An orthonormal basis (e1, e2) of the plane perpendicular to v0.
    let helper = if v0.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let e1 = v0.cross(&helper).normalize();
    let e2 = v0.cross(&e1);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for i in 0..FIT_SAMPLES {
        let p = mv.orientation(i as f64 / (FIT_SAMPLES - 1) as f64);
        let (x, y) = (p.dot(&e1), p.dot(&e2));
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
    }
    let theta = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let d = e1 * theta.cos() + e2 * theta.sin();
    v0.cross(&d).normalize()
}

/// Eq (25): the Group I error at `u = 0.5` as a fraction of `L`, in terms of the start angle of
/// M and the increments (radians). `None` where the denominator `|V0 × V1|` vanishes.
pub fn approx_group1(theta_m: f64, d_m: f64, d_k: f64) -> Option<f64> {
    let (m0, m1, mh) = (theta_m, theta_m + d_m, theta_m + 0.5 * d_m);
    let num = m0.sin() * m1.sin() * mh.cos() * d_k.sin()
        - mh.sin() * (0.5 * d_k).sin() * (2.0 * theta_m + d_m).sin();
    let c = m0.cos() * m1.cos() + m0.sin() * m1.sin() * d_k.cos();
    let den = (1.0 - c * c).max(0.0).sqrt();
    (den >= DEGENERATE_SINE).then(|| (num / den).abs())
}

/// Eq (30): the Group II error at `u = 0.5` as a fraction of `L` (see [`approx_group1`]).
pub fn approx_group2(theta_m: f64, d_m: f64, d_k: f64) -> Option<f64> {
    let (m0, m1, mh) = (theta_m, theta_m + d_m, theta_m + 0.5 * d_m);
    let num = m0.cos() * m1.cos() * mh.sin() * d_k.sin()
        - mh.cos() * (2.0 * theta_m + d_m).sin() * (0.5 * d_k).sin();
    let c = m0.sin() * m1.sin() + m0.cos() * m1.cos() * d_k.cos();
    let den = (1.0 - c * c).max(0.0).sqrt();
    (den >= DEGENERATE_SINE).then(|| (num / den).abs())
}

/// The paper's u = 0.5 approximation for the type's group (eq 25 or eq 30), fraction of `L`.
pub fn approx_half(group: Group, theta_m: f64, d_m: f64, d_k: f64) -> Option<f64> {
    match group {
        Group::I => approx_group1(theta_m, d_m, d_k),
        Group::II => approx_group2(theta_m, d_m, d_k),
    }
}

/// Eq (26): `|sin(Δθm/2)·sin(Δθk/2)|`, the u = 0.5 error (fraction of `L`) of a move starting
/// at the pole: θm0 = 0 (mod π) for Group I, θm0 = ±π/2 (mod π) for Group II (by eq 31).
/// Note that it is the value at u = 0.5, which is the exact maximum only when |Δθk| = |Δθm|; at
/// the pole the exact error curve is `|sin(u·Δθm)·sin((1-u)·Δθk)|`.
pub fn closed_form_pole(d_m: f64, d_k: f64) -> f64 {
    ((0.5 * d_m).sin() * (0.5 * d_k).sin()).abs()
}

/// True when a move of this group starting at `theta_m` starts at the pole (eq 26 applies).
pub fn starts_at_pole(group: Group, theta_m: f64) -> bool {
    let shifted = match group {
        Group::I => theta_m,
        Group::II => theta_m + PI / 2.0,
    };
    let r = shifted.rem_euclid(PI);
    r < 1e-12 || PI - r < 1e-12
}

/// Everything the page shows about one move (the export `nonlinearMove`). Lengths in mm, `u`
/// dimensionless, angles in degrees at the edge (radians in Rust).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct MoveAnalysis {
    /// The machine's rotary-axis type.
    #[serde(rename = "type")]
    pub rtype: RotaryType,
    /// Its group (eq 25 or eq 30 gives the approximation).
    pub group: Group,
    /// `L` used, mm (given, or the machine's).
    pub length: f64,
    /// Exact maximum error δ, mm.
    pub max: f64,
    /// Where it occurs, `u ∈ [0, 1]`.
    pub u_at_max: f64,
    /// The error at u = 0.5 from the vectors, mm.
    pub at_half: f64,
    /// The paper's approximation (eq 25 or 30), mm; null for coincident or opposite ends.
    pub approx: Option<f64>,
    /// `(max - approx) / max`, the fraction by which the approximation falls short.
    pub approx_shortfall: Option<f64>,
    /// Eq 26, mm, when the move starts at the pole; else null.
    pub closed_form: Option<f64>,
    /// How the reference plane was defined.
    pub reference: Reference,
    /// `|V0 × V1|`.
    pub plane_sine: f64,
    /// Angle between V0 and V1, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub sweep_angle: f64,
    /// Start tool orientation V0 (unit vector, workpiece coordinates).
    pub start_vector: [f64; 3],
    /// End tool orientation V1.
    pub end_vector: [f64; 3],
    /// Unit normal of the reference plane (for coincident ends: -V0).
    pub normal: [f64; 3],
    /// Sample parameters of the curve, equally spaced in [0, 1].
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub u: Vec<f64>,
    /// δ(u) at those samples, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub delta: Vec<f64>,
    /// With a `tolerance`: the fewest equal steps of the move that keep δ within it
    /// ([`split_within`]); null without a tolerance (and from [`analyze`]).
    pub split: Option<Split>,
}

/// Analyses one move: the δ(u) curve at `samples` points (≥ 2), the exact maximum, the
/// approximations. `length` is `L` in mm.
pub fn analyze(mv: Move, length: f64, samples: usize) -> Result<MoveAnalysis> {
    mv.validate()?;
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_count("samples", samples, 2, 100_000)?;
    let dev = Deviation::new(mv);
    let peak = dev.peak();
    let (dk, dm) = mv.increments();
    let group = mv.rtype.group();
    let approx = match dev.reference {
        Reference::Plane => approx_half(group, mv.start.m, dm, dk).map(|a| a * length),
        _ => None,
    };
    let max = peak.value * length;
    let approx_shortfall = match approx {
        Some(a) if max > 1e-15 * length => Some((max - a) / max),
        _ => None,
    };
    let closed_form = starts_at_pole(group, mv.start.m).then(|| closed_form_pole(dm, dk) * length);
    let u: Vec<f64> = (0..samples)
        .map(|i| i as f64 / (samples - 1) as f64)
        .collect();
    let delta = u.iter().map(|&x| dev.at(x) * length).collect();
    let (v0, v1) = dev.ends();
    Ok(MoveAnalysis {
        rtype: mv.rtype,
        group,
        length,
        max,
        u_at_max: peak.u,
        at_half: dev.at(0.5) * length,
        approx,
        approx_shortfall,
        closed_form,
        reference: dev.reference,
        plane_sine: dev.plane_sine,
        sweep_angle: angle_between(&v0, &v1),
        start_vector: v0.into(),
        end_vector: v1.into(),
        normal: dev.w.into(),
        u,
        delta,
        split: None,
    })
}

/// Most pieces [`split_within`] considers; a move that needs more is reported without a count.
pub const MAX_SPLIT: usize = 10_000;

/// How finely a move must be programmed for its nonlinear error to stay within a tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Split {
    /// The tolerance asked for, mm.
    pub tolerance: f64,
    /// The number of equal steps `n` (1: the move as it is is within); null when even
    /// `maxSteps` steps are not.
    pub steps: Option<usize>,
    /// The most steps considered ([`MAX_SPLIT`]).
    pub max_steps: usize,
    /// `|Δθk|/n`, the step of K per block, degrees (radians in Rust; of `maxSteps` steps when
    /// `steps` is null).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub step_k: f64,
    /// `|Δθm|/n`, the step of M per block, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub step_m: f64,
    /// The largest δ of the `n` pieces, mm (`≤ tolerance` when `steps` is given).
    pub max: f64,
}

/// The fewest equal steps that keep a move's nonlinear error within `tolerance` (mm) at the
/// tool point `length` (mm) from the pivot (Geng, Wu & Qiu 2018, Section 5: "the error can be
/// reduced by interpolating more points"; eqs 19-21 for each piece).
///
/// The move from `(θk0, θm0)` to `(θk1, θm1)` is programmed as `n` blocks, block `i` from the
/// pose at `u = i/n` to the pose at `u = (i+1)/n` (eq 10), each interpolated linearly by the
/// control and so measured against the plane of its own end orientations:
///
/// ```text
/// δn = max over i of L · max over u of |P_i(u) · n_i|,   n = min { n ≥ 1 : δn ≤ tolerance }
/// ```
///
/// `δn` falls about as `1/n²` (a block's error is second order in its increments, eq 25), so `n`
/// is found as in [`crate::toolpath::refine`]: doubling from 2 until within, then bisection
/// (`O(log n)` trials of `n` peaks each); for a move of K alone all blocks are alike and `δn` is
/// strictly decreasing, so this `n` is exactly the smallest. Steps are reported as `|Δθ|/n`,
/// radians. Errors: a `tolerance` or `length` not positive and finite.
pub fn split_within(mv: Move, length: f64, tolerance: f64) -> Result<Split> {
    mv.validate()?;
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_positive("tolerance", tolerance, MAX_LENGTH_MM, "mm")?;
    let worst = |n: usize| -> f64 {
        (0..n)
            .map(|i| {
                let a = mv.pose_at(i as f64 / n as f64);
                let b = mv.pose_at((i + 1) as f64 / n as f64);
                Deviation::new(Move::new(mv.rtype, a, b)).peak().value * length
            })
            .fold(0.0, f64::max)
    };
    let (dk, dm) = mv.increments();
    let split = |n: usize, max: f64, found: bool| Split {
        tolerance,
        steps: found.then_some(n),
        max_steps: MAX_SPLIT,
        step_k: dk.abs() / n as f64,
        step_m: dm.abs() / n as f64,
        max,
    };
    let first = worst(1);
    if first <= tolerance {
        return Ok(split(1, first, true));
    }
    // Doubling: `lo` is known to be above the tolerance, `hi` within it.
    let mut lo = 1;
    let mut hi = 2;
    let mut at_hi = worst(hi);
    while at_hi > tolerance {
        if hi >= MAX_SPLIT {
            return Ok(split(MAX_SPLIT, at_hi, false));
        }
        lo = hi;
        hi = (2 * hi).min(MAX_SPLIT);
        at_hi = worst(hi);
    }
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        let at = worst(mid);
        if at <= tolerance {
            hi = mid;
            at_hi = at;
        } else {
            lo = mid;
        }
    }
    Ok(split(hi, at_hi, true))
}

/// The exact maximum error (fraction of `L`) of many moves of one type, for bulk use:
/// `moves` holds `[θk0, θm0, θk1, θm1]` per move (radians), the result one value per move.
pub fn max_errors(rtype: RotaryType, moves: &[[f64; 4]]) -> Vec<f64> {
    moves
        .iter()
        .map(|m| {
            let mv = Move::new(rtype, Pose::new(m[0], m[1]), Pose::new(m[2], m[3]));
            Deviation::new(mv).peak().value
        })
        .collect()
}

/// The bulk export `nonlinearMaxErrors`: the exact maximum error, mm, of many moves of the type
/// named `rtype` at the tool point `length` (mm) from the pivot. `moves` holds
/// `[θk0, θm0, θk1, θm1]` per move in degrees (a length that is a multiple of 4, each within
/// ±[`MAX_ANGLE_DEG`]); the result one value per move ([`max_errors`] times `length`).
pub fn max_errors_mm(rtype: &str, length: f64, moves: &[f64]) -> Result<Vec<f64>> {
    let t = RotaryType::parse(rtype)?;
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    if moves.len() % 4 != 0 {
        return Err(crate::Error::field(
            "moves",
            format!("length must be a multiple of 4, got {}", moves.len()),
        ));
    }
    let lim = MAX_ANGLE_DEG;
    let mut quads = Vec::with_capacity(moves.len() / 4);
    for (n, c) in moves.chunks_exact(4).enumerate() {
        let mut q = [0.0; 4];
        for (j, v) in c.iter().enumerate() {
            q[j] = v.to_radians();
            if v.is_finite() && v.abs() <= lim {
                continue; // the message (and its formatted path) only for a bad value
            }
            check_range(&format!("moves[{}]", 4 * n + j), *v, -lim, lim, "degrees")?;
        }
        quads.push(q);
    }
    Ok(max_errors(t, &quads)
        .into_iter()
        .map(|v| v * length)
        .collect())
}

/// Fig 4: the maximum error (mm) against the start angle of K, `k_from..=k_to` (radians) at `n`
/// points, for fixed `theta_m`, increments `d_k`, `d_m`. The paper's finding: a constant.
pub fn sweep_start_k(
    rtype: RotaryType,
    length: f64,
    theta_m: f64,
    d_k: f64,
    d_m: f64,
    k_range: (f64, f64),
    n: usize,
) -> Result<Vec<f64>> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_count("n", n, 2, 100_000)?;
    let ks = linspace(k_range.0, k_range.1, n);
    ks.iter()
        .map(|&k| {
            let mv = Move::new(
                rtype,
                Pose::new(k, theta_m),
                Pose::new(k + d_k, theta_m + d_m),
            );
            mv.validate()?;
            Ok(Deviation::new(mv).peak().value * length)
        })
        .collect()
}

/// One curve of [`sweep_start_m`]: the increment ratio and the errors along θm0.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct RatioCurve {
    /// `K = Δθk / Δθm`.
    pub ratio: f64,
    /// Exact maximum error, mm, one per θm0.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub exact: Vec<f64>,
    /// The u = 0.5 approximation (eq 25/30), mm; null where the ends coincide or are opposite.
    pub approx: Vec<Option<f64>>,
}

/// Fig 4 (the export `nonlinearSweepK`): the maximum error against the start command of K.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct SweepK {
    /// Start commands of K, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub k: Vec<f64>,
    /// Exact maximum error, mm, one per start command.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub max: Vec<f64>,
}

/// Fig 7 (the export `nonlinearSweepM`): the maximum error against the start command of M, one
/// curve per ratio of the increments.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct SweepM {
    /// Start commands of M, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub m: Vec<f64>,
    /// One curve per ratio, in the order given.
    pub curves: Vec<RatioCurve>,
}

/// Fig 7: the maximum error (mm) against the start angle of M over `m_range` (radians, `n`
/// points), one curve per increment ratio `K = Δθk/Δθm` with `Δθm = d_m` fixed (θk0 = 0; the
/// error does not depend on it).
pub fn sweep_start_m(
    rtype: RotaryType,
    length: f64,
    d_m: f64,
    ratios: &[f64],
    m_range: (f64, f64),
    n: usize,
) -> Result<Vec<RatioCurve>> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_count("n", n, 2, 100_000)?;
    check_count("ratios.length", ratios.len(), 1, 16)?;
    let ms = linspace(m_range.0, m_range.1, n);
    let group = rtype.group();
    ratios
        .iter()
        .enumerate()
        .map(|(i, &ratio)| {
            check_range(&format!("ratios[{i}]"), ratio, -100.0, 100.0, "")?;
            let d_k = ratio * d_m;
            let mut exact = Vec::with_capacity(n);
            let mut approx = Vec::with_capacity(n);
            for &m in &ms {
                let mv = Move::new(rtype, Pose::new(0.0, m), Pose::new(d_k, m + d_m));
                mv.validate()?;
                let dev = Deviation::new(mv);
                exact.push(dev.peak().value * length);
                approx.push(match dev.reference {
                    Reference::Plane => approx_half(group, m, d_m, d_k).map(|a| a * length),
                    _ => None,
                });
            }
            Ok(RatioCurve {
                ratio,
                exact,
                approx,
            })
        })
        .collect()
}

/// Figs 3, 5 and 8: the maximum error and where it occurs over a grid of increments.
/// Grids are row-major with `ny` rows (Δθm, `m_range`) and `nx` columns (Δθk, `k_range`):
/// entry `[iy * nx + ix]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct IncrementGrid {
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Δθk of each column, degrees (radians in Rust; the commands' for
    /// [`NonlinearCase::grid`]).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub d_k: Vec<f64>,
    /// Δθm of each row, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub d_m: Vec<f64>,
    /// Exact maximum error, mm, row-major `ny × nx`.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub max: Vec<f64>,
    /// u of the maximum, row-major like `max`; null where the error is zero (no unique
    /// maximum).
    pub u_at_max: Vec<Option<f64>>,
}

/// Computes an [`IncrementGrid`] for moves starting at `(0, theta_m)`.
pub fn sweep_increments(
    rtype: RotaryType,
    length: f64,
    theta_m: f64,
    k_range: (f64, f64),
    m_range: (f64, f64),
    nx: usize,
    ny: usize,
) -> Result<IncrementGrid> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_count("nx", nx, 2, 2001)?;
    check_count("ny", ny, 2, 2001)?;
    let d_k = linspace(k_range.0, k_range.1, nx);
    let d_m = linspace(m_range.0, m_range.1, ny);
    let mut max = Vec::with_capacity(nx * ny);
    let mut u_at_max = Vec::with_capacity(nx * ny);
    for &dm in &d_m {
        for &dk in &d_k {
            let mv = Move::new(rtype, Pose::new(0.0, theta_m), Pose::new(dk, theta_m + dm));
            mv.validate()?;
            let peak = Deviation::new(mv).peak();
            max.push(peak.value * length);
            u_at_max.push((peak.value > 1e-12).then_some(peak.u));
        }
    }
    Ok(IncrementGrid {
        nx,
        ny,
        d_k,
        d_m,
        max,
        u_at_max,
    })
}

/// One row of [`NonlinearCase::compare_types`]: the same tool path on one type.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct TypeComparison {
    /// The type.
    #[serde(rename = "type")]
    pub rtype: RotaryType,
    /// Its group.
    pub group: Group,
    /// Its commands `[K, M]` that give the start tool vector (the smallest tilt), degrees
    /// (radians in Rust); null when out of travel.
    #[serde(serialize_with = "degrees_pair")]
    pub start: Option<[f64; 2]>,
    /// Its commands `[K, M]` that give the end tool vector (the solution nearest the start),
    /// degrees (radians in Rust); null when out of travel.
    #[serde(serialize_with = "degrees_pair")]
    pub end: Option<[f64; 2]>,
    /// Exact maximum error, mm; null when out of travel.
    pub max: Option<f64>,
    /// u of the maximum.
    pub u_at_max: Option<f64>,
    /// Why the type cannot make the move within the machine's travel.
    pub unreachable: Option<String>,
}

/// A pair of commands `[K, M]` held in radians, written in degrees (`null` when absent).
fn degrees_pair<S: serde::Serializer>(
    pair: &Option<[f64; 2]>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    pair.map(|p| p.map(f64::to_degrees)).serialize(s)
}

/// `n ≥ 2` equally spaced values from `a` to `b` inclusive (`[a]` when `n < 2`).
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    if n < 2 {
        return vec![a];
    }
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}
