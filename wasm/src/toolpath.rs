//! Exports of the toolpath study (see `fiveaxis::toolpath`): the customer's path on the machine
//! and on the twelve rotary-axis types, and the path refined to a tolerance. A path crosses as a
//! `Float64Array` of `[x, y, z, i, j, k]` per point (tip mm, tool axis any length, workpiece
//! coordinates), the case (machine, `L`, tolerance) as a plain object.

use crate::{f64_array, js_error, json, output, Series};
use fiveaxis::rotary::Group;
use fiveaxis::toolpath::{Summary, ToolpathCase, Unreachable};
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

fn degrees(v: &[f64]) -> Series {
    f64_array(&v.iter().map(|x| x.to_degrees()).collect::<Vec<_>>())
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
/// travel), ranked: those that follow the whole path first, by largest δ.
#[wasm_bindgen(js_name = toolpathCompare, unchecked_return_type = "ToolpathSummary[]")]
pub fn toolpath_compare(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let (_, axes) = points(&path)?;
    let rows: Vec<ToolpathSummary> = c
        .compare(&axes)
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
    })
}
