//! The machine, entered once for every study: its kind, its rotary-axis type, how its linear axes
//! are stacked, the geometry that matters for its errors, the travel of its rotary axes and its
//! geometric errors ([`errors`]). [`Machine::build`] turns it into the one kinematic chain
//! ([`crate::chain`]) that every study computes with, and gives the inverse kinematics within the
//! travel ([`Model::inverse`]).
//!
//! # Layout
//! * **Kind** ([`MachineKind`]): which rotary axes carry the workpiece. With the type `KMH`
//!   ([`RotaryType`]; K the rotary axis nearer the workpiece, M the one nearer the tool, H the
//!   spindle direction at zero): *table-table*, M on the bed carries K, K carries the table;
//!   *head-table*, K is the table axis, M the head axis carrying the spindle; *head-head*, K on
//!   the ram carries M, M carries the spindle.
//! * **Linear axes** ([`LinearLayout`]): which of X, Y, Z move the table (they sit under the
//!   table's rotary axes) and which the spindle (under the head's), in the order they are
//!   stacked from the bed.
//!
//! # MachineGeometry (all axes at zero, machine coordinates, mm)
//! The machine origin is the *rotary centre*: on the bed-side table axis (M for table-table, K
//! for head-table) or, for head-head, where the workpiece is set. Chain branches
//! (`crate::chain`'s notation):
//! * table-table: workpiece branch `[table linear axes…, M, K]`, K's axis at
//!   `rotaryOffset·e₃` from M's (`e₃` the third direction, perpendicular to both axes);
//!   tool branch `[spindle linear axes…]`, tool tip `toolLength` from the spindle nose along
//!   `−e_H`.
//! * head-table: `[table linear axes…, K]`; `[spindle linear axes…, M]`, the tip
//!   `pivotLength + toolLength` from M's axis along `−e_H`.
//! * head-head: `[table linear axes…]`; `[spindle linear axes…, K, M]`, M's axis at
//!   `rotaryOffset·e₃` from K's, the tip as for head-table.
//!
//! The table surface (the workpiece origin of the chain; studies add the workpiece's place on
//! it) is `tableHeight·e_H` from the machine origin. Every frame is nominally parallel to the
//! machine axes.
//!
//! # Signs
//! ISO 841: a positive command moves the tool positively relative to the workpiece, so axes on
//! the table side move their frame by `−q` ([`crate::chain::Link::on_table`]). A rotary axis
//! whose control turns the other way (Chanal et al.'s C: `tan C = −R·y/R·x`) is marked
//! `reversed`. With these signs the tool orientation in workpiece coordinates is
//! `R_K(θk)·R_M(θm)·e_H` with `θ = ±q` (`−q` for a reversed axis), for every kind.
//!
//! # Inverse kinematics within the travel ([`Model::inverse`])
//! The two orientation solutions of the type (one at a singular orientation, tool along K,
//! where K keeps its previous value, 0 without one) are written in the travel of each axis:
//! without a previous pose in `[0°, 360°)` if that lies within the travel, else nearest 0°;
//! with one, nearest its value. Solutions outside the travel are dropped; if none is left the
//! pose is reported unreachable with the angles it would need. Of the rest, [`BranchRule`]
//! picks: the smallest tilt `|M|`, and of two equal tilts the one with `M ≥ 0` (Li et al.'s
//! Table 2, Chanal et al.'s `B ≥ 0`); or the one nearest the previous pose. The linear axes
//! then follow exactly ([`Chain::solve_linear`]).

pub mod api;
pub mod errors;
pub mod follow;
pub mod motions;
pub mod schematic;

use crate::chain::{Chain, Joint, Link, RotaryLayout};
use crate::error::{Error, Result};
use crate::geometry::Axis;
use crate::rotary::{Pose, RotaryAxis, RotaryType};
use crate::schema::{self, DefaultValue, Inputs, Kind, Quantity};
use errors::{ErrorDef, ErrorValues, TABLE};
use motions::{ErrorMotions, MOTIONS};
use nalgebra::Vector3;
use serde::Serialize;
use std::f64::consts::TAU;

/// Tolerance on the travel limits, rad: an angle this far outside still counts as inside.
pub const TRAVEL_TOLERANCE: f64 = 1e-9;

crate::choices! {
    /// Which rotary axes carry the workpiece (module docs).
    pub enum MachineKind {
        /// Both rotary axes in the table.
        TableTable = "table-table" {
            label: "Table-table: both rotary axes in the table",
            help: "A tilting rotary table (trunnion): M on the bed tilts, K on it turns the workpiece; the spindle keeps its direction.",
        },
        /// K in the table, M in the head.
        HeadTable = "head-table" {
            label: "Head-table: one rotary axis in the table, one in the head",
            help: "A rotary table (K) carries the workpiece, a swivelling head (M) tilts the spindle.",
        },
        /// Both rotary axes in the head.
        HeadHead = "head-head" {
            label: "Head-head: both rotary axes in the spindle head",
            help: "A fork or nutating head: K on the ram carries M, M tilts the spindle; the table does not turn.",
        },
    }
}

crate::choices! {
    /// Which linear axes move the table and which the spindle, stacked from the bed.
    pub enum LinearLayout {
        /// X, Y, Z all on the spindle side.
        SpindleXyz = "spindle-xyz" {
            label: "X, Y and Z move the spindle",
            help: "Gantry or moving-column machine: the table stands on the bed.",
        },
        /// Y under the table, X and Z on the spindle side.
        TableY = "table-y" {
            label: "Y moves the table; X and Z the spindle",
            help: "Chanal et al.'s machine: the table slides in Y, the column in X, the head in Z.",
        },
        /// X under the table, Y and Z on the spindle side.
        TableX = "table-x" {
            label: "X moves the table; Y and Z the spindle",
            help: "Travelling table in X, the column carries Y and Z.",
        },
        /// Y then X under the table (a cross table), Z on the spindle side.
        TableXy = "table-xy" {
            label: "X and Y move the table (cross table); Z the spindle",
            help: "C-frame vertical machining centre: Y on the bed, X on Y, the head moves in Z.",
        },
        /// Z under the table, X and Y on the spindle side.
        TableZ = "table-z" {
            label: "Z moves the table; X and Y the spindle",
            help: "Horizontal machining centre: the table moves towards the spindle.",
        },
    }
}

impl LinearLayout {
    /// The linear axes under the table and under the spindle, each from the bed outwards.
    pub fn split(self) -> (&'static [Axis], &'static [Axis]) {
        use Axis::{X, Y, Z};
        match self {
            LinearLayout::SpindleXyz => (&[], &[X, Y, Z]),
            LinearLayout::TableY => (&[Y], &[X, Z]),
            LinearLayout::TableX => (&[X], &[Y, Z]),
            LinearLayout::TableXy => (&[Y, X], &[Z]),
            LinearLayout::TableZ => (&[Z], &[X, Y]),
        }
    }
}

crate::choices! {
    /// Which of the inverse-kinematics solutions a study uses (module docs).
    pub enum BranchRule {
        /// The smallest tilt; of two equal tilts the one with M ≥ 0.
        SmallestTilt = "smallest-tilt" {
            label: "Smallest tilt, M ≥ 0 first",
            help: "Of the two ways to reach a tool direction, the one that tilts least; where both tilt alike, the one with the tilting axis at 0° or above (the papers' choice).",
        },
        /// Nearest the previous pose.
        Nearest = "nearest" {
            label: "Nearest the previous pose",
            help: "Along a path, the solution that moves the rotary axes least from the previous point.",
        },
    }
}

crate::inputs! {
    /// The geometry that matters for the errors, mm (module docs).
    pub struct MachineGeometry {
        /// Distance between the two rotary axes along their common perpendicular, mm.
        pub rotary_offset: f64 = "rotaryOffset" optional {
            label: "Offset between the rotary axes",
            help: "How far K's axis lies from M's along the direction square to both (X for B and C, Y for A and C, Z for A and B); 0: they intersect.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(0.0),
            group: "Geometry",
            kinds: &["table-table", "head-head"],
        },
        /// Table surface from the machine origin along the spindle direction, mm.
        pub table_height: f64 = "tableHeight" optional {
            label: "Table surface above the rotary centre",
            help: "Distance of the table surface from the machine origin (the rotary centre of a rotary table) towards the spindle at zero; negative below it.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(100.0),
            group: "Geometry",
        },
        /// Head's last rotary axis to the spindle nose, mm.
        pub pivot_length: f64 = "pivotLength" optional {
            label: "Head pivot length",
            help: "From the axis of the head's tilting axis (M) to the spindle nose (gauge line), along the spindle.",
            kind: schema::number(Quantity::Length, 0.0, 5000.0),
            default: DefaultValue::Num(300.0),
            group: "Geometry",
            kinds: &["head-table", "head-head"],
        },
        /// Spindle nose to tool tip, mm.
        pub tool_length: f64 = "toolLength" optional {
            label: "Tool length",
            help: "From the spindle nose (gauge line) to the tool tip.",
            kind: schema::number(Quantity::Length, 0.0, 2000.0),
            default: DefaultValue::Num(100.0),
            group: "Geometry",
        },
    }
}

crate::inputs! {
    /// RotaryTravel and sense of rotation of the two rotary axes (angles in degrees at the edge, radians in Rust).
    pub struct RotaryTravel {
        /// Lowest position of K.
        pub k_from: f64 = "kFrom" optional {
            label: "{K} travel from",
            help: "Lowest position the control accepts for K (the rotary axis nearer the workpiece).",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(-360.0),
            group: "Rotary axes",
        },
        /// Highest position of K.
        pub k_to: f64 = "kTo" optional {
            label: "{K} travel to",
            help: "Highest position of K; a rotary table that turns endlessly: ±360° is enough.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(360.0),
            group: "Rotary axes",
        },
        /// K turns without a travel limit (a rotary table).
        pub k_continuous: bool = "kContinuous" optional {
            label: "{K} turns without limit (continuous)",
            help: "Tick for a rotary table that turns endlessly: the control then takes whole turns as the program says, and the travel limits of K above are not used.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(false),
            group: "Rotary axes",
        },
        /// K moves the shorter way round to a commanded angle (rollover).
        pub k_rollover: bool = "kRollover" optional {
            label: "{K} takes the shorter way round (rollover)",
            help: "Tick when the control moves K the shorter way to a commanded angle (rotary rollover on Haas and Fanuc, M126 on Heidenhain, a modulo axis on Siemens): a program's K commands are then read modulo 360°. Unticked, the control turns as far as the numbers say.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(false),
            group: "Rotary axes",
        },
        /// K turns against ISO 841.
        pub k_reversed: bool = "kReversed" optional {
            label: "{K} turns the other way (not ISO 841)",
            help: "Tick when a positive K command turns the axis against ISO 841's sense (the tool moving positively round the workpiece), as on Chanal et al.'s C table.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(false),
            group: "Rotary axes",
        },
        /// Lowest position of M.
        pub m_from: f64 = "mFrom" optional {
            label: "{M} travel from",
            help: "Lowest position of M (the rotary axis nearer the tool; the tilting axis).",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(-120.0),
            group: "Rotary axes",
        },
        /// Highest position of M.
        pub m_to: f64 = "mTo" optional {
            label: "{M} travel to",
            help: "Highest position of M.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(120.0),
            group: "Rotary axes",
        },
        /// M turns against ISO 841.
        pub m_reversed: bool = "mReversed" optional {
            label: "{M} turns the other way (not ISO 841)",
            help: "Tick when a positive M command turns the axis against ISO 841's sense.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(false),
            group: "Rotary axes",
        },
    }
}

crate::inputs! {
    /// The machine: entered once, used by every study (module docs).
    pub struct Machine {
        /// Which rotary axes carry the workpiece.
        pub kind: MachineKind = "kind" optional {
            label: "Machine kind",
            help: "Where the two rotary axes are: both in the table, one in each, or both in the head.",
            kind: Kind::Choice(MachineKind::CHOICES),
            default: DefaultValue::Str("table-table"),
            group: "Machine",
        },
        /// The rotary-axis type KMH.
        pub rotary_type: RotaryType = "type" optional {
            label: "Rotary axes and spindle direction",
            help: "The type code KMH of Geng et al. K: the rotary axis nearer the workpiece, M: the one nearer the tool, H: the spindle direction with both at zero. A/C trunnion with a vertical spindle: CAZ; B/C tilting table: CBZ.",
            kind: Kind::Choice(&RotaryType::CHOICES),
            default: DefaultValue::Str("CBZ"),
            group: "Machine",
        },
        /// The linear axes.
        pub linear: LinearLayout = "linear" optional {
            label: "Linear axes",
            help: "Which linear axes move the table and which the spindle: it decides where the squareness errors act.",
            kind: Kind::Choice(LinearLayout::CHOICES),
            default: DefaultValue::Str("spindle-xyz"),
            group: "Machine",
        },
        /// MachineGeometry, mm.
        pub geometry: MachineGeometry = "geometry" optional {
            label: "Geometry",
            kind: Kind::Object(MachineGeometry::FIELDS),
            default: DefaultValue::Empty,
        },
        /// RotaryTravel and sense of the rotary axes.
        pub rotary: RotaryTravel = "rotary" optional {
            label: "Rotary axes",
            kind: Kind::Object(RotaryTravel::FIELDS),
            default: DefaultValue::Empty,
        },
        /// The geometric errors by ISO 230-1 name (mm; degrees at the edge, rad inside).
        pub errors: ErrorValues = "errors" optional {
            label: "Geometric errors (ISO 230-1)",
            help: "The location errors of the machine's axes: positions in mm, orientations in degrees; those not given are zero.",
            kind: errors::VALUES,
            default: DefaultValue::Empty,
            group: "Errors",
        },
        /// The error motions by ISO 230-1 name: constants, polynomials or tables against the
        /// axis position (engine units inside).
        pub motions: ErrorMotions = "motions" optional {
            label: "Error motions (ISO 230-1)",
            help: "The errors that change along an axis (positioning, straightness, roll, pitch, yaw; radial, axial, tilt and angular error motions of the rotary axes): each a constant, a polynomial in the position or a measured table.",
            kind: motions::KIND,
            default: DefaultValue::Empty,
            group: "Error motions",
        },
    }
}

crate::inputs! {
    /// Rotary-axis commands, degrees at the edge.
    pub struct AxisAngles {
        /// K.
        pub k: f64 = "k" {
            label: "{K}", kind: schema::number(Quantity::Angle, -3600.0, 3600.0), shown: false,
        },
        /// M.
        pub m: f64 = "m" {
            label: "{M}", kind: schema::number(Quantity::Angle, -3600.0, 3600.0), shown: false,
        },
    }
}

crate::inputs! {
    /// The machine at a pose, for its drawing ([`schematic::schematic`]).
    pub struct SchematicInput {
        /// The machine.
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// K's command.
        pub k: f64 = "k" optional {
            label: "{K} in the drawing",
            help: "Where K stands in the drawing of the machine.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0),
            group: "Drawing",
        },
        /// M's command.
        pub m: f64 = "m" optional {
            label: "{M} in the drawing",
            help: "Where M stands in the drawing; tilt it to see which parts move with it.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0),
            group: "Drawing",
        },
        /// Tool tip above the table centre, mm.
        pub standoff: f64 = "standoff" optional {
            label: "Tool tip from the table centre",
            kind: schema::number(Quantity::Length, 0.0, 5000.0),
            default: DefaultValue::Num(30.0),
            shown: false,
        },
    }
}

crate::inputs! {
    /// The tool direction at given commands.
    pub struct ToolVectorInput {
        /// The machine.
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// K's command.
        pub k: f64 = "k" {
            label: "{K}", kind: schema::number(Quantity::Angle, -3600.0, 3600.0), shown: false,
        },
        /// M's command.
        pub m: f64 = "m" {
            label: "{M}", kind: schema::number(Quantity::Angle, -3600.0, 3600.0), shown: false,
        },
    }
}

crate::inputs! {
    /// Inverse kinematics of a tool direction ([`Model::inverse`]).
    pub struct InverseInput {
        /// The machine.
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// Tool direction `(i, j, k)` in workpiece coordinates (any length).
        pub vector: Vec<f64> = "vector" {
            label: "Tool vector (i, j, k)",
            help: "Workpiece coordinates, from the tip towards the spindle; any length.",
            kind: Kind::NumberList { quantity: Quantity::Number, min: -1e6, max: 1e6, min_len: 3, max_len: 3, nonzero: false },
            default: DefaultValue::Str("0.5, 0, 0.8660254"),
            group: "Tool vector → axis angles",
        },
        /// Which solution.
        pub rule: BranchRule = "rule" optional {
            label: "Solution", kind: Kind::Choice(BranchRule::CHOICES),
            default: DefaultValue::Str("nearest"), shown: false,
        },
        /// The pose to continue from (commands, degrees at the edge).
        pub previous: Option<AxisAngles> = "previous" optional {
            label: "Previous pose", kind: Kind::Object(AxisAngles::FIELDS), shown: false,
        },
    }
}

/// An axis of a built machine, in chain order, for descriptions and the schematic.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct AxisInfo {
    /// `"X"` … `"C"`.
    pub name: String,
    /// `"linear"` or `"rotary"`.
    pub motion: &'static str,
    /// `"table"` or `"spindle"`.
    pub side: &'static str,
    /// `"K"`, `"M"` or `""` for a linear axis.
    pub role: &'static str,
    /// What it is on this machine, in words.
    pub description: String,
}

impl Machine {
    /// The machine of the defaults: a B/C tilting table (table-table CBZ), X Y Z on the spindle,
    /// no errors.
    pub fn standard() -> Result<Self> {
        Self::from_value(&serde_json::Value::Null, "machine")
    }

    /// K's axis letter.
    pub fn k(&self) -> RotaryAxis {
        self.rotary_type.k
    }

    /// M's axis letter.
    pub fn m(&self) -> RotaryAxis {
        self.rotary_type.m
    }

    /// The spindle direction at zero, `e_H`.
    pub fn home(&self) -> Axis {
        self.rotary_type.home
    }

    /// The letters of the machine's axes: the two rotary axes and X, Y, Z.
    pub fn has_axis(&self, letter: char) -> bool {
        matches!(letter, 'X' | 'Y' | 'Z')
            || letter == self.k().letter()
            || letter == self.m().letter()
    }

    /// The entries of the error table that belong to this machine's axes, in table order.
    pub fn error_defs(&self) -> Vec<&'static ErrorDef> {
        TABLE.iter().filter(|d| self.has_axis(d.axis)).collect()
    }

    /// The distance of the tool tip from the axis it swings about, mm: the nonlinear study's `L`
    /// for a head (pivot length plus tool length); for a table-table machine the distance of the
    /// table surface's centre from the rotary centre. `None` where that is zero.
    pub fn swing_length(&self) -> Option<f64> {
        let g = &self.geometry;
        let l = match self.kind {
            MachineKind::HeadHead | MachineKind::HeadTable => g.pivot_length + g.tool_length,
            MachineKind::TableTable => g.table_height.hypot(g.rotary_offset),
        };
        (l >= 1e-9).then_some(l)
    }

    /// Checks what the schema cannot: the travel ranges and that every error belongs to one of
    /// the machine's axes. `path` is the machine's path (`"machine"`).
    pub fn validate(&self, path: &str) -> Result<()> {
        let t = &self.rotary;
        for (name, from, to, letter) in [
            ("k", t.k_from, t.k_to, self.k().letter()),
            ("m", t.m_from, t.m_to, self.m().letter()),
        ] {
            if from >= to {
                let deg = |x: f64| format!("{}°", (x.to_degrees() * 1e9).round() / 1e9);
                return Err(Error::field(
                    schema::join(path, &format!("rotary.{name}To")),
                    format!(
                        "must be above where the travel of {letter} starts ({} to {})",
                        deg(from),
                        deg(to)
                    ),
                ));
            }
        }
        for name in self.errors.0.keys() {
            let def = errors::find(name).ok_or_else(|| {
                Error::field(
                    schema::join(path, &format!("errors.{name}")),
                    "unknown error name",
                )
            })?;
            if !self.has_axis(def.axis) {
                return Err(Error::field(
                    schema::join(path, &format!("errors.{name}")),
                    format!(
                        "this machine has no {} axis (its axes are {}, {}, X, Y, Z)",
                        def.axis,
                        self.k().letter(),
                        self.m().letter()
                    ),
                ));
            }
        }
        for name in self.motions.0.keys() {
            let p = schema::join(path, &format!("motions.{name}"));
            let def = motions::find(name).ok_or_else(|| motions::unknown(&p, name))?;
            if !self.has_axis(def.axis) {
                return Err(Error::field(
                    p,
                    format!(
                        "this machine has no {} axis (its axes are {}, {}, X, Y, Z)",
                        def.axis,
                        self.k().letter(),
                        self.m().letter()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The same machine without errors (what the control knows of it).
    pub fn without_errors(&self) -> Machine {
        Machine {
            errors: ErrorValues::none(),
            motions: ErrorMotions::default(),
            ..self.clone()
        }
    }

    /// The error motions that belong to this machine's axes, in table order.
    pub fn motion_defs(&self) -> Vec<&'static ErrorDef> {
        MOTIONS.iter().filter(|d| self.has_axis(d.axis)).collect()
    }

    /// The machine's axes in chain order (module docs), with what each does.
    pub fn axes(&self) -> Vec<AxisInfo> {
        self.axes_of(&self.nominal_chain())
    }

    /// [`Machine::axes`] read from the machine's nominal `chain`: each branch from its base
    /// (the bed, the ram) to its end (the workpiece, the spindle).
    fn axes_of(&self, chain: &Chain) -> Vec<AxisInfo> {
        let k = self.k().letter().to_string();
        let mut out = Vec::with_capacity(chain.len());
        for (links, side, what, base, end) in [
            (
                &chain.work,
                "table",
                "table axis",
                "the bed",
                "the workpiece",
            ),
            (
                &chain.tool,
                "spindle",
                "head axis",
                "the ram",
                "the spindle",
            ),
        ] {
            let rotary: Vec<&str> = links
                .iter()
                .filter(|l| matches!(l.joint, Joint::Rotary(_)))
                .map(|l| l.name.as_str())
                .collect();
            for l in links {
                let name = l.name.clone();
                let Some(i) = rotary.iter().position(|r| *r == name) else {
                    out.push(AxisInfo {
                        description: format!("{name}: linear axis, moves the {side}"),
                        name,
                        motion: "linear",
                        side,
                        role: "",
                    });
                    continue;
                };
                let role = if name == k { "K" } else { "M" };
                // "on" only where the branch has two rotary axes: the first sits on the base.
                let on = match (rotary.len(), i) {
                    (2, 0) => format!(" on {base}"),
                    (2, _) => format!(" on {}", rotary[0]),
                    _ => String::new(),
                };
                let carries = rotary.get(i + 1).copied().unwrap_or(end);
                out.push(AxisInfo {
                    description: format!("{name} ({role}): {what}{on}, carries {carries}"),
                    name,
                    motion: "rotary",
                    side,
                    role,
                });
            }
        }
        out
    }

    /// The nominal chain (no errors), module docs.
    pub fn nominal_chain(&self) -> Chain {
        let t = self.rotary_type;
        let home = t.home.unit();
        let third = t.k.axis().third(t.m.axis()).unit();
        let g = &self.geometry;
        let (table, spindle) = self.linear.split();
        let name = |a: Axis| a.letter().to_string();
        let mut work: Vec<Link> = table
            .iter()
            .map(|&a| Link::linear(&name(a), a).on_table())
            .collect();
        let mut tool: Vec<Link> = spindle.iter().map(|&a| Link::linear(&name(a), a)).collect();
        let rotary = |axis: RotaryAxis, table_side: bool, reversed: bool| {
            let mut l = Link::rotary(&axis.letter().to_string(), axis.axis());
            if table_side {
                l = l.on_table();
            }
            if reversed {
                l.sign = -l.sign;
            }
            l
        };
        let (kr, mr) = (self.rotary.k_reversed, self.rotary.m_reversed);
        let head = g.pivot_length + g.tool_length;
        let tip = match self.kind {
            MachineKind::TableTable => {
                work.push(rotary(t.m, true, mr));
                work.push(rotary(t.k, true, kr).at(third * g.rotary_offset));
                -home * g.tool_length
            }
            MachineKind::HeadTable => {
                work.push(rotary(t.k, true, kr));
                tool.push(rotary(t.m, false, mr));
                -home * head
            }
            MachineKind::HeadHead => {
                tool.push(rotary(t.k, false, kr));
                tool.push(rotary(t.m, false, mr).at(third * g.rotary_offset));
                -home * head
            }
        };
        Chain {
            work,
            tool,
            work_origin: home * g.table_height,
            tool_tip: tip,
            tool_axis: t.home,
        }
    }

    /// Validates the machine and builds its chain with the errors applied.
    pub fn build(&self) -> Result<Model> {
        self.validate("machine")?;
        let nominal = self.nominal_chain();
        let mut chain = nominal.clone();
        for def in self.error_defs() {
            let link = link_of(&chain, def)?;
            chain
                .link_mut(link)
                .location
                .set(def.component, self.errors.get(def.name));
        }
        for link in 0..chain.len() {
            let axis = chain.link(link).name.chars().next().unwrap_or(' ');
            if let Some(list) = self.motions.of_axis(axis) {
                chain.link_mut(link).motion = Some(std::sync::Arc::new(move |p| {
                    ErrorMotions::rigid(&list, p, axis)
                }));
            }
        }
        let layout = chain.rotary_type()?;
        Ok(Model {
            machine: self.clone(),
            chain,
            nominal,
            layout,
        })
    }

    /// The face frame of the spindle direction: `(u, v, n)` with `n = e_H` and `u, v` the next
    /// two machine axes in cyclic order (X, Y for a vertical spindle), right-handed. Studies lay
    /// their test pieces out in it: a face square to the spindle at zero.
    pub fn face_frame(&self) -> [Vector3<f64>; 3] {
        face_frame(self.home())
    }
}

/// The chain index of the axis error `def` belongs to.
fn link_of(chain: &Chain, def: &ErrorDef) -> Result<usize> {
    chain.index_of(&def.axis.to_string()).ok_or_else(|| {
        Error::field(
            format!("errors.{}", def.name),
            format!("this machine has no {} axis", def.axis),
        )
    })
}

/// The chain indices of the linear axes X, Y, Z (an error naming `machine.linear` when one is
/// missing).
pub fn linear_axes(chain: &Chain) -> Result<[usize; 3]> {
    let mut out = [0; 3];
    for (k, letter) in ["X", "Y", "Z"].iter().enumerate() {
        out[k] = chain
            .index_of(letter)
            .filter(|&i| matches!(chain.link(i).joint, Joint::Linear(_)))
            .ok_or_else(|| Error::field("machine.linear", format!("no {letter} axis")))?;
    }
    Ok(out)
}

/// The face frame of a spindle direction (see [`Machine::face_frame`]).
pub fn face_frame(home: Axis) -> [Vector3<f64>; 3] {
    face_axes(home).map(Axis::unit)
}

/// The machine axes of the face frame of a spindle direction: the next two in cyclic order,
/// then the spindle's own (X, Y, Z for a vertical spindle).
pub fn face_axes(home: Axis) -> [Axis; 3] {
    let i = home.index();
    [Axis::ALL[(i + 1) % 3], Axis::ALL[(i + 2) % 3], home]
}

/// A machine ready to compute with: its chain (errors applied) and where K and M sit in it.
#[derive(Debug, Clone)]
pub struct Model {
    /// The machine it was built from.
    pub machine: Machine,
    /// The chain with the machine's errors.
    pub chain: Chain,
    /// The same chain without errors (the control's model of the machine), [`Model::nominal`].
    nominal: Chain,
    /// K and M in the chain and the factors `θ = f·q`.
    pub layout: RotaryLayout,
}

/// One orientation solution of [`Model::orientations`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Candidate {
    /// K, degrees (radians in Rust), written in its travel when a turn fits.
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M, degrees (radians in Rust), likewise.
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m: f64,
    /// Both axes are within their travel.
    pub in_travel: bool,
}

/// What [`Model::orientations`] finds.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Orientations {
    /// Every solution of the type (two, or one at a singular orientation).
    pub solutions: Vec<Candidate>,
    /// The solution the rule picks within the travel (index into `solutions`); `None` when none
    /// is within it.
    pub chosen: Option<usize>,
    /// Why none is chosen: the angles needed and the travel.
    pub unreachable: Option<String>,
    /// The tool lies along K: K is arbitrary and was kept.
    pub singular: bool,
    /// Angle between the direction and the nearer of ±K, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub pole_angle: f64,
}

impl Orientations {
    /// The chosen solution, or an error on `field` saying why none is within the travel.
    pub fn pick(&self, field: &str) -> Result<Candidate> {
        self.chosen
            .map(|i| self.solutions[i])
            .ok_or_else(|| Error::field(field, self.unreachable.clone().unwrap_or_default()))
    }
}

/// A pose from [`Model::inverse`].
#[derive(Debug, Clone, PartialEq)]
pub struct Solved {
    /// Axis positions in chain order (mm, rad).
    pub q: Vec<f64>,
    /// The tool lies along K: K is arbitrary and was kept.
    pub singular: bool,
}

impl Model {
    /// The nominal chain (the machine without errors).
    pub fn nominal(&self) -> &Chain {
        &self.nominal
    }

    /// Moves the workpiece origin of both chains by `offset` (mm, in the table frame at zero):
    /// where a study sets its test piece on the table.
    pub fn place_workpiece(&mut self, offset: &Vector3<f64>) {
        self.chain.work_origin += offset;
        self.nominal.work_origin += offset;
    }

    /// Where the sensitivity of error `def` sits in [`Chain::jacobian`]'s output.
    pub fn error_column(&self, def: &ErrorDef) -> Result<usize> {
        Ok(Chain::location_index(
            link_of(&self.chain, def)?,
            def.component,
        ))
    }

    /// The commanded travel `(from, to)` of K and M, rad; `(−∞, ∞)` for a K marked continuous.
    pub fn travel(&self) -> [(f64, f64); 2] {
        let t = &self.machine.rotary;
        let k = if t.k_continuous {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (t.k_from, t.k_to)
        };
        [k, (t.m_from, t.m_to)]
    }

    /// The letters of K and M.
    pub fn letters(&self) -> [char; 2] {
        [self.machine.k().letter(), self.machine.m().letter()]
    }

    /// The K and M commands of chain positions `q`, rad.
    pub fn rotary_of(&self, q: &[f64]) -> [f64; 2] {
        [q[self.layout.k], q[self.layout.m]]
    }

    /// Positions (chain order) with the rotary axes at `k`, `m` (commands, rad) and the linear
    /// axes at zero.
    pub fn positions(&self, k: f64, m: f64) -> Vec<f64> {
        let mut q = vec![0.0; self.chain.len()];
        q[self.layout.k] = k;
        q[self.layout.m] = m;
        q
    }

    /// The rotary commands that give the tool `direction` (workpiece coordinates): every
    /// solution of the type, each written in the travel where a turn fits (module docs), and the
    /// one `rule` picks among those within it (`None` when none is), continuing from the K and M
    /// commands `previous` (rad) when given.
    pub fn orientations(
        &self,
        direction: &Vector3<f64>,
        rule: BranchRule,
        previous: Option<[f64; 2]>,
    ) -> Result<Orientations> {
        let lay = self.layout;
        let prev_pose = previous.map(|[k, m]| Pose::new(lay.k_factor * k, lay.m_factor * m));
        let sol = lay.rtype.inverse(direction, prev_pose)?;
        let [(k_lo, k_hi), (m_lo, m_hi)] = self.travel();
        let solutions: Vec<Candidate> = sol
            .solutions
            .iter()
            .map(|s| {
                let (k, m) = (s.k / lay.k_factor, s.m / lay.m_factor);
                let kf = fit(k, k_lo, k_hi, previous.map(|p| p[0]));
                let mf = fit(m, m_lo, m_hi, previous.map(|p| p[1]));
                Candidate {
                    k: kf.unwrap_or(k),
                    m: mf.unwrap_or(m),
                    in_travel: kf.is_some() && mf.is_some(),
                }
            })
            .collect();
        let reachable = solutions
            .iter()
            .enumerate()
            .filter(|(_, c)| c.in_travel)
            .map(|(i, c)| (i, [c.k, c.m]));
        let chosen = match (rule, previous) {
            (BranchRule::Nearest, Some(p)) => reachable.min_by(|(_, a), (_, b)| {
                let d = |x: &[f64; 2]| (x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2);
                d(a).total_cmp(&d(b))
            }),
            _ => reachable.min_by(|(_, a), (_, b)| {
                let key = |x: &[f64; 2]| {
                    (
                        (x[1].abs() * 1e9).round(),
                        u8::from(x[1] < -1e-12),
                        (x[0].abs() * 1e9).round(),
                    )
                };
                key(a)
                    .partial_cmp(&key(b))
                    .unwrap_or(std::cmp::Ordering::Equal)
            }),
        }
        .map(|(i, _)| i);
        let unreachable = chosen.is_none().then(|| self.unreachable(&sol.solutions));
        Ok(Orientations {
            solutions,
            chosen,
            unreachable,
            singular: sol.singular,
            pole_angle: sol.pole_angle,
        })
    }

    /// Inverse kinematics within the travel (module docs): the positions (chain order) that put
    /// the tool tip at `tip` with the tool along `direction` (workpiece coordinates, nominal
    /// machine), by `rule`, continuing from `previous` (chain order) when given. A pose outside
    /// the travel is an error whose message gives the angles it would need.
    pub fn inverse(
        &self,
        tip: &Vector3<f64>,
        direction: &Vector3<f64>,
        rule: BranchRule,
        previous: Option<&[f64]>,
    ) -> Result<Solved> {
        let lay = self.layout;
        if let Some(p) = previous {
            if p.len() != self.chain.len() {
                return Err(Error::field("previous", "wrong number of axis positions"));
            }
        }
        let o = self.orientations(direction, rule, previous.map(|p| [p[lay.k], p[lay.m]]))?;
        let c = o.pick("")?;
        let mut q = previous.map_or_else(|| vec![0.0; self.chain.len()], <[f64]>::to_vec);
        q[lay.k] = c.k;
        q[lay.m] = c.m;
        let q = self.nominal.solve_linear(tip, &q)?;
        Ok(Solved {
            q,
            singular: o.singular,
        })
    }

    /// Why no solution is within the travel: the angles each needs, and the travel.
    fn unreachable(&self, solutions: &[Pose]) -> String {
        let lay = self.layout;
        let [kl, ml] = self.letters();
        let [(k_lo, k_hi), (m_lo, m_hi)] = self.travel();
        let d = |x: f64| format!("{:.4}°", x.to_degrees()).replace(".0000°", "°");
        let needs: Vec<String> = solutions
            .iter()
            .map(|s| {
                format!(
                    "{kl} = {}, {ml} = {}",
                    d(s.k / lay.k_factor),
                    d(s.m / lay.m_factor)
                )
            })
            .collect();
        let k_travel = if k_lo.is_finite() {
            format!("{kl} travels from {} to {} and {ml}", d(k_lo), d(k_hi))
        } else {
            format!("{kl} turns without limit and {ml} travels")
        };
        format!(
            "outside the travel: this tool direction needs {} (or a whole turn more or less), \
             but {k_travel} from {} to {}",
            needs.join(" or "),
            d(m_lo),
            d(m_hi)
        )
    }
}

/// The angle `a` (rad) plus whole turns within `[lo, hi]` (with [`TRAVEL_TOLERANCE`]): nearest
/// `near` when given; else in `[0, 2π)` if that is within, else nearest 0. `None` when no turn
/// fits. `(−∞, ∞)` is no limit.
pub fn fit(a: f64, lo: f64, hi: f64, near: Option<f64>) -> Option<f64> {
    if lo == f64::NEG_INFINITY && hi == f64::INFINITY {
        // No limit: nearest `near`, else in [0, 2π).
        return Some(match near {
            Some(p) => a + TAU * ((p - a) / TAU).round(),
            None => {
                let c = a.rem_euclid(TAU);
                if TAU - c < 1e-12 {
                    0.0
                } else {
                    c
                }
            }
        });
    }
    let tol = TRAVEL_TOLERANCE;
    let n_lo = ((lo - tol - a) / TAU).ceil();
    let n_hi = ((hi + tol - a) / TAU).floor();
    if !n_lo.is_finite() || !n_hi.is_finite() || n_lo > n_hi {
        return None;
    }
    let at = |n: f64| a + TAU * n;
    let nearest = |target: f64| {
        let n = ((target - a) / TAU).round().clamp(n_lo, n_hi);
        at(n)
    };
    Some(match near {
        Some(p) => nearest(p),
        None => {
            let canonical = a.rem_euclid(TAU);
            let canonical = if TAU - canonical < 1e-12 {
                0.0
            } else {
                canonical
            };
            if canonical >= lo - tol && canonical <= hi + tol {
                canonical
            } else {
                nearest(0.0)
            }
        }
    })
}
