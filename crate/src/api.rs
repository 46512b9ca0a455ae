//! The engine's API: every export declared once ([`for_each_export!`]), and the conventions its
//! results cross the JSON/JavaScript edge with.
//!
//! An export is a name, an input type, a result type and the engine function between them
//! (`fn(&Input) -> Result<Output>`). From that one line:
//! * the binding crate (`wasm/`) writes the `#[wasm_bindgen]` function and its `schema()` entry;
//! * [`call`] runs the same export natively on JSON (benches, tests, scripts);
//! * tsify writes the TypeScript declarations of the input and result types (feature `ts`).
//!
//! The edge's conventions for inputs and results are in [`crate::edge`]; this module sits on top
//! of every study (it names them all), and no study names it.

pub use crate::edge::{ApiInput, Checked};
use crate::machine::errors::{ErrorDef, TABLE};
use crate::machine::motions::MOTIONS;
use crate::machine::Machine;
use crate::schema::{describe, FieldInfo, Inputs};
use crate::Result;
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;

/// Every input the page renders and the engine reads (see `schema`).
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(
    feature = "ts",
    derive(tsify::Tsify),
    tsify(missing_as_null, hashmap_as_object)
)]
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
    /// Per list kind of a field (its `kind`, e.g. `"ballbarTests"`), the fields of one item,
    /// paths relative to the item (`"ball.x"` of `tests[0].ball.x`).
    pub lists: BTreeMap<String, Vec<FieldInfo>>,
}

/// The schema of every input: the machine's fields, the error table and each export's fields
/// (the declared ones and `extra`, the binding's hand-written ones), with labels, plain-language
/// help, units (mm, deg), limits and defaults.
pub fn schema(extra: Vec<(&str, Vec<FieldInfo>)>) -> Schema {
    Schema {
        machine: describe(Machine::FIELDS, "machine"),
        errors: TABLE.to_vec(),
        motions: MOTIONS.to_vec(),
        exports: export_fields()
            .into_iter()
            .chain(extra)
            .map(|(n, f)| (n.to_string(), f))
            .collect(),
        lists: BTreeMap::from([(
            crate::ballbar::rotary::TESTS_KIND.to_string(),
            describe(crate::ballbar::rotary::RotaryTest::FIELDS, ""),
        )]),
    }
}

/// Every export, declared once, handed to the macro `$then` as rows of
/// `$(#[doc = "…"])* jsName(Input as "TS input") -> "TS output" = engine::function;`
/// (`Input` implements [`ApiInput`]; the function is `fn(&Input) -> Result<impl Serialize>`).
/// The docs are `#[doc = "…"]` lines, not `///`: wasm-bindgen copies a `///` passed through a
/// macro into the `.d.ts` with its raw-string quotes.
#[macro_export]
macro_rules! for_each_export {
    ($then:ident) => {
        $then! {
            // machine
            #[doc = "The twelve rotary-axis types with their group and axes."]
            rotaryTypes(() as "undefined | void") -> "RotaryTypeInfo[]" = $crate::machine::api::rotary_types;
            #[doc = "The machine drawn from its chain at the commands `k`, `m` (degrees), and its axes in"]
            #[doc = "words: so that the user can see that the machine entered is theirs."]
            machineSchematic($crate::machine::SchematicInput as "SchematicInput")
                -> "MachineDrawing" = $crate::machine::api::drawing;
            #[doc = "The tool direction `(i, j, k)` in workpiece coordinates at the commands `k`, `m`"]
            #[doc = "(degrees), from the machine's nominal chain."]
            toolVector($crate::machine::ToolVectorInput as "ToolVectorInput")
                -> "[number, number, number]" = $crate::machine::api::tool_vector;
            #[doc = "The rotary commands that give a tool direction on this machine: every solution"]
            #[doc = "(degrees), whether it is within the travel, and `chosen`, the index of the one the"]
            #[doc = "rule picks (nearest `previous` by default; null when none is within the travel,"]
            #[doc = "with `unreachable` saying why)."]
            machineInverse($crate::machine::InverseInput as "InverseInput")
                -> "Orientations" = $crate::machine::api::inverse;
            // volumetric
            #[doc = "The tool tip's deviation over a plane of the working volume for all the machine's"]
            #[doc = "errors and error motions, its worst point and the error budget."]
            volumetricMap($crate::volumetric::VolumetricInput as "VolumetricInput")
                -> "VolumetricMap" = $crate::volumetric::map;
            #[doc = "Tan & Lim's RRTTT model (their loop and their printed first-order formulas) beside"]
            #[doc = "the machine's exact model at one pose of their machine."]
            volumetricPaper($crate::volumetric::VolumetricPaperInput as "VolumetricPaperInput")
                -> "PaperComparison" = $crate::volumetric::compare_input;
            #[doc = "Reads a measured table of one error motion from CSV (`{ name: \"E_XX\", text }`):"]
            #[doc = "positions in mm or degrees, values in mm or degrees, converted from the units in"]
            #[doc = "the header. Errors name the line: `csv: line 7: …`. The result's `position` and"]
            #[doc = "`value` go into `machine.motions[name]` as they are."]
            volumetricReadTable($crate::volumetric::MotionTableInput as "MotionTableInput")
                -> "CsvTable" = $crate::volumetric::read_table;
            // ballbar (ISO 230-4)
            #[doc = "A ball-bar circular test (ISO 230-4) from its trace: the circular deviation G"]
            #[doc = "(each way and both), the hysteresis H, and the faults fitted by least squares"]
            #[doc = "with 95 % intervals: centre offset, scale mismatch (ppm), squareness (µm/m),"]
            #[doc = "servo mismatch (ms), backlash per axis, harmonics and reversal spikes."]
            ballbarEvaluate($crate::ballbar::BallbarInput as "BallbarInput")
                -> "Ballbar" = $crate::ballbar::evaluate;
            // positioning (ISO 230-2)
            #[doc = "A positioning test of one axis (laser runs, ISO 230-2:2014): per target the mean"]
            #[doc = "deviations each way, s, R_i and B_i; for the axis B, R, E, M and A each way and"]
            #[doc = "bidirectional, judged against the tolerances given; and the mean bidirectional"]
            #[doc = "deviation as the axis's positioning error motion (`motion` goes into"]
            #[doc = "`machine.motions[motion.name]`). Values in mm, or degrees for a rotary axis."]
            positioningEvaluate($crate::positioning::PositioningInput as "PositioningInput")
                -> "Positioning" = $crate::positioning::evaluate;
            // nonlinear and reversal
            #[doc = "One move of the machine's rotary axes from `start` to `end` (commands, degrees): the"]
            #[doc = "δ(u) curve, its exact maximum, the paper's approximations and, with a `tolerance`,"]
            #[doc = "the fewest equal steps that keep δ within it."]
            nonlinearMove(($crate::nonlinear::NonlinearCase, $crate::nonlinear::NonlinearMoveInput)
                as "NonlinearCase & NonlinearMoveInput") -> "MoveAnalysis" = $crate::nonlinear::analyze_move;
            #[doc = "Fig 4: the maximum error against the start angle of K (the paper: constant)."]
            nonlinearSweepK(($crate::nonlinear::NonlinearCase, $crate::nonlinear::SweepKInput)
                as "NonlinearCase & SweepKInput") -> "SweepK" = $crate::nonlinear::sweep_k;
            #[doc = "Fig 7: the maximum error against the start angle of M, one curve per ratio Δθk/Δθm."]
            nonlinearSweepM(($crate::nonlinear::NonlinearCase, $crate::nonlinear::SweepMInput)
                as "NonlinearCase & SweepMInput") -> "SweepM" = $crate::nonlinear::sweep_m;
            #[doc = "Figs 3, 5, 8: maximum error and its u over a grid of increments Δθk × Δθm."]
            nonlinearGrid(($crate::nonlinear::NonlinearCase, $crate::nonlinear::NonlinearGridInput)
                as "NonlinearCase & NonlinearGridInput") -> "IncrementGrid" = $crate::nonlinear::grid;
            #[doc = "The machine's move from `start` to `end` as a tool path (its start and end tool vectors),"]
            #[doc = "made by each of the twelve types on the machine's kind and travel."]
            nonlinearCompareTypes(($crate::nonlinear::NonlinearCase, $crate::nonlinear::TypeCompareInput)
                as "NonlinearCase & TypeCompareInput") -> "TypeComparison[]" = $crate::nonlinear::compare_types;
            #[doc = "Simulates the reversal test on the machine: the ball-bar trace with and without C's"]
            #[doc = "friction, the axes against time, the dent, and whether X and Y change direction with C."]
            reversalSimulate(($crate::reversal::ReversalCase, $crate::reversal::ReversalRunInput)
                as "ReversalCase & ReversalRunInput") -> "ReversalSimulation" = $crate::reversal::simulation;
            #[doc = "The dent for Table 1's feeds (1000, 2000, 3000 mm/min) and radii r (25, 50 mm), the other"]
            #[doc = "inputs as given."]
            reversalDents($crate::reversal::ReversalCase as "ReversalCase")
                -> "DentRow[]" = $crate::reversal::table1_dents;
            #[doc = "Fits C's friction (f_c, a) and position-loop gain to a measured trace (`csv`), the other"]
            #[doc = "inputs as given (the fit starts from the entered values)."]
            reversalFit(($crate::reversal::ReversalCase, $crate::reversal::ReversalFitInput)
                as "ReversalCase & ReversalFitInput") -> "FrictionFit" = $crate::reversal::fit::fit_trace;
            #[doc = "Reads a measured trace (`csv`) and measures its dent: depth and width from the trace itself,"]
            #[doc = "and the machine its file names. Fast (no simulation); the test's R and F give the width in"]
            #[doc = "time."]
            reversalTrace(($crate::reversal::ReversalCase, $crate::reversal::ReversalFitInput)
                as "ReversalCase & ReversalFitInput") -> "MeasuredTrace" = $crate::reversal::fit::measure_trace;
            // probe
            #[doc = "The sphere test of the rotary axes: the simple layout and the designed poses (the"]
            #[doc = "smallest scaled singular value maximised), their expected centres, CSV and NC blocks,"]
            #[doc = "what a single sphere cannot see and what a second sphere position would add."]
            probeDesign(($crate::probe::ProbeInput, $crate::probe::design::ProbeDesignInput)
                as "ProbeInput & ProbeDesignInput") -> "ProbeDesign" = $crate::probe::api::design;
            #[doc = "The sphere's centre at given poses (degrees) as the control expects it and as the"]
            #[doc = "probe measures it on the machine with its errors (linear-axis positions, mm), and"]
            #[doc = "the sensitivities of the centres to each error (per mm, per degree)."]
            probeSimulate(($crate::probe::ProbeInput, $crate::probe::api::ProbeSimulateInput)
                as "ProbeInput & ProbeSimulateInput") -> "ProbeSimulation" = $crate::probe::api::simulate;
            #[doc = "Reads measured sphere centres from CSV (one line per pose: K, M, X, Y, Z, units in"]
            #[doc = "the header); errors name the line: `csv: line 7: …`."]
            probeReadCsv($crate::probe::api::ProbeCsvInput as "ProbeCsvInput")
                -> "Measurements" = $crate::probe::api::read_csv;
            #[doc = "Identifies the rotary axes' location errors from measured sphere centres: values,"]
            #[doc = "intervals, Holm decisions, the spread before and after, the correction in words and"]
            #[doc = "`errors` to put into `machine.errors`."]
            probeIdentify(($crate::probe::ProbeInput, $crate::probe::fit::ProbeIdentifyInput)
                as "ProbeInput & ProbeIdentifyInput") -> "ProbeIdentification" = $crate::probe::api::identify;
            // cubic and S-shape
            #[doc = "Zone heights and tilts (exact and first-order), sensitivities of every error of the"]
            #[doc = "machine on every zone, the exact effect of each error alone, and what the test cannot see."]
            cubicTest($crate::cubic::CubicInput as "CubicInput")
                -> "CubicResult" = $crate::cubic::results::test;
            #[doc = "The simulated machined face (Fig 16(b)): ball-end zig-zag passes, scallops included, on an"]
            #[doc = "`nx × ny` grid (`ny` automatic when left out), with each zone's average height."]
            cubicHeightMap(($crate::cubic::CubicInput, $crate::cubic::CubicGrid) as "CubicInput & CubicGrid")
                -> "HeightMap" = $crate::cubic::results::map;
            #[doc = "Identification of the machine's errors from measured zone heights (and slopes) of a cubic"]
            #[doc = "test piece, the paper's layout or a designed one (`csv`, see `fiveaxis::cubic::identify`)."]
            cubicIdentify(($crate::cubic::CubicInput, $crate::cubic::identify::CubicIdentifyInput) as "CubicInput & CubicIdentifyInput")
                -> "CubicIdentifyResult" = $crate::cubic::results::identify;
            #[doc = "The test designer: the zones' tool vectors (and optionally a second set-up) that make every"]
            #[doc = "error a face of this kind can reveal identifiable, beside the paper's layout."]
            cubicDesign(($crate::cubic::CubicInput, $crate::cubic::design::CubicDesignInput) as "CubicInput & CubicDesignInput")
                -> "CubicDesignResult" = $crate::cubic::results::design;
            #[doc = "The part for a 3D view: both surfaces on an `nu × nv` grid (default 131 × 7) and the 100"]
            #[doc = "measurement points, in the part's own frame (z up from its base)."]
            sshapePart($crate::sshape::study::SShapePartInput as "SShapePartInput | undefined")
                -> "SShapePartResult" = $crate::sshape::results::part;
            #[doc = "The overcut maps of both surfaces (eq 6 and the exact gouge) on an `nu × nv` grid."]
            sshapeOvercut($crate::sshape::study::SShapeOvercutInput as "SShapeOvercutInput")
                -> "SShapeOvercutResult" = $crate::sshape::results::overcut;
            #[doc = "The machining defect at the 100 points for the machine's errors (eq 14) and a tool-radius"]
            #[doc = "error, with the sensitivities of Fig 19 and the machine poses."]
            sshapeDefects(($crate::sshape::study::SShapeCase, $crate::sshape::study::SShapeDefectsInput) as "SShapeCase & SShapeDefectsInput")
                -> "SShapeDefectsResult" = $crate::sshape::results::defects;
            #[doc = "Identification of the machine's errors (all, or `parameters`) and the tool-radius error from"]
            #[doc = "a measurement CSV."]
            sshapeIdentify(($crate::sshape::study::SShapeCase, $crate::sshape::study::SShapeIdentifyInput) as "SShapeCase & SShapeIdentifyInput")
                -> "SShapeIdentifyResult" = $crate::sshape::results::identify;
            // ballbar rotary
            #[doc = "Ball-bar tests with a rotary axis moving (ISO 10791-6 style: C with X and Y, the tilt axis"]
            #[doc = "with Y and Z or X and Z), simulated on the machine with its errors through its chain: per"]
            #[doc = "test and angle (degrees) the commanded pose, both balls, the bar's exact length change (mm),"]
            #[doc = "its first-order value and sensitivities (per mm, per degree), what the tests can see, and"]
            #[doc = "the traces as a file."]
            ballbarRotarySimulate($crate::ballbar::rotary::BallbarRotaryInput as "BallbarRotaryInput")
                -> "BallbarRotarySimulation" = $crate::ballbar::rotary::simulate::simulate;
            #[doc = "The rotary axes' location errors identified from measured ball-bar traces (`csv` with a"]
            #[doc = "test column, or each test's own `csv`): values, intervals, Holm decisions, groups, goodness"]
            #[doc = "of fit, what the tests cannot see and why, and `errors` to put into `machine.errors`."]
            ballbarRotaryIdentify(($crate::ballbar::rotary::BallbarRotaryInput, $crate::ballbar::rotary::fit::BallbarRotaryIdentifyInput)
                as "BallbarRotaryInput & BallbarRotaryIdentifyInput") -> "BallbarRotaryIdentification" = $crate::ballbar::rotary::fit::identify;
        }
    };
}

macro_rules! native_call {
    ($( $(#[doc = $doc:tt])* $js:ident ($input:ty as $ts_in:tt) -> $ts_out:tt = $f:path; )*) => {
        /// Runs the export `name` natively on a JSON input and returns its result as JSON
        /// (angles in degrees, series as arrays): the same declaration the binding exports.
        pub fn call(name: &str, input: &Value) -> Result<Value> {
            match name {
                $(stringify!($js) => {
                    let i = <$input as ApiInput>::read(input)?;
                    let out = $f(&i)?;
                    serde_json::to_value(&out)
                        .map_err(|e| crate::Error::field(name, format!("cannot be written ({e})")))
                })*
                _ => Err(crate::Error::field(name, "no such export")),
            }
        }

        /// The names of every declared export, in declaration order.
        pub const EXPORTS: &[&str] = &[$(stringify!($js)),*];

        /// Each declared export's input fields, for `schema()`.
        pub fn export_fields() -> Vec<(&'static str, Vec<FieldInfo>)> {
            vec![$((stringify!($js), <$input as ApiInput>::fields())),*]
        }
    };
}

for_each_export!(native_call);
