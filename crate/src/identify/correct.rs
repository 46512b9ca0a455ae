//! What an identification hands back to the machine, shared by the tests of the rotary axes
//! (the probe and sphere, [`crate::probe`]; the ball-bar, [`crate::ballbar::rotary`]): the
//! errors found present as the machine's own error values ([`found`], [`api_errors`]), each in
//! words and as the number to enter in the control ([`Correction`], [`enter`]), and what the
//! test cannot see ([`Unseen`], [`Inseparable`]).
//!
//! # Signs of the correction
//! ISO 230-1's sign is the axis's real place minus the control's belief, in the machine frame
//! with all axes at zero, so a position is **added** to the control's value of the axis line's
//! position, a tilt turns the control's axis direction by the angle (right-hand rule, degrees),
//! and a zero error `E_C0C = +ε` (the axis stands at +ε when the control shows 0°) is corrected
//! by shifting the axis's zero by −ε. The same values are the machine's errors: put into
//! `machine.errors` as they are, the model reproduces the measurement.

use super::{meaning, Judgement, Verdict};
use crate::error::Result;
use crate::machine::errors::{ErrorDef, ErrorValues};
use serde::Serialize;

/// An error found present: what it means and what to enter.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Correction {
    /// ISO name.
    pub name: String,
    /// Its value, `unit`.
    pub value: f64,
    /// "mm" or "deg".
    pub unit: String,
    /// What it means on the machine.
    pub words: String,
    /// What to enter in the control (module docs: signs).
    pub enter: String,
}

/// An error that the test cannot see at all.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Unseen {
    /// ISO name.
    pub name: String,
    /// Why, in words.
    pub why: String,
}

/// Unknowns the test cannot separate, and what of them is measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Inseparable {
    /// The unknowns (errors, and the test's own unknowns: the sphere's position, the bar's
    /// length).
    pub members: Vec<String>,
    /// The combinations measured (first coefficient 1; the unknowns in mm and degrees).
    pub combinations: Vec<String>,
    /// Why, in words.
    pub why: String,
}

/// The machine errors among the judged parameters (`defs[j]`: the error table's entry of
/// parameter `j`, `None` for a test's own unknown) that are found present (either verdict):
/// their values (engine units), and each in words and as the number to enter.
pub fn found(
    judgement: &Judgement,
    defs: &[Option<&'static ErrorDef>],
) -> Result<(ErrorValues, Vec<Correction>)> {
    let mut values = ErrorValues::none();
    let mut corrections = Vec::new();
    for (def, d) in defs.iter().zip(&judgement.decisions) {
        let (Some(def), Some(v)) = (def, d.value) else {
            continue;
        };
        if !matches!(d.verdict, Verdict::Present | Verdict::BelowTolerance) {
            continue;
        }
        values.set(def.name, v)?;
        corrections.push(Correction {
            name: def.name.to_string(),
            value: def.quantity.to_api(v),
            unit: def.quantity.api_unit().to_string(),
            words: meaning(def, v),
            enter: enter(def, v),
        });
    }
    Ok((values, corrections))
}

/// What to enter for error `def` of value `v` (engine units), module docs.
pub fn enter(def: &ErrorDef, v: f64) -> String {
    let dir = ['X', 'Y', 'Z'][def.component % 3];
    let a = def.axis;
    let own = matches!((a, def.component), ('A', 3) | ('B', 4) | ('C', 5));
    if def.component < 3 {
        format!(
            "{a} axis line, position along {dir}: add {:+.4} mm to the control's value",
            v
        )
    } else if own {
        format!(
            "{a} axis zero: shift it by {:+.5}° so that {a} stands at 0° when the control shows 0°",
            -v.to_degrees()
        )
    } else {
        format!(
            "{a} axis direction: turn it by {:+.5}° about {dir} (right-hand rule) in the control's kinematics",
            v.to_degrees()
        )
    }
}
