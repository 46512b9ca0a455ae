//! The machine's own exports: its drawing and axes in words, the tool direction at a pose, the
//! inverse kinematics of a tool direction within the travel, and the twelve rotary-axis types.

use super::schematic::{schematic, Schematic};
use super::{face_axes, AxisInfo, InverseInput, Orientations, SchematicInput, ToolVectorInput};
use crate::chain::Setup;
use crate::edge::Checked;
use crate::rotary::{Group, RotaryType};
use crate::{Error, Result};
use nalgebra::Vector3;
use serde::Serialize;

impl Checked for SchematicInput {}
impl Checked for ToolVectorInput {}
impl Checked for InverseInput {}

/// The drawing of a machine and what its axes are.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct MachineDrawing {
    /// The drawing at the pose asked for (mm, unit vectors; machine coordinates).
    pub drawing: Schematic,
    /// The axes in chain order with their roles, in words.
    pub axes: Vec<AxisInfo>,
    /// Letter of K.
    pub k: char,
    /// Letter of M.
    pub m: char,
    /// The spindle direction at zero.
    pub home: char,
    /// "I" or "II".
    pub group: Group,
    /// The face's axes (the test pieces lie in them): `[u, v, n]` letters.
    pub face: [char; 3],
    /// The distance the nonlinear study uses for `L` when none is given, mm (null: none).
    pub swing_length: Option<f64>,
}

/// The machine drawn from its chain at the commands `k`, `m`, and its axes in words: so that the
/// user can see that the machine entered is theirs.
pub fn drawing(i: &SchematicInput) -> Result<MachineDrawing> {
    let m = &i.machine;
    Ok(MachineDrawing {
        drawing: schematic(m, i.k, i.m, i.standoff)?,
        axes: m.axes(),
        k: m.k().letter(),
        m: m.m().letter(),
        home: m.home().letter(),
        group: m.rotary_type.group(),
        face: face_axes(m.home()).map(|a| a.letter()),
        swing_length: m.swing_length(),
    })
}

/// The tool direction `(i, j, k)` in workpiece coordinates at the commands `k`, `m`, from the
/// machine's nominal chain (a unit vector).
pub fn tool_vector(i: &ToolVectorInput) -> Result<[f64; 3]> {
    let model = i.machine.build()?;
    let q = model.positions(i.k, i.m);
    let pose = model.nominal().tool_pose(&q, false, &Setup::None)?;
    Ok([pose.axis[0], pose.axis[1], pose.axis[2]])
}

/// Every orientation solution of a tool direction, whether each is within the travel, and the
/// one the rule picks (nearest `previous` by default); a degenerate vector is refused on
/// `vector`.
pub fn inverse(i: &InverseInput) -> Result<Orientations> {
    let model = i.machine.build()?;
    let v = Vector3::new(i.vector[0], i.vector[1], i.vector[2]);
    let previous = i.previous.as_ref().map(|p| [p.k, p.m]);
    model
        .orientations(&v, i.rule, previous)
        .map_err(|e| Error::field("vector", e.message))
}

/// One of the twelve rotary-axis types.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct RotaryTypeInfo {
    /// "CAZ" …
    pub name: String,
    /// Group I or II.
    pub group: Group,
    /// K's letter.
    pub k: char,
    /// M's letter.
    pub m: char,
    /// The spindle direction at zero.
    pub home: char,
}

/// The twelve rotary-axis types with their group and axes, in the engine's order.
pub fn rotary_types(_: &()) -> Result<Vec<RotaryTypeInfo>> {
    Ok(RotaryType::ALL
        .iter()
        .map(|t| RotaryTypeInfo {
            name: t.name(),
            group: t.group(),
            k: t.k.letter(),
            m: t.m.letter(),
            home: t.home.letter(),
        })
        .collect())
}
