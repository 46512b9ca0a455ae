//! The cubic-machining test (Li, Sato, Shirase & Sakamoto, *Precision Engineering* 71, 2021) on
//! any five-axis machine: which of the nine zones of the test piece come out high or low for
//! the machine's geometric errors, and which errors the test can see at all.
//!
//! # The test piece (Section 2, Tables 1 and 2, Fig 2)
//! A `3·zoneSize` square face (48 × 48 mm) in 3 × 3 zones (16 × 16 mm), [`ZONES`] in Table 1's
//! order (also the machining order of Section 5.1). Each zone is cut with a fixed tool vector
//! (Table 1, from the tip to the spindle), a ball-end mill of radius `r` (3 mm), zig-zag passes
//! along the face's first axis with a pick feed `p` (0.1 mm) along its second.
//!
//! **On any machine** the face is square to the spindle's home direction `e_H` and laid out in
//! the machine's face frame `(u, v, n)` ([`crate::machine::face_frame`]: `n = e_H`, `u, v` the
//! next two machine axes in cyclic order, X and Y for a vertical spindle as in the paper). The
//! zones keep the paper's tool vectors in that frame: `(i, j, k)` of Table 1 is `i·u + j·v +
//! k·n`. The workpiece frame W has its origin at the centre of the nominal face and the machine
//! axes' directions; the face is `n·p = 0`, heights are along `n`, positions on the face
//! `(x, y) = (u·p, v·p)`. The face centre sits `workpieceHeight` above the table surface and
//! `(workpieceX, workpieceY)` along `(u, v)` from the table centre ([`crate::machine`] puts the
//! table surface `tableHeight` from the rotary centre).
//!
//! **Rotary angles** come from the machine's inverse kinematics within its travel
//! ([`crate::machine::Model::inverse`], rule [`BranchRule::SmallestTilt`]): the smallest tilt, of
//! two equal tilts the one with M ≥ 0, each axis written in `[0°, 360°)` when its travel allows
//! (else nearest 0°). On Li et al.'s B/C table this is their Table 2 (B = 30° ≥ 0, C in
//! `[0°, 360°)`). A zone the machine cannot reach within its travel is an error naming the zone,
//! not a result.
//!
//! A functional point `P_f` on the face becomes the tool tip of the NC program by eq 1,
//! `P_t = P_f + r·(n − v_tool)` (the paper's `P_f + r·(−i, −j, 1 − k)`), and the tool centre is
//! `P_c = P_t + r·v_tool` (eq 14), carried into W by the chain with errors.
//!
//! # Errors
//! Every location error of the machine's table ([`crate::machine::errors`]) acts. Li et al.'s
//! eight are those of a B/C table written with the opposite sign (`E_X0B = −δxBY`, …); the
//! chain test `the_chain_reproduces_eqs_2_and_10_to_12_of_the_cubic_paper_exactly` checks that
//! this is exact, not only to first order: the chain's `D(−ε) = T(−δ)·R_X(−α)·R_Y(−β)·R_Z(−γ)`
//! is the inverse of the paper's `M_γ·M_β·M_α·M_δ` (eqs 4–9).
//!
//! # Height deviation and tilt of a zone (Section 4)
//! Within a zone the rotary axes stand still, so the actual tool centres are the nominal ones
//! moved by one rigid displacement (the linear axes' squareness errors included: their effect
//! is affine in the linear positions): they lie on a plane, and the machined surface (the
//! envelope of the ball) is that plane moved down by `r` along its normal. Three actual centres
//! (the zone centre and `zoneSize/2` along `u` and `v`) give the surface's **height** at the
//! nominal zone centre (exactly, mm) and its **slopes** `∂h/∂x`, `∂h/∂y` (the tilt). The ball
//! radius cancels. **Sign** (Section 4.2): positive is a surface above nominal, material left.
//!
//! **Frames** ([`CubicReference`], `transform`): with the workpiece transform (eqs 10–12, Fig 12) the
//! workpiece is set up with every axis at zero, where it coincides with the nominal table
//! ([`Setup::AtPose`](crate::chain::Setup::AtPose)), so a zone cut there (ZONE I on a Group I machine) is exact; without it
//! (eq 2, Fig 10) W is the erroneous table frame. The heights are measured from W, or from the
//! measurement frame of Section 5.1 set on ZONE I: shifted to ZONE I's height (the text), or also
//! levelled on ZONE I's plane (Fig 15).
//!
//! **Sensitivities** (eq 15, Figs 10, 12): `k = E/ε` per mm or per rad, from the chain's analytic
//! first-order derivatives ([`crate::chain::Chain::jacobian`]: centre sensitivity
//! `∂tip/∂ε + r·∂axis/∂ε` along `n`); [`analyze`] also gives the exact deviation of each error
//! alone at its entered value, so that `E/ε` can be compared with `k`. [`Visibility`] says which
//! errors the test cannot see at all (zero height sensitivity in every zone) and which it cannot
//! tell apart (proportional height sensitivities).

pub mod design;
pub mod identify;
mod map;
pub mod results;
mod zones;

pub use map::{height_map, HeightMap, ZoneAt, MAX_GRID_POINTS, MAX_GRID_SIDE};
pub use zones::{ZoneDef, ZoneSpec, ZONES};

use crate::error::{Error, Result};
use crate::machine::errors::{ErrorDef, ErrorValues};
use crate::machine::{BranchRule, Machine};
use crate::schema::{self, DefaultValue, Inputs, Kind, Quantity};
use serde::Serialize;
use serde_json::Value;
use zones::Test;

crate::choices! {
    /// What the heights are measured from (module docs).
    pub enum CubicReference {
        /// The workpiece frame: the nominal face is at height 0.
        Workpiece = "workpiece" {
            label: "Workpiece frame (nominal face)",
            help: "Heights from the nominal face of the workpiece coordinate system.",
        },
        /// Section 5.1's measurement frame, shifted to ZONE I's height.
        ZoneIHeight = "zone1-height" {
            label: "ZONE I's height",
            help: "Heights relative to ZONE I (the centre zone), as Li et al. measure them (Section 5.1).",
        },
        /// Levelled on ZONE I's plane (Fig 15).
        ZoneIPlane = "zone1-plane" {
            label: "ZONE I's plane, levelled",
            help: "Heights relative to ZONE I's surface, tilt included, as a profilometer levels them (Fig 15).",
        },
    }
}

/// Largest accepted set-up distance (workpiece height and position), mm.
pub const MAX_SETUP_MM: f64 = 2000.0;
/// Most zig-zag passes per zone.
pub const MAX_PASSES_PER_ZONE: usize = 20_000;

crate::inputs! {
    /// The test piece, where it sits on the table, and the cut, mm.
    ///
    /// Defaults: Li et al.'s 50 mm block centred on the table, 16 mm zones, a ball-end mill of
    /// radius 3 mm (Ø6, Table 4), 0.1 mm pick feed and 0.1 mm stock (the depth of cut, Table 4).
    /// The vertical set-up never enters the first-order zone heights (a small rotation moves a
    /// point along `n` in proportion to its distance from the axis across `n`); the workpiece's
    /// place on the table does.
    pub struct CubicPiece {
        /// Height of the face above the table surface, mm.
        pub workpiece_height: f64 = "workpieceHeight" optional {
            label: "Workpiece height",
            help: "Top face (the machined face) above the table surface.",
            kind: schema::positive(Quantity::Length, MAX_SETUP_MM),
            default: DefaultValue::Num(50.0),
            group: "Test piece",
        },
        /// Face centre from the table centre along `u`, mm.
        pub workpiece_x: f64 = "workpieceX" optional {
            label: "Face centre off the table centre, along {U}",
            help: "Where the test piece stands on the table: its centre's distance from the table's centre (the rotary axis) along the face's first axis.",
            kind: schema::number(Quantity::Length, -MAX_SETUP_MM, MAX_SETUP_MM),
            default: DefaultValue::Num(0.0),
            group: "Test piece",
        },
        /// Face centre from the table centre along `v`, mm.
        pub workpiece_y: f64 = "workpieceY" optional {
            label: "Face centre off the table centre, along {V}",
            help: "The same along the face's second axis.",
            kind: schema::number(Quantity::Length, -MAX_SETUP_MM, MAX_SETUP_MM),
            default: DefaultValue::Num(0.0),
            group: "Test piece",
        },
        /// Side of one zone, mm.
        pub zone_size: f64 = "zoneSize" optional {
            label: "Zone size",
            help: "Side of one zone; the face is 3 × 3 zones.",
            kind: schema::number(Quantity::Length, 1.0, 200.0),
            default: DefaultValue::Num(16.0),
            group: "Test piece",
        },
        /// Radius `r` of the ball-end mill, mm.
        pub tool_radius: f64 = "toolRadius" optional {
            label: "Ball-end radius r",
            help: "Radius of the ball-end mill (Li et al.: Ø6 mm).",
            kind: schema::number(Quantity::Length, 0.05, 50.0),
            default: DefaultValue::Num(3.0),
            group: "Test piece",
        },
        /// Pick feed between passes, mm.
        pub pick: f64 = "pick" optional {
            label: "Pick feed p",
            help: "Step between zig-zag passes; the passes of a zone run at its two edges and in equal steps no larger than this between.",
            kind: schema::number(Quantity::Length, 0.001, 200.0),
            default: DefaultValue::Num(0.1),
            group: "Test piece",
        },
        /// Material above the nominal face before the finishing cut, mm.
        pub stock: f64 = "stock" optional {
            label: "Stock above the face",
            help: "Depth of cut: what stays where no pass reaches (a zone moved sideways by large errors).",
            kind: schema::positive(Quantity::SmallLength, 50.0),
            default: DefaultValue::Num(0.1),
            group: "Test piece",
        },
    }
}

crate::inputs! {
    /// The inputs of the cubic-machining test.
    pub struct CubicInput {
        /// The machine and its errors.
        pub machine: Machine = "machine" optional {
            label: "Machine",
            kind: Kind::Object(Machine::FIELDS),
            default: DefaultValue::Empty,
        },
        /// The test piece.
        pub setup: CubicPiece = "setup" optional {
            label: "Test piece",
            kind: Kind::Object(CubicPiece::FIELDS),
            default: DefaultValue::Empty,
        },
        /// With the workpiece transform `M_WC` (eqs 10–12): set up with every axis at zero.
        pub transform: bool = "transform" optional {
            label: "Workpiece set with every axis at zero",
            help: "On: the workpiece coordinate system is set with every axis at zero, as a probe would set it, so a zone cut there is exact. Off: the workpiece frame is the erroneous table frame (the conventional model). Li et al.'s M_WC, eqs 10–12.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(true),
            group: "Model",
        },
        /// What the heights are measured from.
        pub reference: CubicReference = "reference" optional {
            label: "Heights measured from",
            help: "The nominal face, or ZONE I as Li et al. measure (its height, or its plane).",
            kind: Kind::Choice(CubicReference::CHOICES),
            default: DefaultValue::Str("workpiece"),
            group: "Model",
        },
    }
}

crate::inputs! {
    /// The grid of the simulated face.
    pub struct CubicGrid {
        /// Points along the face's first axis.
        pub nx: usize = "nx" {
            label: "Height-map points along {U}",
            help: "193 gives 0.25 mm steps over 48 mm.",
            kind: Kind::Count { min: 4, max: MAX_GRID_SIDE },
            default: DefaultValue::Num(193.0),
            group: "Height map",
        },
        /// Points along the second axis; automatic when left out.
        pub ny: Option<usize> = "ny" optional {
            label: "Height-map points along {V}",
            help: "Left empty: four points per pass step, aligned with the passes, so that the scallops are sampled evenly.",
            kind: Kind::Count { min: 4, max: MAX_GRID_SIDE },
            group: "Height map",
        },
    }
}

impl CubicPiece {
    /// Checks what the field table cannot: the pick against the ball and the number of passes
    /// (messages name `setup.<field>`).
    pub fn validate(&self) -> Result<()> {
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
        if self.pick > self.zone_size {
            return Err(Error::field(
                "setup.pick",
                format!(
                    "must be at most the zone size {} mm, got {}",
                    self.zone_size, self.pick
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

impl CubicInput {
    /// Reads and checks the inputs (schema, then the machine and the piece).
    pub fn read(value: &Value) -> Result<Self> {
        <Self as crate::edge::ApiInput>::read(value)
    }

    /// Reads and checks the inputs of the height map: the test's and the grid's keys in one
    /// object.
    pub fn read_with_grid(value: &Value) -> Result<(Self, CubicGrid)> {
        Self::read_with(value)
    }

    /// Reads and checks the test's inputs and an export's own (`B`) from one object.
    pub fn read_with<B: Inputs>(value: &Value) -> Result<(Self, B)> {
        let (input, own): (Self, B) = schema::read_split(value, "")?;
        crate::edge::Checked::check(&input)?;
        Ok((input, own))
    }

    /// The options of the evaluation.
    pub fn options(&self) -> Options {
        Options {
            transform: self.transform,
            reference: self.reference,
        }
    }
}

/// How the deviations are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// With the workpiece transform `M_WC`: the workpiece set with every axis at zero.
    pub transform: bool,
    /// What the heights are measured from.
    pub reference: CubicReference,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            transform: true,
            reference: CubicReference::Workpiece,
        }
    }
}

/// The rule the test uses to pick the rotary angles of a zone (module docs).
pub const BRANCH: BranchRule = BranchRule::SmallestTilt;

/// A plane over a zone: its height at the zone centre and its slopes.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ZonePlane {
    /// Height at the nominal zone centre, mm (or per unit error for a sensitivity).
    pub height: f64,
    /// `∂h/∂x` along the face's first axis, dimensionless (or per unit error).
    pub slope_x: f64,
    /// `∂h/∂y` along its second axis, dimensionless (or per unit error).
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

/// Planes of the nine zones (Table 1 order) measured from `reference`: ZONE I (index 0) is the
/// reference zone. Linear in the planes, so it applies to sensitivities as well.
pub(crate) fn relative(
    planes: &[ZonePlane],
    centres: &[(f64, f64)],
    reference: CubicReference,
) -> Vec<ZonePlane> {
    let z1 = planes[0];
    planes
        .iter()
        .zip(centres)
        .map(|(p, &(x, y))| match reference {
            CubicReference::Workpiece => *p,
            CubicReference::ZoneIHeight => ZonePlane {
                height: p.height - z1.height,
                ..*p
            },
            CubicReference::ZoneIPlane => ZonePlane {
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
    /// Nominal centre `(x, y)` on the face (along `u`, `v`), mm.
    pub centre: [f64; 2],
    /// The tool vector in the workpiece frame (machine axes), tip → spindle.
    pub tool: [f64; 3],
    /// K and M commands that cut it, rad (Table 2).
    pub rotary: [f64; 2],
    /// The tool lies along K here (K is arbitrary; 0 is used).
    pub singular: bool,
    /// The exact machined plane for all the entered errors together.
    pub exact: ZonePlane,
    /// The first-order estimate `Σ k·ε` over the machine's errors.
    pub linear: ZonePlane,
}

/// What the test can see of each error (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Visibility {
    /// Errors with zero height sensitivity in every zone: the test cannot see them at all.
    pub invisible: Vec<&'static str>,
    /// Of those, the ones that do tilt some zone (visible to a profilometer's levelling only).
    pub tilt_only: Vec<&'static str>,
    /// Groups of errors whose height sensitivities are proportional: the heights cannot tell
    /// them apart. Each member with its factor: `k_member = factor · k_first`.
    pub alike: Vec<Vec<(&'static str, f64)>>,
    /// Rank of the 9 × n height-sensitivity matrix: how many independent combinations of the
    /// errors the zone heights can determine.
    pub rank: usize,
}

/// Everything [`analyze`] finds, in the frame and reference of its [`Options`].
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// The nine zones in Table 1's order.
    pub zones: Vec<ZoneResult>,
    /// The machine's errors, the columns of the tables below (table order).
    pub errors: Vec<&'static ErrorDef>,
    /// `sensitivity[zone][error]`: `k = ∂E/∂ε` of the height (mm/mm or mm/rad) and the slopes
    /// (1/mm or 1/rad).
    pub sensitivity: Vec<Vec<ZonePlane>>,
    /// `single[zone][error]`: the exact height deviation, mm, with only that error present at
    /// its entered value (0 where the entered value is 0): `E_ε` of eq 15.
    pub single: Vec<Vec<f64>>,
    /// What the test can and cannot see.
    pub visibility: Visibility,
}

/// Zone heights, slopes and sensitivities of the cubic-machining test on `machine` (module
/// docs).
pub fn analyze(machine: &Machine, piece: &CubicPiece, options: &Options) -> Result<Analysis> {
    let test = Test::new(machine, piece, options)?;
    let centres: Vec<(f64, f64)> = test.zones.iter().map(|z| z.centre).collect();
    let exact: Vec<ZonePlane> = test
        .zones
        .iter()
        .map(|z| test.plane(z))
        .collect::<Result<_>>()?;
    let exact = relative(&exact, &centres, options.reference);

    let errors = machine.error_defs();
    let raw: Vec<Vec<ZonePlane>> = test
        .zones
        .iter()
        .map(|z| test.sensitivities(z, &errors))
        .collect::<Result<_>>()?;
    let mut sensitivity = vec![vec![ZonePlane::default(); errors.len()]; raw.len()];
    for e in 0..errors.len() {
        let column: Vec<ZonePlane> = raw.iter().map(|k| k[e]).collect();
        for (z, p) in relative(&column, &centres, options.reference)
            .into_iter()
            .enumerate()
        {
            sensitivity[z][e] = p;
        }
    }

    let mut single = vec![vec![0.0; errors.len()]; test.zones.len()];
    for (e, def) in errors.iter().enumerate() {
        let v = machine.errors.get(def.name);
        if v == 0.0 {
            continue;
        }
        let t = test.with_errors(ErrorValues::single(def.name, v)?)?;
        let planes: Vec<ZonePlane> = t.zones.iter().map(|z| t.plane(z)).collect::<Result<_>>()?;
        for (z, p) in relative(&planes, &centres, options.reference)
            .into_iter()
            .enumerate()
        {
            single[z][e] = p.height;
        }
    }

    let zones = ZONES
        .iter()
        .zip(&test.zones)
        .zip(&exact)
        .zip(&sensitivity)
        .map(|(((def, z), p), k)| {
            let linear = k
                .iter()
                .zip(&errors)
                .fold(ZonePlane::default(), |acc, (k, d)| {
                    acc.plus(&k.scaled(machine.errors.get(d.name)))
                });
            ZoneResult {
                zone: *def,
                centre: [z.centre.0, z.centre.1],
                tool: z.dir.into(),
                rotary: z.rotary,
                singular: z.singular,
                exact: *p,
                linear,
            }
        })
        .collect();
    let visibility = visibility(&errors, &sensitivity, piece.zone_size);
    Ok(Analysis {
        zones,
        errors,
        sensitivity,
        single,
        visibility,
    })
}

/// Below this a sensitivity counts as zero: per mm for a position, per `zoneSize` radians for an
/// angle (so both compare as dimensionless height changes).
pub const ZERO_SENSITIVITY: f64 = 1e-9;

/// Which errors the heights cannot see or tell apart (module docs of [`Visibility`]).
fn visibility(errors: &[&'static ErrorDef], k: &[Vec<ZonePlane>], zone: f64) -> Visibility {
    let n = errors.len();
    let scale = |e: usize| {
        if errors[e].quantity == Quantity::SmallAngle {
            zone
        } else {
            1.0
        }
    };
    let column = |e: usize, f: fn(&ZonePlane) -> f64| -> Vec<f64> {
        k.iter().map(|row| f(&row[e]) / scale(e)).collect()
    };
    let norm = |c: &[f64]| c.iter().map(|x| x * x).sum::<f64>().sqrt();
    let heights: Vec<Vec<f64>> = (0..n).map(|e| column(e, |p| p.height)).collect();
    let mut invisible = Vec::new();
    let mut tilt_only = Vec::new();
    for e in 0..n {
        if norm(&heights[e]) < ZERO_SENSITIVITY {
            invisible.push(errors[e].name);
            let tilts = norm(&column(e, |p| p.slope_x)) + norm(&column(e, |p| p.slope_y));
            if tilts * zone >= ZERO_SENSITIVITY {
                tilt_only.push(errors[e].name);
            }
        }
    }
    let mut grouped = vec![false; n];
    let mut alike = Vec::new();
    for a in 0..n {
        let na = norm(&heights[a]);
        if grouped[a] || na < ZERO_SENSITIVITY {
            continue;
        }
        let mut group = vec![(errors[a].name, 1.0)];
        for b in a + 1..n {
            let nb = norm(&heights[b]);
            if grouped[b] || nb < ZERO_SENSITIVITY {
                continue;
            }
            let dot: f64 = heights[a].iter().zip(&heights[b]).map(|(x, y)| x * y).sum();
            if (dot.abs() / (na * nb) - 1.0).abs() < 1e-9 {
                grouped[b] = true;
                // k_b = factor · k_a in the errors' own units (per mm or per rad).
                group.push((errors[b].name, dot / (na * na) * scale(b) / scale(a)));
            }
        }
        if group.len() > 1 {
            alike.push(group);
        }
    }
    let m = nalgebra::DMatrix::from_fn(k.len(), n, |z, e| heights[e][z]);
    let rank = if n == 0 {
        0
    } else {
        m.svd(false, false)
            .singular_values
            .iter()
            .filter(|s| **s > ZERO_SENSITIVITY)
            .count()
    };
    Visibility {
        invisible,
        tilt_only,
        alike,
        rank,
    }
}
