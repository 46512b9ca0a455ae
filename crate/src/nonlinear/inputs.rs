//! The inputs of the nonlinear-error study: the machine (its rotary-axis type and pivot), the
//! length `L`, and per export the move or the sweep. Angles are the machine's commands (degrees
//! at the edge); with ISO 841 senses they are the study's θk, θm (a reversed axis flips the sign,
//! [`NonlinearCase::angles`]).

use super::{linspace, MoveAnalysis, SweepK, SweepM};
use super::{
    sweep_increments, sweep_start_k, sweep_start_m, Deviation, IncrementGrid, Move, RatioCurve,
    TypeComparison, MAX_ANGLE_DEG, MAX_LENGTH_MM,
};
use crate::edge::{ApiInput, Checked};
use crate::error::{Error, Result};
use crate::machine::Machine;
use crate::rotary::{Pose, RotaryType};
use crate::schema::{self, DefaultValue, Kind, Quantity};
use serde_json::Value;

/// Largest accepted axis angle, degrees (ten turns).
const ANGLE: f64 = MAX_ANGLE_DEG;

crate::inputs! {
    /// What every export of the study needs: the machine and `L`.
    pub struct NonlinearCase {
        /// The machine (its type, senses and pivot).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// `L`, mm; the machine's when left out.
        pub length: Option<f64> = "length" optional {
            label: "Tool length / pivot distance L",
            help: "Distance of the tool point from the axis it swings about. Left empty: the machine's pivot length plus tool length (head), or its table surface's distance from the rotary centre (table-table).",
            kind: schema::positive(Quantity::Length, MAX_LENGTH_MM),
            group: "Move",
        },
    }
}

crate::inputs! {
    /// The axis angles at the start of a move.
    pub struct MoveStart {
        /// K, degrees at the edge.
        pub k: f64 = "k" optional {
            label: "Start {K}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE),
            default: DefaultValue::Num(0.0), group: "Move",
        },
        /// M, degrees at the edge.
        pub m: f64 = "m" optional {
            label: "Start {M}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE),
            default: DefaultValue::Num(10.0), group: "Move",
        },
    }
}

crate::inputs! {
    /// The axis angles at the end of a move.
    pub struct MoveEnd {
        /// K, degrees at the edge.
        pub k: f64 = "k" optional {
            label: "End {K}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE),
            default: DefaultValue::Num(30.0), group: "Move",
        },
        /// M, degrees at the edge.
        pub m: f64 = "m" optional {
            label: "End {M}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE),
            default: DefaultValue::Num(25.0), group: "Move",
        },
    }
}

crate::inputs! {
    /// One move (with a [`NonlinearCase`]).
    pub struct NonlinearMoveInput {
        /// MoveStart angles.
        pub start: MoveStart = "start" optional {
            label: "Start", kind: Kind::Object(MoveStart::FIELDS), default: DefaultValue::Empty,
        },
        /// MoveEnd angles.
        pub end: MoveEnd = "end" optional {
            label: "End", kind: Kind::Object(MoveEnd::FIELDS), default: DefaultValue::Empty,
        },
        /// Points of the δ(u) curve.
        pub samples: usize = "samples" optional {
            label: "Points of the δ(u) curve", kind: Kind::Count { min: 2, max: 100_000 },
            default: DefaultValue::Num(201.0), shown: false,
        },
        /// The largest acceptable δ, mm: with it, the move's split into steps that keep within it.
        pub tolerance: Option<f64> = "tolerance" optional {
            label: "Tolerance on the tool point",
            help: "The largest nonlinear error of the move you accept; the verdict says how finely to split the move if it is above. 10 µm is typical for finishing.",
            kind: schema::positive(Quantity::SmallLength, 10.0),
            default: DefaultValue::Num(0.01),
            group: "Move",
        },
    }
}

crate::inputs! {
    /// A sweep of the start angle of K (Fig 4), with a [`NonlinearCase`].
    pub struct SweepKInput {
        /// MoveStart angle of M.
        pub theta_m: f64 = "thetaM" {
            label: "Start {M}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Increment of K.
        pub d_k: f64 = "dK" {
            label: "Increment of {K}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Increment of M.
        pub d_m: f64 = "dM" {
            label: "Increment of {M}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// First start angle of K.
        pub from: f64 = "from" {
            label: "Start {K} from", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Last start angle of K.
        pub to: f64 = "to" {
            label: "Start {K} to", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Points.
        pub n: usize = "n" {
            label: "Points", kind: Kind::Count { min: 2, max: 100_000 }, shown: false,
        },
    }
}

crate::inputs! {
    /// A sweep of the start angle of M, one curve per increment ratio (Fig 7), with a [`NonlinearCase`].
    pub struct SweepMInput {
        /// Increment of M.
        pub d_m: f64 = "dM" {
            label: "Increment of {M}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Ratios Δθk/Δθm.
        pub ratios: Vec<f64> = "ratios" {
            label: "Ratios of the two axes' increments, {K} to {M}",
            help: "One curve per ratio, comma separated (the paper's Δθk/Δθm, Fig 7).",
            kind: Kind::NumberList { quantity: Quantity::Number, min: -100.0, max: 100.0, min_len: 1, max_len: 8, nonzero: true },
            default: DefaultValue::Str("0.5, 2, 3, 5"),
            group: "Sweeps",
        },
        /// First start angle of M.
        pub from: f64 = "from" {
            label: "Start {M} from", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Last start angle of M.
        pub to: f64 = "to" {
            label: "Start {M} to", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Points.
        pub n: usize = "n" {
            label: "Points", kind: Kind::Count { min: 2, max: 100_000 }, shown: false,
        },
    }
}

crate::inputs! {
    /// A range of increments, degrees at the edge.
    pub struct AngleSpan {
        /// First value.
        pub from: f64 = "from" {
            label: "from", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Last value.
        pub to: f64 = "to" {
            label: "to", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
    }
}

crate::inputs! {
    /// A grid of increments (Figs 3, 5, 8), with a [`NonlinearCase`].
    pub struct NonlinearGridInput {
        /// MoveStart angle of M.
        pub theta_m: f64 = "thetaM" {
            label: "Start {M}", kind: schema::number(Quantity::Angle, -ANGLE, ANGLE), shown: false,
        },
        /// Increments of K (columns).
        pub d_k: AngleSpan = "dK" {
            label: "Increments of {K}", kind: Kind::Object(AngleSpan::FIELDS), shown: false,
        },
        /// Increments of M (rows).
        pub d_m: AngleSpan = "dM" {
            label: "Increments of {M}", kind: Kind::Object(AngleSpan::FIELDS), shown: false,
        },
        /// Columns.
        pub nx: usize = "nx" {
            label: "Grid points per side (maps)",
            help: "361 gives 0.5° steps over ±90°.",
            kind: Kind::Count { min: 2, max: 2001 },
            default: DefaultValue::Num(61.0),
            group: "Sweeps",
        },
        /// Rows.
        pub ny: usize = "ny" {
            label: "Grid rows", kind: Kind::Count { min: 2, max: 2001 }, shown: false,
        },
    }
}

crate::inputs! {
    /// The same move on the twelve types, with a [`NonlinearCase`].
    pub struct TypeCompareInput {
        /// MoveStart angles.
        pub start: MoveStart = "start" optional {
            label: "Start", kind: Kind::Object(MoveStart::FIELDS), default: DefaultValue::Empty,
        },
        /// MoveEnd angles.
        pub end: MoveEnd = "end" optional {
            label: "End", kind: Kind::Object(MoveEnd::FIELDS), default: DefaultValue::Empty,
        },
    }
}

impl NonlinearCase {
    /// Reads a case and the export's own inputs from one object (the keys of `B` go to `B`).
    pub fn read_with<B: Checked>(value: &Value) -> Result<(NonlinearCase, B)> {
        <(NonlinearCase, B) as ApiInput>::read(value)
    }

    /// The machine's rotary-axis type.
    pub fn rtype(&self) -> RotaryType {
        self.machine.rotary_type
    }

    /// `L`: given, or the machine's ([`swing_length`]).
    pub fn length(&self) -> Result<f64> {
        swing_length(self.length, &self.machine)
    }

    /// The study's angles `(θk, θm)` of the commands `k`, `m` (rad): the sign of a reversed axis
    /// flipped, so that `V = R_K(θk)·R_M(θm)·e_H` holds (see [`crate::machine`]).
    pub fn angles(&self, k: f64, m: f64) -> Pose {
        let r = &self.machine.rotary;
        let s = |rev: bool| if rev { -1.0 } else { 1.0 };
        Pose::new(s(r.k_reversed) * k, s(r.m_reversed) * m)
    }

    /// The factors `θ = f·command` of K and M (±1).
    fn factors(&self) -> (f64, f64) {
        let p = self.angles(1.0, 1.0);
        (p.k, p.m)
    }

    /// The move from `start` to `end` (commands, rad) in the study's angles.
    pub fn move_between(&self, start: &MoveStart, end: &MoveEnd) -> Move {
        Move::new(
            self.rtype(),
            self.angles(start.k, start.m),
            self.angles(end.k, end.m),
        )
    }

    /// Fig 4 on this machine ([`sweep_start_k`]): the maximum error (mm) at each start command
    /// of K in `i.from..=i.to` (`i.n` points, the commands given by [`super::linspace`]).
    pub fn sweep_k(&self, i: &SweepKInput) -> Result<Vec<f64>> {
        let (fk, fm) = self.factors();
        sweep_start_k(
            self.rtype(),
            self.length()?,
            fm * i.theta_m,
            fk * i.d_k,
            fm * i.d_m,
            (fk * i.from, fk * i.to),
            i.n,
        )
    }

    /// Fig 7 on this machine ([`sweep_start_m`]), one curve per ratio of the commands' increments
    /// `ΔK/ΔM` (its [`RatioCurve::ratio`] as given); the errors at each start command of M in
    /// `i.from..=i.to`.
    pub fn sweep_m(&self, i: &SweepMInput) -> Result<Vec<RatioCurve>> {
        let (fk, fm) = self.factors();
        // ΔK = ratio·ΔM in commands; in the study's angles the ratio takes both senses.
        let ratios: Vec<f64> = i.ratios.iter().map(|r| r * fk * fm).collect();
        let curves = sweep_start_m(
            self.rtype(),
            self.length()?,
            fm * i.d_m,
            &ratios,
            (fm * i.from, fm * i.to),
            i.n,
        )?;
        Ok(curves
            .into_iter()
            .zip(&i.ratios)
            .map(|(c, &ratio)| RatioCurve { ratio, ..c })
            .collect())
    }

    /// The move from `start` to `end` (this machine's commands) as a tool path, its start and end
    /// tool vectors, made by each of the twelve types (the machine's kind, senses and travel;
    /// [`crate::machine::follow::follow`]: the smallest tilt at the start, the nearest solution at the
    /// end; the machine's own type by the commands given), with its exact maximum error at this
    /// `L`.
    pub fn compare_types(&self, start: &MoveStart, end: &MoveEnd) -> Result<Vec<TypeComparison>> {
        let length = self.length()?;
        let mv = self.move_between(start, end);
        mv.validate()?;
        let ends = [mv.orientation(0.0), mv.orientation(1.0)];
        RotaryType::ALL
            .iter()
            .map(|&t| {
                let model = crate::machine::follow::machine_of_type(&self.machine, t).build()?;
                // The machine's own type makes the move as commanded; the others as they would
                // follow the tool vectors.
                let f = if t == self.rtype() {
                    crate::machine::follow::Following {
                        k: vec![start.k, end.k],
                        m: vec![start.m, end.m],
                        unreachable: None,
                    }
                } else {
                    crate::machine::follow::follow(&model, &ends)?
                };
                let lay = model.layout;
                let pose = |i: usize| Pose::new(lay.k_factor * f.k[i], lay.m_factor * f.m[i]);
                let reached = f.unreachable.is_none();
                let peak = reached.then(|| Deviation::new(Move::new(t, pose(0), pose(1))).peak());
                Ok(TypeComparison {
                    rtype: t,
                    group: t.group(),
                    start: reached.then(|| [f.k[0], f.m[0]]),
                    end: reached.then(|| [f.k[1], f.m[1]]),
                    max: peak.map(|p| p.value * length),
                    u_at_max: peak.map(|p| p.u),
                    unreachable: f.unreachable.map(|(_, why)| why),
                })
            })
            .collect()
    }

    /// Figs 3, 5, 8 on this machine ([`sweep_increments`]); the grid's increments are the
    /// commands' (rad). An empty range (`from` = `to`) is refused.
    pub fn grid(&self, i: &NonlinearGridInput) -> Result<IncrementGrid> {
        for (key, span) in [("dK", &i.d_k), ("dM", &i.d_m)] {
            if span.from == span.to {
                return Err(Error::field(key, "the range is empty: 'from' equals 'to'"));
            }
        }
        let (fk, fm) = self.factors();
        let g = sweep_increments(
            self.rtype(),
            self.length()?,
            fm * i.theta_m,
            (fk * i.d_k.from, fk * i.d_k.to),
            (fm * i.d_m.from, fm * i.d_m.to),
            i.nx,
            i.ny,
        )?;
        let commands = |a: Vec<f64>, f: f64| a.into_iter().map(|x| x / f).collect();
        Ok(IncrementGrid {
            d_k: commands(g.d_k, fk),
            d_m: commands(g.d_m, fm),
            ..g
        })
    }
}

impl Checked for NonlinearCase {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")
    }
}
impl Checked for NonlinearMoveInput {}
impl Checked for SweepKInput {}
impl Checked for SweepMInput {}
impl Checked for NonlinearGridInput {}
impl Checked for TypeCompareInput {}

/// The export `nonlinearMove`: one move of the machine's rotary axes from `start` to `end`
/// (commands), the δ(u) curve and its exact maximum at the case's `L`, and with a `tolerance`
/// the fewest equal steps that keep δ within it ([`super::split_within`]).
pub fn analyze_move((case, i): &(NonlinearCase, NonlinearMoveInput)) -> Result<MoveAnalysis> {
    let length = case.length()?;
    let mv = case.move_between(&i.start, &i.end);
    let mut a = super::analyze(mv, length, i.samples)?;
    a.split = match i.tolerance {
        Some(t) => Some(super::split_within(mv, length, t)?),
        None => None,
    };
    Ok(a)
}

/// The export `nonlinearSweepK`: Fig 4 on the machine ([`NonlinearCase::sweep_k`]) with its
/// start commands of K.
pub fn sweep_k((case, i): &(NonlinearCase, SweepKInput)) -> Result<SweepK> {
    Ok(SweepK {
        max: case.sweep_k(i)?,
        k: linspace(i.from, i.to, i.n),
    })
}

/// The export `nonlinearSweepM`: Fig 7 on the machine ([`NonlinearCase::sweep_m`]) with its
/// start commands of M.
pub fn sweep_m((case, i): &(NonlinearCase, SweepMInput)) -> Result<SweepM> {
    Ok(SweepM {
        curves: case.sweep_m(i)?,
        m: linspace(i.from, i.to, i.n),
    })
}

/// The export `nonlinearGrid`: Figs 3, 5, 8 on the machine ([`NonlinearCase::grid`]).
pub fn grid((case, i): &(NonlinearCase, NonlinearGridInput)) -> Result<IncrementGrid> {
    case.grid(i)
}

/// The export `nonlinearCompareTypes`: the move as a tool path on each of the twelve types
/// ([`NonlinearCase::compare_types`]).
pub fn compare_types((case, i): &(NonlinearCase, TypeCompareInput)) -> Result<Vec<TypeComparison>> {
    case.compare_types(&i.start, &i.end)
}

/// `L` (mm): `given`, or the machine's ([`Machine::swing_length`]); an error on `length` when the
/// machine gives none.
pub fn swing_length(given: Option<f64>, machine: &Machine) -> Result<f64> {
    match given {
        Some(l) => Ok(l),
        None => machine.swing_length().ok_or_else(|| {
            Error::field(
                "length",
                "this machine's table surface is at its rotary centre, so it gives no distance: enter L",
            )
        }),
    }
}
