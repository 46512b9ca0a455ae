//! What ball-bar tests of the rotary axes can see (module docs of [`super`]): the system of
//! their points (one row per point: the bar's sensitivity to each error, and a one for the
//! offset of its test and direction), the errors it cannot see at all and why, the groups it
//! cannot separate and the combinations of them it measures, and what the tests see alone and
//! together.
//!
//! # The offsets
//! The bar's nominal length is calibrated only to a few micrometres and the balls are set on
//! the table and in the spindle by hand: each test and direction gets its own constant, named
//! `offset_<test>_ccw` or `offset_<test>_cw` (mm, + longer). An error whose effect on the bar
//! is the same at every angle is inseparable from it.
//!
//! # The decision
//! An error's column counts as no effect at all when its effect, scaled by a typical size (10 µm
//! for a position, 10⁻⁴ rad for an angle, as the probe's designer scales), is at most 10⁻⁹ of the
//! largest: such columns are set to zero before the fit (a column of rounding noise, scaled to
//! unit norm, would be a random direction). The groups are [`crate::identify::fit`]'s (rank at
//! the relative singular value `rtol`, 0.01 by default).

use super::{Study, Test};
use crate::cubic::design::{TYPICAL_ANGLE, TYPICAL_POSITION};
use crate::error::{Error, Result};
use crate::identify::correct::{Inseparable, Unseen};
use crate::identify::{api_text, fit, Fit};
use crate::machine::errors::ErrorDef;
use nalgebra::DMatrix;
use serde::Serialize;

/// A column at or below this fraction of the largest (scaled) is no effect at all.
const ZERO_COLUMN: f64 = 1e-9;
/// A column whose every sensitivity is below this (mm of bar length per mm or per rad) is no
/// effect at all, whatever the other columns: the chain's rounding (10⁻¹⁵ for C's zero with a
/// radial bar). Without it, an error no test sees, chosen alone, kept its column of rounding,
/// the largest and so not zero by [`ZERO_COLUMN`], and was called a group of which nothing is
/// measured instead of an error the test cannot see.
const EFFECT_FLOOR: f64 = 1e-10;

/// One measured or simulated point of a test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Index of the test.
    pub test: usize,
    /// The moving axis's command, rad.
    pub angle: f64,
    /// +1 ccw, −1 cw.
    pub direction: f64,
}

/// The system of the points: the columns (errors, then offsets) and their names.
#[derive(Debug, Clone)]
pub struct System {
    /// Per point, per unknown: mm per mm or per rad; offsets 1. Columns of no effect are zero.
    pub a: DMatrix<f64>,
    /// The unknowns' names: the study's errors, then the offsets.
    pub names: Vec<String>,
    /// The error table's entry of each column (`None` for an offset).
    pub defs: Vec<Option<&'static ErrorDef>>,
    /// The offsets' tests and directions, in column order after the errors.
    pub offsets: Vec<(usize, f64)>,
    /// The errors' columns set to zero (no effect at any point).
    pub zero: Vec<bool>,
}

/// The offset's name of test `t` in direction `d` (module docs).
pub fn offset_name(t: &Test, d: f64) -> String {
    format!("offset_{}_{}", t.name, if d > 0.0 { "ccw" } else { "cw" })
}

/// The system of `points` (module docs).
pub fn system(study: &Study, points: &[Point]) -> Result<System> {
    let ne = study.unknowns.len();
    let mut offsets: Vec<(usize, f64)> = Vec::new();
    for p in points {
        if !offsets.contains(&(p.test, p.direction)) {
            offsets.push((p.test, p.direction));
        }
    }
    offsets.sort_by(|a, b| {
        (a.0, -a.1)
            .partial_cmp(&(b.0, -b.1))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let p = ne + offsets.len();
    let mut a = DMatrix::zeros(points.len(), p);
    for (i, pt) in points.iter().enumerate() {
        let t = &study.tests[pt.test];
        for (j, s) in study.sensitivities(t, pt.angle)?.into_iter().enumerate() {
            a[(i, j)] = s;
        }
        if let Some(k) = offsets.iter().position(|o| *o == (pt.test, pt.direction)) {
            a[(i, ne + k)] = 1.0;
        }
    }
    let typical = |d: &ErrorDef| {
        if d.quantity.is_angle() {
            TYPICAL_ANGLE
        } else {
            TYPICAL_POSITION
        }
    };
    let scaled: Vec<f64> = (0..ne)
        .map(|j| a.column(j).norm() * typical(study.unknowns[j]))
        .collect();
    let largest = scaled.iter().fold(0.0f64, |x, y| x.max(*y));
    let zero: Vec<bool> = (0..ne)
        .map(|j| scaled[j] <= ZERO_COLUMN * largest || a.column(j).amax() < EFFECT_FLOOR)
        .collect();
    for (j, z) in zero.iter().enumerate() {
        if *z {
            a.column_mut(j).fill(0.0);
        }
    }
    let mut names: Vec<String> = study.unknowns.iter().map(|d| d.name.to_string()).collect();
    names.extend(
        offsets
            .iter()
            .map(|&(t, d)| offset_name(&study.tests[t], d)),
    );
    let mut defs: Vec<Option<&'static ErrorDef>> =
        study.unknowns.iter().map(|d| Some(*d)).collect();
    defs.extend(offsets.iter().map(|_| None));
    Ok(System {
        a,
        names,
        defs,
        offsets,
        zero,
    })
}

/// What the tests can see: the errors each identifiable on its own, those with no effect on the
/// bar and why, and the groups only combinations of which are measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct RotaryVisibility {
    /// The errors each identifiable on its own.
    pub identifiable: Vec<String>,
    /// Errors with no effect on the bar at any angle of the tests.
    pub invisible: Vec<Unseen>,
    /// Groups only combinations of which are measured.
    pub inseparable: Vec<Inseparable>,
}

/// What one test sees alone.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct RotaryTestSees {
    /// The test's name.
    pub name: String,
    /// The errors it identifies on its own.
    pub identifiable: Vec<String>,
}

/// What the tests see alone and together.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct RotaryTogether {
    /// Each test alone.
    pub alone: Vec<RotaryTestSees>,
    /// All the tests together.
    pub identifiable: Vec<String>,
    /// Identifiable together, by no test alone.
    pub gained: Vec<String>,
    /// In words.
    pub words: String,
}

/// The fit's view of a system without data: its groups (rows padded with zeros so that the
/// fit always has a residual).
pub fn view(a: &DMatrix<f64>, names: &[String], rtol: f64) -> Result<Fit> {
    let (m, p) = a.shape();
    let rows = m.max(p) + 1;
    let padded = DMatrix::from_fn(rows, p, |r, c| if r < m { a[(r, c)] } else { 0.0 });
    fit(&padded, names, &vec![0.0; rows], rtol).map_err(|e| {
        if e.message.contains("no parameter has any effect") {
            Error::field(
                "parameters",
                "none of the errors changes the bar's length in these tests",
            )
        } else {
            e
        }
    })
}

/// Why an error has no effect on the bar (module docs of [`super`]).
fn why_unseen(study: &Study, def: &ErrorDef) -> String {
    let own = match def.axis {
        'A' => 0,
        'B' => 1,
        'C' => 2,
        _ => usize::MAX,
    };
    let moved = study.tests.iter().any(|t| t.letters[0] == def.axis);
    let bars: Vec<&str> = {
        let mut v: Vec<&str> = study.tests.iter().map(|t| t.direction.value()).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let bars = bars.join(", ");
    if moved && def.component == own + 3 {
        format!(
            "a turn about the {a} axis's own line (its zero) moves the ball along its circle about that line, square to the {bars} bar: the bar's length changes only to the second order.",
            a = def.axis
        )
    } else if moved && def.component == own {
        format!(
            "a shift along the {a} axis's own line moves the ball along that line, square to the {bars} bar: the bar's length changes only to the second order.",
            a = def.axis
        )
    } else {
        "it moves the tool ball relative to the table only square to the bar, at every angle of the tests: the bar's length changes only to the second order.".to_string()
    }
}

/// What the system sees, from its fit's groups (module docs).
pub fn visibility(study: &Study, sys: &System, f: &Fit) -> RotaryVisibility {
    let ne = study.unknowns.len();
    let invisible: Vec<Unseen> = (0..ne)
        .filter(|&j| sys.zero[j])
        .map(|j| Unseen {
            name: sys.names[j].clone(),
            why: why_unseen(study, study.unknowns[j]),
        })
        .collect();
    let is_offset = |n: &str| sys.names[ne..].iter().any(|o| o == n);
    let mut inseparable = Vec::new();
    for g in &f.groups {
        let members: Vec<String> = g
            .members
            .iter()
            .filter(|n| !invisible.iter().any(|u| &u.name == *n))
            .cloned()
            .collect();
        let errors: Vec<&String> = members.iter().filter(|n| !is_offset(n)).collect();
        if errors.is_empty() {
            continue;
        }
        let with_offset = members.iter().any(|n| is_offset(n));
        // With an offset in the group the measured combinations mix errors and offsets in an
        // arbitrary basis of the group: nothing of the errors themselves is measured.
        let combos: Vec<String> = if with_offset {
            Vec::new()
        } else {
            g.combinations.iter().map(api_text).collect()
        };
        let list = errors
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        let why = if with_offset {
            format!(
                "{list}: {} the bar's length by the same amount at every angle of a test, as the bar's own length and the balls' set-up do (fitted per test and direction as offsets): the tests cannot tell {} from them.",
                if errors.len() == 1 { "changes" } else { "change" },
                if errors.len() == 1 { "it" } else { "them" }
            )
        } else if combos.is_empty() {
            format!("{list} change the bar's length alike at every angle of these tests: nothing of them is measured.")
        } else {
            format!(
                "{list} change the bar's length alike at every angle of these tests: only {} measured; another test (the ball at another height or radius, another bar direction, or the other axis moving) may separate them.",
                combos.join("; ")
            )
        };
        inseparable.push(Inseparable {
            members,
            combinations: combos,
            why,
        });
    }
    RotaryVisibility {
        identifiable: identifiable(f, ne),
        invisible,
        inseparable,
    }
}

/// The errors (the first `ne` unknowns) the fit identifies on their own.
fn identifiable(f: &Fit, ne: usize) -> Vec<String> {
    f.estimates[..ne]
        .iter()
        .filter(|e| e.group.is_none())
        .map(|e| e.name.clone())
        .collect()
}

/// What each test sees alone and what the tests see together (at `rtol`).
pub fn together(
    study: &Study,
    sys: &System,
    points: &[Point],
    rtol: f64,
) -> Result<RotaryTogether> {
    let ne = study.unknowns.len();
    let all = view(&sys.a, &sys.names, rtol)?;
    let identifiable_all = identifiable(&all, ne);
    let mut alone = Vec::with_capacity(study.tests.len());
    for (ti, t) in study.tests.iter().enumerate() {
        let rows: Vec<usize> = (0..points.len())
            .filter(|&i| points[i].test == ti)
            .collect();
        let cols: Vec<usize> = (0..ne)
            .chain(
                sys.offsets
                    .iter()
                    .enumerate()
                    .filter(|(_, o)| o.0 == ti)
                    .map(|(k, _)| ne + k),
            )
            .collect();
        let a = DMatrix::from_fn(rows.len(), cols.len(), |r, c| sys.a[(rows[r], cols[c])]);
        let names: Vec<String> = cols.iter().map(|&c| sys.names[c].clone()).collect();
        let seen = if a.iter().any(|v| *v != 0.0) {
            identifiable(&view(&a, &names, rtol)?, ne)
        } else {
            Vec::new()
        };
        alone.push(RotaryTestSees {
            name: t.name.clone(),
            identifiable: seen,
        });
    }
    let gained: Vec<String> = identifiable_all
        .iter()
        .filter(|n| !alone.iter().any(|a| a.identifiable.contains(n)))
        .cloned()
        .collect();
    let words = if study.tests.len() < 2 {
        "One test: add a second (the ball at another height or radius, another bar direction, or the other axis moving) to see what two tests separate.".to_string()
    } else if gained.is_empty() {
        "Together the tests identify no error that one of them alone does not.".to_string()
    } else {
        format!(
            "Together the tests also identify {}, which no test alone separates: their effects differ from test to test.",
            gained.join(", ")
        )
    };
    Ok(RotaryTogether {
        alone,
        identifiable: identifiable_all,
        gained,
        words,
    })
}
