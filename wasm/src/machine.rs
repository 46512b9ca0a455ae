//! Exports about the machine itself: the schema of every input, the error table, the drawing of
//! the machine, its tool direction and its inverse kinematics within the travel.

use crate::{js_error, json, output};
use fiveaxis::machine::errors::{ErrorDef, TABLE};
use fiveaxis::machine::motions::MOTIONS;
use fiveaxis::machine::schematic::{schematic, Schematic};
use fiveaxis::machine::{AxisInfo, InverseInput, Machine, SchematicInput, ToolVectorInput};
use fiveaxis::nonlinear::{
    NonlinearCase, NonlinearGridInput, NonlinearMoveInput, SweepKInput, SweepMInput,
    TypeCompareInput,
};
use fiveaxis::reversal::{ReversalCase, ReversalFitInput, ReversalRunInput};
use fiveaxis::rotary::{Group, RotaryType};
use fiveaxis::schema::{describe, FieldInfo, Inputs};
use fiveaxis::toolpath::{ToolpathCase, ToolpathReadInput};
use serde::Serialize;
use std::collections::BTreeMap;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// Every input the page renders and the engine reads (see `fiveaxis::schema`).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct Schema {
    /// The machine's fields, paths under `machine.`.
    pub machine: Vec<FieldInfo>,
    /// The error table: every ISO 230-1 location error a machine can have.
    pub errors: Vec<ErrorDef>,
    /// The error motions of every axis (ISO 230-1 `E_XX` … `E_CC`), functions of its position.
    pub motions: Vec<ErrorDef>,
    /// Per export, every field of its input object (the machine's included).
    pub exports: BTreeMap<String, Vec<FieldInfo>>,
}

fn fields<A: Inputs>() -> Vec<FieldInfo> {
    describe(A::FIELDS, "")
}

fn both<A: Inputs, B: Inputs>() -> Vec<FieldInfo> {
    let mut v = fields::<A>();
    v.extend(fields::<B>());
    v
}

/// The schema of every input: the machine's fields, the error table and each export's fields,
/// with labels, plain-language help, units (mm, deg), limits and defaults. The page renders its
/// forms from it. Labels may hold `{K}`, `{M}` (the machine's rotary axes) and `{U}`, `{V}` (the
/// face's axes), which the page replaces.
#[wasm_bindgen(js_name = schema, unchecked_return_type = "Schema")]
pub fn schema() -> Result<JsValue, JsError> {
    let mut exports = BTreeMap::new();
    let mut put = |name: &str, f: Vec<FieldInfo>| {
        exports.insert(name.to_string(), f);
    };
    put("machineSchematic", fields::<SchematicInput>());
    put("machineInverse", fields::<InverseInput>());
    put("toolVector", fields::<ToolVectorInput>());
    put("nonlinearMove", both::<NonlinearCase, NonlinearMoveInput>());
    put("toolpathAnalyse", fields::<ToolpathCase>());
    put("toolpathCompare", fields::<ToolpathCase>());
    put("toolpathRefine", fields::<ToolpathCase>());
    put("toolpathParse", fields::<ToolpathReadInput>());
    put("toolpathWrite", fields::<ToolpathReadInput>());
    put("nonlinearSweepK", both::<NonlinearCase, SweepKInput>());
    put("nonlinearSweepM", both::<NonlinearCase, SweepMInput>());
    put("nonlinearGrid", both::<NonlinearCase, NonlinearGridInput>());
    put(
        "nonlinearCompareTypes",
        both::<NonlinearCase, TypeCompareInput>(),
    );
    put("reversalSimulate", both::<ReversalCase, ReversalRunInput>());
    put("reversalDents", fields::<ReversalCase>());
    put("reversalFit", both::<ReversalCase, ReversalFitInput>());
    put("reversalTrace", both::<ReversalCase, ReversalFitInput>());
    for (name, f) in fiveaxis::api::export_fields() {
        put(name, f);
    }
    output(&Schema {
        machine: describe(Machine::FIELDS, "machine"),
        errors: TABLE.to_vec(),
        motions: MOTIONS.to_vec(),
        exports,
    })
}

/// One of the twelve rotary-axis types.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct RotaryTypeInfo {
    /// "CAZ" …
    pub name: String,
    /// Group I or II.
    pub group: Group,
    /// K's letter.
    pub k: String,
    /// M's letter.
    pub m: String,
    /// The spindle direction at zero.
    pub home: String,
}

/// The twelve rotary-axis types with their group and axes.
#[wasm_bindgen(js_name = rotaryTypes, unchecked_return_type = "RotaryTypeInfo[]")]
pub fn rotary_types() -> Result<JsValue, JsError> {
    let list: Vec<RotaryTypeInfo> = RotaryType::ALL
        .iter()
        .map(|t| RotaryTypeInfo {
            name: t.name(),
            group: t.group(),
            k: t.k.letter().to_string(),
            m: t.m.letter().to_string(),
            home: t.home.letter().to_string(),
        })
        .collect();
    output(&list)
}

/// The drawing of a machine and what its axes are.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct SchematicResult {
    /// The drawing at the pose asked for (mm, unit vectors; machine coordinates).
    pub drawing: Schematic,
    /// The axes in chain order with their roles, in words.
    pub axes: Vec<AxisInfo>,
    /// Letters of K and M.
    pub k: String,
    /// Letter of M.
    pub m: String,
    /// The spindle direction at zero.
    pub home: String,
    /// "I" or "II".
    pub group: Group,
    /// The face's axes (the test pieces lie in them): `[u, v, n]` letters.
    pub face: [String; 3],
    /// The distance the nonlinear study uses for `L` when none is given, mm (null: none).
    pub swing_length: Option<f64>,
}

/// The machine drawn from its chain at the commands `k`, `m` (degrees), and its axes in words:
/// so that the user can see that the machine entered is theirs.
#[wasm_bindgen(js_name = machineSchematic, unchecked_return_type = "SchematicResult")]
pub fn machine_schematic(
    #[wasm_bindgen(unchecked_param_type = "SchematicInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let i = SchematicInput::from_value(&json(&value)?, "").map_err(js_error)?;
    let m = &i.machine;
    let drawing = schematic(m, i.k, i.m, i.standoff).map_err(js_error)?;
    output(&SchematicResult {
        drawing,
        axes: m.axes(),
        k: m.k().letter().to_string(),
        m: m.m().letter().to_string(),
        home: m.home().letter().to_string(),
        group: m.rotary_type.group(),
        face: fiveaxis::machine::face_axes(m.home()).map(|a| a.letter().to_string()),
        swing_length: m.swing_length(),
    })
}

/// The tool direction `(i, j, k)` in workpiece coordinates at the commands `k`, `m` (degrees),
/// from the machine's nominal chain.
#[wasm_bindgen(js_name = toolVector, unchecked_return_type = "number[]")]
pub fn tool_vector(
    #[wasm_bindgen(unchecked_param_type = "ToolVectorInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let i = ToolVectorInput::from_value(&json(&value)?, "").map_err(js_error)?;
    let model = i.machine.build().map_err(js_error)?;
    let q = model.positions(i.k, i.m);
    let pose = model
        .nominal()
        .tool_pose(&q, false, &fiveaxis::chain::Setup::None)
        .map_err(js_error)?;
    output(&pose.axis.iter().copied().collect::<Vec<f64>>())
}

/// K and M commands, degrees.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct AxisPair {
    /// K, degrees.
    pub k: f64,
    /// M, degrees.
    pub m: f64,
}

/// One solution of [`machine_inverse`].
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct InverseSolution {
    /// K, degrees (written in the travel when a turn fits).
    pub k: f64,
    /// M, degrees.
    pub m: f64,
    /// Within the travel of both axes.
    pub in_travel: bool,
    /// The one the rule picks (`chosen` of the result).
    pub chosen: bool,
}

/// Result of [`machine_inverse`].
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct InverseResult {
    /// Every orientation solution (two, or one at a singular orientation), degrees.
    pub solutions: Vec<InverseSolution>,
    /// The one the rule picks within the travel; null when none is within it.
    pub chosen: Option<AxisPair>,
    /// Why none was chosen (the travel), or null.
    pub message: Option<String>,
    /// The tool lies along K: K is arbitrary (kept at the previous value).
    pub singular: bool,
    /// Angle between the tool vector and the nearer of ±K, degrees.
    pub pole_angle: f64,
}

/// The rotary commands that give a tool direction on this machine: every solution, whether it is
/// within the travel, and the one the rule picks (nearest `previous` by default).
#[wasm_bindgen(js_name = machineInverse, unchecked_return_type = "InverseResult")]
pub fn machine_inverse(
    #[wasm_bindgen(unchecked_param_type = "InverseInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let i = InverseInput::from_value(&json(&value)?, "").map_err(js_error)?;
    let model = i.machine.build().map_err(js_error)?;
    let v = nalgebra::Vector3::new(i.vector[0], i.vector[1], i.vector[2]);
    let previous = i.previous.as_ref().map(|p| [p.k, p.m]);
    let o = model
        .orientations(&v, i.rule, previous)
        .map_err(|e| js_error(fiveaxis::Error::field("vector", e.message)))?;
    let deg = |x: f64| x.to_degrees();
    output(&InverseResult {
        solutions: o
            .solutions
            .iter()
            .enumerate()
            .map(|(i, c)| InverseSolution {
                k: deg(c.k),
                m: deg(c.m),
                in_travel: c.in_travel,
                chosen: o.chosen == Some(i),
            })
            .collect(),
        chosen: o.chosen.map(|i| AxisPair {
            k: deg(o.solutions[i].k),
            m: deg(o.solutions[i].m),
        }),
        message: o.unreachable,
        singular: o.singular,
        pole_angle: deg(o.pole_angle),
    })
}
