//! Li et al. (2021) in their own terms, for the tests of the cubic-machining study: their B/C
//! tilting table with its set-up, their eight errors in their own signs and order (Table 3),
//! and the engine's results turned back into those terms.
//!
//! The engine takes ISO 230-1 names; the paper's symbols enter through the engine's alias table
//! (`ErrorValues::from_aliases`), and the sensitivities come back per ISO error, which this
//! file turns into the paper's by its own definition `E_iso = −ε_paper` (so a wrong sign in the
//! engine's alias table would flip every height the tests compare with closed forms).
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use fiveaxis::cubic::{self, Analysis, CubicGrid, CubicPiece, HeightMap, Options, ZonePlane};
use fiveaxis::machine::errors::ErrorValues;
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use serde_json::json;

/// One of the paper's errors: its symbol, ASCII key, ISO name and whether it is an angle.
pub struct PaperError {
    pub symbol: &'static str,
    pub key: &'static str,
    pub iso: &'static str,
    pub angular: bool,
}

const fn e(
    symbol: &'static str,
    key: &'static str,
    iso: &'static str,
    angular: bool,
) -> PaperError {
    PaperError {
        symbol,
        key,
        iso,
        angular,
    }
}

/// Table 3's order.
pub const ERRORS: [PaperError; 8] = [
    e("δxBY", "dxBY", "E_X0B", false),
    e("δyBY", "dyBY", "E_Y0B", false),
    e("δzBY", "dzBY", "E_Z0B", false),
    e("αBY", "alphaBY", "E_A0B", true),
    e("βBY", "betaBY", "E_B0B", true),
    e("γBY", "gammaBY", "E_C0B", true),
    e("αCB", "alphaCB", "E_A0C", true),
    e("δxCB", "dxCB", "E_X0C", false),
];

/// The paper's eight errors, mm and rad, in the paper's signs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GeometricErrors(pub [f64; 8]);

impl GeometricErrors {
    pub fn single(k: usize, v: f64) -> Self {
        let mut a = [0.0; 8];
        a[k] = v;
        Self(a)
    }

    /// Table 5 (identified by ball bar).
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

    /// The machine's ISO errors, through the engine's alias table.
    pub fn iso(&self) -> ErrorValues {
        let values: Vec<(&str, f64)> = ERRORS
            .iter()
            .zip(self.0)
            .map(|(d, v)| (d.symbol, v))
            .collect();
        ErrorValues::from_aliases(&values).unwrap()
    }
}

/// The set-up of the earlier, paper-only version of the study: the trunnion's geometry and the
/// test piece together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicSetup {
    pub table_above_b: f64,
    pub workpiece_height: f64,
    pub c_offset: f64,
    pub workpiece_x: f64,
    pub workpiece_y: f64,
    pub zone_size: f64,
    pub tool_radius: f64,
    pub pick: f64,
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

impl CubicSetup {
    pub fn piece(&self) -> CubicPiece {
        CubicPiece::from_value(
            &json!({
                "workpieceHeight": self.workpiece_height, "workpieceX": self.workpiece_x,
                "workpieceY": self.workpiece_y, "zoneSize": self.zone_size,
                "toolRadius": self.tool_radius, "pick": self.pick, "stock": self.stock,
            }),
            "setup",
        )
        .unwrap()
    }

    pub fn passes_per_zone(&self) -> usize {
        self.piece().passes_per_zone()
    }

    pub fn step(&self) -> f64 {
        self.piece().step()
    }
}

/// The paper's machine (the page's preset): B on the bed, C on B, X Y Z on the spindle, with the
/// set-up's table height and C offset, and the errors.
pub fn machine(setup: &CubicSetup, errors: &GeometricErrors) -> Machine {
    let mut v = super::machine_preset("B/C tilting table, vertical spindle (Li et al. 2021)");
    v["geometry"]["rotaryOffset"] = json!(setup.c_offset);
    v["geometry"]["tableHeight"] = json!(setup.table_above_b);
    let mut m = Machine::from_value(&v, "machine").unwrap();
    m.errors = errors.iso();
    m
}

/// A zone in the paper's terms.
pub struct PaperZone {
    pub zone: cubic::ZoneDef,
    pub centre: [f64; 2],
    /// B and C, rad.
    pub b: f64,
    pub c: f64,
    pub exact: ZonePlane,
    pub linear: ZonePlane,
}

/// [`cubic::analyze`]'s results with the paper's errors as columns, in the paper's signs.
pub struct PaperAnalysis {
    pub zones: Vec<PaperZone>,
    pub sensitivity: Vec<[ZonePlane; 8]>,
    pub single: Vec<[f64; 8]>,
    pub engine: Analysis,
}

fn neg(p: &ZonePlane) -> ZonePlane {
    ZonePlane {
        height: -p.height,
        slope_x: -p.slope_x,
        slope_y: -p.slope_y,
    }
}

pub fn run(setup: &CubicSetup, e: &GeometricErrors, o: &Options) -> PaperAnalysis {
    try_run(setup, e, o).unwrap()
}

pub fn try_run(
    setup: &CubicSetup,
    e: &GeometricErrors,
    o: &Options,
) -> fiveaxis::Result<PaperAnalysis> {
    let a = cubic::analyze(&machine(setup, e), &setup.piece(), o)?;
    let col = |k: usize| {
        a.errors
            .iter()
            .position(|d| d.name == ERRORS[k].iso)
            .unwrap()
    };
    let sensitivity = a
        .sensitivity
        .iter()
        .map(|row| std::array::from_fn(|k| neg(&row[col(k)])))
        .collect();
    // An error alone gives the same deviation whichever name it is entered by.
    let single = a
        .single
        .iter()
        .map(|row| std::array::from_fn(|k| row[col(k)]))
        .collect();
    let zones = a
        .zones
        .iter()
        .map(|z| PaperZone {
            zone: z.zone,
            centre: z.centre,
            // CBZ: K = C, M = B.
            b: z.rotary[1],
            c: z.rotary[0],
            exact: z.exact,
            linear: z.linear,
        })
        .collect();
    Ok(PaperAnalysis {
        zones,
        sensitivity,
        single,
        engine: a,
    })
}

pub fn height_map(
    setup: &CubicSetup,
    e: &GeometricErrors,
    o: &Options,
    nx: usize,
    ny: usize,
) -> fiveaxis::Result<HeightMap> {
    cubic::height_map(
        &machine(setup, e),
        &setup.piece(),
        o,
        &CubicGrid { nx, ny: Some(ny) },
    )
}
