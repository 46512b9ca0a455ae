//! The nine zones on one machine: their poses from the inverse kinematics, the exact machined
//! plane of each, and its first-order sensitivities (module docs of [`super`]).

use super::{CubicPiece, Options, ZonePlane, BRANCH};
use crate::chain::{Chain, Setup};
use crate::error::{Error, Result};
use crate::machine::errors::{ErrorDef, ErrorValues};
use crate::machine::{Machine, Model};
use nalgebra::Vector3;
use serde::Serialize;

/// A zone of the test piece (Fig 2, Table 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZoneDef {
    /// "I", "II-1", … "III-4".
    pub name: &'static str,
    /// Column −1 (left, −u), 0, 1 (right).
    pub col: i32,
    /// Row −1 (bottom, −v), 0, 1 (top).
    pub row: i32,
    /// Tool vector `(i, j, k)` of Table 1 in the face frame `(u, v, n)`, tip → spindle.
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

/// A zone of any layout: its name, centre on the face and tool vector in the face frame.
#[derive(Debug, Clone, PartialEq)]
pub struct ZoneSpec {
    /// Its name ("II-1", "Z3").
    pub name: String,
    /// Centre `(x, y)` on the face (along `u`, `v`), mm.
    pub centre: (f64, f64),
    /// Tool vector `(i, j, k)` in the face frame `(u, v, n)`, unit, tip → spindle.
    pub tool: [f64; 3],
}

impl ZoneSpec {
    /// Table 1's zone on a piece with zones of `size` mm.
    pub fn paper(def: &ZoneDef, size: f64) -> Self {
        Self {
            name: def.name.to_string(),
            centre: (def.col as f64 * size, def.row as f64 * size),
            tool: def.tool,
        }
    }
}

/// A zone placed on the face: its definition, centre and the pose used to cut it.
#[derive(Debug, Clone)]
pub(super) struct Zone {
    /// Centre on the face `(x, y)`, mm.
    pub(super) centre: (f64, f64),
    /// Tool vector in the workpiece frame.
    pub(super) dir: Vector3<f64>,
    /// Axis positions (chain order) for the zone centre.
    q: Vec<f64>,
    /// K and M commands, rad.
    pub(super) rotary: [f64; 2],
    pub(super) singular: bool,
}

/// The test on one machine: the model (errors, workpiece placed), its set-up and the zones.
pub(super) struct Test {
    model: Model,
    setup: Setup,
    piece: CubicPiece,
    /// The face frame `(u, v, n)` in workpiece coordinates.
    frame: [Vector3<f64>; 3],
    pub(super) zones: Vec<Zone>,
}

/// The machine's model with the test piece placed on the table (face frame `frame`).
fn placed(machine: &Machine, piece: &CubicPiece, frame: &[Vector3<f64>; 3]) -> Result<Model> {
    let mut model = machine.build()?;
    let [u, v, n] = frame;
    model.place_workpiece(
        &(u * piece.workpiece_x + v * piece.workpiece_y + n * piece.workpiece_height),
    );
    Ok(model)
}

impl Test {
    /// The paper's nine zones (Table 1, Fig 2).
    pub(super) fn new(machine: &Machine, piece: &CubicPiece, options: &Options) -> Result<Self> {
        let specs: Vec<ZoneSpec> = ZONES
            .iter()
            .map(|d| ZoneSpec::paper(d, piece.zone_size))
            .collect();
        Self::with_zones(machine, piece, options, &specs)
    }

    /// Any layout of zones; the first is the reference zone of [`super::CubicReference`].
    pub(super) fn with_zones(
        machine: &Machine,
        piece: &CubicPiece,
        options: &Options,
        specs: &[ZoneSpec],
    ) -> Result<Self> {
        piece.validate()?;
        let frame = machine.face_frame();
        let model = placed(machine, piece, &frame)?;
        let setup = if options.transform {
            Setup::AtPose(vec![0.0; model.chain.len()])
        } else {
            Setup::None
        };
        let mut test = Self {
            model,
            setup,
            piece: piece.clone(),
            frame,
            zones: Vec::with_capacity(specs.len()),
        };
        for spec in specs {
            let zone = test.place(spec)?;
            test.zones.push(zone);
        }
        Ok(test)
    }

    /// A zone of `spec` on this test's machine and set-up: its pose by the inverse kinematics
    /// within the travel (an error naming the zone when out of it).
    pub(super) fn place(&self, spec: &ZoneSpec) -> Result<Zone> {
        let [u, v, n] = self.frame;
        let [i, j, k] = spec.tool;
        let dir = u * i + v * j + n * k;
        let centre = spec.centre;
        let tip = nominal_tip(
            &self.frame,
            centre.0,
            centre.1,
            &dir,
            self.piece.tool_radius,
        );
        let s = self
            .model
            .inverse(&tip, &dir, BRANCH, None)
            .map_err(|e| Error::field("machine", format!("ZONE {}: {}", spec.name, e.message)))?;
        Ok(Zone {
            centre,
            dir,
            rotary: self.model.rotary_of(&s.q),
            q: s.q,
            singular: s.singular,
        })
    }

    /// The same test on the machine with only the location errors `errors` (no error motions):
    /// the zones' poses come from the nominal machine, so only the model is built again.
    pub(super) fn with_errors(&self, errors: ErrorValues) -> Result<Self> {
        let mut machine = self.model.machine.without_errors();
        machine.errors = errors;
        Ok(Self {
            model: placed(&machine, &self.piece, &self.frame)?,
            setup: self.setup.clone(),
            piece: self.piece.clone(),
            frame: self.frame,
            zones: self.zones.clone(),
        })
    }

    fn chain(&self) -> &Chain {
        &self.model.chain
    }

    /// Axis positions that cut the functional point `(x, y)` of the face in `zone` (same rotary
    /// pose).
    fn positions(&self, zone: &Zone, x: f64, y: f64) -> Result<Vec<f64>> {
        let tip = nominal_tip(&self.frame, x, y, &zone.dir, self.piece.tool_radius);
        self.model.nominal().solve_linear(&tip, &zone.q)
    }

    /// The actual tool centre in face coordinates `(x, y, h)` when the NC program cuts `(x, y)`.
    pub(super) fn centre(&self, zone: &Zone, x: f64, y: f64) -> Result<Vector3<f64>> {
        let q = self.positions(zone, x, y)?;
        let p = self.chain().tool_pose(&q, true, &self.setup)?;
        Ok(self.to_face(&(p.tip + self.piece.tool_radius * p.axis)))
    }

    /// Workpiece coordinates → face coordinates `(u·p, v·p, n·p)`.
    fn to_face(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let [u, v, n] = &self.frame;
        Vector3::new(u.dot(p), v.dot(p), n.dot(p))
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
    pub(super) fn plane(&self, zone: &Zone) -> Result<ZonePlane> {
        let [p1, p2, p3] = self.probe_points(zone);
        let c1 = self.centre(zone, p1.0, p1.1)?;
        let c2 = self.centre(zone, p2.0, p2.1)?;
        let c3 = self.centre(zone, p3.0, p3.1)?;
        let n = (c2 - c1).cross(&(c3 - c1));
        let n = n / n.norm();
        if !n.z.is_finite() || n.z < 0.5 {
            return Err(Error::field(
                "machine.errors",
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

    /// First-order sensitivities of a zone's plane to `errors` (per mm, per rad).
    pub(super) fn sensitivities(
        &self,
        zone: &Zone,
        errors: &[&'static ErrorDef],
    ) -> Result<Vec<ZonePlane>> {
        let r = self.piece.tool_radius;
        let n = self.frame[2];
        let columns: Vec<usize> = errors
            .iter()
            .map(|d| self.model.error_column(d))
            .collect::<Result<_>>()?;
        let mut dz = vec![vec![0.0; errors.len()]; 3];
        for (j, (x, y)) in self.probe_points(zone).into_iter().enumerate() {
            let q = self.positions(zone, x, y)?;
            let jac = self.chain().jacobian(&q, &self.setup)?;
            for (e, &c) in columns.iter().enumerate() {
                let s = &jac[c];
                dz[j][e] = n.dot(&(s.tip + r * s.axis));
            }
        }
        let a = self.probe_step();
        Ok((0..errors.len())
            .map(|e| ZonePlane {
                height: dz[0][e],
                slope_x: (dz[1][e] - dz[0][e]) / a,
                slope_y: (dz[2][e] - dz[0][e]) / a,
            })
            .collect())
    }
}

/// The tool tip of the NC program for the functional point `(x, y)` of the face (eq 1):
/// `P_f + r·(n − v_tool)`, workpiece coordinates.
fn nominal_tip(
    frame: &[Vector3<f64>; 3],
    x: f64,
    y: f64,
    dir: &Vector3<f64>,
    r: f64,
) -> Vector3<f64> {
    let [u, v, n] = frame;
    u * x + v * y + (n - dir) * r
}
