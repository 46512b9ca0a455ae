//! The toolpath study as the binding exports it: a path read from JavaScript's arrays and
//! checked ([`PathInput`]), the results the exports return ([`ToolpathAnalysis`],
//! [`ToolpathRefined`], [`ParsedToolpath`], the ranking's [`ToolpathSummary`] rows) and the streaming
//! reader ([`Reading`]). The binding only copies typed arrays in and calls these.
//!
//! A path crosses as a `ToolpathPath`: `{points, motions?, angles?, readFor?}` with `points` a
//! `Float64Array` of `[x, y, z, i, j, k]` per point (tip mm, tool axis any length, workpiece
//! coordinates), `motions` the motion code of each point (0 rapid, 1 feed, 2 arc; all feed when
//! left out), and for NC blocks `angles` (`[K, M]` degrees per point) with `readFor`, the type of
//! the machine they command. A bare `Float64Array` of points is a path of feed moves. The
//! reader's `ParsedToolpath.path` is one.

use super::read::{Format, Motion, Parser, Point, Report};
use super::write::write;
use super::{Commands, Path, RapidMove, ToolpathCase, ToolpathReadInput, ToolpathSummary};
use crate::error::{check_range, Error, Result};
use crate::rotary::RotaryType;
use nalgebra::Vector3;
use serde::{Serialize, Serializer};
use serde_json::Value;

/// Largest accepted coordinate of a point, mm.
pub const MAX_COORDINATE: f64 = 1e5;

/// The keys of a path object.
pub const PATH_KEYS: [&str; 4] = ["points", "motions", "angles", "readFor"];

/// One part of a path as it comes from JavaScript, not yet checked: a typed array copied as it
/// is, or any other value as JSON (`null` when absent).
#[derive(Debug, Clone, PartialEq)]
pub enum Part {
    /// A `Float64Array`.
    Float64(Vec<f64>),
    /// A `Uint8Array` (motion codes).
    Uint8(Vec<u8>),
    /// Anything else.
    Json(Value),
}

/// A path value as it comes from JavaScript.
pub enum PathValue<'a> {
    /// A bare `Float64Array` of points.
    Points(Vec<f64>),
    /// An object: its keys, and the part at a key (read only once the keys are checked).
    Object {
        /// Its own keys.
        keys: Vec<String>,
        /// The value at a key.
        get: &'a dyn Fn(&str) -> Result<Part>,
    },
    /// Anything else (refused).
    Other,
}

/// A path read and checked: tips, axes, motions and the program's commands.
#[derive(Debug, Clone, PartialEq)]
pub struct PathInput {
    /// Tool tips, mm.
    pub tips: Vec<Vector3<f64>>,
    /// Tool axes (not zero, any length).
    pub axes: Vec<Vector3<f64>>,
    /// How each point is reached; `None`: feed moves.
    pub motions: Option<Vec<Motion>>,
    /// `[K, M]` degrees per point and the type they command.
    pub commands: Option<(Vec<[f64; 2]>, RotaryType)>,
}

/// The numbers of a part at `field`: a typed array, or a JSON list of numbers.
fn numbers(part: Part, field: &str, what: &str) -> Result<Vec<f64>> {
    match part {
        Part::Float64(v) => Ok(v),
        Part::Uint8(v) => Ok(v.into_iter().map(f64::from).collect()),
        Part::Json(v) => v
            .as_array()
            .and_then(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>())
            .ok_or_else(|| Error::field(field, format!("expected {what}"))),
    }
}

fn absent(part: &Part) -> bool {
    matches!(part, Part::Json(Value::Null))
}

impl PathInput {
    /// Reads a path (module docs), each number checked (`points[i][j]` within
    /// ±[`MAX_COORDINATE`] mm, no zero tool axis), the motions, the commands and the type they
    /// were written for; then [`Path::check`].
    pub fn read(value: PathValue) -> Result<Self> {
        let (points, motions, angles, read_for) =
            match value {
                PathValue::Points(p) => (
                    Part::Float64(p),
                    Part::Json(Value::Null),
                    Part::Json(Value::Null),
                    Part::Json(Value::Null),
                ),
                PathValue::Object { keys, get } => {
                    if let Some(k) = keys.iter().find(|k| !PATH_KEYS.contains(&k.as_str())) {
                        return Err(Error::field(
                            format!("path.{k}"),
                            "unknown key; a path has points, motions, angles and readFor",
                        ));
                    }
                    (
                        get("points")?,
                        get("motions")?,
                        get("angles")?,
                        get("readFor")?,
                    )
                }
                PathValue::Other => return Err(Error::field(
                    "points",
                    "expected a Float64Array of [x, y, z, i, j, k] per point, or a path {points, \
                     motions, angles, readFor}",
                )),
            };
        let Part::Float64(a) = points else {
            return Err(Error::field(
                "points",
                "expected a Float64Array of [x, y, z, i, j, k] per point",
            ));
        };
        let (tips, axes) = points_of(&a)?;
        let motions = if absent(&motions) {
            None
        } else {
            let codes = numbers(
                motions,
                "motions",
                "a motion code per point (0 rapid, 1 feed, 2 arc)",
            )?;
            Some(
                codes
                    .iter()
                    .enumerate()
                    .map(|(i, c)| {
                        Motion::from_code(*c).ok_or_else(|| {
                            Error::field(
                                format!("motions[{i}]"),
                                format!("expected 0 (rapid), 1 (feed) or 2 (arc), got {c}"),
                            )
                        })
                    })
                    .collect::<Result<Vec<_>>>()?,
            )
        };
        let commands = if absent(&angles) {
            if !absent(&read_for) {
                return Err(Error::field(
                    "readFor",
                    "readFor names the machine the angles were written for; give angles too",
                ));
            }
            None
        } else {
            let v = numbers(angles, "angles", "[K, M] degrees per point")?;
            if v.len() % 2 != 0 {
                return Err(Error::field(
                    "angles",
                    format!("expected [K, M] per point, got {} numbers", v.len()),
                ));
            }
            let name = match read_for {
                Part::Json(Value::String(s)) => s,
                _ => {
                    return Err(Error::field(
                        "readFor",
                        "expected the type of the machine the angles command, such as \"CAZ\"",
                    ))
                }
            };
            let t = RotaryType::parse(&name).map_err(|e| Error::field("readFor", e.message))?;
            Some((v.chunks_exact(2).map(|c| [c[0], c[1]]).collect(), t))
        };
        let input = PathInput {
            tips,
            axes,
            motions,
            commands,
        };
        input.path().check()?;
        Ok(input)
    }

    /// The engine's view of it.
    pub fn path(&self) -> Path<'_> {
        Path {
            axes: &self.axes,
            motions: self.motions.as_deref(),
            commands: self.commands.as_ref().map(|(a, t)| Commands {
                angles: a,
                rtype: *t,
            }),
        }
    }
}

/// Tips or axes, one per point.
type Vectors = Vec<Vector3<f64>>;

/// Tips and axes of `[x, y, z, i, j, k]` per point, each number checked.
fn points_of(a: &[f64]) -> Result<(Vectors, Vectors)> {
    if a.len() % 6 != 0 {
        return Err(Error::field(
            "points",
            format!(
                "length must be a multiple of 6 ([x, y, z, i, j, k] per point), got {}",
                a.len()
            ),
        ));
    }
    let n = a.len() / 6;
    let mut tips = Vec::with_capacity(n);
    let mut axes = Vec::with_capacity(n);
    for (i, p) in a.chunks_exact(6).enumerate() {
        for (j, v) in p.iter().enumerate() {
            if v.is_finite() && v.abs() <= MAX_COORDINATE {
                continue; // the message (and its formatted path) only for a bad value
            }
            check_range(
                &format!("points[{i}][{j}]"),
                *v,
                -MAX_COORDINATE,
                MAX_COORDINATE,
                "mm",
            )?;
        }
        let axis = Vector3::new(p[3], p[4], p[5]);
        if axis.norm() < 1e-12 {
            return Err(Error::field(
                format!("points[{i}]"),
                "the tool axis (i, j, k) must not be zero",
            ));
        }
        tips.push(Vector3::new(p[0], p[1], p[2]));
        axes.push(axis);
    }
    Ok((tips, axes))
}

/// The types to rank: `types` a list of names such as `["CAZ"]`, every one of
/// [`RotaryType::ALL`] when `null`.
pub fn types_of(types: &Value) -> Result<Vec<RotaryType>> {
    if types.is_null() {
        return Ok(RotaryType::ALL.to_vec());
    }
    let names = types
        .as_array()
        .ok_or_else(|| Error::field("types", "expected a list of type names such as [\"CAZ\"]"))?;
    names
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let name = n.as_str().ok_or_else(|| {
                Error::field(
                    format!("types[{i}]"),
                    "expected a type name such as \"CAZ\"",
                )
            })?;
            RotaryType::parse(name).map_err(|e| Error::field(format!("types[{i}]"), e.message))
        })
        .collect()
}

/// An optional series (`null` when absent).
fn series_opt<S: Serializer>(
    values: &Option<Vec<f64>>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    match values {
        Some(v) => crate::edge::series(v, s),
        None => s.serialize_none(),
    }
}

/// The path on the machine, segment by segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ToolpathAnalysis {
    /// `L` used, mm.
    pub length: f64,
    /// Tolerance, mm.
    pub tolerance: f64,
    /// Totals of the cutting segments, and the rapids apart.
    pub summary: ToolpathSummary,
    /// K command at each point reached, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub k: Vec<f64>,
    /// M command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub m: Vec<f64>,
    /// δ of each segment (rapids included), mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub delta: Vec<f64>,
    /// Where along each segment δ is largest, u ∈ [0, 1].
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub u: Vec<f64>,
    /// Indices of the cutting segments that flip.
    pub flips: Vec<usize>,
    /// Indices of the cutting segments passing by the pole.
    pub poles: Vec<usize>,
    /// Indices of the rapid segments (segment i ends at point i + 1).
    pub rapids: Vec<usize>,
    /// Each rapid move: its segment, the turns of K and M (degrees, signed) and the tool tip's
    /// largest excursion from the straight line (mm), a positioning and collision note.
    pub rapid_moves: Vec<RapidMove>,
}

/// The path on the case's machine: its commands, each segment's nonlinear error and where,
/// flips and pole passages, the rapids apart, and the totals of the cutting segments.
pub fn analyse(case: &ToolpathCase, path: &PathInput) -> Result<ToolpathAnalysis> {
    let a = case.analyse(&path.path())?;
    let pick = |f: fn(&super::Segment) -> bool| -> Vec<usize> {
        (0..a.segments.len())
            .filter(|&i| f(&a.segments[i]))
            .collect()
    };
    Ok(ToolpathAnalysis {
        length: case.length()?,
        tolerance: case.tolerance,
        delta: a.segments.iter().map(|s| s.delta).collect(),
        u: a.segments.iter().map(|s| s.u).collect(),
        flips: pick(|s| s.flip && !s.rapid),
        poles: pick(|s| s.pole && !s.rapid),
        rapids: pick(|s| s.rapid),
        rapid_moves: a.rapid_moves(),
        k: a.following.k,
        m: a.following.m,
        summary: a.summary,
    })
}

/// The path on each of `types` (names, [`types_of`]; the twelve when `null`), the case's
/// machine with its type replaced, ranked ([`super::rank`]).
pub fn compare(
    case: &ToolpathCase,
    path: &PathInput,
    types: &Value,
) -> Result<Vec<ToolpathSummary>> {
    case.compare(&path.path(), &types_of(types)?)
}

/// The refined path.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ToolpathRefined {
    /// `[x, y, z, i, j, k]` per point (unit axes), the inserted points among the original ones.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub points: Vec<f64>,
    /// The motion code of each point (0 rapid, 1 feed, 2 arc).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub motions: Vec<f64>,
    /// K command at each point, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub k: Vec<f64>,
    /// M command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub m: Vec<f64>,
    /// For each point, the index of the original point it is, or -1 for an inserted one.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub source: Vec<f64>,
    /// Points inserted.
    pub added: usize,
    /// Largest δ of the refined path's cutting segments, mm.
    pub max: f64,
    /// Segments (index of their first original point) that no number of points keeps within the
    /// tolerance (a swing round at the end of the travel), left as they were.
    pub unfixed: Vec<usize>,
}

/// The path with the fewest equally spaced points inserted into each cutting segment above the
/// tolerance, so that every piece stays within it on the machine ([`super::refine_path`]).
pub fn refine(case: &ToolpathCase, path: &PathInput) -> Result<ToolpathRefined> {
    let r = case.refine(&path.tips, &path.path())?;
    Ok(ToolpathRefined {
        points: r
            .tips
            .iter()
            .zip(&r.axes)
            .flat_map(|(t, a)| [t.x, t.y, t.z, a.x, a.y, a.z])
            .collect(),
        motions: r.motions.iter().map(|m| f64::from(m.code())).collect(),
        source: r
            .source
            .iter()
            .map(|s| s.map_or(-1.0, |i| i as f64))
            .collect(),
        k: r.k,
        m: r.m,
        added: r.added,
        max: r.max,
        unfixed: r.unfixed,
    })
}

/// Writes a path in the options' format: CSV, APT, or ISO NC blocks for the machine, for which
/// the path's angles are needed ([`write`]).
pub fn write_path(options: &ToolpathReadInput, path: &PathInput) -> Result<String> {
    let format = options
        .format
        .format()
        .ok_or_else(|| Error::field("format", "say which format to write: csv, apt or nc"))?;
    if format.is_nc() && path.commands.is_none() {
        return Err(Error::field(
            "angles",
            "NC blocks need the machine's commands [K, M] of each point",
        ));
    }
    let pts: Vec<Point> = (0..path.tips.len())
        .map(|i| Point {
            tip: path.tips[i],
            axis: path.axes[i].normalize(),
            line: 0,
            motion: path.motions.as_ref().map_or(Motion::Feed, |m| m[i]),
            angles: path.commands.as_ref().map(|(a, _)| a[i]),
        })
        .collect();
    let letters = options.machine.build()?.letters();
    write(format, &pts, Some(letters))
}

/// A path as the analyses take it (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ToolpathPath {
    /// `[x, y, z, i, j, k]` per point: tip mm, unit tool axis, workpiece coordinates.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub points: Vec<f64>,
    /// The motion code of each point: 0 rapid, 1 feed, 2 arc (a chord of an arc).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub motions: Vec<f64>,
    /// NC blocks: the commands `[K, M]` of each point, degrees; null for CL data, or where a
    /// tilted working plane gives the tool axis.
    #[serde(serialize_with = "series_opt")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array | null"))]
    pub angles: Option<Vec<f64>>,
    /// NC blocks: the type of the machine the angles command (null with no angles).
    #[cfg_attr(feature = "ts", tsify(type = "RotaryType | null"))]
    pub read_for: Option<RotaryType>,
}

/// A toolpath read from a file.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ParsedToolpath {
    /// The format read: `"csv"`, `"apt"`, `"nc"`, `"siemens"` or `"heidenhain"`.
    pub format: Format,
    /// Points read.
    pub count: usize,
    /// The path, for the analyses.
    pub path: ToolpathPath,
    /// The file's line of each point (1-based).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub lines: Vec<f64>,
    /// Lines read.
    pub lines_read: u32,
    /// What the reader found: dialect, unit and why, frames, tool-centre-point control, what it
    /// skipped.
    pub report: Report,
}

/// A toolpath file read piece by piece ([`Reading::feed`], [`Reading::feed_bytes`], then
/// [`Reading::finish`]): the parser is made for the format of the first piece when the options
/// say to recognise it.
#[derive(Debug, Clone)]
pub struct Reading {
    options: ToolpathReadInput,
    parser: Option<Parser>,
    points: Vec<Point>,
}

impl Reading {
    /// A reading with `options` (read and checked).
    pub fn new(options: ToolpathReadInput) -> Self {
        Self {
            options,
            parser: None,
            points: Vec::new(),
        }
    }

    /// The parser, made for the format of the file's first piece when it is to be recognised.
    fn parser(&mut self, first: impl FnOnce() -> Format) -> Result<&mut Parser> {
        if self.parser.is_none() {
            let format = self.options.format.format().unwrap_or_else(first);
            self.parser = Some(Parser::new(
                format,
                Some(&self.options.machine),
                self.options.options(),
            )?);
        }
        self.parser
            .as_mut()
            .ok_or_else(|| Error::field("toolpath", "no parser"))
    }

    /// Reads the next piece of text; the lines read so far.
    pub fn feed(&mut self, text: &str) -> Result<u32> {
        let mut out = std::mem::take(&mut self.points);
        let parser = self.parser(|| Format::detect(text))?;
        let r = parser.feed(text, &mut out).map(|()| parser.lines());
        self.points = out;
        r
    }

    /// Reads the next piece of the file's bytes (UTF-8, else Windows-1252); the lines read so
    /// far.
    pub fn feed_bytes(&mut self, bytes: &[u8]) -> Result<u32> {
        let mut out = std::mem::take(&mut self.points);
        let parser = self.parser(|| Format::detect(&String::from_utf8_lossy(bytes)))?;
        let r = parser.feed_bytes(bytes, &mut out).map(|()| parser.lines());
        self.points = out;
        r
    }

    /// Ends the file: the points read, as a path, and the report. The commands go with the
    /// path only when every point has them (a tilted plane gives axes without).
    pub fn finish(&mut self) -> Result<ParsedToolpath> {
        if self.parser.is_none() {
            self.feed("")?;
        }
        let parser = self
            .parser
            .as_mut()
            .ok_or_else(|| Error::field("toolpath", "no parser"))?;
        let report = parser.finish(&mut self.points)?;
        let p = std::mem::take(&mut self.points);
        let format = parser.format();
        let angles: Option<Vec<f64>> = p
            .iter()
            .map(|q| q.angles)
            .collect::<Option<Vec<_>>>()
            .filter(|_| format.is_nc())
            .map(|a| a.into_iter().flatten().collect());
        let read_for = angles.as_ref().map(|_| self.options.machine.rotary_type);
        Ok(ParsedToolpath {
            format,
            count: p.len(),
            path: ToolpathPath {
                points: p
                    .iter()
                    .flat_map(|q| [q.tip.x, q.tip.y, q.tip.z, q.axis.x, q.axis.y, q.axis.z])
                    .collect(),
                motions: p.iter().map(|q| f64::from(q.motion.code())).collect(),
                angles,
                read_for,
            },
            lines: p.iter().map(|q| f64::from(q.line)).collect(),
            lines_read: parser.lines(),
            report,
        })
    }
}
