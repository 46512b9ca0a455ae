//! The customer's toolpath on every rotary-axis type: which configuration machines it more
//! accurately (Geng, Wu & Qiu 2018, Section 5 and Table 4: an impeller path on AB against AC).
//!
//! # The model
//! A toolpath is a list of points in workpiece coordinates: the tool tip (mm) and the unit tool
//! axis `a` (from the tip towards the spindle). The CAM system means the tool axis to turn on the
//! great circle from one point's axis to the next; the control instead interpolates the rotary
//! axes linearly between the poses that give those axes, and the tool axis leaves the great
//! circle: the nonlinear error of [`crate::nonlinear`], `δ = L·max_u |P(u)·n|` in mm at the tool
//! tip, `L` the distance of the tip from the axis it swings about.
//!
//! For one machine (its kind, rotary-axis type, senses and travel) the path is followed by
//! inverse kinematics with continuity ([`follow`]): the first point takes the smallest tilt
//! ([`BranchRule::SmallestTilt`], each angle at the turn nearest 0), every later point the solution within the travel nearest the
//! previous commands ([`BranchRule::Nearest`]), whole turns added or removed as the travel needs
//! (unwinding). A point no solution within the travel reaches stops the following: the machine
//! cannot run the path as given, and says which point and what it would need.
//!
//! # What is flagged
//! * **Pole**: the great-circle arc of a segment passes within [`POLE_ANGLE_DEG`] of the K axis
//!   (`±e_K`, the singular orientation where K is undefined): there K must turn at least
//!   `1/sin 1° ≈ 57` times as fast as the tool axis.
//! * **Flip**: the rotary axes swing much more than the tool axis turns: K or M moves by more
//!   than [`FLIP_ANGLE_DEG`] in one segment, and `|ΔK| + |ΔM|` exceeds [`FLIP_RATIO`] times the
//!   angle between the segment's two tool axes. That is what passing next to the pole does (K
//!   turns by up to 180° while the tool axis turns by a degree), and what unwinding at the end of
//!   the travel does (a whole turn). On a short segment K turns by about `1/sin(tilt)` times the
//!   tool's turn, so short segments at tilts above about 6° are not flagged.
//!
//! # Ranking
//! [`compare`] follows the path on each of the twelve types of [`RotaryType::ALL`] (the given
//! machine with its type replaced: same kind, geometry, senses and travel) and ranks them:
//! types that can follow the whole path first, by their largest δ; then the others, the farthest
//! along the path first.
//!
//! # Fixing the path
//! [`refine`] inserts points into each segment whose δ exceeds the tolerance: `n − 1` points at
//! equal steps of the intended motion (tip on the straight line, axis on the great circle,
//! `u = i/n`), `n` such that every piece, interpolated by the control as before, stays within the
//! tolerance and `n − 1` pieces would not: `n` doubles from 2 until the pieces are within, then
//! is bisected (a piece's δ falls about as `1/n²`, so that is the smallest `n` in practice, found
//! in `O(log n)` trials). The inserted axes lie on the segment's great circle, so each piece is
//! measured against the same plane as the whole segment. Segments within the tolerance get no
//! point.

use crate::error::{check_positive, Error, Result};
use crate::geometry::angle_between;
use crate::machine::{BranchRule, Machine, Model};
use crate::nonlinear::{swing_length, Deviation, Move, MAX_LENGTH_MM};
use crate::rotary::{Group, Pose, RotaryType};
use crate::schema::{self, DefaultValue, Kind, Quantity};
use nalgebra::Vector3;
use serde::Serialize;
use serde_json::Value;

pub mod parse;

crate::choices! {
    /// The format of a toolpath file ([`parse`]).
    pub enum FileFormat {
        /// Recognised from the first lines ([`parse::Format::detect`]).
        Auto = "auto" {
            label: "Recognise it",
            help: "From its first lines: GOTO/ statements are APT, letter words (X… A… C…) NC blocks, numbers CSV.",
        },
        /// `x,y,z,i,j,k` per line.
        Csv = "csv" {
            label: "CSV: x, y, z, i, j, k",
            help: "One point per line: the tool tip (mm) and the tool axis, workpiece coordinates.",
        },
        /// APT CL data.
        Apt = "apt" {
            label: "APT CL data (GOTO/x,y,z,i,j,k)",
            help: "CL data from the CAM system, with MULTAX.",
        },
        /// NC blocks for this machine.
        Nc = "nc" {
            label: "NC blocks for this machine (X Y Z and its two rotary axes)",
            help: "With tool-centre-point control on: X Y Z the tool tip, the rotary words the machine's commands.",
        },
    }
}

impl FileFormat {
    /// The parser's format, `None` for [`FileFormat::Auto`].
    pub fn format(self) -> Option<parse::Format> {
        match self {
            FileFormat::Auto => None,
            FileFormat::Csv => Some(parse::Format::Csv),
            FileFormat::Apt => Some(parse::Format::Apt),
            FileFormat::Nc => Some(parse::Format::Nc),
        }
    }
}

crate::inputs! {
    /// How to read a toolpath file.
    pub struct ToolpathReadInput {
        /// The machine (NC blocks are its commands).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// The file's format.
        pub format: FileFormat = "format" optional {
            label: "File format",
            help: "How the toolpath file is written; NC blocks are read for the machine above.",
            kind: Kind::Choice(FileFormat::CHOICES),
            default: DefaultValue::Str("auto"),
            group: "Toolpath",
        },
    }
}

impl ToolpathReadInput {
    /// Reads the options (unknown keys refused) and checks the machine.
    pub fn read(value: &Value) -> Result<Self> {
        let c = <Self as schema::Inputs>::from_value(value, "")?;
        c.machine.validate("machine")?;
        Ok(c)
    }
}

crate::inputs! {
    /// What every toolpath export needs besides the points: the machine, `L` and the tolerance.
    pub struct ToolpathCase {
        /// The machine (its kind, type, senses and travel; its type is replaced in a ranking).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// `L`, mm; the machine's when left out.
        pub length: Option<f64> = "length" optional {
            label: "Tool length / pivot distance L",
            help: "Distance of the tool tip from the axis it swings about. Left empty: the machine's pivot length plus tool length (head), or its table surface's distance from the rotary centre (table-table).",
            kind: schema::positive(Quantity::Length, MAX_LENGTH_MM),
            group: "Toolpath",
        },
        /// Largest acceptable nonlinear error, mm.
        pub tolerance: f64 = "tolerance" optional {
            label: "Tolerance on the tool tip",
            help: "The largest deviation of the tool tip from the programmed motion you accept between two points of the path; 10 µm for finishing is typical.",
            kind: schema::positive(Quantity::SmallLength, 10.0),
            default: DefaultValue::Num(0.01),
            group: "Toolpath",
        },
    }
}

impl ToolpathCase {
    /// Reads a case (unknown keys refused, ranges checked) and checks the machine.
    pub fn read(value: &Value) -> Result<Self> {
        let c = <Self as schema::Inputs>::from_value(value, "")?;
        c.machine.validate("machine")?;
        Ok(c)
    }

    /// `L`: given, or the machine's.
    pub fn length(&self) -> Result<f64> {
        swing_length(self.length, &self.machine)
    }

    /// The path on the machine ([`analyse`]).
    pub fn analyse(&self, axes: &[Vector3<f64>]) -> Result<Analysis> {
        let model = self.machine.without_errors().build()?;
        analyse(&model, axes, self.length()?, self.tolerance)
    }

    /// The path on `types` ([`compare_types`]), ranked.
    pub fn compare(&self, axes: &[Vector3<f64>], types: &[RotaryType]) -> Result<Vec<Summary>> {
        compare_types(&self.machine, axes, self.length()?, self.tolerance, types)
    }

    /// The path refined on the machine ([`refine`]).
    pub fn refine(&self, tips: &[Vector3<f64>], axes: &[Vector3<f64>]) -> Result<Refined> {
        let model = self.machine.without_errors().build()?;
        refine(&model, tips, axes, self.length()?, self.tolerance)
    }
}

/// A segment whose arc passes within this angle (degrees) of the K axis is flagged as a pole.
pub const POLE_ANGLE_DEG: f64 = 1.0;
/// Smallest rotary move (degrees, K or M) of a segment flagged as a flip.
pub const FLIP_ANGLE_DEG: f64 = 30.0;
/// A flip moves the rotary axes by more than this many times the tool axis's turn.
pub const FLIP_RATIO: f64 = 10.0;
/// Most pieces one segment may be cut into by [`refine`].
pub const MAX_PIECES: usize = 10_000;

/// Where the machine follows the path: commands of K and M (rad) at each point reached.
#[derive(Debug, Clone, PartialEq)]
pub struct Following {
    /// K commands, rad, one per point reached.
    pub k: Vec<f64>,
    /// M commands, rad.
    pub m: Vec<f64>,
    /// The first point no solution within the travel reaches, and why; `None` when every point
    /// is reached.
    pub unreachable: Option<(usize, String)>,
}

/// One segment (from point `i` to `i + 1`) on one machine.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Segment {
    /// Nonlinear error, mm at the tool tip.
    pub delta: f64,
    /// Where along the segment (`u ∈ [0, 1]`) it is largest.
    pub u: f64,
    /// The segment is a flip (module docs).
    pub flip: bool,
    /// The segment passes by the pole (module docs).
    pub pole: bool,
}

/// The path on one machine: the commands and each segment.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// The commands.
    pub following: Following,
    /// One per segment between points reached.
    pub segments: Vec<Segment>,
    /// Totals.
    pub summary: Summary,
}

/// Totals of one machine on the path (a row of the ranking).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Summary {
    /// The rotary-axis type.
    #[serde(rename = "type")]
    pub rtype: RotaryType,
    /// Its group.
    pub group: Group,
    /// Segments analysed (between points reached).
    pub segments: usize,
    /// Largest δ, mm.
    pub max: f64,
    /// Index of the segment with the largest δ (the first of equals).
    pub max_segment: usize,
    /// Mean δ, mm.
    pub mean: f64,
    /// 95th percentile of δ, mm (nearest rank).
    pub p95: f64,
    /// Segments with δ above the tolerance.
    pub above: usize,
    /// Flips.
    pub flips: usize,
    /// Segments passing by the pole.
    pub poles: usize,
    /// Total travel of K, rad (sum of |ΔK|).
    pub k_travel: f64,
    /// Total travel of M, rad.
    pub m_travel: f64,
    /// The first point that cannot be reached and why, when one cannot.
    pub unreachable: Option<Unreachable>,
}

/// A point outside the travel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unreachable {
    /// Index of the point.
    pub point: usize,
    /// What it would need.
    pub message: String,
}

/// The given machine with rotary-axis type `t` and no errors (the control's model).
pub fn machine_of_type(machine: &Machine, t: RotaryType) -> Machine {
    Machine {
        rotary_type: t,
        ..machine.without_errors()
    }
}

/// Follows the tool axes `axes` (workpiece coordinates, any non-zero length) on `model` with
/// continuity (module docs).
pub fn follow(model: &Model, axes: &[Vector3<f64>]) -> Result<Following> {
    let mut k = Vec::with_capacity(axes.len());
    let mut m = Vec::with_capacity(axes.len());
    let mut previous: Option<[f64; 2]> = None;
    for (i, a) in axes.iter().enumerate() {
        // The first point: the smallest tilt, each angle at the turn nearest 0 (room both ways).
        let (rule, near) = match previous {
            Some(p) => (BranchRule::Nearest, p),
            None => (BranchRule::SmallestTilt, [0.0, 0.0]),
        };
        let o = model
            .orientations(a, rule, Some(near))
            .map_err(|e| Error::field(format!("points[{i}]"), e.message))?;
        match o.chosen {
            Some(c) => {
                let s = o.solutions[c];
                k.push(s.k);
                m.push(s.m);
                previous = Some([s.k, s.m]);
            }
            None => {
                return Ok(Following {
                    k,
                    m,
                    unreachable: Some((i, o.unreachable.unwrap_or_default())),
                })
            }
        }
    }
    Ok(Following {
        k,
        m,
        unreachable: None,
    })
}

/// The segment from commands `(k0, m0)` to `(k1, m1)` (rad) on `model`, with tool axes `a0`,
/// `a1` (unit) and `L = length` mm.
fn segment(
    model: &Model,
    length: f64,
    (k0, m0): (f64, f64),
    (k1, m1): (f64, f64),
    a0: &Vector3<f64>,
    a1: &Vector3<f64>,
) -> Segment {
    let lay = model.layout;
    let pose = |k: f64, m: f64| Pose::new(lay.k_factor * k, lay.m_factor * m);
    let peak = Deviation::new(Move::new(lay.rtype, pose(k0, m0), pose(k1, m1))).peak();
    let (dk, dm) = ((k1 - k0).abs(), (m1 - m0).abs());
    let flip =
        dk.max(dm) > FLIP_ANGLE_DEG.to_radians() && dk + dm > FLIP_RATIO * angle_between(a0, a1);
    let e_k = lay.rtype.k.axis().unit();
    let zone = POLE_ANGLE_DEG.to_radians();
    // Every point of the arc is within `turn ≤ π/2·|a1 − a0|` of a0 (a chord is at least 2/π
    // of its arc), so an a0 whose angle φ from ±K has sin φ = |a0 × e_K| > zone + that bound
    // (sin φ ≤ φ) rules the pole out without measuring the arc.
    let turn_bound = std::f64::consts::FRAC_PI_2 * (a1 - a0).norm();
    let far = a0.cross(&e_k).norm() > zone + turn_bound;
    let pole = !far && arc_distance(a0, a1, &e_k).min(arc_distance(a0, a1, &-e_k)) < zone;
    Segment {
        delta: length * peak.value,
        u: peak.u,
        flip,
        pole,
    }
}

/// Angle (rad) from the unit vector `p` to the shorter great-circle arc from `a0` to `a1` (unit).
pub fn arc_distance(a0: &Vector3<f64>, a1: &Vector3<f64>, p: &Vector3<f64>) -> f64 {
    let ends = angle_between(p, a0).min(angle_between(p, a1));
    let cross = a0.cross(a1);
    let s = cross.norm();
    if s < 1e-12 {
        return ends;
    }
    let n = cross / s;
    let q = p - n * n.dot(p);
    if q.norm() < 1e-12 {
        return ends;
    }
    // q lies on the arc when it is on a0's far side towards a1 and a1's far side towards a0.
    let on_arc = a0.cross(&q).dot(&n) >= 0.0 && q.cross(a1).dot(&n) >= 0.0;
    if on_arc {
        n.dot(p).abs().atan2(q.norm())
    } else {
        ends
    }
}

/// The path (tool axes, unit) on `model` with `L = length` mm and tolerance `tolerance` mm.
pub fn analyse(
    model: &Model,
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
) -> Result<Analysis> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_positive("tolerance", tolerance, MAX_LENGTH_MM, "mm")?;
    if axes.len() < 2 {
        return Err(Error::field(
            "points",
            format!("a toolpath needs at least 2 points, got {}", axes.len()),
        ));
    }
    let unit;
    let axes = if axes.iter().all(|a| (a.norm() - 1.0).abs() < 1e-12) {
        axes
    } else {
        unit = axes.iter().map(|a| a.normalize()).collect::<Vec<_>>();
        &unit
    };
    let following = follow(model, axes)?;
    let reached = following.k.len();
    let segments: Vec<Segment> = (1..reached)
        .map(|i| {
            segment(
                model,
                length,
                (following.k[i - 1], following.m[i - 1]),
                (following.k[i], following.m[i]),
                &axes[i - 1],
                &axes[i],
            )
        })
        .collect();
    let summary = summarise(model.layout.rtype, &following, &segments, tolerance);
    Ok(Analysis {
        following,
        segments,
        summary,
    })
}

fn summarise(
    rtype: RotaryType,
    following: &Following,
    segments: &[Segment],
    tolerance: f64,
) -> Summary {
    let n = segments.len();
    let (mut max, mut max_segment, mut sum) = (0.0_f64, 0, 0.0);
    for (i, s) in segments.iter().enumerate() {
        if s.delta > max {
            max = s.delta;
            max_segment = i;
        }
        sum += s.delta;
    }
    let p95 = if n == 0 {
        0.0
    } else {
        let mut d: Vec<f64> = segments.iter().map(|s| s.delta).collect();
        // Nearest rank: the smallest value with at least 95 % of the values at or below it.
        let rank = ((0.95 * n as f64).ceil() as usize).clamp(1, n) - 1;
        *d.select_nth_unstable_by(rank, f64::total_cmp).1
    };
    let travel = |v: &[f64]| v.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    Summary {
        rtype,
        group: rtype.group(),
        segments: n,
        max,
        max_segment,
        mean: if n == 0 { 0.0 } else { sum / n as f64 },
        p95,
        above: segments.iter().filter(|s| s.delta > tolerance).count(),
        flips: segments.iter().filter(|s| s.flip).count(),
        poles: segments.iter().filter(|s| s.pole).count(),
        k_travel: travel(&following.k),
        m_travel: travel(&following.m),
        unreachable: following
            .unreachable
            .as_ref()
            .map(|(point, message)| Unreachable {
                point: *point,
                message: message.clone(),
            }),
    }
}

/// The path on each of the twelve types (the machine's kind, geometry, senses and travel),
/// ranked (module docs).
pub fn compare(
    machine: &Machine,
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
) -> Result<Vec<Summary>> {
    compare_types(machine, axes, length, tolerance, &RotaryType::ALL)
}

/// [`compare`] on the given types only (the page shares the twelve among its workers).
pub fn compare_types(
    machine: &Machine,
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
    types: &[RotaryType],
) -> Result<Vec<Summary>> {
    let mut rows = types
        .iter()
        .map(|&t| {
            let model = machine_of_type(machine, t).build()?;
            Ok(analyse(&model, axes, length, tolerance)?.summary)
        })
        .collect::<Result<Vec<Summary>>>()?;
    rank(&mut rows);
    Ok(rows)
}

/// Sorts rows: those that follow the whole path first, by largest δ, then by mean δ; then those
/// that cannot, the farthest along the path first.
pub fn rank(rows: &mut [Summary]) {
    rows.sort_by(|a, b| {
        let stop = |s: &Summary| s.unreachable.as_ref().map(|u| u.point);
        match (stop(a), stop(b)) {
            (None, None) => a.max.total_cmp(&b.max).then(a.mean.total_cmp(&b.mean)),
            (None, Some(_)) => std::cmp::Ordering::Less,
            (Some(_), None) => std::cmp::Ordering::Greater,
            (Some(x), Some(y)) => y.cmp(&x),
        }
    });
}

/// A path refined by [`refine`].
#[derive(Debug, Clone, PartialEq)]
pub struct Refined {
    /// Tool tips, mm.
    pub tips: Vec<Vector3<f64>>,
    /// Unit tool axes.
    pub axes: Vec<Vector3<f64>>,
    /// K and M commands, rad.
    pub k: Vec<f64>,
    /// M commands, rad.
    pub m: Vec<f64>,
    /// For each point, the index of the original point it is, or `None` for an inserted one.
    pub source: Vec<Option<usize>>,
    /// Points inserted.
    pub added: usize,
    /// Largest δ of the refined path, mm.
    pub max: f64,
    /// Segments (by the index of their first point) that no number of pieces keeps within the
    /// tolerance, left as they were: the rotary axes swing round in them whatever the steps
    /// (unwinding at the end of the travel).
    pub unfixed: Vec<usize>,
}

/// Inserts equally spaced points into each segment above `tolerance` (mm) so that every piece
/// stays within it, one piece fewer would not (module docs), and segments within it get none;
/// a segment that [`MAX_PIECES`] pieces do not fix is left as it is and listed in
/// [`Refined::unfixed`]. The machine must reach the whole path.
pub fn refine(
    model: &Model,
    tips: &[Vector3<f64>],
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
) -> Result<Refined> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_positive("tolerance", tolerance, MAX_LENGTH_MM, "mm")?;
    if tips.len() != axes.len() || axes.len() < 2 {
        return Err(Error::field(
            "points",
            "at least 2 points, each with a tool tip and a tool axis, are needed",
        ));
    }
    let unit: Vec<Vector3<f64>> = axes.iter().map(|v| v.normalize()).collect();
    let first = follow(model, &unit[..1])?;
    if let Some((i, why)) = first.unreachable {
        return Err(Error::field(format!("points[{i}]"), why));
    }
    let mut out = Refined {
        tips: vec![tips[0]],
        axes: vec![unit[0]],
        k: vec![first.k[0]],
        m: vec![first.m[0]],
        source: vec![Some(0)],
        added: 0,
        max: 0.0,
        unfixed: Vec::new(),
    };
    for i in 0..unit.len() - 1 {
        let last = out.k.len() - 1;
        let prev = (out.k[last], out.m[last]);
        let at = |e: Error| Error::field(format!("points[{}]", i + 1), e.message);
        let o = model
            .orientations(&unit[i + 1], BranchRule::Nearest, Some([prev.0, prev.1]))
            .map_err(at)?;
        let c = o.pick(&format!("points[{}]", i + 1))?;
        // The segment as it is now (its start may be an inserted point's commands).
        let s = segment(model, length, prev, (c.k, c.m), &unit[i], &unit[i + 1]);
        let mut end = (c.k, c.m);
        if s.delta <= tolerance {
            out.max = out.max.max(s.delta);
        } else {
            match split(model, length, tolerance, &out, (tips[i + 1], unit[i + 1])).map_err(at)? {
                Some(pieces) => {
                    out.max = out.max.max(pieces.max);
                    let n = pieces.k.len();
                    for p in 0..n - 1 {
                        out.tips.push(pieces.tips[p]);
                        out.axes.push(pieces.axes[p]);
                        out.k.push(pieces.k[p]);
                        out.m.push(pieces.m[p]);
                        out.source.push(None);
                        out.added += 1;
                    }
                    end = (pieces.k[n - 1], pieces.m[n - 1]);
                }
                None => {
                    // No number of pieces helps (a flip at the end of the travel): left as it is.
                    out.max = out.max.max(s.delta);
                    out.unfixed.push(i);
                }
            }
        }
        out.tips.push(tips[i + 1]);
        out.axes.push(unit[i + 1]);
        out.k.push(end.0);
        out.m.push(end.1);
        out.source.push(Some(i + 1));
    }
    Ok(out)
}

/// The points after the last of `done` that cut the segment to `(tip, axis)` into equal pieces
/// within the tolerance: tips, axes and commands of the inner points and the end (the end last).
/// `n` pieces are tried doubling from 2, then bisected, so that `n` pieces are within the
/// tolerance and `n − 1` are not (when `n > 2`). `Ok(None)` beyond [`MAX_PIECES`]; an error when
/// an inner point is outside the travel.
fn split(
    model: &Model,
    length: f64,
    tolerance: f64,
    done: &Refined,
    (tip1, a1): (Vector3<f64>, Vector3<f64>),
) -> Result<Option<Pieces>> {
    let last = done.k.len() - 1;
    let (tip0, a0, start) = (
        done.tips[last],
        done.axes[last],
        (done.k[last], done.m[last]),
    );
    // `n` equal pieces, or `None` when one exceeds the tolerance.
    let pieces = |n: usize| -> Result<Option<Pieces>> {
        let mut p = Pieces::default();
        let mut prev = start;
        let mut prev_axis = a0;
        for i in 1..=n {
            let u = i as f64 / n as f64;
            let axis = slerp(&a0, &a1, u);
            let o = model.orientations(&axis, BranchRule::Nearest, Some([prev.0, prev.1]))?;
            let c = o.pick("points")?;
            let s = segment(model, length, prev, (c.k, c.m), &prev_axis, &axis);
            if s.delta > tolerance {
                return Ok(None);
            }
            p.max = p.max.max(s.delta);
            p.tips.push(tip0 + (tip1 - tip0) * u);
            p.axes.push(axis);
            p.k.push(c.k);
            p.m.push(c.m);
            prev = (c.k, c.m);
            prev_axis = axis;
        }
        Ok(Some(p))
    };
    // Doubling: `fails` pieces exceed the tolerance (1: the segment itself), `works` do not.
    let mut fails = 1;
    let mut works = 2;
    let mut found = loop {
        if let Some(p) = pieces(works)? {
            break p;
        }
        if works >= MAX_PIECES {
            return Ok(None);
        }
        fails = works;
        works = (2 * works).min(MAX_PIECES);
    };
    // Bisection between them.
    while works - fails > 1 {
        let mid = fails + (works - fails) / 2;
        match pieces(mid)? {
            Some(p) => {
                works = mid;
                found = p;
            }
            None => fails = mid,
        }
    }
    Ok(Some(found))
}

#[derive(Default)]
struct Pieces {
    tips: Vec<Vector3<f64>>,
    axes: Vec<Vector3<f64>>,
    k: Vec<f64>,
    m: Vec<f64>,
    max: f64,
}

/// The unit vector at fraction `u` of the shorter great-circle arc from `a` to `b` (unit); for
/// opposite vectors the arc is not unique and the straight interpolation is normalised.
pub fn slerp(a: &Vector3<f64>, b: &Vector3<f64>, u: f64) -> Vector3<f64> {
    let theta = angle_between(a, b);
    let s = theta.sin();
    if s < 1e-12 {
        return (a * (1.0 - u) + b * u).try_normalize(0.0).unwrap_or(*a);
    }
    (a * ((1.0 - u) * theta).sin() + b * (u * theta).sin()) / s
}
