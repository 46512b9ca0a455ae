//! Exports of the toolpath study (see `fiveaxis::toolpath`): the customer's path on the machine
//! and on the twelve rotary-axis types, and the path refined to a tolerance. A path crosses as a
//! `Float64Array` of `[x, y, z, i, j, k]` per point (tip mm, tool axis any length, workpiece
//! coordinates), the case (machine, `L`, tolerance) as a plain object.

use crate::{degrees, f64_array, js_error, json, output, Series};
use fiveaxis::rotary::{Group, RotaryType};
use fiveaxis::toolpath::parse::{write, Format, Parser, Point};
use fiveaxis::toolpath::{Summary, ToolpathCase, ToolpathReadInput, Unreachable};
use fiveaxis::Error;
use js_sys::Float64Array;
use nalgebra::Vector3;
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

/// Largest accepted coordinate of a point, mm.
const MAX_COORDINATE: f64 = 1e5;

/// Tool tips and tool axes of a path, mm and any length.
type TipsAndAxes = (Vec<Vector3<f64>>, Vec<Vector3<f64>>);

/// Tool tips and axes of a `Float64Array` of 6 numbers per point, each checked (`points[i]`).
pub(crate) fn points(value: &JsValue) -> Result<TipsAndAxes, JsError> {
    let bad = |msg: String| js_error(Error::field("points", msg));
    let a = value
        .dyn_ref::<Float64Array>()
        .ok_or_else(|| bad("expected a Float64Array of [x, y, z, i, j, k] per point".into()))?
        .to_vec();
    if a.len() % 6 != 0 {
        return Err(bad(format!(
            "length must be a multiple of 6 ([x, y, z, i, j, k] per point), got {}",
            a.len()
        )));
    }
    let mut tips = Vec::with_capacity(a.len() / 6);
    let mut axes = Vec::with_capacity(a.len() / 6);
    for (n, p) in a.chunks_exact(6).enumerate() {
        for (j, v) in p.iter().enumerate() {
            if v.is_finite() && v.abs() <= MAX_COORDINATE {
                continue; // the message (and its formatted path) only for a bad value
            }
            fiveaxis::error::check_range(
                &format!("points[{n}][{j}]"),
                *v,
                -MAX_COORDINATE,
                MAX_COORDINATE,
                "mm",
            )
            .map_err(js_error)?;
        }
        let axis = Vector3::new(p[3], p[4], p[5]);
        if axis.norm() < 1e-12 {
            return Err(js_error(Error::field(
                format!("points[{n}]"),
                "the tool axis (i, j, k) must not be zero",
            )));
        }
        tips.push(Vector3::new(p[0], p[1], p[2]));
        axes.push(axis);
    }
    Ok((tips, axes))
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

/// One machine on the path: a row of the ranking (mm, degrees).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ToolpathSummary {
    /// The rotary-axis type.
    #[serde(rename = "type")]
    pub rtype: String,
    /// Its group.
    pub group: Group,
    /// Segments analysed.
    pub segments: usize,
    /// Largest δ, mm.
    pub max: f64,
    /// Index of the segment with the largest δ.
    pub max_segment: usize,
    /// Mean δ, mm.
    pub mean: f64,
    /// 95th percentile of δ, mm.
    pub p95: f64,
    /// Segments above the tolerance.
    pub above: usize,
    /// Flips.
    pub flips: usize,
    /// Segments passing by the pole.
    pub poles: usize,
    /// Total travel of K, degrees.
    pub k_travel: f64,
    /// Total travel of M, degrees.
    pub m_travel: f64,
    /// The first point out of reach, when one is.
    pub unreachable: Option<ToolpathUnreachable>,
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
    /// Totals.
    pub summary: ToolpathSummary,
    /// K command at each point reached, degrees.
    pub k: Series,
    /// M command, degrees.
    pub m: Series,
    /// δ of each segment, mm.
    pub delta: Series,
    /// Where along each segment δ is largest, u ∈ [0, 1].
    pub u: Series,
    /// Indices of the segments that flip.
    pub flips: Vec<usize>,
    /// Indices of the segments passing by the pole.
    pub poles: Vec<usize>,
}

/// The path on the machine: its commands, each segment's nonlinear error and where, flips and
/// pole passages, and the totals.
#[wasm_bindgen(js_name = toolpathAnalyse, unchecked_return_type = "ToolpathAnalysis")]
pub fn toolpath_analyse(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let (_, axes) = points(&path)?;
    let a = c.analyse(&axes).map_err(js_error)?;
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
        flips: pick(|s| s.flip),
        poles: pick(|s| s.pole),
        summary: a.summary.into(),
    })
}

/// The path on each of the twelve rotary-axis types (the machine's kind, geometry, senses and
/// travel), or on `types` (names such as `"CAZ"`) when given, ranked: those that follow the whole
/// path first, by largest δ.
#[wasm_bindgen(js_name = toolpathCompare, unchecked_return_type = "ToolpathSummary[]")]
pub fn toolpath_compare(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] path: JsValue,
    #[wasm_bindgen(unchecked_param_type = "RotaryType[] | undefined")] types: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let (_, axes) = points(&path)?;
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
        .compare(&axes, &types)
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
    /// K command at each point, degrees.
    pub k: Series,
    /// M command, degrees.
    pub m: Series,
    /// For each point, the index of the original point it is, or -1 for an inserted one.
    pub source: Series,
    /// Points inserted.
    pub added: usize,
    /// Largest δ of the refined path, mm.
    pub max: f64,
    /// Segments (index of their first original point) that no number of points keeps within the
    /// tolerance (a swing round at the end of the travel), left as they were.
    pub unfixed: Vec<usize>,
}

/// The path with the fewest equally spaced points inserted into each segment above the
/// tolerance, so that every piece stays within it on the machine.
#[wasm_bindgen(js_name = toolpathRefine, unchecked_return_type = "ToolpathRefined")]
pub fn toolpath_refine(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let (tips, axes) = points(&path)?;
    let r = c.refine(&tips, &axes).map_err(js_error)?;
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
        k: degrees(&r.k),
        m: degrees(&r.m),
        source: f64_array(&source),
        added: r.added,
        max: r.max,
        unfixed: r.unfixed,
    })
}

/// A toolpath read from a file.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null)]
#[serde(rename_all = "camelCase")]
pub struct ParsedToolpath {
    /// The format read: `"csv"`, `"apt"` or `"nc"`.
    pub format: String,
    /// Points read.
    pub count: usize,
    /// `[x, y, z, i, j, k]` per point: tip mm, unit tool axis, workpiece coordinates.
    pub points: Series,
    /// The file's line of each point (1-based).
    pub lines: Series,
    /// NC blocks: the commands `[K, M]` of each point, degrees; null for CL data.
    pub angles: Option<Series>,
    /// Lines read.
    pub lines_read: u32,
}

/// Reads a toolpath file piece by piece, so that a large file never needs to be one string:
/// `new ToolpathReader({format, machine})`, then `feed(text)` for each piece (pieces may split
/// lines anywhere; returns the lines read so far), then `finish()`. A bad line throws an Error
/// `"toolpath: line 12, column 7: …"`.
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

    /// Reads the next piece of the file; returns the lines read so far. (The piece is taken as a
    /// `JsValue` and checked: wasm-bindgen does not check that a `&str` argument is a string.)
    pub fn feed(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    ) -> Result<u32, JsError> {
        let text = text
            .as_string()
            .ok_or_else(|| js_error(Error::field("text", "expected a piece of the file's text")))?;
        self.feed_str(&text)
    }

    /// Ends the file: the points read.
    #[wasm_bindgen(unchecked_return_type = "ParsedToolpath")]
    pub fn finish(&mut self) -> Result<JsValue, JsError> {
        self.finish_points()
    }
}

impl ToolpathReader {
    fn feed_str(&mut self, text: &str) -> Result<u32, JsError> {
        let parser = match &mut self.parser {
            Some(p) => p,
            None => {
                let format = self
                    .options
                    .format
                    .format()
                    .unwrap_or_else(|| Format::detect(text));
                self.parser
                    .insert(Parser::new(format, Some(&self.options.machine)).map_err(js_error)?)
            }
        };
        parser.feed(text, &mut self.points).map_err(js_error)?;
        Ok(parser.lines())
    }

    fn finish_points(&mut self) -> Result<JsValue, JsError> {
        if self.parser.is_none() {
            self.feed_str("")?;
        }
        let parser = self
            .parser
            .as_mut()
            .ok_or_else(|| js_error("toolpath: no parser"))?;
        parser.finish(&mut self.points).map_err(js_error)?;
        let p = std::mem::take(&mut self.points);
        let flat: Vec<f64> = p
            .iter()
            .flat_map(|q| [q.tip.x, q.tip.y, q.tip.z, q.axis.x, q.axis.y, q.axis.z])
            .collect();
        let angles: Option<Vec<f64>> = p
            .iter()
            .map(|q| q.angles)
            .collect::<Option<Vec<_>>>()
            .filter(|_| parser.format() == Format::Nc)
            .map(|a| a.into_iter().flatten().collect());
        output(&ParsedToolpath {
            format: parser.format().name().to_string(),
            count: p.len(),
            points: f64_array(&flat),
            lines: f64_array(&p.iter().map(|q| f64::from(q.line)).collect::<Vec<_>>()),
            angles: angles.map(|a| f64_array(&a)),
            lines_read: parser.lines(),
        })
    }
}

/// Reads a whole toolpath text at once (see [`ToolpathReader`]).
#[wasm_bindgen(js_name = toolpathParse, unchecked_return_type = "ParsedToolpath")]
pub fn toolpath_parse(
    #[wasm_bindgen(unchecked_param_type = "string")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
) -> Result<JsValue, JsError> {
    let text = text
        .as_string()
        .ok_or_else(|| js_error(Error::field("text", "expected the file's text")))?;
    let mut r = ToolpathReader::new(options)?;
    r.feed_str(&text)?;
    r.finish_points()
}

/// Writes points (`[x, y, z, i, j, k]` each) in a format: CSV, APT, or NC blocks for the
/// machine, for which `angles` (`[K, M]` degrees per point, e.g. a refined path's) are needed.
#[wasm_bindgen(js_name = toolpathWrite)]
pub fn toolpath_write(
    #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] path: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array | undefined")] angles: JsValue,
) -> Result<String, JsError> {
    let o = ToolpathReadInput::read(&json(&options)?).map_err(js_error)?;
    let format = o.format.format().ok_or_else(|| {
        js_error(Error::field(
            "format",
            "say which format to write: csv, apt or nc",
        ))
    })?;
    let (tips, axes) = points(&path)?;
    let angles: Option<Vec<f64>> = if angles.is_undefined() || angles.is_null() {
        None
    } else {
        Some(
            angles
                .dyn_ref::<Float64Array>()
                .ok_or_else(|| {
                    js_error(Error::field(
                        "angles",
                        "expected a Float64Array of [K, M] per point",
                    ))
                })?
                .to_vec(),
        )
    };
    if let Some(a) = &angles {
        if a.len() != 2 * tips.len() {
            return Err(js_error(Error::field(
                "angles",
                format!(
                    "expected {} numbers ([K, M] per point), got {}",
                    2 * tips.len(),
                    a.len()
                ),
            )));
        }
    }
    if format == Format::Nc && angles.is_none() {
        return Err(js_error(Error::field(
            "angles",
            "NC blocks need the machine's commands [K, M] of each point",
        )));
    }
    let pts: Vec<Point> = (0..tips.len())
        .map(|i| Point {
            tip: tips[i],
            axis: axes[i].normalize(),
            line: 0,
            angles: angles.as_ref().map(|a| [a[2 * i], a[2 * i + 1]]),
        })
        .collect();
    let letters = o.machine.build().map_err(js_error)?.letters();
    write(format, &pts, Some(letters)).map_err(js_error)
}
