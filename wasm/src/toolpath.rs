//! Exports of the toolpath study (see `fiveaxis::toolpath`): reading the customer's file
//! (`ToolpathReader`, `toolpathParse`), the path on the machine and on the twelve rotary-axis
//! types, and the path refined to a tolerance.
//!
//! A path crosses as a `ToolpathPath`: `{points, motions?, angles?, readFor?}` with `points` a
//! `Float64Array` of `[x, y, z, i, j, k]` per point (tip mm, tool axis any length, workpiece
//! coordinates), `motions` the motion code of each point (0 rapid, 1 feed, 2 arc; all feed when
//! left out), and for NC blocks `angles` (`[K, M]` degrees per point) with `readFor`, the type of
//! the machine they command. A bare `Float64Array` of points is a path of feed moves. The
//! reader's `ParsedToolpath.path` is one.

use crate::{degrees, f64_array, js_error, json, output, Series};
use fiveaxis::rotary::{Group, RotaryType};
use fiveaxis::toolpath::read::{Format, Motion, Parser, Point, Report};
use fiveaxis::toolpath::write::write;
use fiveaxis::toolpath::{
    Commands, Path, Rapids, Summary, ToolpathCase, ToolpathReadInput, Unreachable,
};
use fiveaxis::Error;
use js_sys::{Float64Array, Object, Reflect};
use nalgebra::Vector3;
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

/// Largest accepted coordinate of a point, mm.
const MAX_COORDINATE: f64 = 1e5;

/// A path read from JavaScript: tips, axes, motions, and the program's commands.
pub(crate) struct PathInput {
    pub tips: Vec<Vector3<f64>>,
    pub axes: Vec<Vector3<f64>>,
    pub motions: Option<Vec<Motion>>,
    pub commands: Option<(Vec<[f64; 2]>, RotaryType)>,
}

impl PathInput {
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

/// The numbers of a `Float64Array` (or a plain array of numbers) at `field`.
fn numbers(value: &JsValue, field: &str, what: &str) -> Result<Vec<f64>, JsError> {
    if let Some(a) = value.dyn_ref::<Float64Array>() {
        return Ok(a.to_vec());
    }
    let v = json(value)?;
    v.as_array()
        .and_then(|a| {
            a.iter()
                .map(serde_json::Value::as_f64)
                .collect::<Option<Vec<f64>>>()
        })
        .ok_or_else(|| js_error(Error::field(field, format!("expected {what}"))))
}

/// A path (module docs), each number checked (`points[i]`).
pub(crate) fn points(value: &JsValue) -> Result<PathInput, JsError> {
    let bad = |field: &str, msg: String| js_error(Error::field(field, msg));
    let (pts, motions, angles, read_for) = if value.is_instance_of::<Float64Array>() {
        (
            value.clone(),
            JsValue::UNDEFINED,
            JsValue::UNDEFINED,
            JsValue::UNDEFINED,
        )
    } else if value.is_object()
        && !value.is_function()
        && !js_sys::Array::is_array(value)
        && !js_sys::ArrayBuffer::is_view(value)
    {
        let obj: &Object = value.unchecked_ref();
        for key in Object::keys(obj).iter() {
            let k = key.as_string().unwrap_or_default();
            if !matches!(k.as_str(), "points" | "motions" | "angles" | "readFor") {
                return Err(bad(
                    &format!("path.{k}"),
                    "unknown key; a path has points, motions, angles and readFor".into(),
                ));
            }
        }
        let get = |k: &str| Reflect::get(obj, &JsValue::from_str(k)).unwrap_or(JsValue::UNDEFINED);
        (get("points"), get("motions"), get("angles"), get("readFor"))
    } else {
        return Err(bad("points", "expected a Float64Array of [x, y, z, i, j, k] per point, or a path {points, motions, angles, readFor}".into()));
    };
    let a = pts
        .dyn_ref::<Float64Array>()
        .ok_or_else(|| {
            bad(
                "points",
                "expected a Float64Array of [x, y, z, i, j, k] per point".into(),
            )
        })?
        .to_vec();
    if a.len() % 6 != 0 {
        return Err(bad(
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
            fiveaxis::error::check_range(
                &format!("points[{i}][{j}]"),
                *v,
                -MAX_COORDINATE,
                MAX_COORDINATE,
                "mm",
            )
            .map_err(js_error)?;
        }
        let axis = Vector3::new(p[3], p[4], p[5]);
        if axis.norm() < 1e-12 {
            return Err(bad(
                &format!("points[{i}]"),
                "the tool axis (i, j, k) must not be zero".into(),
            ));
        }
        tips.push(Vector3::new(p[0], p[1], p[2]));
        axes.push(axis);
    }
    let motions = if motions.is_undefined() || motions.is_null() {
        None
    } else {
        let codes = if let Some(u) = motions.dyn_ref::<js_sys::Uint8Array>() {
            u.to_vec().into_iter().map(f64::from).collect()
        } else {
            numbers(
                &motions,
                "motions",
                "a motion code per point (0 rapid, 1 feed, 2 arc)",
            )?
        };
        Some(
            codes
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    Motion::from_code(*c).ok_or_else(|| {
                        bad(
                            &format!("motions[{i}]"),
                            format!("expected 0 (rapid), 1 (feed) or 2 (arc), got {c}"),
                        )
                    })
                })
                .collect::<Result<Vec<_>, _>>()?,
        )
    };
    let commands = if angles.is_undefined() || angles.is_null() {
        if !(read_for.is_undefined() || read_for.is_null()) {
            return Err(bad(
                "readFor",
                "readFor names the machine the angles were written for; give angles too".into(),
            ));
        }
        None
    } else {
        let v = numbers(&angles, "angles", "[K, M] degrees per point")?;
        if v.len() % 2 != 0 {
            return Err(bad(
                "angles",
                format!("expected [K, M] per point, got {} numbers", v.len()),
            ));
        }
        let name = read_for.as_string().ok_or_else(|| {
            bad(
                "readFor",
                "expected the type of the machine the angles command, such as \"CAZ\"".into(),
            )
        })?;
        let t = RotaryType::parse(&name).map_err(|e| bad("readFor", e.message))?;
        Some((v.chunks_exact(2).map(|c| [c[0], c[1]]).collect(), t))
    };
    let input = PathInput {
        tips,
        axes,
        motions,
        commands,
    };
    input.path().check().map_err(js_error)?;
    Ok(input)
}

fn case(value: &JsValue) -> Result<ToolpathCase, JsError> {
    ToolpathCase::read(&json(value)?).map_err(js_error)
}

/// A point the machine cannot reach (API form).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
pub struct ToolpathUnreachable {
    /// Index of the point.
    pub point: usize,
    /// What it would need (angles in degrees) and the travel.
    pub message: String,
}

/// The rapid moves of a path on one machine, apart from the cutting ones (mm, degrees).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathRapids {
    /// Rapid segments.
    pub count: usize,
    /// Rapids that turn a rotary axis.
    pub swings: usize,
    /// Largest excursion of the tool tip from the straight line in a rapid, mm.
    pub max: f64,
    /// Index of that segment.
    pub max_segment: usize,
    /// Largest turn of K in one rapid, degrees.
    pub k_swing: f64,
    /// Largest turn of M in one rapid, degrees.
    pub m_swing: f64,
}

impl From<Rapids> for ToolpathRapids {
    fn from(r: Rapids) -> Self {
        Self {
            count: r.count,
            swings: r.swings,
            max: r.max,
            max_segment: r.max_segment,
            k_swing: r.k_swing.to_degrees(),
            m_swing: r.m_swing.to_degrees(),
        }
    }
}

/// One machine on the path: a row of the ranking (mm, degrees), on its cutting segments.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathSummary {
    /// The rotary-axis type.
    #[serde(rename = "type")]
    pub rtype: String,
    /// Its group.
    pub group: Group,
    /// Cutting segments analysed.
    pub segments: usize,
    /// Largest δ of a cutting segment, mm.
    pub max: f64,
    /// Index of the segment with the largest δ.
    pub max_segment: usize,
    /// Mean δ, mm.
    pub mean: f64,
    /// 95th percentile of δ, mm.
    pub p95: f64,
    /// Cutting segments above the tolerance.
    pub above: usize,
    /// Flips while cutting.
    pub flips: usize,
    /// Cutting segments passing by the pole.
    pub poles: usize,
    /// Total travel of K, degrees (rapids included).
    pub k_travel: f64,
    /// Total travel of M, degrees.
    pub m_travel: f64,
    /// The first point out of reach, when one is.
    pub unreachable: Option<ToolpathUnreachable>,
    /// The rapids, apart.
    pub rapids: ToolpathRapids,
    /// The row follows the program's own commands.
    pub commanded: bool,
}

impl From<Summary> for ToolpathSummary {
    fn from(s: Summary) -> Self {
        Self {
            rtype: s.rtype.name(),
            group: s.group,
            segments: s.segments,
            max: s.max,
            max_segment: s.max_segment,
            mean: s.mean,
            p95: s.p95,
            above: s.above,
            flips: s.flips,
            poles: s.poles,
            k_travel: s.k_travel.to_degrees(),
            m_travel: s.m_travel.to_degrees(),
            unreachable: s
                .unreachable
                .map(|Unreachable { point, message }| ToolpathUnreachable { point, message }),
            rapids: s.rapids.into(),
            commanded: s.commanded,
        }
    }
}

/// The path on the machine, segment by segment.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathAnalysis {
    /// `L` used, mm.
    pub length: f64,
    /// Tolerance, mm.
    pub tolerance: f64,
    /// Totals of the cutting segments, and the rapids apart.
    pub summary: ToolpathSummary,
    /// K command at each point reached, degrees.
    pub k: Series,
    /// M command, degrees.
    pub m: Series,
    /// δ of each segment (rapids included), mm.
    pub delta: Series,
    /// Where along each segment δ is largest, u ∈ [0, 1].
    pub u: Series,
    /// Indices of the cutting segments that flip.
    pub flips: Vec<usize>,
    /// Indices of the cutting segments passing by the pole.
    pub poles: Vec<usize>,
    /// Indices of the rapid segments (segment i ends at point i + 1).
    pub rapids: Vec<usize>,
    /// Each rapid move: its segment, the turns of K and M (degrees, signed) and the tool tip's
    /// largest excursion from the straight line (mm), a positioning and collision note.
    pub rapid_moves: Vec<ToolpathRapidMove>,
}

/// One rapid move (mm, degrees).
#[derive(Serialize, Tsify)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathRapidMove {
    /// The segment (from point `segment` to `segment + 1`).
    pub segment: usize,
    /// The turn of K, degrees.
    pub k_turn: f64,
    /// The turn of M, degrees.
    pub m_turn: f64,
    /// The tool tip's largest excursion from the straight line, mm.
    pub excursion: f64,
}

/// The path on the machine: its commands, each segment's nonlinear error and where, flips and
/// pole passages, the rapids apart, and the totals of the cutting segments.
#[wasm_bindgen(js_name = toolpathAnalyse, unchecked_return_type = "ToolpathAnalysis")]
pub fn toolpath_analyse(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let p = points(&path)?;
    let a = c.analyse(&p.path()).map_err(js_error)?;
    let pick = |f: fn(&fiveaxis::toolpath::Segment) -> bool| -> Vec<usize> {
        (0..a.segments.len())
            .filter(|&i| f(&a.segments[i]))
            .collect()
    };
    output(&ToolpathAnalysis {
        length: c.length().map_err(js_error)?,
        tolerance: c.tolerance,
        k: degrees(&a.following.k),
        m: degrees(&a.following.m),
        delta: f64_array(&a.segments.iter().map(|s| s.delta).collect::<Vec<_>>()),
        u: f64_array(&a.segments.iter().map(|s| s.u).collect::<Vec<_>>()),
        flips: pick(|s| s.flip && !s.rapid),
        poles: pick(|s| s.pole && !s.rapid),
        rapids: pick(|s| s.rapid),
        rapid_moves: a
            .rapid_moves()
            .into_iter()
            .map(|r| ToolpathRapidMove {
                segment: r.segment,
                k_turn: r.k_turn.to_degrees(),
                m_turn: r.m_turn.to_degrees(),
                excursion: r.excursion,
            })
            .collect(),
        summary: a.summary.into(),
    })
}

/// The path on each of the twelve rotary-axis types (the machine's kind, geometry, senses and
/// travel), or on `types` (names such as `"CAZ"`) when given, ranked: those that follow the whole
/// path first, by largest δ of the cutting segments.
#[wasm_bindgen(js_name = toolpathCompare, unchecked_return_type = "ToolpathSummary[]")]
pub fn toolpath_compare(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
    #[wasm_bindgen(unchecked_param_type = "RotaryType[] | undefined")] types: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let p = points(&path)?;
    let types = if types.is_undefined() || types.is_null() {
        RotaryType::ALL.to_vec()
    } else {
        let list = json(&types)?;
        let names = list.as_array().ok_or_else(|| {
            js_error(Error::field(
                "types",
                "expected a list of type names such as [\"CAZ\"]",
            ))
        })?;
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
            .collect::<Result<Vec<_>, Error>>()
            .map_err(js_error)?
    };
    let rows: Vec<ToolpathSummary> = c
        .compare(&p.path(), &types)
        .map_err(js_error)?
        .into_iter()
        .map(Into::into)
        .collect();
    output(&rows)
}

/// The refined path.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathRefined {
    /// `[x, y, z, i, j, k]` per point (unit axes), the inserted points among the original ones.
    pub points: Series,
    /// The motion code of each point (0 rapid, 1 feed, 2 arc).
    pub motions: Series,
    /// K command at each point, degrees.
    pub k: Series,
    /// M command, degrees.
    pub m: Series,
    /// For each point, the index of the original point it is, or -1 for an inserted one.
    pub source: Series,
    /// Points inserted.
    pub added: usize,
    /// Largest δ of the refined path's cutting segments, mm.
    pub max: f64,
    /// Segments (index of their first original point) that no number of points keeps within the
    /// tolerance (a swing round at the end of the travel), left as they were.
    pub unfixed: Vec<usize>,
}

/// The path with the fewest equally spaced points inserted into each cutting segment above the
/// tolerance, so that every piece stays within it on the machine; rapids are left as they are.
#[wasm_bindgen(js_name = toolpathRefine, unchecked_return_type = "ToolpathRefined")]
pub fn toolpath_refine(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let p = points(&path)?;
    let r = c.refine(&p.tips, &p.path()).map_err(js_error)?;
    let flat: Vec<f64> = r
        .tips
        .iter()
        .zip(&r.axes)
        .flat_map(|(t, a)| [t.x, t.y, t.z, a.x, a.y, a.z])
        .collect();
    let source: Vec<f64> = r
        .source
        .iter()
        .map(|s| s.map_or(-1.0, |i| i as f64))
        .collect();
    output(&ToolpathRefined {
        points: f64_array(&flat),
        motions: f64_array(
            &r.motions
                .iter()
                .map(|m| f64::from(m.code()))
                .collect::<Vec<_>>(),
        ),
        k: degrees(&r.k),
        m: degrees(&r.m),
        source: f64_array(&source),
        added: r.added,
        max: r.max,
        unfixed: r.unfixed,
    })
}

/// A path as the analyses take it (module docs).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathPath {
    /// `[x, y, z, i, j, k]` per point: tip mm, unit tool axis, workpiece coordinates.
    pub points: Series,
    /// The motion code of each point: 0 rapid, 1 feed, 2 arc (a chord of an arc).
    pub motions: Series,
    /// NC blocks: the commands `[K, M]` of each point, degrees; null for CL data, or where a
    /// tilted working plane gives the tool axis.
    pub angles: Option<Series>,
    /// NC blocks: the type of the machine the angles command (null with no angles).
    pub read_for: Option<String>,
}

/// A toolpath read from a file.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ParsedToolpath {
    /// The format read: `"csv"`, `"apt"`, `"nc"`, `"siemens"` or `"heidenhain"`.
    pub format: String,
    /// Points read.
    pub count: usize,
    /// The path, for the analyses.
    pub path: ToolpathPath,
    /// The file's line of each point (1-based).
    pub lines: Series,
    /// Lines read.
    pub lines_read: u32,
    /// What the reader found: dialect, unit and why, frames, tool-centre-point control, what it
    /// skipped.
    pub report: Report,
}

/// Reads a toolpath file piece by piece, so that a large file never needs to be one string:
/// `new ToolpathReader({format, machine, unit, aptFrame, chordTolerance})`, then `feed(text)`
/// for each piece (pieces may split lines anywhere; returns the lines read so far), then
/// `finish()`. A bad line throws an Error `"toolpath: line 12, column 7: …"`.
#[wasm_bindgen]
pub struct ToolpathReader {
    options: ToolpathReadInput,
    parser: Option<Parser>,
    points: Vec<Point>,
}

#[wasm_bindgen]
impl ToolpathReader {
    /// A reader for the format and machine of `options` (`format` `"auto"` recognises it from
    /// the first piece).
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
    ) -> Result<ToolpathReader, JsError> {
        let options = ToolpathReadInput::read(&json(&options)?).map_err(js_error)?;
        Ok(Self {
            options,
            parser: None,
            points: Vec::new(),
        })
    }

    /// Reads the next piece of the file, its text or its bytes (a `Uint8Array`: UTF-8, else
    /// Windows-1252; the cheaper way, as no string is copied); returns the lines read so far.
    /// (The piece is taken as a `JsValue` and checked: wasm-bindgen does not check that a `&str`
    /// argument is a string.)
    pub fn feed(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    ) -> Result<u32, JsError> {
        if let Some(bytes) = text.dyn_ref::<js_sys::Uint8Array>() {
            return self.feed_bytes(&bytes.to_vec());
        }
        let text = text.as_string().ok_or_else(|| {
            js_error(Error::field(
                "text",
                "expected a piece of the file: its text or its bytes (Uint8Array)",
            ))
        })?;
        self.feed_str(&text)
    }

    /// Ends the file: the points read and the report.
    #[wasm_bindgen(unchecked_return_type = "ParsedToolpath")]
    pub fn finish(&mut self) -> Result<JsValue, JsError> {
        self.finish_points()
    }
}

impl ToolpathReader {
    /// The parser, made for the format of the file's first piece when it is to be recognised.
    fn parser(&mut self, first: impl FnOnce() -> Format) -> Result<&mut Parser, JsError> {
        if self.parser.is_none() {
            let format = self.options.format.format().unwrap_or_else(first);
            self.parser = Some(
                Parser::new(format, Some(&self.options.machine), self.options.options())
                    .map_err(js_error)?,
            );
        }
        self.parser
            .as_mut()
            .ok_or_else(|| js_error("toolpath: no parser"))
    }

    fn feed_str(&mut self, text: &str) -> Result<u32, JsError> {
        let mut out = std::mem::take(&mut self.points);
        let parser = self.parser(|| Format::detect(text))?;
        let r = parser.feed(text, &mut out).map(|()| parser.lines());
        self.points = out;
        r.map_err(js_error)
    }

    fn feed_bytes(&mut self, bytes: &[u8]) -> Result<u32, JsError> {
        let mut out = std::mem::take(&mut self.points);
        let parser = self.parser(|| Format::detect(&String::from_utf8_lossy(bytes)))?;
        let r = parser.feed_bytes(bytes, &mut out).map(|()| parser.lines());
        self.points = out;
        r.map_err(js_error)
    }

    fn finish_points(&mut self) -> Result<JsValue, JsError> {
        if self.parser.is_none() {
            self.feed_str("")?;
        }
        let parser = self
            .parser
            .as_mut()
            .ok_or_else(|| js_error("toolpath: no parser"))?;
        let report = parser.finish(&mut self.points).map_err(js_error)?;
        let p = std::mem::take(&mut self.points);
        let flat: Vec<f64> = p
            .iter()
            .flat_map(|q| [q.tip.x, q.tip.y, q.tip.z, q.axis.x, q.axis.y, q.axis.z])
            .collect();
        let format = parser.format();
        // The commands: only when every point has them (a tilted plane gives axes without).
        let angles: Option<Vec<f64>> = p
            .iter()
            .map(|q| q.angles)
            .collect::<Option<Vec<_>>>()
            .filter(|_| format.is_nc())
            .map(|a| a.into_iter().flatten().collect());
        let read_for = angles
            .as_ref()
            .map(|_| self.options.machine.rotary_type.name());
        output(&ParsedToolpath {
            format: format.name().to_string(),
            count: p.len(),
            path: ToolpathPath {
                points: f64_array(&flat),
                motions: f64_array(
                    &p.iter()
                        .map(|q| f64::from(q.motion.code()))
                        .collect::<Vec<_>>(),
                ),
                angles: angles.map(|a| f64_array(&a)),
                read_for,
            },
            lines: f64_array(&p.iter().map(|q| f64::from(q.line)).collect::<Vec<_>>()),
            lines_read: parser.lines(),
            report,
        })
    }
}

/// Reads a whole toolpath file at once, its text or its bytes (see [`ToolpathReader`]).
#[wasm_bindgen(js_name = toolpathParse, unchecked_return_type = "ParsedToolpath")]
pub fn toolpath_parse(
    #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
) -> Result<JsValue, JsError> {
    let mut r = ToolpathReader::new(options)?;
    if let Some(bytes) = text.dyn_ref::<js_sys::Uint8Array>() {
        r.feed_bytes(&bytes.to_vec())?;
    } else {
        let text = text.as_string().ok_or_else(|| {
            js_error(Error::field(
                "text",
                "expected the file: its text or its bytes (Uint8Array)",
            ))
        })?;
        r.feed_str(&text)?;
    }
    r.finish_points()
}

/// Writes a path in a format: CSV, APT, or ISO NC blocks for the machine, for which the path's
/// `angles` (`[K, M]` degrees per point, e.g. a refined path's) are needed; rapids are written
/// as rapids (`RAPID`, `G0`).
#[wasm_bindgen(js_name = toolpathWrite)]
pub fn toolpath_write(
    #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
) -> Result<String, JsError> {
    let o = ToolpathReadInput::read(&json(&options)?).map_err(js_error)?;
    let format = o.format.format().ok_or_else(|| {
        js_error(Error::field(
            "format",
            "say which format to write: csv, apt or nc",
        ))
    })?;
    let p = points(&path)?;
    if format.is_nc() && p.commands.is_none() {
        return Err(js_error(Error::field(
            "angles",
            "NC blocks need the machine's commands [K, M] of each point",
        )));
    }
    let pts: Vec<Point> = (0..p.tips.len())
        .map(|i| Point {
            tip: p.tips[i],
            axis: p.axes[i].normalize(),
            line: 0,
            motion: p.motions.as_ref().map_or(Motion::Feed, |m| m[i]),
            angles: p.commands.as_ref().map(|(a, _)| a[i]),
        })
        .collect();
    let letters = o.machine.build().map_err(js_error)?.letters();
    write(format, &pts, Some(letters)).map_err(js_error)
}
