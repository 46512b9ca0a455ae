//! The S-shape test piece of ISO 10791-7:2020 as Chanal, Duc & Chevalier (2022) define it:
//! two ruled surfaces between cubic B-splines, their outward normals, and the 100 measurement
//! points.
//!
//! # Geometry (Section 2.1, Fig 3, eq 1)
//! Four cubic B-splines with 16 control points each (mm, workpiece coordinates) and the clamped
//! knot vector `{0,0,0,0, 1/13, …, 12/13, 1,1,1,1}`: `Q` (z = 0) and `P` (z = 30) for surface A,
//! `N` (z = 0) and `M` (z = 30) for surface B. Each surface is ruled (eq 1):
//! `S(u, v) = (1 − v)·C0(u) + v·C1(u)`, with `C0` the bottom curve and `C1` the top one, so
//! `z = 30·v` exactly and the measurement curve at height z is the iso-curve `v = z/30`.
//!
//! **Control point N11.** Fig 3 gives `N11 = (30, −93, 0)`, while both of the paper's NC programs
//! (Table 1 lists N11 as `X30 Y-95`, and Table 2's Z11/Z25 curves are only consistent with
//! `y = −95`) use `(30, −95, 0)`. The standard's figure is followed here (`−93`); the tests show
//! that Table 2 agrees with every other control point.
//!
//! # Vectors (Section 3.1, Fig 7)
//! * `R(u) = (C1 − C0)/‖C1 − C0‖`, the ruling, pointing up (from the bottom to the top curve).
//! * `T(u, v) = S_u/‖S_u‖`, the unit tangent of the iso-curve `v`. The paper calls it
//!   perpendicular to `R`; it is not in general (the rulings are not perpendicular to the
//!   iso-curves), so the engine also gives `T⊥`, its unit component perpendicular to `R`.
//! * `N(u, v) = ±(R × S_u)/‖R × S_u‖`, the unit normal of the surface (the tangent plane is spanned
//!   by `S_u` and `S_v ∥ R`), oriented out of the part, i.e. away from the other surface
//!   (the wall of material lies between A and B): `+` for surface A, `−` for surface B. The paper
//!   writes `N = ±R × T` without normalising; `‖R × T‖ < 1` where `T` is not perpendicular to `R`.
//!
//! # Measurement points (Section 2.1, Fig 4)
//! 25 points on each of the four measurement curves: TOP (z = 25 mm) and BOTTOM (z = 11 mm) on
//! surfaces A and B. The paper does not give their positions; here they are at **equal arc length**:
//! point `k` (1..25) of a curve sits at arc length `(k − ½)/25` of the curve's length from the
//! `u = 0` end (the end at y = −95.5 mm), i.e. at the centres of 25 equal pieces, so none lies on
//! the part's edge. **Numbering** as in the paper: on each curve, 1..25 on surface A and 26..50 on
//! surface B, both running from the `u = 0` end to the `u = 1` end. The list order is TOP 1..50,
//! then BOTTOM 1..50.

use super::bspline::{BSpline, CurvePoint};
use crate::error::{quote, Error, Result};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// Degree of the four curves.
pub const DEGREE: usize = 3;
/// Height of the top curves above the bottom ones, mm.
pub const HEIGHT: f64 = 30.0;
/// Height of the TOP measurement curve, mm.
pub const Z_TOP: f64 = 25.0;
/// Height of the BOTTOM measurement curve, mm.
pub const Z_BOTTOM: f64 = 11.0;
/// Points per measurement curve and surface.
pub const POINTS_PER_CURVE: usize = 25;
/// All measurement points: 2 curves × 2 surfaces × 25.
pub const N_POINTS: usize = 4 * POINTS_PER_CURVE;

/// Control points of Fig 3 (x, y), mm; the top curves are at z = 30, the bottom ones at z = 0.
const P_TOP_A: [[f64; 2]; 16] = [
    [-131.0, -95.5],
    [-126.0, -41.0],
    [-131.0, 23.0],
    [-116.0, 78.0],
    [-51.0, 77.0],
    [-20.0, 46.0],
    [-11.0, 10.0],
    [-9.0, 2.0],
    [-7.0, -6.0],
    [-5.0, -14.0],
    [3.0, -46.0],
    [32.0, -80.0],
    [103.0, -81.0],
    [116.0, -13.0],
    [110.0, 43.0],
    [115.0, 99.5],
];
const Q_BOTTOM_A: [[f64; 2]; 16] = [
    [-137.0, -95.5],
    [-134.0, -41.0],
    [-138.0, 23.0],
    [-118.0, 87.0],
    [-49.0, 84.0],
    [-23.0, 58.0],
    [-11.0, 10.0],
    [-9.0, 2.0],
    [-7.0, -6.0],
    [-5.0, -14.0],
    [3.0, -46.0],
    [36.0, -88.0],
    [111.0, -84.0],
    [119.0, -13.0],
    [118.0, 43.0],
    [121.0, 99.5],
];
const M_TOP_B: [[f64; 2]; 16] = [
    [-121.0, -95.5],
    [-117.0, -29.0],
    [-121.0, 30.0],
    [-107.0, 68.0],
    [-62.0, 67.0],
    [-31.0, 48.0],
    [-22.0, 12.0],
    [-20.0, 4.0],
    [-18.0, -4.0],
    [-16.0, -12.0],
    [-7.0, -48.0],
    [26.0, -88.0],
    [95.0, -91.0],
    [129.0, -42.0],
    [118.0, 28.0],
    [125.0, 99.5],
];
const N_BOTTOM_B: [[f64; 2]; 16] = [
    [-127.0, -95.5],
    [-124.0, -29.0],
    [-128.0, 30.0],
    [-108.0, 76.0],
    [-62.0, 74.0],
    [-33.0, 56.0],
    [-22.0, 12.0],
    [-20.0, 4.0],
    [-18.0, -4.0],
    [-16.0, -12.0],
    [-7.0, -48.0],
    [30.0, -93.0],
    [100.0, -97.0],
    [132.0, -46.0],
    [127.0, 27.0],
    [131.0, 99.5],
];

/// Surface A (control points P over Q) or B (M over N).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub enum SurfaceId {
    /// The surface through P (top) and Q (bottom).
    A,
    /// The surface through M (top) and N (bottom).
    B,
}

impl SurfaceId {
    /// Both, A first.
    pub const BOTH: [SurfaceId; 2] = [SurfaceId::A, SurfaceId::B];

    /// "A" or "B".
    pub fn name(self) -> &'static str {
        match self {
            SurfaceId::A => "A",
            SurfaceId::B => "B",
        }
    }
}

/// A measurement curve: TOP (z = 25 mm) or BOTTOM (z = 11 mm).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "lowercase")]
pub enum Curve {
    /// z = 25 mm.
    Top,
    /// z = 11 mm.
    Bottom,
}

impl Curve {
    /// Both, in list order.
    pub const BOTH: [Curve; 2] = [Curve::Top, Curve::Bottom];

    /// Height above the part's base, mm.
    pub fn z(self) -> f64 {
        match self {
            Curve::Top => Z_TOP,
            Curve::Bottom => Z_BOTTOM,
        }
    }

    /// "top" or "bottom".
    pub fn name(self) -> &'static str {
        match self {
            Curve::Top => "top",
            Curve::Bottom => "bottom",
        }
    }
}

/// A ruled surface `S(u, v) = (1 − v)·C0(u) + v·C1(u)` (eq 1) with its outward side.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// Which surface of the part.
    pub id: SurfaceId,
    /// `C0`, the bottom curve (z = 0).
    pub bottom: BSpline,
    /// `C1`, the top curve (z = 30 mm).
    pub top: BSpline,
    /// `+1` when `R × S_u` points out of the part, else `−1`.
    pub outward: f64,
}

/// Everything about the surface at `(u, v)` that the studies need.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// `S(u, v)`, mm.
    pub point: Vector3<f64>,
    /// `∂S/∂u`, mm.
    pub s_u: Vector3<f64>,
    /// `∂²S/∂u²`, mm.
    pub s_uu: Vector3<f64>,
    /// `C1 − C0`, mm (the generator; `S_v`).
    pub ruling_vector: Vector3<f64>,
    /// `R(u)`, unit.
    pub ruling: Vector3<f64>,
    /// `dR/du`.
    pub ruling_u: Vector3<f64>,
    /// The paper's `T(u, v) = S_u/‖S_u‖`.
    pub tangent: Vector3<f64>,
    /// `T⊥`: the unit component of `T` perpendicular to `R` (so `(T⊥, N, R)` is orthonormal).
    pub tangent_perp: Vector3<f64>,
    /// `N(u, v)`, unit, outward.
    pub normal: Vector3<f64>,
    /// `∂N/∂u`.
    pub normal_u: Vector3<f64>,
}

fn spline(points: &[[f64; 2]; 16], z: f64) -> Result<BSpline> {
    BSpline::clamped_uniform(
        DEGREE,
        points.iter().map(|p| Vector3::new(p[0], p[1], z)).collect(),
    )
}

impl Surface {
    /// Surface A or B of the standard (Fig 3).
    pub fn standard(id: SurfaceId) -> Result<Self> {
        let (bottom, top, outward) = match id {
            SurfaceId::A => (spline(&Q_BOTTOM_A, 0.0)?, spline(&P_TOP_A, HEIGHT)?, 1.0),
            SurfaceId::B => (spline(&N_BOTTOM_B, 0.0)?, spline(&M_TOP_B, HEIGHT)?, -1.0),
        };
        Ok(Self {
            id,
            bottom,
            top,
            outward,
        })
    }

    /// `S(u, v)`, mm (eq 1).
    pub fn point(&self, u: f64, v: f64) -> Vector3<f64> {
        self.bottom.point(u) * (1.0 - v) + self.top.point(u) * v
    }

    /// The surface and its vectors at `(u, v)`. Degenerate cases (a zero generator or a ruling
    /// along the iso-curve) do not occur on the standard's surfaces; the vectors are then not
    /// finite.
    pub fn frame(&self, u: f64, v: f64) -> Frame {
        let c0 = self.bottom.eval(u);
        let c1 = self.top.eval(u);
        frame_from(&c0, &c1, v, self.outward)
    }

    /// The surface on an `nu × nv` grid (`nu, nv ≥ 2`; u and v from 0 to 1): `[x, y, z]`, each
    /// row-major `nv × nu` (`[iv * nu + iu]`), mm.
    pub fn mesh(&self, nu: usize, nv: usize) -> [Vec<f64>; 3] {
        let mut xyz: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(nu * nv));
        let at = |i: usize, n: usize| i as f64 / (n.max(2) - 1) as f64;
        for iv in 0..nv {
            for iu in 0..nu {
                let p = self.point(at(iu, nu), at(iv, nv));
                for (c, x) in xyz.iter_mut().zip(p.iter()) {
                    c.push(*x);
                }
            }
        }
        xyz
    }

    /// The iso-curve parameter `v` of the height `z` (mm): `v = z/30`.
    pub fn v_at_height(z: f64) -> f64 {
        z / HEIGHT
    }

    /// Length of the iso-curve `v` from `u = 0` to `u = 1`, mm.
    pub fn curve_length(&self, v: f64) -> f64 {
        self.arc_lengths(v).last().copied().unwrap_or(0.0)
    }

    /// Cumulative arc length of the iso-curve `v` at the breakpoints `u_j = j/ARC_PIECES`
    /// (Gauss–Legendre, 5 points per piece; the integrand `‖S_u‖` is smooth on each piece).
    fn arc_lengths(&self, v: f64) -> Vec<f64> {
        let mut out = Vec::with_capacity(ARC_PIECES + 1);
        out.push(0.0);
        let mut s = 0.0;
        for j in 0..ARC_PIECES {
            let (a, b) = (
                j as f64 / ARC_PIECES as f64,
                (j + 1) as f64 / ARC_PIECES as f64,
            );
            s += gauss5(a, b, |u| self.frame(u, v).s_u.norm());
            out.push(s);
        }
        out
    }

    /// The parameter `u` at which the iso-curve `v` has arc length `s` (mm) from `u = 0`
    /// (Newton on `ds/du = ‖S_u‖`, kept inside the bracketing piece; `s` is clamped to the
    /// curve's length).
    pub fn u_at_arc_length(&self, v: f64, s: f64) -> f64 {
        let table = self.arc_lengths(v);
        self.u_at(&table, v, s)
    }

    fn u_at(&self, table: &[f64], v: f64, s: f64) -> f64 {
        let total = table[table.len() - 1];
        let s = s.clamp(0.0, total);
        let j = table.partition_point(|&x| x <= s).clamp(1, ARC_PIECES) - 1;
        let (a, b) = (
            j as f64 / ARC_PIECES as f64,
            (j + 1) as f64 / ARC_PIECES as f64,
        );
        let (mut lo, mut hi) = (a, b);
        let mut u = a + (b - a) * (s - table[j]) / (table[j + 1] - table[j]).max(1e-300);
        for _ in 0..50 {
            let f = table[j] + gauss5(a, u, |x| self.frame(x, v).s_u.norm()) - s;
            if f > 0.0 {
                hi = u;
            } else {
                lo = u;
            }
            let speed = self.frame(u, v).s_u.norm();
            let mut next = u - f / speed;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - u).abs() < 1e-15 {
                u = next;
                break;
            }
            u = next;
        }
        u
    }
}

/// Pieces of `[0, 1]` for the arc-length quadrature (13 knot spans × 16).
const ARC_PIECES: usize = 13 * 16;

/// 5-point Gauss–Legendre quadrature of `f` over `[a, b]`.
fn gauss5(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    const X: [f64; 5] = [
        0.0,
        0.538_469_310_105_683_1,
        -0.538_469_310_105_683_1,
        0.906_179_845_938_664,
        -0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.568_888_888_888_888_9,
        0.478_628_670_499_366_5,
        0.478_628_670_499_366_5,
        0.236_926_885_056_189_1,
        0.236_926_885_056_189_1,
    ];
    let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
    h * X.iter().zip(W).map(|(x, w)| w * f(m + h * x)).sum::<f64>()
}

/// The frame of the ruled surface between `c0` and `c1` (points with derivatives) at `v`.
fn frame_from(c0: &CurvePoint, c1: &CurvePoint, v: f64, outward: f64) -> Frame {
    let point = c0.point * (1.0 - v) + c1.point * v;
    let s_u = c0.d1 * (1.0 - v) + c1.d1 * v;
    let s_uu = c0.d2 * (1.0 - v) + c1.d2 * v;
    let d = c1.point - c0.point;
    let d_u = c1.d1 - c0.d1;
    let len = d.norm();
    let ruling = d / len;
    let ruling_u = (d_u - ruling * ruling.dot(&d_u)) / len;
    let tangent = s_u / s_u.norm();
    let perp = s_u - ruling * ruling.dot(&s_u);
    let tangent_perp = perp / perp.norm();
    // N = ±w/‖w‖ with w = R × S_u; dN/du from w_u = R_u × S_u + R × S_uu.
    let w = ruling.cross(&s_u);
    let w_u = ruling_u.cross(&s_u) + ruling.cross(&s_uu);
    let wn = w.norm();
    let w_hat = w / wn;
    let normal = w_hat * outward;
    let normal_u = (w_u - w_hat * w_hat.dot(&w_u)) / wn * outward;
    Frame {
        point,
        s_u,
        s_uu,
        ruling_vector: d,
        ruling,
        ruling_u,
        tangent,
        tangent_perp,
        normal,
        normal_u,
    }
}

/// One of the 100 measurement points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct MeasurementPoint {
    /// TOP or BOTTOM.
    pub curve: Curve,
    /// 1..50 on its curve (1..25 on A, 26..50 on B).
    pub number: usize,
    /// Which surface.
    pub surface: SurfaceId,
    /// Surface parameters.
    pub u: f64,
    /// `v = z/30`.
    pub v: f64,
    /// Position, mm (workpiece coordinates).
    pub point: [f64; 3],
    /// Outward unit normal.
    pub normal: [f64; 3],
}

impl MeasurementPoint {
    /// Position in the list order (TOP 1..50, then BOTTOM 1..50): 0..100.
    pub fn index(&self) -> usize {
        index_of(self.curve, self.number)
    }

    /// A label such as "top 7".
    pub fn label(&self) -> String {
        format!("{} {}", self.curve.name(), self.number)
    }
}

/// Position of point `number` (1..=50) of `curve` in the list order.
pub fn index_of(curve: Curve, number: usize) -> usize {
    let c = match curve {
        Curve::Top => 0,
        Curve::Bottom => 1,
    };
    c * 2 * POINTS_PER_CURVE + number - 1
}

/// The S-shape part: both surfaces.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Surface A.
    pub a: Surface,
    /// Surface B.
    pub b: Surface,
}

impl Part {
    /// The part of the standard (Fig 3).
    pub fn standard() -> Result<Self> {
        Ok(Self {
            a: Surface::standard(SurfaceId::A)?,
            b: Surface::standard(SurfaceId::B)?,
        })
    }

    /// Surface A or B.
    pub fn surface(&self, id: SurfaceId) -> &Surface {
        match id {
            SurfaceId::A => &self.a,
            SurfaceId::B => &self.b,
        }
    }

    /// The standard part's 100 measurement points, computed once per process.
    pub fn standard_points() -> Result<&'static [MeasurementPoint]> {
        static POINTS: OnceLock<Result<Vec<MeasurementPoint>>> = OnceLock::new();
        POINTS
            .get_or_init(|| Ok(Part::standard()?.measurement_points()))
            .as_deref()
            .map_err(Clone::clone)
    }

    /// The lengths of the four measurement curves, mm, in list order: top A, top B, bottom A,
    /// bottom B.
    pub fn curve_lengths(&self) -> Vec<f64> {
        Curve::BOTH
            .iter()
            .flat_map(|c| {
                SurfaceId::BOTH
                    .iter()
                    .map(|id| self.surface(*id).curve_length(Surface::v_at_height(c.z())))
            })
            .collect()
    }

    /// The 100 measurement points in list order (see the module documentation).
    pub fn measurement_points(&self) -> Vec<MeasurementPoint> {
        let mut out = Vec::with_capacity(N_POINTS);
        for curve in Curve::BOTH {
            let v = Surface::v_at_height(curve.z());
            for (k, id) in SurfaceId::BOTH.iter().enumerate() {
                let s = self.surface(*id);
                let table = s.arc_lengths(v);
                let total = table[table.len() - 1];
                for j in 0..POINTS_PER_CURVE {
                    let target = (j as f64 + 0.5) / POINTS_PER_CURVE as f64 * total;
                    let u = s.u_at(&table, v, target);
                    let f = s.frame(u, v);
                    out.push(MeasurementPoint {
                        curve,
                        number: k * POINTS_PER_CURVE + j + 1,
                        surface: *id,
                        u,
                        v,
                        point: f.point.into(),
                        normal: f.normal.into(),
                    });
                }
            }
        }
        out
    }
}

/// Parses a measurement curve name: `top`/`bottom`, `T`/`B`, `Z25`/`Z11`, `25`/`11`
/// (case-insensitive).
pub fn parse_curve(text: &str) -> Result<Curve> {
    match text.trim().to_ascii_lowercase().as_str() {
        "top" | "t" | "z25" | "25" => Ok(Curve::Top),
        "bottom" | "b" | "z11" | "11" => Ok(Curve::Bottom),
        other => Err(Error::field(
            "curve",
            format!(
                "unknown measurement curve {}; expected top (z = 25 mm) or bottom (z = 11 mm)",
                quote(other)
            ),
        )),
    }
}
