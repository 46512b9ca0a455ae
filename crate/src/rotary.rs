//! The twelve rotary-axis types of Geng, Wu & Qiu (2018), their forward and inverse kinematics
//! for the tool orientation, and how the three machine types map onto them.
//!
//! # The type KMH
//! A type is written with three letters: the rotary-axis feature `KM` (two distinct letters of
//! A, B, C, rotating about X, Y, Z, listed from the workpiece towards the tool) and the home tool
//! orientation `H` (X, Y or Z, the tool direction at zero angles; it may not lie along M's axis,
//! since a tool cannot be tilted by rotating about its own axis). The tool orientation in
//! workpiece coordinates is (eq 4)
//!
//! ```text
//! V(θk, θm) = R_K(θk) · R_M(θm) · e_H
//! ```
//!
//! with the right-handed rotation matrices of eqs (5)-(7). **Group I** has H along K's axis
//! (`ABX ACX BCY BAY CAZ CBZ`), **Group II** has H along the third axis (`ABZ ACY BCX BAZ CAY CBX`).
//!
//! # Machine types
//! K is the rotary axis nearer the workpiece in the chain workpiece → tool, M the one nearer the
//! tool. So, for a given type:
//! * **table-table** (both axes carry the workpiece): K is the secondary table axis that carries
//!   the workpiece and is itself carried by M; M is the primary table axis on the bed (its
//!   direction fixed). Example: a trunnion table A with a rotary table C on it and a vertical
//!   spindle is type `CAZ`.
//! * **head-head** (both axes carry the tool): K is the primary head axis on the ram (direction
//!   fixed); M is carried by K and carries the spindle. Example: a C-A fork head is `CAZ`.
//! * **head-table**: K is the table axis (carries the workpiece), M the head axis (carries the
//!   spindle). Example: a rotary table C and a B-tilting head is `CBZ`.
//!
//! Table angles follow ISO 841: a positive table command turns the table so that the tool moves
//! positively relative to the workpiece, i.e. the table itself turns by the negative angle. With
//! that convention `V` above holds with the commanded angles for all three machine types, so the
//! nonlinear error depends only on the type, not the machine type (paper, end of Section 2).

use crate::error::{quote, Error, Result};
use crate::geometry::{cross_axis, rotate, rotate_sc, wrap_pi, Axis};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;
use std::fmt;

/// Angle (rad) between a tool vector and ±K below which the orientation counts as singular: K is
/// then undefined (a tilt of 1e-9 rad moves a point 500 mm away by 0.5 nm).
pub const SINGULAR_ANGLE: f64 = 1e-9;

/// A rotary axis A, B or C, rotating about X, Y or Z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RotaryAxis {
    /// Rotates about X.
    A,
    /// Rotates about Y.
    B,
    /// Rotates about Z.
    C,
}

impl RotaryAxis {
    /// The direction the axis rotates about.
    pub fn axis(self) -> Axis {
        match self {
            RotaryAxis::A => Axis::X,
            RotaryAxis::B => Axis::Y,
            RotaryAxis::C => Axis::Z,
        }
    }

    /// The letter "A", "B" or "C".
    pub fn letter(self) -> char {
        ['A', 'B', 'C'][self.axis().index()]
    }

    fn from_letter(c: char) -> Option<Self> {
        match c {
            'A' => Some(RotaryAxis::A),
            'B' => Some(RotaryAxis::B),
            'C' => Some(RotaryAxis::C),
            _ => None,
        }
    }
}

/// Group I (home orientation along K's axis) or Group II (along the third axis).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub enum Group {
    /// H parallel to the axis of K: `ABX ACX BCY BAY CAZ CBZ`.
    I,
    /// H parallel to neither rotary axis: `ABZ ACY BCX BAZ CAY CBX`.
    II,
}

/// Angles of the two rotary axes in radians: `k` for K, `m` for M.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose {
    /// Angle of the K axis (nearer the workpiece), radians.
    pub k: f64,
    /// Angle of the M axis (nearer the tool), radians.
    pub m: f64,
}

impl Pose {
    /// A pose from two angles in radians.
    pub fn new(k: f64, m: f64) -> Self {
        Self { k, m }
    }
}

/// One of the twelve rotary-axis types `KMH`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "ts",
    derive(tsify::Tsify),
    tsify(
        type = "\"ABX\" | \"ACX\" | \"BCY\" | \"BAY\" | \"CAZ\" | \"CBZ\" | \"ABZ\" | \"ACY\" | \"BCX\" | \"BAZ\" | \"CAY\" | \"CBX\""
    )
)]
pub struct RotaryType {
    /// The axis nearer the workpiece.
    pub k: RotaryAxis,
    /// The axis nearer the tool.
    pub m: RotaryAxis,
    /// Home tool orientation (tool direction at zero angles).
    pub home: Axis,
}

impl RotaryType {
    /// The twelve types as the options of a choice (schema), in the order of [`Self::ALL`].
    pub const CHOICES: [crate::schema::Choice; 12] = {
        use crate::schema::Choice;
        const fn c(value: &'static str, label: &'static str) -> Choice {
            Choice {
                value,
                label,
                help: "",
            }
        }
        [
            c("ABX", "ABX: A (K) and B (M), tool along X at zero; Group I"),
            c("ACX", "ACX: A (K) and C (M), tool along X at zero; Group I"),
            c("BCY", "BCY: B (K) and C (M), tool along Y at zero; Group I"),
            c("BAY", "BAY: B (K) and A (M), tool along Y at zero; Group I"),
            c("CAZ", "CAZ: C (K) and A (M), tool along Z at zero; Group I"),
            c("CBZ", "CBZ: C (K) and B (M), tool along Z at zero; Group I"),
            c(
                "ABZ",
                "ABZ: A (K) and B (M), tool along Z at zero; Group II",
            ),
            c(
                "ACY",
                "ACY: A (K) and C (M), tool along Y at zero; Group II",
            ),
            c(
                "BCX",
                "BCX: B (K) and C (M), tool along X at zero; Group II",
            ),
            c(
                "BAZ",
                "BAZ: B (K) and A (M), tool along Z at zero; Group II",
            ),
            c(
                "CAY",
                "CAY: C (K) and A (M), tool along Y at zero; Group II",
            ),
            c(
                "CBX",
                "CBX: C (K) and B (M), tool along X at zero; Group II",
            ),
        ]
    };

    /// The twelve types: Group I `ABX ACX BCY BAY CAZ CBZ`, then Group II
    /// `ABZ ACY BCX BAZ CAY CBX` (the order of Table 1 of the paper).
    pub const ALL: [RotaryType; 12] = {
        use Axis::{X, Y, Z};
        use RotaryAxis::{A, B, C};
        const fn t(k: RotaryAxis, m: RotaryAxis, home: Axis) -> RotaryType {
            RotaryType { k, m, home }
        }
        [
            t(A, B, X),
            t(A, C, X),
            t(B, C, Y),
            t(B, A, Y),
            t(C, A, Z),
            t(C, B, Z),
            t(A, B, Z),
            t(A, C, Y),
            t(B, C, X),
            t(B, A, Z),
            t(C, A, Y),
            t(C, B, X),
        ]
    };

    /// Parses a name such as `"CAZ"` (case-insensitive). Rejects K = M and H along M's axis.
    pub fn parse(name: &str) -> Result<Self> {
        let upper = name.trim().to_ascii_uppercase();
        let chars: Vec<char> = upper.chars().collect();
        let bad = || {
            Error::field(
                "type",
                format!(
                    "unknown rotary-axis type {}; expected one of ABX ACX BCY BAY CAZ CBZ \
                     (Group I) or ABZ ACY BCX BAZ CAY CBX (Group II)",
                    quote(name)
                ),
            )
        };
        if chars.len() != 3 {
            return Err(bad());
        }
        let k = RotaryAxis::from_letter(chars[0]).ok_or_else(bad)?;
        let m = RotaryAxis::from_letter(chars[1]).ok_or_else(bad)?;
        let home = match chars[2] {
            'X' => Axis::X,
            'Y' => Axis::Y,
            'Z' => Axis::Z,
            _ => return Err(bad()),
        };
        if k == m || home == m.axis() {
            return Err(bad());
        }
        Ok(Self { k, m, home })
    }

    /// Group I when the home orientation lies along K's axis, else Group II.
    pub fn group(&self) -> Group {
        if self.home == self.k.axis() {
            Group::I
        } else {
            Group::II
        }
    }

    /// Tool orientation `V(θk, θm) = R_K(θk) R_M(θm) e_H` (eq 4), a unit vector in workpiece
    /// coordinates.
    pub fn tool_vector(&self, pose: Pose) -> Vector3<f64> {
        let w = rotate(self.m.axis(), pose.m, &self.home.unit());
        rotate(self.k.axis(), pose.k, &w)
    }

    /// The tool orientation and its first and second derivatives along the straight line in
    /// angle space `pose(u) = pose + u·(dk, dm)` at `u = 0`: returns `(V, V', V'')`.
    ///
    /// With `w = R_M(θm) e_H`: `V' = dk·(e_K × V) + dm·R_K(e_M × w)` and
    /// `V'' = dk²·e_K×(e_K×V) + 2·dk·dm·e_K×R_K(e_M×w) + dm²·R_K(e_M×(e_M×w))`.
    pub fn tool_vector_derivatives(
        &self,
        pose: Pose,
        dk: f64,
        dm: f64,
    ) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let [v, d1, d2, _] = self.tool_vector_jet(pose, dk, dm);
        (v, d1, d2)
    }

    /// The tool orientation and its first three derivatives along the straight line in angle
    /// space `pose(u) = pose + u·(dk, dm)` at `u = 0`: returns `[V, V', V'', V''']`.
    ///
    /// With `K = [e_K×]`, `M = [e_M×]` (so `K³ = -K`, `M³ = -M`) and `w = R_M(θm) e_H`, the
    /// derivative `d/du` acts as `dk·K` on the left of `R_K` plus `dm·M` between `R_K` and `R_M`
    /// (each commutes with its own rotation), so
    /// `V''' = dk³·K³V + 3·dk²·dm·K²R_K(Mw) + 3·dk·dm²·K R_K(M²w) + dm³·R_K(M³w)`.
    /// [`Self::tool_vector_derivatives`] is its first three terms.
    pub fn tool_vector_jet(&self, pose: Pose, dk: f64, dm: f64) -> [Vector3<f64>; 4] {
        let (ka, ma) = (self.k.axis(), self.m.axis());
        let w = rotate(ma, pose.m, &self.home.unit());
        let mw = cross_axis(ma, &w);
        let mmw = cross_axis(ma, &mw);
        let v = rotate(ka, pose.k, &w);
        let r_mw = rotate(ka, pose.k, &mw);
        let r_mmw = rotate(ka, pose.k, &mmw);
        let kv = cross_axis(ka, &v);
        let k_rmw = cross_axis(ka, &r_mw);
        let d1 = kv * dk + r_mw * dm;
        let d2 = cross_axis(ka, &kv) * (dk * dk) + k_rmw * (2.0 * dk * dm) + r_mmw * (dm * dm);
        let d3 = -kv * (dk * dk * dk)
            + cross_axis(ka, &k_rmw) * (3.0 * dk * dk * dm)
            + cross_axis(ka, &r_mmw) * (3.0 * dk * dm * dm)
            - r_mw * (dm * dm * dm);
        [v, d1, d2, d3]
    }

    /// Every pose `(θk, θm)` with `V(θk, θm)` along `direction` (any non-zero vector; it is
    /// normalised), and the one that continues best from `previous`.
    ///
    /// The K component of `v` is untouched by `R_K`, so `e_K·R_M(θm)e_H = v_K`, i.e.
    /// `a·cos θm + b·sin θm = v_K` with `a = e_K·e_H`, `b = e_K·(e_M×e_H)`: two solutions
    /// `θm = atan2(b, a) ± acos(v_K)`. Then `θk` turns the part of `R_M(θm)e_H` perpendicular to
    /// K onto the part of `v` perpendicular to K.
    ///
    /// **Singular orientations**: `v = ±e_K` (within [`SINGULAR_ANGLE`]) (for Group I at θm = 0 or π; for Group II at
    /// θm = ±90°). There θk is arbitrary; one solution is returned with θk kept at the previous
    /// value (0 without one) and `singular` set. Angles are in `(-π, π]` except `chosen`, which is
    /// unwrapped to the turn nearest `previous`.
    pub fn inverse(
        &self,
        direction: &Vector3<f64>,
        previous: Option<Pose>,
    ) -> Result<InverseSolution> {
        let norm = direction.norm();
        if !norm.is_finite() || norm < 1e-12 {
            return Err(Error::field(
                "vector",
                "the tool vector must be finite and non-zero",
            ));
        }
        let v = direction / norm;
        let (ka, ma) = (self.k.axis(), self.m.axis());
        let e_k = ka.unit();
        let e_h = self.home.unit();
        let a = e_k.dot(&e_h);
        let b = e_k.dot(&cross_axis(ma, &e_h));
        let vk = v.dot(&e_k).clamp(-1.0, 1.0);
        let v_perp = v - e_k * vk;
        let phase = b.atan2(a);
        // acos(v_K), computed as an atan2 so that it stays accurate next to the poles.
        let spread = v_perp.norm().atan2(vk);
        let pole_angle = if vk >= 0.0 {
            spread
        } else {
            v_perp.norm().atan2(-vk)
        };
        let singular = pole_angle < SINGULAR_ANGLE;
        // sin and cos of θm = phase + sign·spread by the angle-sum formulas (no trigonometry):
        // cos(phase), sin(phase) = (a, b)/|(a, b)|, cos(spread), sin(spread) = (v_K, |v⊥|)/|v|.
        let r = a.hypot(b);
        let (sp, cp) = (b / r, a / r);
        let rho = v_perp.norm().hypot(vk);
        let (ss, cs) = (v_perp.norm() / rho, vk / rho);
        let theta_k_for = |sign: f64| -> f64 {
            let w = rotate_sc(ma, sp * cs + sign * cp * ss, cp * cs - sign * sp * ss, &e_h);
            let w_perp = w - e_k * w.dot(&e_k);
            let s = e_k.dot(&w_perp.cross(&v_perp));
            let c = w_perp.dot(&v_perp);
            s.atan2(c)
        };
        let mut solutions = Vec::with_capacity(2);
        if singular {
            let theta_m = wrap_pi(phase + spread);
            let k = previous.map_or(0.0, |p| p.k);
            solutions.push(Pose::new(wrap_pi(k), theta_m));
        } else {
            for sign in [1.0, -1.0] {
                let theta_m = wrap_pi(phase + sign * spread);
                solutions.push(Pose::new(theta_k_for(sign), theta_m));
            }
        }
        let chosen = match previous {
            Some(p) => {
                let mut best = unwrap_near(solutions[0], p);
                for s in &solutions[1..] {
                    let c = unwrap_near(*s, p);
                    if dist2(c, p) < dist2(best, p) {
                        best = c;
                    }
                }
                if singular {
                    best.k = p.k;
                }
                best
            }
            None => {
                // Smallest tilt |θm| first, then smallest |θk|, then θm >= 0.
                let mut sorted = solutions.clone();
                sorted.sort_by(|x, y| {
                    let key = |p: &Pose| {
                        (
                            round9(p.m.abs()),
                            round9(p.k.abs()),
                            if p.m >= 0.0 { 0 } else { 1 },
                        )
                    };
                    key(x)
                        .partial_cmp(&key(y))
                        .unwrap_or(std::cmp::Ordering::Equal)
                });
                sorted[0]
            }
        };
        Ok(InverseSolution {
            solutions,
            singular,
            chosen,
            pole_angle,
        })
    }

    /// The name, e.g. `"CAZ"`.
    pub fn name(&self) -> String {
        format!(
            "{}{}{}",
            self.k.letter(),
            self.m.letter(),
            self.home.letter()
        )
    }
}

fn round9(x: f64) -> f64 {
    (x * 1e9).round()
}

fn dist2(a: Pose, b: Pose) -> f64 {
    (a.k - b.k).powi(2) + (a.m - b.m).powi(2)
}

/// Adds whole turns to each angle of `p` to bring it nearest `near`.
fn unwrap_near(p: Pose, near: Pose) -> Pose {
    let f = |x: f64, y: f64| x + TAU * ((y - x) / TAU).round();
    Pose::new(f(p.k, near.k), f(p.m, near.m))
}

impl fmt::Display for RotaryType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name())
    }
}

impl Serialize for RotaryType {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

impl<'de> Deserialize<'de> for RotaryType {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        RotaryType::parse(&s).map_err(|e| serde::de::Error::custom(e.message))
    }
}

/// The result of [`RotaryType::inverse`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InverseSolution {
    /// Every pose giving the tool vector, angles in `(-π, π]` radians: two, or one when singular.
    pub solutions: Vec<Pose>,
    /// True when the vector lies along the K axis and θk is arbitrary.
    pub singular: bool,
    /// The pose nearest `previous` (whole turns added as needed), or the smallest tilt without one.
    pub chosen: Pose,
    /// Angle in radians between the vector and the nearer of ±e_K: how close to the singularity.
    pub pole_angle: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twelve_valid_names_in_two_groups() {
        let names: Vec<String> = RotaryType::ALL.iter().map(|t| t.name()).collect();
        assert_eq!(
            names.join(" "),
            "ABX ACX BCY BAY CAZ CBZ ABZ ACY BCX BAZ CAY CBX"
        );
        for (i, t) in RotaryType::ALL.iter().enumerate() {
            assert_eq!(t.group(), if i < 6 { Group::I } else { Group::II });
            assert_eq!(RotaryType::parse(&t.name().to_lowercase()), Ok(*t));
        }
        for bad in ["ABY", "AAX", "CCZ", "CAZZ", "", "DAX", "CAW"] {
            assert!(RotaryType::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_choices_are_the_twelve_types_in_order() {
        for (c, t) in RotaryType::CHOICES.iter().zip(RotaryType::ALL) {
            assert_eq!(c.value, t.name());
            assert!(c.label.starts_with(&format!("{}: ", t.name())));
            let group = if t.group() == Group::I {
                "Group I"
            } else {
                "Group II"
            };
            assert!(c.label.ends_with(group), "{}", c.label);
        }
    }

    #[test]
    fn appendix_tool_vectors() {
        // Appendix A (A.1): ABX gives (cos θY, sin θX sin θY, -cos θX sin θY).
        // Appendix B (B.1): ABZ gives (sin θY, -sin θX cos θY, cos θX cos θY).
        let (x, y) = (0.37_f64, -1.1_f64);
        let abx = RotaryType::parse("ABX")
            .unwrap()
            .tool_vector(Pose::new(x, y));
        let abz = RotaryType::parse("ABZ")
            .unwrap()
            .tool_vector(Pose::new(x, y));
        let e1 = Vector3::new(y.cos(), x.sin() * y.sin(), -x.cos() * y.sin());
        let e2 = Vector3::new(y.sin(), -x.sin() * y.cos(), x.cos() * y.cos());
        assert!((abx - e1).norm() < 1e-15);
        assert!((abz - e2).norm() < 1e-15);
    }
}
