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
//! # Rapids and the program's own commands
//! Each point carries how it was reached ([`read::Motion`]). The statistics, the ranking and
//! every verdict are on the **cutting** segments (feed and arc moves); rapid positioning moves
//! (`G0`, APT `RAPID`, Heidenhain `FMAX`) do not touch the part and are summarised apart
//! ([`Rapids`]: their count, their largest rotary swing and the largest excursion of the tool
//! tip from the straight line, a positioning and collision note). NC blocks carry the program's
//! commanded angles ([`Commands`]): on the type they were written for, the machine follows those
//! commands, its branch and its turns, instead of the inverse kinematics; they must lie within
//! the travel (a rotary table marked continuous has none). The other types follow the tool axes
//! by their own continuity.
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
/// Following tool axes lives with the machine (the nonlinear study uses it too).
pub use crate::machine::follow::{follow, machine_of_type, Following};
use crate::machine::{BranchRule, Machine, Model};
use crate::nonlinear::{swing_length, Deviation, Move, MAX_LENGTH_MM};
use crate::rotary::{Group, Pose, RotaryType};
use crate::schema::{self, DefaultValue, Kind, Quantity};
use nalgebra::Vector3;
use read::Motion;
use serde::Serialize;
use serde_json::Value;

pub mod export;
pub mod read;
pub mod write;

crate::choices! {
    /// The format of a toolpath file ([`read`]).
    pub enum FileFormat {
        /// Recognised from the first lines ([`read::Format::detect`]).
        Auto = "auto" {
            label: "Recognise it",
            help: "From its first lines: GOTO/ statements are APT, BEGIN PGM and L blocks Heidenhain, TRAORI, R1= or X= Siemens, letter words (G1 X… A…) ISO G-code, numbers CSV.",
        },
        /// `x,y,z,i,j,k` per line.
        Csv = "csv" {
            label: "CSV: x, y, z, i, j, k",
            help: "One point per line: the tool tip and the tool axis, workpiece coordinates.",
        },
        /// APT CL data.
        Apt = "apt" {
            label: "APT CL data (NX CLSF, CATIA, SolidWorks CAM, Mastercam …)",
            help: "CL data from the CAM system: GOTO/, RAPID, CIRCLE/, MSYS/, CSYS/, UNITS/.",
        },
        /// ISO G-code for this machine.
        Nc = "nc" {
            label: "ISO G-code for this machine (Fanuc, Haas, LinuxCNC)",
            help: "NC blocks with X Y Z the tool tip and the machine's two rotary words; G43.4, G234 or G254 for tool-centre-point control.",
        },
        /// Siemens Sinumerik 840D blocks for this machine.
        Siemens = "siemens" {
            label: "Siemens Sinumerik 840D for this machine",
            help: "NC blocks with TRAORI, R parameters, TRANS/ROT frames.",
        },
        /// Heidenhain conversational for this machine.
        Heidenhain = "heidenhain" {
            label: "Heidenhain conversational for this machine",
            help: "BEGIN PGM … L X+… FMAX, CC/C arcs, M128 or FUNCTION TCPM, PLANE SPATIAL.",
        },
    }
}

impl FileFormat {
    /// The reader's format, `None` for [`FileFormat::Auto`].
    pub fn format(self) -> Option<read::Format> {
        match self {
            FileFormat::Auto => None,
            FileFormat::Csv => Some(read::Format::Csv),
            FileFormat::Apt => Some(read::Format::Apt),
            FileFormat::Nc => Some(read::Format::Nc),
            FileFormat::Siemens => Some(read::Format::Siemens),
            FileFormat::Heidenhain => Some(read::Format::Heidenhain),
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
            group: "Reading the file",
        },
        /// The unit where the file states none.
        pub unit: read::UnitChoice = "unit" optional {
            label: "Length unit of the file",
            help: "A unit the file states (G20/G21, G70/G71, UNITS/, BEGIN PGM … INCH) is always used; this decides where it states none.",
            kind: Kind::Choice(read::UnitChoice::CHOICES),
            default: DefaultValue::Str("auto"),
            group: "Reading the file",
        },
        /// How an APT output frame (MSYS/, CSYS/) is read.
        pub apt_frame: read::AptFrameChoice = "aptFrame" optional {
            label: "APT output frame (MSYS/, CSYS/)",
            help: "Whether the GOTO/ points after an MSYS/ or CSYS/ are written in that frame (NX's reading: turned into the frame it is given in) or already in the machine's frame.",
            kind: Kind::Choice(read::AptFrameChoice::CHOICES),
            default: DefaultValue::Str("apply"),
            group: "Reading the file",
        },
        /// Largest distance of an arc from its chords, mm.
        pub chord_tolerance: f64 = "chordTolerance" optional {
            label: "Chord tolerance of arcs",
            help: "Arcs (G2/G3, CIRCLE/, C/CR/CP) are cut into straight chords that stay this close to the arc, as the control moves along it.",
            kind: schema::positive(Quantity::SmallLength, 1.0),
            default: DefaultValue::Num(read::DEFAULT_CHORD_TOLERANCE),
            group: "Reading the file",
        },
    }
}

impl crate::edge::Checked for ToolpathReadInput {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")
    }
}

impl crate::edge::Checked for ToolpathCase {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")
    }
}

impl ToolpathReadInput {
    /// Reads the options (unknown keys refused) and checks the machine.
    pub fn read(value: &Value) -> Result<Self> {
        <Self as crate::edge::ApiInput>::read(value)
    }

    /// The reader's options.
    pub fn options(&self) -> read::ReadOptions {
        read::ReadOptions {
            unit: self.unit,
            chord_tolerance: self.chord_tolerance,
            apt_frame: self.apt_frame,
        }
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
        <Self as crate::edge::ApiInput>::read(value)
    }

    /// `L`: given, or the machine's.
    pub fn length(&self) -> Result<f64> {
        swing_length(self.length, &self.machine)
    }

    /// The path on the machine ([`analyse_path`]).
    pub fn analyse(&self, path: &Path) -> Result<Analysis> {
        let model = self.machine.without_errors().build()?;
        analyse_path(&model, path, self.length()?, self.tolerance)
    }

    /// The path on `types` ([`compare_path`]), ranked.
    pub fn compare(&self, path: &Path, types: &[RotaryType]) -> Result<Vec<ToolpathSummary>> {
        compare_path(&self.machine, path, self.length()?, self.tolerance, types)
    }

    /// The path refined on the machine ([`refine_path`]).
    pub fn refine(&self, tips: &[Vector3<f64>], path: &Path) -> Result<Refined> {
        let model = self.machine.without_errors().build()?;
        refine_path(&model, tips, path, self.length()?, self.tolerance)
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
    /// The segment is a rapid positioning move (not cutting).
    pub rapid: bool,
}

/// The path on one machine: the commands and each segment.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// The commands.
    pub following: Following,
    /// One per segment between points reached.
    pub segments: Vec<Segment>,
    /// Totals.
    pub summary: ToolpathSummary,
}

/// One rapid move of a path on one machine: a positioning and collision note.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct RapidMove {
    /// The segment (from point `segment` to `segment + 1`).
    pub segment: usize,
    /// The turn of K (signed), degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k_turn: f64,
    /// The turn of M (signed), degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m_turn: f64,
    /// The tool tip's largest excursion from the straight line (the segment's δ), mm.
    pub excursion: f64,
}

impl Analysis {
    /// The rapid moves, in the order of the path.
    pub fn rapid_moves(&self) -> Vec<RapidMove> {
        let f = &self.following;
        self.segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.rapid)
            .map(|(i, s)| RapidMove {
                segment: i,
                k_turn: f.k[i + 1] - f.k[i],
                m_turn: f.m[i + 1] - f.m[i],
                excursion: s.delta,
            })
            .collect()
    }
}

/// Totals of one machine on the path (a row of the ranking), on its cutting segments; the
/// rapids apart.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ToolpathSummary {
    /// The rotary-axis type.
    #[serde(rename = "type")]
    pub rtype: RotaryType,
    /// Its group.
    pub group: Group,
    /// Cutting segments analysed (between points reached).
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
    /// Total travel of K along the cutting segments (sum of |ΔK|; rapids not counted),
    /// degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k_travel: f64,
    /// Total travel of M along the cutting segments, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m_travel: f64,
    /// The first point that cannot be reached and why, when one cannot.
    pub unreachable: Option<Unreachable>,
    /// The rapid moves, apart from the cutting ones.
    pub rapids: Rapids,
    /// The row follows the program's own commands (the machine it was written for).
    pub commanded: bool,
    /// The row's place by the ranking rule ([`rank`]), numbers compared in turn, smaller first:
    /// 0 when the machine follows the whole path, else 1; minus the first point out of reach
    /// (0 when none is); the largest δ and the mean δ of a machine that follows the whole path
    /// (0 for one that does not); the type's place in [`RotaryType::ALL`]. Rows computed apart
    /// (the page's workers) are ranked by sorting on it.
    pub rank: [f64; 5],
}

impl ToolpathSummary {
    /// The ranking rule's key of this row ([`ToolpathSummary::rank`]).
    fn rank_key(&self) -> [f64; 5] {
        let place = RotaryType::ALL
            .iter()
            .position(|t| *t == self.rtype)
            .unwrap_or(RotaryType::ALL.len()) as f64;
        match &self.unreachable {
            None => [0.0, 0.0, self.max, self.mean, place],
            Some(u) => [1.0, -(u.point as f64), 0.0, 0.0, place],
        }
    }
}

/// The rapid positioning moves of a path on one machine (module docs): not cutting, so not in
/// the statistics; a positioning and collision note.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Rapids {
    /// Rapid segments.
    pub count: usize,
    /// Rapids that turn a rotary axis.
    pub swings: usize,
    /// Largest excursion of the tool tip from the straight line in a rapid (its δ), mm.
    pub max: f64,
    /// Index of that segment (0 when there is no rapid).
    pub max_segment: usize,
    /// Largest turn of K in one rapid, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k_swing: f64,
    /// Largest turn of M in one rapid, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m_swing: f64,
}

/// A point outside the travel.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct Unreachable {
    /// Index of the point.
    pub point: usize,
    /// What it would need (angles in degrees) and the travel.
    pub message: String,
}

/// A path to analyse: the tool axes, how each point was reached and, for NC blocks, the
/// program's own commands.
#[derive(Debug, Clone, Copy)]
pub struct Path<'a> {
    /// Tool axes, workpiece coordinates, any non-zero length.
    pub axes: &'a [Vector3<f64>],
    /// How each point was reached; `None`: every point by a feed move.
    pub motions: Option<&'a [Motion]>,
    /// The program's commands, for the machine they were written for.
    pub commands: Option<Commands<'a>>,
}

impl<'a> Path<'a> {
    /// Tool axes alone: every point a feed move, no commands.
    pub fn axes(axes: &'a [Vector3<f64>]) -> Self {
        Path {
            axes,
            motions: None,
            commands: None,
        }
    }

    /// Checks the motions and commands against the axes: one per point, commands finite.
    pub fn check(&self) -> Result<()> {
        let n = self.axes.len();
        if let Some(m) = self.motions {
            if m.len() != n {
                return Err(Error::field(
                    "motions",
                    format!("expected one motion per point ({n}), got {}", m.len()),
                ));
            }
        }
        if let Some(c) = self.commands {
            if c.angles.len() != n {
                return Err(Error::field(
                    "angles",
                    format!("expected [K, M] per point ({n}), got {}", c.angles.len()),
                ));
            }
            if let Some(i) = c
                .angles
                .iter()
                .position(|a| !a.iter().all(|x| x.is_finite()))
            {
                return Err(Error::field(format!("angles[{i}]"), "must be finite"));
            }
        }
        Ok(())
    }

    /// The motion that reaches point `i`.
    pub fn motion(&self, i: usize) -> Motion {
        self.motions.map_or(Motion::Feed, |m| m[i])
    }

    /// The program's commands when they were written for `rtype`.
    fn commands_for(&self, rtype: RotaryType) -> Option<&'a [[f64; 2]]> {
        self.commands.filter(|c| c.rtype == rtype).map(|c| c.angles)
    }
}

/// The K and M angles an NC program commands at each point (degrees), and the rotary-axis type
/// of the machine it was read for: they are that machine's commands only.
#[derive(Debug, Clone, Copy)]
pub struct Commands<'a> {
    /// `[K, M]` per point, degrees.
    pub angles: &'a [[f64; 2]],
    /// The type they were written for.
    pub rtype: RotaryType,
}

/// The program's own commands (degrees) on `model`: followed as they are, up to the first one
/// outside the travel (a rotary table marked continuous has no limit).
pub fn follow_commands(model: &Model, angles: &[[f64; 2]]) -> Following {
    let [(k_lo, k_hi), (m_lo, m_hi)] = model.travel();
    let [kl, ml] = model.letters();
    let tol = crate::machine::TRAVEL_TOLERANCE;
    let inside = |x: f64, lo: f64, hi: f64| x >= lo - tol && x <= hi + tol;
    let mut k = Vec::with_capacity(angles.len());
    let mut m = Vec::with_capacity(angles.len());
    for (i, a) in angles.iter().enumerate() {
        let (kr, mr) = (a[0].to_radians(), a[1].to_radians());
        for (letter, x, lo, hi) in [(kl, kr, k_lo, k_hi), (ml, mr, m_lo, m_hi)] {
            if !inside(x, lo, hi) {
                return Following {
                    k,
                    m,
                    unreachable: Some((
                        i,
                        format!(
                            "commanded {letter} = {}°, outside the travel of {letter} ({}° to \
                             {}°); {}",
                            round4(x.to_degrees()),
                            round4(lo.to_degrees()),
                            round4(hi.to_degrees()),
                            if letter == kl {
                                "if the machine reaches it, widen the travel in the machine \
                                 (a table that turns without limit: tick its continuous box)"
                            } else {
                                "if the machine reaches it, widen the travel in the machine"
                            }
                        ),
                    )),
                };
            }
        }
        k.push(kr);
        m.push(mr);
    }
    Following {
        k,
        m,
        unreachable: None,
    }
}

/// `x` to 4 decimals.
fn round4(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
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
        rapid: false,
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

/// The path (tool axes, unit) on `model` with `L = length` mm and tolerance `tolerance` mm,
/// every point a feed move ([`analyse_path`]).
pub fn analyse(
    model: &Model,
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
) -> Result<Analysis> {
    analyse_path(model, &Path::axes(axes), length, tolerance)
}

/// The path on `model` with `L = length` mm and tolerance `tolerance` mm (module docs): the
/// program's commands where they were written for this type, else the inverse kinematics with
/// continuity; every segment; the totals of the cutting ones and the rapids apart.
pub fn analyse_path(model: &Model, path: &Path, length: f64, tolerance: f64) -> Result<Analysis> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_positive("tolerance", tolerance, MAX_LENGTH_MM, "mm")?;
    path.check()?;
    let axes = path.axes;
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
        unit = axes
            .iter()
            .enumerate()
            .map(|(i, a)| {
                a.try_normalize(0.0).ok_or_else(|| {
                    Error::field(format!("points[{i}]"), "the tool axis must not be zero")
                })
            })
            .collect::<Result<Vec<_>>>()?;
        &unit
    };
    let commands = path.commands_for(model.layout.rtype);
    let following = match commands {
        Some(c) => follow_commands(model, c),
        None => follow(model, axes)?,
    };
    let reached = following.k.len();
    let segments: Vec<Segment> = (1..reached)
        .map(|i| {
            let mut s = segment(
                model,
                length,
                (following.k[i - 1], following.m[i - 1]),
                (following.k[i], following.m[i]),
                &axes[i - 1],
                &axes[i],
            );
            s.rapid = !path.motion(i).cuts();
            s
        })
        .collect();
    let mut summary = summarise(model.layout.rtype, &following, &segments, tolerance);
    summary.commanded = commands.is_some();
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
) -> ToolpathSummary {
    let cutting = || segments.iter().enumerate().filter(|(_, s)| !s.rapid);
    let n = cutting().count();
    // The first of equals: strictly larger replaces.
    let mut best: Option<(usize, f64)> = None;
    let mut sum = 0.0;
    for (i, s) in cutting() {
        if best.map_or(true, |(_, m)| s.delta > m) {
            best = Some((i, s.delta));
        }
        sum += s.delta;
    }
    let (max_segment, max) = best.unwrap_or((0, 0.0));
    let p95 = if n == 0 {
        0.0
    } else {
        let mut d: Vec<f64> = cutting().map(|(_, s)| s.delta).collect();
        // Nearest rank: the smallest value with at least 95 % of the values at or below it.
        let rank = ((0.95 * n as f64).ceil() as usize).clamp(1, n) - 1;
        *d.select_nth_unstable_by(rank, f64::total_cmp).1
    };
    // Along the cutting segments (what the ranking compares; rapids are apart).
    let travel = |v: &[f64]| {
        cutting()
            .filter(|(i, _)| i + 1 < v.len())
            .map(|(i, _)| (v[i + 1] - v[i]).abs())
            .sum()
    };
    let mut rapids = Rapids::default();
    for (i, s) in segments.iter().enumerate().filter(|(_, s)| s.rapid) {
        let (dk, dm) = (
            (following.k[i + 1] - following.k[i]).abs(),
            (following.m[i + 1] - following.m[i]).abs(),
        );
        rapids.count += 1;
        rapids.swings += usize::from(dk > 1e-12 || dm > 1e-12);
        if s.delta > rapids.max || rapids.count == 1 {
            rapids.max = s.delta;
            rapids.max_segment = i;
        }
        rapids.k_swing = rapids.k_swing.max(dk);
        rapids.m_swing = rapids.m_swing.max(dm);
    }
    let mut summary = ToolpathSummary {
        rtype,
        group: rtype.group(),
        segments: n,
        max,
        max_segment,
        mean: if n == 0 { 0.0 } else { sum / n as f64 },
        p95,
        above: cutting().filter(|(_, s)| s.delta > tolerance).count(),
        flips: cutting().filter(|(_, s)| s.flip).count(),
        poles: cutting().filter(|(_, s)| s.pole).count(),
        k_travel: travel(&following.k),
        m_travel: travel(&following.m),
        unreachable: following
            .unreachable
            .as_ref()
            .map(|(point, message)| Unreachable {
                point: *point,
                message: message.clone(),
            }),
        rapids,
        commanded: false,
        rank: [0.0; 5],
    };
    summary.rank = summary.rank_key();
    summary
}

/// The path on each of the twelve types (the machine's kind, geometry, senses and travel),
/// ranked (module docs).
pub fn compare(
    machine: &Machine,
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
) -> Result<Vec<ToolpathSummary>> {
    compare_types(machine, axes, length, tolerance, &RotaryType::ALL)
}

/// [`compare`] on the given types only (the page shares the twelve among its workers).
pub fn compare_types(
    machine: &Machine,
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
    types: &[RotaryType],
) -> Result<Vec<ToolpathSummary>> {
    compare_path(machine, &Path::axes(axes), length, tolerance, types)
}

/// [`compare_types`] of a path with its motions and commands ([`analyse_path`] on each type).
pub fn compare_path(
    machine: &Machine,
    path: &Path,
    length: f64,
    tolerance: f64,
    types: &[RotaryType],
) -> Result<Vec<ToolpathSummary>> {
    let mut rows = types
        .iter()
        .map(|&t| {
            let model = machine_of_type(machine, t).build()?;
            Ok(analyse_path(&model, path, length, tolerance)?.summary)
        })
        .collect::<Result<Vec<ToolpathSummary>>>()?;
    rank(&mut rows);
    Ok(rows)
}

/// Sorts rows: those that follow the whole path first, by largest δ, then by mean δ; then those
/// that cannot, the farthest along the path first; ties in the order of [`RotaryType::ALL`].
/// The rule is each row's [`ToolpathSummary::rank`], compared number by number.
pub fn rank(rows: &mut [ToolpathSummary]) {
    rows.sort_by(|a, b| {
        a.rank
            .iter()
            .zip(&b.rank)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
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
    /// How each point is reached (an inserted point as its segment).
    pub motions: Vec<Motion>,
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
/// [`Refined::unfixed`]. The machine must reach the whole path. Every point a feed move
/// ([`refine_path`]).
pub fn refine(
    model: &Model,
    tips: &[Vector3<f64>],
    axes: &[Vector3<f64>],
    length: f64,
    tolerance: f64,
) -> Result<Refined> {
    refine_path(model, tips, &Path::axes(axes), length, tolerance)
}

/// [`refine`] of a path with its motions and commands: rapid segments get no point (they do
/// not cut) and count in no maximum; on the type the program was written for, its original
/// points keep the program's commands, and a segment whose commanded end is not the one the
/// inserted points lead to (a change of branch) is left as it is and listed as unfixed.
pub fn refine_path(
    model: &Model,
    tips: &[Vector3<f64>],
    path: &Path,
    length: f64,
    tolerance: f64,
) -> Result<Refined> {
    check_positive("length", length, MAX_LENGTH_MM, "mm")?;
    check_positive("tolerance", tolerance, MAX_LENGTH_MM, "mm")?;
    path.check()?;
    let axes = path.axes;
    if tips.len() != axes.len() || axes.len() < 2 {
        return Err(Error::field(
            "points",
            "at least 2 points, each with a tool tip and a tool axis, are needed",
        ));
    }
    let unit: Vec<Vector3<f64>> = axes.iter().map(|v| v.normalize()).collect();
    let commanded = match path.commands_for(model.layout.rtype) {
        Some(c) => {
            let f = follow_commands(model, c);
            if let Some((i, why)) = f.unreachable {
                return Err(Error::field(format!("points[{i}]"), why));
            }
            Some(f)
        }
        None => None,
    };
    let start = match &commanded {
        Some(f) => (f.k[0], f.m[0]),
        None => {
            let first = follow(model, &unit[..1])?;
            if let Some((i, why)) = first.unreachable {
                return Err(Error::field(format!("points[{i}]"), why));
            }
            (first.k[0], first.m[0])
        }
    };
    let mut out = Refined {
        tips: vec![tips[0]],
        axes: vec![unit[0]],
        k: vec![start.0],
        m: vec![start.1],
        motions: vec![path.motion(0)],
        source: vec![Some(0)],
        added: 0,
        max: 0.0,
        unfixed: Vec::new(),
    };
    for i in 0..unit.len() - 1 {
        let last = out.k.len() - 1;
        let prev = (out.k[last], out.m[last]);
        let at = |e: Error| Error::field(format!("points[{}]", i + 1), e.message);
        let c = match &commanded {
            Some(f) => (f.k[i + 1], f.m[i + 1]),
            None => {
                let o = model
                    .orientations(&unit[i + 1], BranchRule::Nearest, Some([prev.0, prev.1]))
                    .map_err(at)?;
                let c = o.pick(&format!("points[{}]", i + 1))?;
                (c.k, c.m)
            }
        };
        let motion = path.motion(i + 1);
        // The segment as it is now (its start may be an inserted point's commands).
        let s = segment(model, length, prev, c, &unit[i], &unit[i + 1]);
        let mut end = c;
        if !motion.cuts() {
            // A rapid: not cut, left as it is.
        } else if s.delta <= tolerance {
            out.max = out.max.max(s.delta);
        } else {
            match split(model, length, tolerance, &out, (tips[i + 1], unit[i + 1])).map_err(at)? {
                Some(pieces)
                    if commanded.is_none()
                        || ((pieces.k[pieces.k.len() - 1] - c.0).abs() < 1e-9
                            && (pieces.m[pieces.m.len() - 1] - c.1).abs() < 1e-9) =>
                {
                    out.max = out.max.max(pieces.max);
                    let n = pieces.k.len();
                    for p in 0..n - 1 {
                        out.tips.push(pieces.tips[p]);
                        out.axes.push(pieces.axes[p]);
                        out.k.push(pieces.k[p]);
                        out.m.push(pieces.m[p]);
                        out.motions.push(motion);
                        out.source.push(None);
                        out.added += 1;
                    }
                    end = (pieces.k[n - 1], pieces.m[n - 1]);
                }
                _ => {
                    // No number of pieces helps (a flip at the end of the travel, or a change
                    // of branch the program commands): left as it is.
                    out.max = out.max.max(s.delta);
                    out.unfixed.push(i);
                }
            }
        }
        out.tips.push(tips[i + 1]);
        out.axes.push(unit[i + 1]);
        out.k.push(end.0);
        out.m.push(end.1);
        out.motions.push(motion);
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
