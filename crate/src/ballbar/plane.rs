//! The plane of a circular test, and what its result gives the one machine model
//! ([`crate::machine`]).
//!
//! # The planes and their axes `u`, `v`
//! The angle `θ` runs from `+u` towards `+v`, counter-clockwise as seen from the plane's positive
//! normal `u × v` (module docs of [`super`]), as the G-code planes have it:
//! * `XY` (G17): `u = X`, `v = Y`, seen from `+Z`;
//! * `YZ` (G19): `u = Y`, `v = Z`, seen from `+X`;
//! * `ZX` (G18): `u = Z`, `v = X`, seen from `+Y`.
//!
//! # The squareness as the plane's ISO 230-1 location error
//! The ball-bar's out-of-squareness `α` (`v` leans towards `+u`; the angle between `+u` and `+v`
//! is `90° − α`) is, in the machine's error table ([`crate::machine::errors`], X the reference,
//! ISO 841 signs: the tool relative to the workpiece), to first order in `α`:
//! * `XY`: `E_C0Y = −α` (the angle between the X and Y motions is `90° + E_C0Y`);
//! * `YZ`: `E_A0Z = −α` (a positive `E_A0Z` leans Z towards `−Y` as it moves up);
//! * `ZX`: `E_B0Z = +α` (a positive `E_B0Z` leans Z towards `+X` as it moves up; here `u = Z`).
//!
//! These signs are checked through the kinematic chain, not only argued:
//! `crate/tests/ballbar/to_machine.rs` builds machines with each error, commands a circle of its
//! plane, takes the tool's distance from the pivot through the chain and evaluates that trace.
//!
//! The machine model holds the angle of one axis line, whichever side of the machine it is on;
//! on a cross table with Y on the bed carrying X (`linear: table-xy`) `E_C0Y` turns X with Y,
//! and the squareness between them is not an error that table can hold (the test above shows
//! it: such a machine makes a round circle).
//!
//! # What is not sent
//! Only the squareness is a geometric error the model holds as a constant. The rest stays with
//! the test: the centre offset and mean radius are the set-up; backlash and reversal spikes
//! depend on the direction of travel, servo mismatch on the feed (the model has neither); the
//! scale mismatch is the difference `ε_u − ε_v` of the two axes' positioning errors, not either
//! one (a laser measures each: the positioning panel); the cyclic error is not assigned to an
//! axis by the trace.

use super::Fitted;
use crate::machine::errors::ErrorValues;

crate::choices! {
    /// The plane of a circular test and its axes `u`, `v` (module docs).
    pub enum BallbarPlane {
        /// `u = X`, `v = Y`.
        Xy = "XY" {
            label: "XY (G17): u = X, v = Y",
            help: "The angle from +X towards +Y, counter-clockwise seen from +Z.",
        },
        /// `u = Y`, `v = Z`.
        Yz = "YZ" {
            label: "YZ (G19): u = Y, v = Z",
            help: "The angle from +Y towards +Z, counter-clockwise seen from +X.",
        },
        /// `u = Z`, `v = X`.
        Zx = "ZX" {
            label: "ZX (G18): u = Z, v = X",
            help: "The angle from +Z towards +X, counter-clockwise seen from +Y.",
        },
    }
}

impl BallbarPlane {
    /// The letters of `u` and `v`.
    pub fn axes(self) -> [&'static str; 2] {
        match self {
            BallbarPlane::Xy => ["X", "Y"],
            BallbarPlane::Yz => ["Y", "Z"],
            BallbarPlane::Zx => ["Z", "X"],
        }
    }

    /// The ISO 230-1 squareness error of the plane and the sign `σ` with `E = σ·α` (module
    /// docs).
    pub fn squareness_error(self) -> (&'static str, f64) {
        match self {
            BallbarPlane::Xy => ("E_C0Y", -1.0),
            BallbarPlane::Yz => ("E_A0Z", -1.0),
            BallbarPlane::Zx => ("E_B0Z", 1.0),
        }
    }
}

/// What the result gives the machine: the errors (engine units, rad), the squareness in words
/// (`None` without a value), and what is not sent.
pub(super) fn for_machine(
    plane: BallbarPlane,
    squareness: &Fitted,
) -> (ErrorValues, Option<String>, Vec<String>) {
    let [u, v] = plane.axes();
    let (name, sign) = plane.squareness_error();
    let mut errors = ErrorValues::none();
    let limit = crate::machine::errors::MAX_ANGLE_ERROR.to_radians();
    let meaning = squareness.value.map(|a| {
        // α in µm/m = µrad.
        let e = sign * a * 1e-6;
        let (towards, angle) = if a >= 0.0 {
            ("+", "closer than 90°")
        } else {
            ("−", "further apart than 90°")
        };
        let words = format!(
            "{v} leans towards {towards}{u} by {:.2} µm/m (+{u} and +{v} {angle})",
            a.abs()
        );
        if e.abs() > limit {
            return format!(
                "{words}; not sent: {name} = {:.4}° is beyond the machine's limit of ±{}°",
                e.to_degrees(),
                crate::machine::errors::MAX_ANGLE_ERROR
            );
        }
        // Always a known name of the table.
        let _ = errors.set(name, e);
        words
    });
    let mut not_sent = vec![
        "centre offset and mean radius: the set-up of the ball-bar, not the machine".to_string(),
        "backlash and reversal spikes: they depend on the direction of travel, which the machine model's geometric errors do not".to_string(),
        "servo mismatch: a lag between the drives at this feed, not a geometric error".to_string(),
        format!("scale mismatch: only the difference of the {u} and {v} positioning errors, not either one (a laser measures each: the positioning panel)"),
        "cyclic error: the trace does not say which axis it belongs to".to_string(),
    ];
    if squareness.value.is_none() {
        not_sent.insert(
            0,
            format!("squareness ({name}): one direction only cannot separate it from the servo mismatch; test both ways"),
        );
    }
    (errors, meaning, not_sent)
}
