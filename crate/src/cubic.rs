//! The cubic-machining test (Li, Sato, Shirase & Sakamoto, *Precision Engineering* 71, 2021):
//! which of the nine zones of the test piece come out high or low on a five-axis machine with a
//! B/C tilting-rotary table, for given geometric errors of its rotary axes.
//!
//! # The machine (Section 3, Fig 4)
//! A vertical machine with a tilting-rotary table: B (about Y) on the bed, C (about Z) on B, the
//! workpiece on C; X, Y, Z carry the spindle, whose axis is Z. It is one [`Chain`] (chain order
//! `B, C, X, Y, Z`, built by [`machine`]), with ISO 841 signs: the commands are the paper's B
//! and C of eq 3 (`P_T = M_C·M_B·P_M` without errors). Frames:
//! * **bed / machine frame**: origin on the B axis, at the foot of the common perpendicular of
//!   the B and C axes (their intersection, the *rotary centre*, when they intersect); X, Y, Z
//!   the machine axes. All the paper's matrices (eqs 2–12) act about this point.
//! * **C-axis (table) frame**: `setup.cOffset` mm along X from the B axis (0 by default: B and C
//!   intersect), turning with B and C.
//! * **workpiece frame W**: on the table, origin at the centre of the nominal top face,
//!   `(workpieceX, workpieceY, tableAboveB + workpieceHeight)` in the table frame; axes parallel
//!   to the table's. The face is `z = 0`, `|x|, |y| ≤ 1.5·zoneSize`. Heights are W's z.
//!
//! # The eight errors (Table 3, eqs 2–9) and the mapping onto the chain
//! The paper's errors are those of the B axis relative to the bed (`δxBY δyBY δzBY αBY βBY γBY`)
//! and of C relative to B (`αCB δxCB`). In eq 2 they are matrices that map **machine
//! coordinates into table coordinates**, the inverse of the axis frame's pose, so each maps onto
//! an ISO 230-1 location error of the chain with a **minus sign** ([`ERRORS`], applied by
//! [`apply_errors`], the one place this mapping is written):
//!
//! ```text
//! E_X0B = −δxBY   E_Y0B = −δyBY   E_Z0B = −δzBY   E_A0B = −αBY   E_B0B = −βBY   E_C0B = −γBY
//! E_X0C = −δxCB   E_A0C = −αCB
//! ```
//!
//! This is exact, not only to first order: the chain's `D(−ε) = T(−δ)·R_X(−α)·R_Y(−β)·R_Z(−γ)`
//! is the inverse of the paper's `M_γ·M_β·M_α·M_δ` (eqs 4–9), and the chain test
//! `the_chain_reproduces_eqs_2_and_10_to_12_of_the_cubic_paper_exactly` checks eq 2 and eq 10.
//! The orientation errors turn about the bed origin (B) and about the C frame origin (C), as in
//! the paper; with offset axes (`cOffset ≠ 0`, which the paper does not treat) `αCB` turns C
//! about its point nearest the B axis. Positions in mm, angles in rad here (degrees at the
//! JavaScript edge).
//!
//! # The test (Section 2, Tables 1 and 2, Fig 2)
//! A `3·zoneSize` square face (48 × 48 mm) in 3 × 3 zones (16 × 16 mm), [`ZONES`] in Table 1's
//! order (also the machining order of Section 5.1). Each zone is cut with a fixed tool vector
//! (Table 1, pointing from the tip to the spindle), a ball-end mill of radius `r` (3 mm), zig-zag
//! passes along X with a pick feed `p` (0.1 mm) in Y. The rotary angles come from the chain's
//! inverse kinematics ([`Chain::inverse_all`]); of its two branches the machine uses the one
//! with the tilt **B ≥ 0**, and C is written in `[0°, 360°)`: this gives Table 2. A functional
//! point `P_f` (the contact point on the face) becomes the tool tip of the NC program by eq 1,
//! `P_t = P_f + r·(−i, −j, 1 − k)`, and the tool centre is `P_c = P_t + r·v` (eq 14: in machine
//! coordinates `P_t + (0, 0, r)`, carried into W by the same chain).
//!
//! # Height deviation and tilt of a zone (Section 4)
//! Within a zone the rotary axes stand still and the linear axes carry no errors here, so the
//! actual tool centres are the nominal ones moved by one rigid displacement: they lie on a plane,
//! and the machined surface (the envelope of the ball) is that plane moved down by `r` along its
//! normal. [`analyze`] takes three actual centres from the chain (the zone centre and
//! `zoneSize/2` along +X and +Y), and reports the surface's **height** at the nominal zone centre
//! (exactly, mm) and its **slopes** `∂z/∂x`, `∂z/∂y` (dimensionless; the tilt). The ball radius
//! cancels out. **Sign** (Section 4.2): a positive height is a surface above nominal, material
//! left to remove. Scallops are not part of these heights (see [`height_map`]).
//!
//! **Frames** ([`Options`]): with the workpiece transform (`transform = true`, eqs 10–12, Fig 12)
//! the workpiece is set up at B = C = 0 where it coincides with the nominal table
//! ([`Setup::AtPose`]), so ZONE I, cut at B = C = 0, is exact; without it (`false`, eq 2, Fig 10)
//! the workpiece frame is the erroneous table frame. [`Reference`] then says what the heights
//! are measured from: the workpiece frame, or the measurement frame of Section 5.1 set on
//! ZONE I, either shifted to ZONE I's height only (the text of Section 5.1: "same direction as
//! the workpiece coordinate system ... a Z-direction shift") or levelled on ZONE I's plane as well
//! (Fig 15: "parallel to the ZONE I surface"; a profilometer's levelling: ZONE I's plane is
//! subtracted from every height, and its slopes from every slope).
//!
//! **Sensitivities** (eq 15, Figs 10 and 12): `k = E/ε`, the height (and slope) change per unit
//! error, mm/mm and mm/rad, from the chain's analytic first-order derivatives
//! ([`Chain::jacobian`]: centre sensitivity `∂tip/∂ε + r·∂axis/∂ε`); the height at the zone
//! centre changes by the centre's z change, a slope by the difference over `zoneSize/2`.
//! [`analyze`] also gives the exact deviation of each error alone at its entered value, so that
//! `E/ε` can be compared with `k`.

use crate::chain::{Chain, Link, RigidError, Setup};
use crate::error::{check_count, check_positive, check_range, Error, Result};
use crate::geometry::Axis;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One of the paper's eight geometric errors (Table 3) and the chain location error it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ErrorDef {
    /// Key at the JavaScript API: `"dxBY"`, `"alphaCB"`, ...
    pub key: &'static str,
    /// The paper's symbol: `"δxBY"`.
    pub symbol: &'static str,
    /// The ISO 230-1 location error it maps onto (with a minus sign): `"E_X0B"`.
    pub iso: &'static str,
    /// The chain link that carries it: `"B"` or `"C"`.
    pub axis: &'static str,
    /// Component of that link's [`RigidError`]: 0..3 translations X Y Z, 3..6 rotations A B C.
    pub component: usize,
    /// An angle (rad; degrees at the JavaScript edge) rather than a position (mm).
    pub angular: bool,
    /// Table 3's description.
    pub description: &'static str,
}

/// `E_iso = MAPPING_SIGN · ε_paper` for every error of [`ERRORS`] (module docs).
pub const MAPPING_SIGN: f64 = -1.0;

/// The eight errors in Table 3's order; [`GeometricErrors`] holds values in this order.
pub const ERRORS: [ErrorDef; 8] = [
    ErrorDef {
        key: "dxBY",
        symbol: "δxBY",
        iso: "E_X0B",
        axis: "B",
        component: 0,
        angular: false,
        description: "Positional error of B-axis average line along X-axis direction",
    },
    ErrorDef {
        key: "dyBY",
        symbol: "δyBY",
        iso: "E_Y0B",
        axis: "B",
        component: 1,
        angular: false,
        description: "Positional error of B-axis average line along Y-axis direction",
    },
    ErrorDef {
        key: "dzBY",
        symbol: "δzBY",
        iso: "E_Z0B",
        axis: "B",
        component: 2,
        angular: false,
        description: "Positional error of B-axis average line along Z-axis direction",
    },
    ErrorDef {
        key: "alphaBY",
        symbol: "αBY",
        iso: "E_A0B",
        axis: "B",
        component: 3,
        angular: true,
        description: "Orientation error between B-axis and Y-axis around X-axis direction",
    },
    ErrorDef {
        key: "betaBY",
        symbol: "βBY",
        iso: "E_B0B",
        axis: "B",
        component: 4,
        angular: true,
        description: "Orientation error between B-axis and Y-axis around Y-axis direction (zero-angle error of B)",
    },
    ErrorDef {
        key: "gammaBY",
        symbol: "γBY",
        iso: "E_C0B",
        axis: "B",
        component: 5,
        angular: true,
        description: "Orientation error between B-axis and Y-axis around Z-axis direction",
    },
    ErrorDef {
        key: "alphaCB",
        symbol: "αCB",
        iso: "E_A0C",
        axis: "C",
        component: 3,
        angular: true,
        description: "Orientation error between C-axis and B-axis around X-axis direction",
    },
    ErrorDef {
        key: "dxCB",
        symbol: "δxCB",
        iso: "E_X0C",
        axis: "C",
        component: 0,
        angular: false,
        description: "Positional error of C-axis and B-axis along X-axis direction",
    },
];

/// Values of the eight errors in the order of [`ERRORS`]: mm for positions, rad for angles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GeometricErrors(pub [f64; 8]);

impl GeometricErrors {
    /// Only error `index` (order of [`ERRORS`]) at `value`, the others zero.
    pub fn single(index: usize, value: f64) -> Self {
        let mut v = [0.0; 8];
        v[index] = value;
        Self(v)
    }

    /// The paper's Table 5 machine (identified by ball bar): δxBY 14.6 µm, δyBY −8.9 µm,
    /// δzBY −14.2 µm, αBY −0.0023°, βBY 0.0029°, γBY −0.00002°, αCB −0.00017°, δxCB 9.4 µm.
    pub fn table5() -> Self {
        let d = f64::to_radians;
        Self([
            0.0146,
            -0.0089,
            -0.0142,
            d(-0.0023),
            d(0.0029),
            d(-0.00002),
            d(-0.00017),
            0.0094,
        ])
    }

    /// Checks that every value is finite and within ±[`MAX_POSITION_ERROR`] mm or
    /// ±[`MAX_ANGLE_ERROR_DEG`]° (messages name `errors.<key>`, angles in degrees).
    pub fn validate(&self) -> Result<()> {
        for (def, v) in ERRORS.iter().zip(self.0) {
            let field = format!("errors.{}", def.key);
            if def.angular {
                let lim = MAX_ANGLE_ERROR_DEG;
                check_range(&field, v.to_degrees(), -lim, lim, "degrees")?;
            } else {
                let lim = MAX_POSITION_ERROR;
                check_range(&field, v, -lim, lim, "mm")?;
            }
        }
        Ok(())
    }
}

/// Largest accepted positional error, mm (ten times the paper's intentional 0.5 mm).
pub const MAX_POSITION_ERROR: f64 = 5.0;
/// Largest accepted angular error, degrees (ten times the paper's intentional 0.5°).
pub const MAX_ANGLE_ERROR_DEG: f64 = 5.0;

/// Sets the location errors of the chain's `B` and `C` links from the paper's eight errors: the
/// mapping of the module docs, `E = MAPPING_SIGN·ε` for each entry of [`ERRORS`]. The other
/// location errors of B and C are set to zero. Fails when the chain has no link named B or C.
pub fn apply_errors(chain: &mut Chain, errors: &GeometricErrors) -> Result<()> {
    for axis in ["B", "C"] {
        let i = link_index(chain, axis)?;
        let mut l = RigidError::default();
        for (def, v) in ERRORS.iter().zip(errors.0) {
            if def.axis == axis {
                l.set(def.component, MAPPING_SIGN * v);
            }
        }
        chain.link_mut(i).location = l;
    }
    Ok(())
}

fn link_index(chain: &Chain, name: &str) -> Result<usize> {
    chain
        .index_of(name)
        .ok_or_else(|| Error::field("machine", format!("the chain has no axis named {name}")))
}

/// The set-up geometry of the workpiece and the test piece's cutting parameters, mm.
///
/// Defaults: the table surface at the height of the B axis (`tableAboveB = 0`), a 50 mm block
/// (`workpieceHeight`, the paper's 50 × 50 × 50 mm stock), centred on the C axis, B and C
/// intersecting (`cOffset = 0`), 16 mm zones, a ball-end mill of radius 3 mm (Ø6, Table 4),
/// 0.1 mm pick feed and 0.1 mm stock left above the nominal face (the depth of cut, Table 4).
/// The paper does not give the trunnion's geometry. The vertical set-up (`tableAboveB`,
/// `workpieceHeight`) never enters the first-order zone heights: a small rotation about an axis
/// through `a` moves a point `w` by `ω×(w − a)`, whose z component involves only the horizontal
/// parts of `w − a`, and the pivots of these errors (the bed origin, the C frame origin) sit at
/// fixed horizontal places in the workpiece frame. Second-order terms depend on it (e.g. αBY at
/// ZONE I without `M_WC` gives `H·(1/cos α − 1)`, H the face's height above the rotary centre). The workpiece's place on the table
/// (`workpieceX`, `workpieceY`) does change the first-order heights; the offset of C from B
/// only shifts βBY's sensitivity by `−cOffset` in every zone, which `M_WC` removes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default, deny_unknown_fields)]
pub struct CubicSetup {
    /// Height of the table surface above the B axis at B = 0, mm (negative: below it).
    pub table_above_b: f64,
    /// Height of the workpiece's top face above the table surface, mm (> 0).
    pub workpiece_height: f64,
    /// Distance of the C axis from the B axis along X at B = 0, mm (0: they intersect).
    pub c_offset: f64,
    /// X of the face centre from the C axis, mm.
    pub workpiece_x: f64,
    /// Y of the face centre from the C axis, mm.
    pub workpiece_y: f64,
    /// Side of one zone, mm (the face is 3 × 3 zones).
    pub zone_size: f64,
    /// Radius `r` of the ball-end mill, mm.
    pub tool_radius: f64,
    /// Pick feed `p` between zig-zag passes, mm. The passes of a zone run at its two edges and
    /// at `n − 1` equal steps between (`n = ⌈zoneSize/p⌉`), so the step is `zoneSize/n ≤ p`.
    pub pick: f64,
    /// Material above the nominal face before the finishing cut, mm: what the height map shows
    /// where no pass reaches (a zone moved sideways by large errors).
    pub stock: f64,
}

impl Default for CubicSetup {
    fn default() -> Self {
        Self {
            table_above_b: 0.0,
            workpiece_height: 50.0,
            c_offset: 0.0,
            workpiece_x: 0.0,
            workpiece_y: 0.0,
            zone_size: 16.0,
            tool_radius: 3.0,
            pick: 0.1,
            stock: 0.1,
        }
    }
}

/// Largest accepted set-up distance (table, offsets, workpiece position), mm.
pub const MAX_SETUP_MM: f64 = 2000.0;
/// Most zig-zag passes per zone.
pub const MAX_PASSES_PER_ZONE: usize = 20_000;

impl CubicSetup {
    /// Checks every field (messages name `setup.<field>`).
    pub fn validate(&self) -> Result<()> {
        let m = MAX_SETUP_MM;
        check_range("setup.tableAboveB", self.table_above_b, -m, m, "mm")?;
        check_positive("setup.workpieceHeight", self.workpiece_height, m, "mm")?;
        check_range("setup.cOffset", self.c_offset, -m, m, "mm")?;
        check_range("setup.workpieceX", self.workpiece_x, -m, m, "mm")?;
        check_range("setup.workpieceY", self.workpiece_y, -m, m, "mm")?;
        check_range("setup.zoneSize", self.zone_size, 1.0, 200.0, "mm")?;
        check_range("setup.toolRadius", self.tool_radius, 0.05, 50.0, "mm")?;
        check_range("setup.pick", self.pick, 0.001, self.zone_size, "mm")?;
        if self.pick >= 2.0 * self.tool_radius {
            return Err(Error::field(
                "setup.pick",
                format!(
                    "must be less than the ball's diameter {} mm, got {}",
                    2.0 * self.tool_radius,
                    self.pick
                ),
            ));
        }
        if self.passes_per_zone() > MAX_PASSES_PER_ZONE {
            return Err(Error::field(
                "setup.pick",
                format!(
                    "gives more than {MAX_PASSES_PER_ZONE} passes per zone: use a larger pick feed \
                     or smaller zones"
                ),
            ));
        }
        check_positive("setup.stock", self.stock, 50.0, "mm")?;
        Ok(())
    }

    /// Intervals between the passes of one zone, `n = ⌈zoneSize/p⌉`.
    fn intervals(&self) -> usize {
        let n = (self.zone_size / self.pick - 1e-9).ceil();
        if n.is_finite() && n >= 1.0 {
            n as usize
        } else {
            1
        }
    }

    /// Passes per zone, `n + 1`.
    pub fn passes_per_zone(&self) -> usize {
        self.intervals() + 1
    }

    /// The actual step between passes, `zoneSize/n` (≤ pick), mm.
    pub fn step(&self) -> f64 {
        self.zone_size / self.intervals() as f64
    }
}

/// A zone of the test piece (Fig 2, Table 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZoneDef {
    /// "I", "II-1", … "III-4".
    pub name: &'static str,
    /// Column −1 (left, −X), 0, 1 (right).
    pub col: i32,
    /// Row −1 (bottom, −Y), 0, 1 (top).
    pub row: i32,
    /// Tool vector `(i, j, k)` of Table 1, tip → spindle, workpiece coordinates.
    pub tool: [f64; 3],
}

const S3: f64 = 0.866_025_403_784_438_6; // √3/2
const Q2: f64 = 0.353_553_390_593_273_8; // √2/4

/// The nine zones in Table 1's order (the machining order of Section 5.1): ZONE I in the
/// centre; II-1 left, II-2 bottom, II-3 right, II-4 top; III-1 bottom-left, III-2 bottom-right,
/// III-3 top-right, III-4 top-left. The tool leans 30° towards the centre of the face.
pub const ZONES: [ZoneDef; 9] = [
    ZoneDef {
        name: "I",
        col: 0,
        row: 0,
        tool: [0.0, 0.0, 1.0],
    },
    ZoneDef {
        name: "II-1",
        col: -1,
        row: 0,
        tool: [0.5, 0.0, S3],
    },
    ZoneDef {
        name: "II-2",
        col: 0,
        row: -1,
        tool: [0.0, 0.5, S3],
    },
    ZoneDef {
        name: "II-3",
        col: 1,
        row: 0,
        tool: [-0.5, 0.0, S3],
    },
    ZoneDef {
        name: "II-4",
        col: 0,
        row: 1,
        tool: [0.0, -0.5, S3],
    },
    ZoneDef {
        name: "III-1",
        col: -1,
        row: -1,
        tool: [Q2, Q2, S3],
    },
    ZoneDef {
        name: "III-2",
        col: 1,
        row: -1,
        tool: [-Q2, Q2, S3],
    },
    ZoneDef {
        name: "III-3",
        col: 1,
        row: 1,
        tool: [-Q2, -Q2, S3],
    },
    ZoneDef {
        name: "III-4",
        col: -1,
        row: 1,
        tool: [Q2, -Q2, S3],
    },
];

/// What the heights are measured from (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Reference {
    /// The workpiece frame: the nominal face is `z = 0`.
    #[default]
    #[serde(rename = "workpiece")]
    Workpiece,
    /// Section 5.1's measurement frame: ZONE I's height (at its centre; in the height map its
    /// average) is subtracted from every height; slopes are unchanged.
    #[serde(rename = "zone1-height")]
    ZoneIHeight,
    /// Levelled on ZONE I (Fig 15): ZONE I's plane (in the height map, the least-squares plane
    /// of its points) is subtracted from every height, its slopes from every slope.
    #[serde(rename = "zone1-plane")]
    ZoneIPlane,
}

/// How the deviations are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// With the workpiece coordinate transformation `M_WC` (eqs 10–12): the workpiece is set up
    /// at B = C = 0.
    pub transform: bool,
    /// What the heights are measured from.
    pub reference: Reference,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            transform: true,
            reference: Reference::Workpiece,
        }
    }
}

/// A plane over a zone: its height at the zone centre and its slopes.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ZonePlane {
    /// Height at the nominal zone centre, mm (or per unit error for a sensitivity).
    pub height: f64,
    /// `∂z/∂x`, dimensionless (or per unit error).
    pub slope_x: f64,
    /// `∂z/∂y`, dimensionless (or per unit error).
    pub slope_y: f64,
}

impl ZonePlane {
    /// The plane's height at `(x, y)` given its zone centre `(xc, yc)`.
    pub fn at(&self, (xc, yc): (f64, f64), x: f64, y: f64) -> f64 {
        self.height + self.slope_x * (x - xc) + self.slope_y * (y - yc)
    }

    fn scaled(&self, s: f64) -> Self {
        Self {
            height: self.height * s,
            slope_x: self.slope_x * s,
            slope_y: self.slope_y * s,
        }
    }

    fn plus(&self, o: &Self) -> Self {
        Self {
            height: self.height + o.height,
            slope_x: self.slope_x + o.slope_x,
            slope_y: self.slope_y + o.slope_y,
        }
    }
}

/// The B/C tilting-rotary table of the paper as a [`Chain`] (chain order `B, C, X, Y, Z`), with
/// the set-up geometry of `setup` and the location errors of `errors` (module docs).
pub fn machine(setup: &CubicSetup, errors: &GeometricErrors) -> Result<Chain> {
    let mut chain = Chain {
        work: vec![
            Link::rotary("B", Axis::Y).on_table(),
            Link::rotary("C", Axis::Z)
                .on_table()
                .at(Vector3::new(setup.c_offset, 0.0, 0.0)),
        ],
        tool: vec![
            Link::linear("X", Axis::X),
            Link::linear("Y", Axis::Y),
            Link::linear("Z", Axis::Z),
        ],
        work_origin: Vector3::new(
            setup.workpiece_x,
            setup.workpiece_y,
            setup.table_above_b + setup.workpiece_height,
        ),
        tool_tip: Vector3::zeros(),
        tool_axis: Axis::Z,
    };
    apply_errors(&mut chain, errors)?;
    Ok(chain)
}

/// The chain's set-up for `options.transform`: at B = C = 0 (all axes zero), or none.
fn setup_of(chain: &Chain, options: &Options) -> Setup {
    if options.transform {
        Setup::AtPose(vec![0.0; chain.len()])
    } else {
        Setup::None
    }
}

/// A zone placed on the face: its definition, centre and the rotary pose used to cut it.
#[derive(Debug, Clone)]
struct Zone {
    def: ZoneDef,
    centre: (f64, f64),
    dir: Vector3<f64>,
    /// Axis positions (chain order) for the zone centre.
    q: Vec<f64>,
}

/// The test on one machine: the chain (with errors), its set-up and the zones with their poses.
struct Test {
    chain: Chain,
    setup: Setup,
    piece: CubicSetup,
    zones: Vec<Zone>,
}

/// The tool tip of the NC program for the functional point `(x, y, 0)` (eq 1).
fn nominal_tip(x: f64, y: f64, dir: &Vector3<f64>, r: f64) -> Vector3<f64> {
    Vector3::new(x - r * dir.x, y - r * dir.y, r * (1.0 - dir.z))
}

impl Test {
    fn new(piece: &CubicSetup, errors: &GeometricErrors, options: &Options) -> Result<Self> {
        piece.validate()?;
        errors.validate()?;
        let chain = machine(piece, errors)?;
        let setup = setup_of(&chain, options);
        let (ib, ic) = (link_index(&chain, "B")?, link_index(&chain, "C")?);
        let mut zones = Vec::with_capacity(ZONES.len());
        for def in ZONES {
            let dir = Vector3::from(def.tool);
            let centre = (
                def.col as f64 * piece.zone_size,
                def.row as f64 * piece.zone_size,
            );
            let tip = nominal_tip(centre.0, centre.1, &dir, piece.tool_radius);
            let (all, _) = chain.inverse_all(&tip, &dir)?;
            // Table 2: the branch with the tilt B >= 0, C written in [0, 360°).
            let mut q = all
                .iter()
                .find(|s| s[ib] >= -1e-12)
                .or(all.first())
                .cloned()
                .ok_or_else(|| Error::field("machine", "no inverse-kinematics solution"))?;
            q[ic] = q[ic].rem_euclid(TAU);
            if TAU - q[ic] < 1e-12 {
                q[ic] = 0.0;
            }
            zones.push(Zone {
                def,
                centre,
                dir,
                q,
            });
        }
        Ok(Self {
            chain,
            setup,
            piece: *piece,
            zones,
        })
    }

    /// Axis positions that cut the functional point `(x, y, 0)` in `zone` (same rotary pose).
    fn positions(&self, zone: &Zone, x: f64, y: f64) -> Result<Vec<f64>> {
        let tip = nominal_tip(x, y, &zone.dir, self.piece.tool_radius);
        self.chain.solve_linear(&tip, &zone.q)
    }

    /// The actual tool centre (workpiece coordinates) when the NC program cuts `(x, y, 0)`.
    fn centre(&self, zone: &Zone, x: f64, y: f64) -> Result<Vector3<f64>> {
        let q = self.positions(zone, x, y)?;
        let p = self.chain.tool_pose(&q, true, &self.setup)?;
        Ok(p.tip + self.piece.tool_radius * p.axis)
    }

    /// The three functional points of a zone used for its plane.
    fn probe_points(&self, zone: &Zone) -> [(f64, f64); 3] {
        let (xc, yc) = zone.centre;
        let a = self.probe_step();
        [(xc, yc), (xc + a, yc), (xc, yc + a)]
    }

    fn probe_step(&self) -> f64 {
        self.piece.zone_size / 2.0
    }

    /// The machined surface of a zone, exactly (module docs).
    fn plane(&self, zone: &Zone) -> Result<ZonePlane> {
        let [p1, p2, p3] = self.probe_points(zone);
        let c1 = self.centre(zone, p1.0, p1.1)?;
        let c2 = self.centre(zone, p2.0, p2.1)?;
        let c3 = self.centre(zone, p3.0, p3.1)?;
        let n = (c2 - c1).cross(&(c3 - c1));
        let n = n / n.norm();
        if !n.z.is_finite() || n.z < 0.5 {
            return Err(Error::field(
                "errors",
                "the errors tilt the machined zone by more than 60°",
            ));
        }
        let s = c1 - self.piece.tool_radius * n;
        let (xc, yc) = zone.centre;
        Ok(ZonePlane {
            height: s.z - (n.x * (xc - s.x) + n.y * (yc - s.y)) / n.z,
            slope_x: -n.x / n.z,
            slope_y: -n.y / n.z,
        })
    }

    /// First-order sensitivities of a zone's plane to the eight errors (per mm, per rad).
    fn sensitivities(&self, zone: &Zone) -> Result<[ZonePlane; 8]> {
        let r = self.piece.tool_radius;
        let mut dz = [[0.0; 8]; 3];
        for (j, (x, y)) in self.probe_points(zone).into_iter().enumerate() {
            let q = self.positions(zone, x, y)?;
            let jac = self.chain.jacobian(&q, &self.setup)?;
            for (e, def) in ERRORS.iter().enumerate() {
                let link = link_index(&self.chain, def.axis)?;
                let s = &jac[Chain::location_index(link, def.component)];
                dz[j][e] = MAPPING_SIGN * (s.tip.z + r * s.axis.z);
            }
        }
        let a = self.probe_step();
        Ok(std::array::from_fn(|e| ZonePlane {
            height: dz[0][e],
            slope_x: (dz[1][e] - dz[0][e]) / a,
            slope_y: (dz[2][e] - dz[0][e]) / a,
        }))
    }
}

/// Planes of the nine zones (Table 1 order) measured from `reference`: ZONE I (index 0) is the
/// reference zone. Linear in the planes, so it applies to sensitivities as well.
fn relative(planes: &[ZonePlane], centres: &[(f64, f64)], reference: Reference) -> Vec<ZonePlane> {
    let z1 = planes[0];
    planes
        .iter()
        .zip(centres)
        .map(|(p, &(x, y))| match reference {
            Reference::Workpiece => *p,
            Reference::ZoneIHeight => ZonePlane {
                height: p.height - z1.height,
                ..*p
            },
            Reference::ZoneIPlane => ZonePlane {
                height: p.height - z1.at(centres[0], x, y),
                slope_x: p.slope_x - z1.slope_x,
                slope_y: p.slope_y - z1.slope_y,
            },
        })
        .collect()
}

/// One zone's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ZoneResult {
    /// The zone.
    pub zone: ZoneDef,
    /// Nominal centre `(x, y)` in the workpiece frame, mm.
    pub centre: [f64; 2],
    /// B command, rad (Table 2).
    pub b: f64,
    /// C command in `[0, 2π)`, rad (Table 2).
    pub c: f64,
    /// The exact machined plane for all the entered errors together.
    pub exact: ZonePlane,
    /// The first-order estimate `Σ k·ε` over the eight errors.
    pub linear: ZonePlane,
}

/// Everything [`analyze`] finds, in the frame and reference of its [`Options`].
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// The nine zones in Table 1's order.
    pub zones: Vec<ZoneResult>,
    /// `sensitivity[zone][error]`: `k = ∂E/∂ε` of the height (mm/mm or mm/rad) and the slopes
    /// (1/mm or 1/rad), errors in the order of [`ERRORS`].
    pub sensitivity: Vec<[ZonePlane; 8]>,
    /// `single[zone][error]`: the exact height deviation, mm, with only that error present at
    /// its entered value (0 where the entered value is 0): `E_ε` of eq 15.
    pub single: Vec<[f64; 8]>,
}

/// Zone heights, slopes and sensitivities of the cubic-machining test for `errors` on the
/// machine of `setup` (module docs).
pub fn analyze(
    setup: &CubicSetup,
    errors: &GeometricErrors,
    options: &Options,
) -> Result<Analysis> {
    let test = Test::new(setup, errors, options)?;
    let centres: Vec<(f64, f64)> = test.zones.iter().map(|z| z.centre).collect();
    let exact: Vec<ZonePlane> = test
        .zones
        .iter()
        .map(|z| test.plane(z))
        .collect::<Result<_>>()?;
    let exact = relative(&exact, &centres, options.reference);

    let raw: Vec<[ZonePlane; 8]> = test
        .zones
        .iter()
        .map(|z| test.sensitivities(z))
        .collect::<Result<_>>()?;
    let mut sensitivity = vec![[ZonePlane::default(); 8]; raw.len()];
    for e in 0..ERRORS.len() {
        let column: Vec<ZonePlane> = raw.iter().map(|k| k[e]).collect();
        for (z, p) in relative(&column, &centres, options.reference)
            .into_iter()
            .enumerate()
        {
            sensitivity[z][e] = p;
        }
    }

    let mut single = vec![[0.0; 8]; test.zones.len()];
    for (e, &v) in errors.0.iter().enumerate() {
        if v == 0.0 {
            continue;
        }
        let one = Test::new(setup, &GeometricErrors::single(e, v), options)?;
        let planes: Vec<ZonePlane> = one
            .zones
            .iter()
            .map(|z| one.plane(z))
            .collect::<Result<_>>()?;
        for (z, p) in relative(&planes, &centres, options.reference)
            .into_iter()
            .enumerate()
        {
            single[z][e] = p.height;
        }
    }

    let zones = test
        .zones
        .iter()
        .zip(&exact)
        .zip(&sensitivity)
        .map(|((z, p), k)| {
            let linear = k
                .iter()
                .zip(errors.0)
                .fold(ZonePlane::default(), |acc, (k, v)| acc.plus(&k.scaled(v)));
            ZoneResult {
                zone: z.def,
                centre: [z.centre.0, z.centre.1],
                b: z.q[0],
                c: z.q[1],
                exact: *p,
                linear,
            }
        })
        .collect();
    Ok(Analysis {
        zones,
        sensitivity,
        single,
    })
}

/// The simulated machined face (like Fig 16(b)): a height field of the ball-end zig-zag.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    /// Grid points along X.
    pub nx: usize,
    /// Grid points along Y.
    pub ny: usize,
    /// X of the grid columns, mm: `nx` equal steps from `−1.5·zoneSize` to `+1.5·zoneSize`.
    pub x: Vec<f64>,
    /// Y of the grid rows, mm, likewise.
    pub y: Vec<f64>,
    /// Heights, mm, row-major `ny × nx`: the point `(x[ix], y[iy])` is `[iy·nx + ix]`.
    pub height: Vec<f64>,
    /// Average height over each zone (Table 1 order), mm: the trapezoidal rule on the grid
    /// (a point on a zone border counts half for each zone). Includes the mean scallop height.
    pub zone_average: Vec<f64>,
    /// The actual step between passes, mm (module docs of [`CubicSetup::pick`]).
    pub step: f64,
    /// Closed-form scallop height for that step, `r − √(r² − (step/2)²)`, mm.
    pub scallop: f64,
    /// Passes simulated (all zones).
    pub passes: usize,
    /// Pass-point evaluations made (a measure of the work).
    pub evaluations: usize,
}

/// Most grid points of a height map.
pub const MAX_GRID_POINTS: usize = 4_000_000;
/// Most grid points along one side of a height map.
pub const MAX_GRID_SIDE: usize = 4001;

/// One pass: the segment of actual ball centres.
struct Pass {
    a: Vector3<f64>,
    /// Unit direction from `a` to the other end.
    e: Vector3<f64>,
    len: f64,
    zmin: f64,
}

impl Pass {
    fn new(a: Vector3<f64>, b: Vector3<f64>) -> Self {
        let d = b - a;
        let len = d.norm();
        Self {
            a,
            e: if len > 0.0 { d / len } else { Vector3::x() },
            len,
            zmin: a.z.min(b.z),
        }
    }

    /// Lowest point of the swept ball (a capsule of radius `r` around the segment) above
    /// `(x, y)`, or +∞ where it does not reach. The cylinder part: the lower root `t = z − a_z`
    /// of `|v|² − (v·e)² = r²`, `v = (x − a_x, y − a_y, t)`, valid where the foot `v·e` lies on
    /// the segment; the two end spheres otherwise.
    fn bottom(&self, x: f64, y: f64, r: f64) -> f64 {
        let (dx, dy) = (x - self.a.x, y - self.a.y);
        let r2 = r * r;
        let sphere = |cx: f64, cy: f64, cz: f64| {
            let d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            if d2 <= r2 {
                cz - (r2 - d2).sqrt()
            } else {
                f64::INFINITY
            }
        };
        let b = self.a + self.e * self.len;
        let mut best = sphere(self.a.x, self.a.y, self.a.z).min(sphere(b.x, b.y, b.z));
        let ve = dx * self.e.x + dy * self.e.y;
        let qa = 1.0 - self.e.z * self.e.z;
        if qa > 1e-12 {
            let qb = -self.e.z * ve;
            let qc = dx * dx + dy * dy - ve * ve - r2;
            let disc = qb * qb - qa * qc;
            if disc >= 0.0 {
                let t = (-qb - disc.sqrt()) / qa;
                let s = ve + t * self.e.z;
                if (0.0..=self.len).contains(&s) {
                    best = best.min(self.a.z + t);
                }
            }
        }
        best
    }
}

/// A regular grid of points over the face.
struct Grid {
    x: Vec<f64>,
    y: Vec<f64>,
    h: Vec<f64>,
}

impl Grid {
    /// Index range of the coordinates `v` within `[lo, hi]` (sorted, equally spaced).
    fn span(v: &[f64], lo: f64, hi: f64) -> std::ops::Range<usize> {
        let n = v.len();
        let (v0, dv) = (v[0], v[1] - v[0]);
        let i0 = ((lo - v0) / dv).ceil().max(0.0);
        let i1 = ((hi - v0) / dv).floor() + 1.0;
        let i0 = if i0.is_finite() { i0 as usize } else { n };
        let i1 = if i1.is_finite() && i1 > 0.0 {
            (i1 as usize).min(n)
        } else {
            0
        };
        i0.min(i1)..i1
    }

    /// Lowers the grid to the pass wherever it cuts deeper, within `w` of the pass (horizontally).
    fn cut(&mut self, p: &Pass, w: f64, r: f64) -> usize {
        let b = p.a + p.e * p.len;
        let xs = Self::span(&self.x, p.a.x.min(b.x) - w, p.a.x.max(b.x) + w);
        let ys = Self::span(&self.y, p.a.y.min(b.y) - w, p.a.y.max(b.y) + w);
        let nx = self.x.len();
        let mut n = 0;
        for iy in ys {
            let y = self.y[iy];
            for ix in xs.clone() {
                let z = p.bottom(self.x[ix], y, r);
                let h = &mut self.h[iy * nx + ix];
                if z < *h {
                    *h = z;
                }
                n += 1;
            }
        }
        n
    }
}

/// Simulates the machined face on an `nx × ny` grid (module docs; like Fig 16(b)).
///
/// Every zone is cut by its zig-zag passes along X ([`CubicSetup::pick`]); a pass is the
/// segment between the actual tool centres (from the chain, eqs 1 and 14) of its two end points,
/// and the ball swept along it removes everything above its lower surface. The face is the
/// lowest of all passes and the stock, whatever the order of cutting. Only passes near a grid
/// point can reach it: a first sweep within one pick of each pass gives an upper bound `M` of
/// the face; a pass whose centres are at least `zmin` high cannot cut below `M` farther than
/// `√(r² − (zmin − M)²)` from its line, so the second, exact sweep stops there.
///
/// Heights are in the frame and reference of `options`: [`Reference::ZoneIHeight`] subtracts
/// the average, [`Reference::ZoneIPlane`] the least-squares plane, of ZONE I's central square
/// (inset from its borders by `r`, at most a quarter of the zone side), which the balls of the
/// neighbouring zones do not reach (they would bias the reference by up to a few per cent of
/// the height differences).
pub fn height_map(
    setup: &CubicSetup,
    errors: &GeometricErrors,
    options: &Options,
    nx: usize,
    ny: usize,
) -> Result<HeightMap> {
    check_count("nx", nx, 4, MAX_GRID_SIDE)?;
    check_count("ny", ny, 4, MAX_GRID_SIDE)?;
    if nx * ny > MAX_GRID_POINTS {
        return Err(Error::field(
            "nx",
            format!("nx·ny must be at most {MAX_GRID_POINTS}, got {}", nx * ny),
        ));
    }
    let test = Test::new(setup, errors, options)?;
    let z = setup.zone_size;
    let r = setup.tool_radius;
    let step = setup.step();
    let half = 0.5 * z;

    let mut passes = Vec::with_capacity(9 * setup.passes_per_zone());
    for zone in &test.zones {
        let (xc, yc) = zone.centre;
        // Each pass runs between the actual tool centres (from the chain) of its two ends.
        for k in 0..setup.passes_per_zone() {
            let y = yc - half + k as f64 * step;
            let a = test.centre(zone, xc - half, y)?;
            let b = test.centre(zone, xc + half, y)?;
            passes.push(Pass::new(a, b));
        }
    }

    let lin = |n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| -1.5 * z + 3.0 * z * i as f64 / (n - 1) as f64)
            .collect()
    };
    let mut grid = Grid {
        x: lin(nx),
        y: lin(ny),
        h: vec![setup.stock; nx * ny],
    };
    let mut evaluations = 0;
    for p in &passes {
        evaluations += grid.cut(p, step, r);
    }
    let bound = grid.h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    for p in &passes {
        let gap = p.zmin - bound;
        if gap >= r {
            continue;
        }
        let w = if gap > 0.0 {
            (r * r - gap * gap).sqrt()
        } else {
            r
        };
        evaluations += grid.cut(p, w * (1.0 + 1e-12) + 1e-12, r);
    }

    // Zone averages (trapezoidal weights: a point on a zone border counts half), then the
    // reference, taken on ZONE I's central square (inset by r, at most a quarter of the zone
    // side) where no pass of another zone reaches unless the errors move zones sideways.
    let weights = |v: &[f64], c: f64, half: f64| -> Vec<(usize, f64)> {
        let tol = 1e-9 * z;
        v.iter()
            .enumerate()
            .filter_map(|(i, &t)| {
                let d = (t - c).abs();
                if d < half - tol {
                    Some((i, 1.0))
                } else if d <= half + tol {
                    Some((i, 0.5))
                } else {
                    None
                }
            })
            .collect()
    };
    let square = |(xc, yc): (f64, f64), half: f64| -> Vec<(usize, f64)> {
        let wx = weights(&grid.x, xc, half);
        weights(&grid.y, yc, half)
            .into_iter()
            .flat_map(|(iy, wy)| wx.iter().map(move |&(ix, w)| (iy * nx + ix, w * wy)))
            .collect()
    };
    let members: Vec<Vec<(usize, f64)>> = test
        .zones
        .iter()
        .map(|zone| square(zone.centre, half))
        .collect();
    let reference_area = {
        let inner = square(test.zones[0].centre, half - r.min(0.25 * z));
        if inner.is_empty() {
            members[0].clone()
        } else {
            inner
        }
    };
    let mean = |h: &[f64], idx: &[(usize, f64)]| -> f64 {
        let w: f64 = idx.iter().map(|p| p.1).sum();
        idx.iter().map(|&(i, wi)| wi * h[i]).sum::<f64>() / w
    };
    match options.reference {
        Reference::Workpiece => {}
        Reference::ZoneIHeight => {
            let m = mean(&grid.h, &reference_area);
            grid.h.iter_mut().for_each(|h| *h -= m);
        }
        Reference::ZoneIPlane => {
            // Weighted least squares over ZONE I's central points: on a rectangular grid the
            // centred x and y are orthogonal, so each slope is a one-dimensional regression.
            let idx = &reference_area;
            let w: f64 = idx.iter().map(|p| p.1).sum();
            let m = mean(&grid.h, idx);
            let xm = idx.iter().map(|&(i, wi)| wi * grid.x[i % nx]).sum::<f64>() / w;
            let ym = idx.iter().map(|&(i, wi)| wi * grid.y[i / nx]).sum::<f64>() / w;
            let (mut sxz, mut sxx, mut syz, mut syy) = (0.0, 0.0, 0.0, 0.0);
            for &(i, wi) in idx {
                let (dx, dy, dz) = (grid.x[i % nx] - xm, grid.y[i / nx] - ym, grid.h[i] - m);
                sxz += wi * dx * dz;
                sxx += wi * dx * dx;
                syz += wi * dy * dz;
                syy += wi * dy * dy;
            }
            let sx = if sxx > 0.0 { sxz / sxx } else { 0.0 };
            let sy = if syy > 0.0 { syz / syy } else { 0.0 };
            for iy in 0..ny {
                for ix in 0..nx {
                    grid.h[iy * nx + ix] -= m + sx * (grid.x[ix] - xm) + sy * (grid.y[iy] - ym);
                }
            }
        }
    }
    let zone_average = members.iter().map(|idx| mean(&grid.h, idx)).collect();
    Ok(HeightMap {
        nx,
        ny,
        x: grid.x,
        y: grid.y,
        height: grid.h,
        zone_average,
        step,
        scallop: r - (r * r - 0.25 * step * step).sqrt(),
        passes: passes.len(),
        evaluations,
    })
}
