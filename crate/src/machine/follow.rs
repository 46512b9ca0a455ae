//! Following tool axes on a machine: the rotary commands that make each tool axis in turn, with
//! continuity. The toolpath study and the nonlinear study's type comparison both use it.

use super::{BranchRule, Machine, Model};
use crate::error::{Error, Result};
use crate::rotary::RotaryType;
use nalgebra::Vector3;

/// Where the machine follows the path: commands of K and M (rad) at each point reached.
#[derive(Debug, Clone, PartialEq)]
pub struct Following {
    /// K commands, rad, one per point reached.
    pub k: Vec<f64>,
    /// M commands, rad.
    pub m: Vec<f64>,
    /// The first point no solution within the travel reaches, and why; `None` when every point
    /// is reached.
    pub unreachable: Option<(usize, String)>,
}

/// The given machine with rotary-axis type `t` and no errors (the control's model).
pub fn machine_of_type(machine: &Machine, t: RotaryType) -> Machine {
    Machine {
        rotary_type: t,
        ..machine.without_errors()
    }
}

/// Follows the tool axes `axes` (workpiece coordinates, any non-zero length) on `model` with
/// continuity: the first point takes the smallest tilt ([`BranchRule::SmallestTilt`]), every
/// later point the solution nearest the previous commands ([`BranchRule::Nearest`]).
pub fn follow(model: &Model, axes: &[Vector3<f64>]) -> Result<Following> {
    let mut k = Vec::with_capacity(axes.len());
    let mut m = Vec::with_capacity(axes.len());
    let mut previous: Option<[f64; 2]> = None;
    for (i, a) in axes.iter().enumerate() {
        // The first point: the smallest tilt, each angle at the turn nearest 0 (room both ways).
        let (rule, near) = match previous {
            Some(p) => (BranchRule::Nearest, p),
            None => (BranchRule::SmallestTilt, [0.0, 0.0]),
        };
        let o = model
            .orientations(a, rule, Some(near))
            .map_err(|e| Error::field(format!("points[{i}]"), e.message))?;
        match o.chosen {
            Some(c) => {
                let s = o.solutions[c];
                k.push(s.k);
                m.push(s.m);
                previous = Some([s.k, s.m]);
            }
            None => {
                return Ok(Following {
                    k,
                    m,
                    unreachable: Some((i, o.unreachable.unwrap_or_default())),
                })
            }
        }
    }
    Ok(Following {
        k,
        m,
        unreachable: None,
    })
}
