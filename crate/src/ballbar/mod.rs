//! A circular test of two linear axes with a ball-bar (ISO 230-4:2005), from a measured trace:
//! the circular deviation and hysteresis, and the faults that distort the circle, each fitted by
//! least squares on its own model.
//!
//! # The trace
//! The ball-bar measures the radial deviation `Δr(θ)` of the tool from a circle of nominal
//! radius `R` about the pivot, at angles `θ` measured from the plane's first axis `u` towards its
//! second `v`, counter-clockwise (CCW, `d = +1`) and clockwise (CW, `d = −1`) as seen from the
//! plane's positive normal. Positive `Δr`: outwards.
//!
//! # Circular deviation and hysteresis (ISO 230-4, 3.2 and 3.3)
//! The centre is the **least-squares circle of both traces together** (its offset and radius,
//! below, removed from every point). Then `G_ccw` and `G_cw` are the spread (largest − smallest
//! `Δr`) of each trace, `G` that of both together (the two concentric circles enclosing both
//! paths), and the hysteresis `H` the largest `|Δr_ccw(θ) − Δr_cw(θ)|` over the angles, the CW
//! trace interpolated linearly at the CCW trace's angles.
//!
//! # The faults (first order in the fault, exact geometry in the tests)
//! With `c = cos θ`, `s = sin θ`, the fitted model is `Δr = Σ_k p_k·f_k(θ, d)`:
//! * radius offset `r₀` (the bar's length is calibrated: this is the mean radius error): `1`;
//! * centre offset `(e_u, e_v)`: `c`, `s`;
//! * scale mismatch: `u` reads `(1 + ε_u)·u`, `v` reads `(1 + ε_v)·v`:
//!   `Δr = R·(ε_u·c² + ε_v·s²)`, whose `cos 2θ` part is `R·(ε_u − ε_v)/2`; reported as
//!   `ε_u − ε_v` in ppm (positive: `u` longer than `v`);
//! * out-of-squareness `α`: the `v` axis leans towards `+u` by `α` (the angle between `+u` and
//!   `+v` is `90° − α`): `u_actual = u + α·v`, `Δr = R·α·s·c = (R·α/2)·sin 2θ`, the same both
//!   ways; reported in µm/m (positive: the axes closer than 90°);
//! * servo mismatch: `u` lags `v` by `τ`: at angular speed `ω = F/R` (`F` the feed),
//!   `u_actual = R·cos(θ − d·ω·τ)`, `Δr = (R·ω·τ/2)·d·sin 2θ`, opposite ways; reported in ms
//!   (positive: `u` lags), only with a feed;
//! * backlash (lost motion) `b_u`: `u` stops `b_u/2` short in its direction of travel:
//!   `Δr = −(b_u/2)·c·sgn(du/dt) = (b_u/2)·d·c·sgn(s)`; `b_v`: `Δr = −(b_v/2)·d·s·sgn(c)`;
//!   steps at the axis's reversal points (`u` reverses at 0° and 180°, `v` at 90° and 270°);
//! * cyclic error: harmonics `cos kθ`, `sin kθ`, `k = 3 … 6`, reported as amplitude and phase.
//!
//! Values and standard errors come from [`crate::identify::fit`] (SVD least squares with rank
//! detection: with one direction only, squareness and servo mismatch are one combination, and
//! both are then given no value), intervals `x̂ ± t·se` at 95 % with `m − rank` degrees of
//! freedom.
//!
//! # Reversal spikes
//! After the fit, at each axis reversal and each direction, the residual over the 20° that
//! follow it is fitted with `h·exp(−φ/w)` (`φ` the angle travelled since the reversal): `h` by
//! linear least squares for each `w`, `w` by golden-section search on 0.1°–10°.
//!
//! # The plane and the machine
//! `u` and `v` are the axes of the plane chosen, and the squareness goes to the machine as that
//! plane's ISO 230-1 location error, with its sign through the kinematic chain ([`plane`]).
//!
//! # Units
//! At the edge: lengths mm, angles degrees, squareness µm/m, scale mismatch ppm, servo
//! mismatch ms. The file gives its units in the header.

mod plane;
pub mod read;
pub mod rotary;

pub use plane::BallbarPlane;
pub use read::{read_trace, Trace};

use crate::edge::Checked;
use crate::identify::fit;
use crate::identify::stats::t_quantile_two_sided;
use crate::machine::errors::ErrorValues;
use crate::schema::{self, DefaultValue, Kind, Quantity};
use crate::{Error, Result};
use nalgebra::DMatrix;
use serde::Serialize;
use std::f64::consts::PI;

crate::inputs! {
    /// A circular test with a ball-bar (ISO 230-4).
    pub struct BallbarInput {
        /// The trace (module docs of `read`).
        pub csv: String = "csv" {
            label: "Ball-bar trace (CSV)",
            help: "Angle (deg) and radial deviation (µm or mm) per line, with a direction column (ccw/cw) or one column per direction. `# radius: 100 mm` and `# feed: 1000 mm/min` lines are read.",
            kind: Kind::Text { max_len: 5_000_000 },
            group: "Circular test (ISO 230-4)",
        },
        /// The plane: `u`, `v` are X, Y (XY), Y, Z (YZ) or Z, X (ZX), the angle from `+u`
        /// towards `+v`, counter-clockwise seen from the plane's positive normal.
        pub plane: BallbarPlane = "plane" optional {
            label: "Plane", help: "The two axes the test moves: u is the first, v the second, the angle from +u towards +v.",
            kind: Kind::Choice(BallbarPlane::CHOICES),
            default: DefaultValue::Str("XY"), group: "Circular test (ISO 230-4)",
        },
        /// Nominal radius, mm (0: from the file).
        pub radius: f64 = "radius" optional {
            label: "Radius", help: "The ball-bar's length. 0: from the file's `# radius:` line.",
            kind: schema::number(Quantity::Length, 0.0, 2000.0),
            default: DefaultValue::Num(0.0), group: "Circular test (ISO 230-4)",
        },
        /// Feed, mm/min (0: from the file; none: no servo mismatch).
        pub feed: f64 = "feed" optional {
            label: "Feed (mm/min)", help: "The test's feed, for the servo mismatch in ms. 0: from the file's `# feed:` line, or not given.",
            kind: schema::number(Quantity::Number, 0.0, 1e6),
            default: DefaultValue::Num(0.0), group: "Circular test (ISO 230-4)",
        },
        /// Tolerance of the circular deviation G, mm (0: not judged).
        pub tolerance: f64 = "tolerance" optional {
            label: "Tolerance of G", help: "The largest circular deviation G that passes. 0: not judged.",
            kind: schema::number(Quantity::SmallLength, 0.0, 10.0),
            default: DefaultValue::Num(0.0), group: "Circular test (ISO 230-4)",
        },
    }
}

impl Checked for BallbarInput {
    fn check(&self) -> Result<()> {
        if self.radius > 0.0 && self.radius < 1.0 {
            return Err(Error::field(
                "radius",
                format!(
                    "must be 0 (from the file) or at least 1 mm, got {}",
                    self.radius
                ),
            ));
        }
        if self.feed > 0.0 && self.feed < 1.0 {
            return Err(Error::field(
                "feed",
                format!(
                    "must be 0 (from the file) or at least 1 mm/min, got {}",
                    self.feed
                ),
            ));
        }
        Ok(())
    }
}

/// A fitted value with its 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Fitted {
    /// The value (unit as the field says); null when the trace cannot separate it.
    pub value: Option<f64>,
    /// Half-width of its 95 % interval, same unit; null with the value.
    pub half_width: Option<f64>,
}

/// A reversal spike.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Spike {
    /// The axis reversing: "u" or "v" (the plane's first or second axis).
    pub axis: &'static str,
    /// Where, degrees (0, 90, 180, 270).
    pub at: f64,
    /// "ccw" or "cw".
    pub direction: &'static str,
    /// Height `h`, mm (positive outwards).
    pub height: f64,
    /// Width `w`, degrees: the angle over which it falls to 1/e.
    pub width: f64,
}

/// A harmonic of the trace (cyclic error).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Harmonic {
    /// `k`: waves per turn.
    pub order: usize,
    /// Amplitude, mm.
    pub amplitude: f64,
    /// Phase, degrees: the wave peaks at `θ = phase/k`.
    pub phase: f64,
}

/// The diagnostics (module docs), each with its 95 % interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Diagnostics {
    /// Mean radius error `r₀`, mm.
    pub radius: Fitted,
    /// Centre offset along `u`, mm.
    pub centre_u: Fitted,
    /// Centre offset along `v`, mm.
    pub centre_v: Fitted,
    /// Scale mismatch `ε_u − ε_v`, ppm.
    pub scale_mismatch: Fitted,
    /// Out-of-squareness `α`, µm/m.
    pub squareness: Fitted,
    /// Servo mismatch `τ`, ms (null without a feed).
    pub servo_mismatch: Fitted,
    /// Backlash of `u`, mm.
    pub backlash_u: Fitted,
    /// Backlash of `v`, mm.
    pub backlash_v: Fitted,
    /// Harmonics 3 … 6, largest first.
    pub harmonics: Vec<Harmonic>,
    /// The reversal spikes.
    pub spikes: Vec<Spike>,
    /// rms of what the model leaves, mm.
    pub residual_rms: f64,
}

/// The evaluation of a circular test.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Ballbar {
    /// Nominal radius used, mm.
    pub radius: f64,
    /// Feed used, mm/min (null: none).
    pub feed: Option<f64>,
    /// How the centre was taken.
    pub centre: &'static str,
    /// Circular deviation of both traces, mm.
    pub g: f64,
    /// Of the CCW trace alone, mm (null: none).
    pub g_ccw: Option<f64>,
    /// Of the CW trace alone, mm (null: none).
    pub g_cw: Option<f64>,
    /// Circular hysteresis, mm (null: one direction only).
    pub h: Option<f64>,
    /// `G ≤ tolerance` (null: no tolerance).
    pub pass: Option<bool>,
    /// The tolerance of G, mm (0: none).
    pub tolerance: f64,
    /// The fitted faults.
    pub diagnostics: Diagnostics,
    /// The plane of the test.
    pub plane: BallbarPlane,
    /// The letters of `u` and `v` in that plane.
    pub axes: [&'static str; 2],
    /// What goes into the one machine model: the out-of-squareness `α` as the plane's ISO 230-1
    /// location error, degrees (radians in Rust), with the sign the kinematic chain gives:
    /// `E_C0Y = −α` for XY, `E_A0Z = −α` for YZ, `E_B0Z = +α` for ZX (crate/src/ballbar/plane.rs).
    /// Put it into `machine.errors` as it is. Empty when the trace cannot separate the
    /// squareness (one direction only).
    #[serde(serialize_with = "crate::machine::errors::api_values")]
    #[cfg_attr(feature = "ts", tsify(type = "Partial<Record<string, number>>"))]
    pub errors: ErrorValues,
    /// That error in words: which axis leans which way, by how much in µm/m (null without a
    /// value).
    pub errors_meaning: Option<String>,
    /// What the machine is not given, and why, one line each: the set-up, backlash, spikes,
    /// servo mismatch, scale mismatch and cyclic error are not geometric errors the machine
    /// model holds as constants of one axis.
    pub not_sent: Vec<String>,
    /// The trace's angles, degrees (for the polar plot).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub angle: Vec<f64>,
    /// Its radial deviations about the least-squares circle, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub deviation: Vec<f64>,
    /// The model's fitted deviation at each point, mm (same centre).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub fitted: Vec<f64>,
    /// +1 CCW, −1 CW, per point.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub direction: Vec<f64>,
}

/// Columns of the fault model (module docs), in this order.
const NAMES: [&str; 8] = ["r0", "eu", "ev", "cos2", "sin2", "servo", "bu", "bv"];
const HARMONICS: std::ops::RangeInclusive<usize> = 3..=6;

fn row(theta: f64, d: f64) -> Vec<f64> {
    let (s, c) = theta.sin_cos();
    let sgn = |x: f64| if x.abs() < 1e-12 { 0.0 } else { x.signum() };
    let mut r = vec![
        1.0,
        c,
        s,
        (2.0 * theta).cos(),
        (2.0 * theta).sin(),
        d * (2.0 * theta).sin(),
        0.5 * d * c * sgn(s),
        -0.5 * d * s * sgn(c),
    ];
    for k in HARMONICS {
        r.push((k as f64 * theta).cos());
        r.push((k as f64 * theta).sin());
    }
    r
}

fn spread(v: impl Iterator<Item = f64> + Clone) -> f64 {
    v.clone().fold(f64::NEG_INFINITY, f64::max) - v.fold(f64::INFINITY, f64::min)
}

/// Fits `h·exp(−φ/w)` to `(φ, r)` pairs: `(h, w)`, `w` in radians.
fn spike(points: &[(f64, f64)]) -> (f64, f64) {
    let h_of = |w: f64| {
        let (num, den) = points.iter().fold((0.0, 0.0), |(n, d), (phi, r)| {
            let g = (-phi / w).exp();
            (n + g * r, d + g * g)
        });
        if den > 0.0 {
            num / den
        } else {
            0.0
        }
    };
    let sse = |w: f64| {
        let h = h_of(w);
        points
            .iter()
            .map(|(phi, r)| (r - h * (-phi / w).exp()).powi(2))
            .sum::<f64>()
    };
    let w = crate::numeric::golden_max(|w| -sse(w), 0.1f64.to_radians(), 10f64.to_radians());
    (h_of(w), w)
}

/// Evaluates a circular test (module docs).
pub fn evaluate(input: &BallbarInput) -> Result<Ballbar> {
    let t = read_trace(&input.csv)?;
    let radius = if input.radius > 0.0 {
        input.radius
    } else {
        t.radius.unwrap_or(0.0)
    };
    if !(1.0..=2000.0).contains(&radius) {
        return Err(Error::field(
            "radius",
            format!("give the ball-bar's length (radius, 1 to 2000 mm), or a `# radius: 100 mm` line in the file; got {radius}"),
        ));
    }
    if let Some(f) = t
        .feed
        .filter(|f| input.feed == 0.0 && !(1.0..=1e6).contains(f))
    {
        return Err(Error::field(
            "csv",
            format!("the file's feed must be 1 to 1000000 mm/min, got {f}"),
        ));
    }
    let feed = if input.feed > 0.0 {
        Some(input.feed)
    } else {
        t.feed
    };
    let n = t.angle.len();
    let both = t.direction.iter().any(|d| *d > 0.0) && t.direction.iter().any(|d| *d < 0.0);
    let cols = NAMES.len() + 2 * HARMONICS.count();
    let mut a = DMatrix::zeros(n, cols);
    for i in 0..n {
        for (j, v) in row(t.angle[i], t.direction[i]).into_iter().enumerate() {
            a[(i, j)] = v;
        }
    }
    let names: Vec<String> = NAMES
        .iter()
        .map(|s| s.to_string())
        .chain(HARMONICS.flat_map(|k| [format!("c{k}"), format!("s{k}")]))
        .collect();
    let f = fit(&a, &names, &t.deviation, 1e-6)?;
    let tq = t_quantile_two_sided(0.05, f.dof as f64);
    let est = |j: usize, scale: f64| {
        let e = &f.estimates[j];
        match (e.value, e.std_error) {
            (Some(v), Some(se)) => Fitted {
                value: Some(v * scale),
                half_width: Some(tq * se * scale.abs()),
            },
            _ => Fitted {
                value: None,
                half_width: None,
            },
        }
    };
    let omega = feed.map(|fd| fd / 60.0 / radius); // rad/s
    let x = |j: usize| f.estimates[j].value.unwrap_or(f.estimates[j].min_norm);
    // The least-squares circle: radius offset and centre removed from every point.
    let centred: Vec<f64> = (0..n)
        .map(|i| t.deviation[i] - x(0) - x(1) * t.angle[i].cos() - x(2) * t.angle[i].sin())
        .collect();
    let fitted: Vec<f64> = (0..n)
        .map(|i| f.fitted[i] - x(0) - x(1) * t.angle[i].cos() - x(2) * t.angle[i].sin())
        .collect();
    let of = |dir: f64| -> Vec<f64> {
        (0..n)
            .filter(|i| t.direction[*i] == dir)
            .map(|i| centred[i])
            .collect()
    };
    let (ccw, cw) = (of(1.0), of(-1.0));
    let g_ccw = (!ccw.is_empty()).then(|| spread(ccw.iter().copied()));
    let g_cw = (!cw.is_empty()).then(|| spread(cw.iter().copied()));
    let h = both.then(|| hysteresis(&t.angle, &centred, &t.direction));
    let mut harmonics: Vec<Harmonic> = HARMONICS
        .enumerate()
        .map(|(i, k)| {
            let (c, s) = (x(NAMES.len() + 2 * i), x(NAMES.len() + 2 * i + 1));
            Harmonic {
                order: k,
                amplitude: c.hypot(s),
                phase: s.atan2(c).to_degrees(),
            }
        })
        .collect();
    harmonics.sort_by(|p, q| q.amplitude.total_cmp(&p.amplitude));
    let mut spikes = Vec::new();
    for (dir, dname) in [(1.0, "ccw"), (-1.0, "cw")] {
        for (axis, at) in [("u", 0.0), ("v", 90.0), ("u", 180.0), ("v", 270.0)] {
            let q: f64 = at * PI / 180.0;
            let pts: Vec<(f64, f64)> = (0..n)
                .filter(|i| t.direction[*i] == dir)
                .map(|i| {
                    (
                        (dir * (t.angle[i] - q)).rem_euclid(2.0 * PI),
                        f.residuals[i],
                    )
                })
                .filter(|(phi, _)| *phi <= 20f64.to_radians())
                .collect();
            if pts.len() >= 3 {
                let (height, w) = spike(&pts);
                spikes.push(Spike {
                    axis,
                    at,
                    direction: dname,
                    height,
                    width: w.to_degrees(),
                });
            }
        }
    }
    let g = spread(centred.iter().copied());
    let squareness = est(4, 2.0 / radius * 1e6);
    let (errors, errors_meaning, not_sent) = plane::for_machine(input.plane, &squareness);
    Ok(Ballbar {
        radius,
        feed,
        centre: "the least-squares circle of both traces",
        g,
        g_ccw,
        g_cw,
        h,
        pass: (input.tolerance > 0.0).then_some(g <= input.tolerance),
        tolerance: input.tolerance,
        diagnostics: Diagnostics {
            radius: est(0, 1.0),
            centre_u: est(1, 1.0),
            centre_v: est(2, 1.0),
            // cos 2θ coefficient = R·(ε_u − ε_v)/2.
            scale_mismatch: est(3, 2.0 / radius * 1e6),
            // sin 2θ coefficient = R·α/2; α in µm/m.
            squareness,
            // d·sin 2θ coefficient = R·ω·τ/2; τ in ms.
            servo_mismatch: match omega {
                Some(w) => est(5, 2.0 / (radius * w) * 1e3),
                None => Fitted {
                    value: None,
                    half_width: None,
                },
            },
            backlash_u: est(6, 1.0),
            backlash_v: est(7, 1.0),
            harmonics,
            spikes,
            residual_rms: f.rms,
        },
        plane: input.plane,
        axes: input.plane.axes(),
        errors,
        errors_meaning,
        not_sent,
        angle: t.angle.iter().map(|a| a.to_degrees()).collect(),
        deviation: centred,
        fitted,
        direction: t.direction,
    })
}

/// The largest `|Δr_ccw(θ) − Δr_cw(θ)|`, the CW trace interpolated at the CCW trace's angles
/// (periodic, linear).
fn hysteresis(angle: &[f64], dev: &[f64], dir: &[f64]) -> f64 {
    let mut cw: Vec<(f64, f64)> = (0..angle.len())
        .filter(|i| dir[*i] < 0.0)
        .map(|i| (angle[i].rem_euclid(2.0 * PI), dev[i]))
        .collect();
    cw.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Extended by one point each side across 0 = 2π, so that every angle lies between two.
    let (first, last) = (cw[0], cw[cw.len() - 1]);
    cw.insert(0, (last.0 - 2.0 * PI, last.1));
    cw.push((first.0 + 2.0 * PI, first.1));
    let at = |th: f64| {
        let th = th.rem_euclid(2.0 * PI);
        let k = cw.partition_point(|p| p.0 <= th).clamp(1, cw.len() - 1);
        let (a, b) = (cw[k - 1], cw[k]);
        if b.0 - a.0 < 1e-15 {
            a.1
        } else {
            a.1 + (b.1 - a.1) * (th - a.0) / (b.0 - a.0)
        }
    };
    (0..angle.len())
        .filter(|i| dir[*i] > 0.0)
        .map(|i| (dev[i] - at(angle[i])).abs())
        .fold(0.0, f64::max)
}
