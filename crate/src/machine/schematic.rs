//! A drawing of the machine from its chain: where each axis sits and points, the table, the
//! spindle and the tool, at a chosen pose of the rotary axes, in machine (bed) coordinates, mm.
//! The page draws it so the user can see that the machine entered is the machine they have.

use super::{AxisInfo, Machine, MachineKind};
use crate::chain::Setup;
use crate::error::Result;
use nalgebra::{Point3, Vector3};
use serde::Serialize;

/// One axis of the drawing.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct DrawnAxis {
    /// The axis and what it does.
    #[serde(flatten)]
    pub axis: AxisInfo,
    /// A point on the axis (a rotary axis's line passes through it), mm.
    pub origin: [f64; 3],
    /// Its direction (unit).
    pub direction: [f64; 3],
}

/// The machine at one pose, for a drawing (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Schematic {
    /// The axes in chain order: table side from the bed up, then spindle side.
    pub axes: Vec<DrawnAxis>,
    /// Centre of the table surface, mm.
    pub table_centre: [f64; 3],
    /// The table's two in-plane directions and its normal (unit vectors, as turned by the
    /// table's rotary axes).
    pub table_frame: [[f64; 3]; 3],
    /// Tool tip, mm.
    pub tool_tip: [f64; 3],
    /// Spindle nose (tool tip plus the tool length along the tool), mm.
    pub spindle_nose: [f64; 3],
    /// The tool direction, tip towards the spindle (unit).
    pub tool_direction: [f64; 3],
    /// A length that fits the drawing (the largest distance in it, at least 100 mm).
    pub scale: f64,
}

/// The machine's drawing with the rotary axes at `k`, `m` (commands, rad) and the tool tip
/// `standoff` mm from the table centre along the tool (linear axes from the inverse kinematics).
pub fn schematic(machine: &Machine, k: f64, m: f64, standoff: f64) -> Result<Schematic> {
    let model = machine.build()?;
    let chain = model.nominal();
    let mut q = model.positions(k, m);
    let pose = chain.tool_pose(&q, false, &Setup::None)?;
    q = chain.solve_linear(&(pose.axis * standoff), &q)?;
    let frames = chain.axis_frames(&q)?;
    let (fw, ft) = chain.frames(&q, false)?;
    let axes: Vec<DrawnAxis> = machine
        .axes_of(chain)
        .into_iter()
        .zip(&frames)
        .zip(chain.links())
        .map(|((axis, f), (_, link))| DrawnAxis {
            axis,
            origin: f.translation.vector.into(),
            direction: (f.rotation * link.joint.axis().unit()).into(),
        })
        .collect();
    let table_centre = (fw * Point3::origin()).coords;
    let [u, v, n] = machine.face_frame();
    let tool_tip = (ft * Point3::origin()).coords;
    let tool_direction = ft.rotation * machine.home().unit();
    let nose = tool_tip + tool_direction * machine.geometry.tool_length;
    let mut scale: f64 = 100.0;
    for p in frames
        .iter()
        .map(|f| f.translation.vector)
        .chain([table_centre, tool_tip, nose])
    {
        for o in [table_centre, tool_tip] {
            scale = scale.max((p - o).norm());
        }
    }
    if machine.kind != MachineKind::TableTable {
        scale = scale.max(machine.geometry.pivot_length + machine.geometry.tool_length);
    }
    let arr = |v: Vector3<f64>| -> [f64; 3] { v.into() };
    Ok(Schematic {
        axes,
        table_centre: arr(table_centre),
        table_frame: [
            arr(fw.rotation * u),
            arr(fw.rotation * v),
            arr(fw.rotation * n),
        ],
        tool_tip: arr(tool_tip),
        spindle_nose: arr(nose),
        tool_direction: arr(tool_direction),
        scale,
    })
}
