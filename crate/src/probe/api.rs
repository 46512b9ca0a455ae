//! The probing study's exports: the design (poses, NC blocks, what cannot be seen), the
//! simulation of the centres and their sensitivities, the reader of a measurement file, and the
//! identification.

use super::design::{self, ProbeDesign, ProbeDesignInput};
use super::fit::{self, ProbeIdentification, ProbeIdentifyInput};
use super::measure::{self, Measurements};
use super::{ProbeInput, Study};
use crate::error::{Error, Result};
use crate::machine::Machine;
use crate::schema::{DefaultValue, Kind, Quantity};
use serde::Serialize;

crate::inputs! {
    /// The poses at which to simulate the centres.
    pub struct ProbeSimulateInput {
        /// K's commands, degrees (radians in Rust).
        pub k: Vec<f64> = "k" {
            label: "{K} at each pose",
            kind: Kind::NumberList { quantity: Quantity::Angle, min: -3600.0, max: 3600.0, min_len: 1, max_len: 2000, nonzero: false },
            shown: false,
        },
        /// M's commands, degrees (radians in Rust), as many as `k`.
        pub m: Vec<f64> = "m" {
            label: "{M} at each pose",
            kind: Kind::NumberList { quantity: Quantity::Angle, min: -3600.0, max: 3600.0, min_len: 1, max_len: 2000, nonzero: false },
            shown: false,
        },
    }
}

impl crate::edge::Checked for ProbeSimulateInput {
    fn check(&self) -> Result<()> {
        if self.k.len() != self.m.len() {
            return Err(Error::field(
                "m",
                format!(
                    "expected as many values as k ({}), got {}",
                    self.k.len(),
                    self.m.len()
                ),
            ));
        }
        Ok(())
    }
}

crate::inputs! {
    /// A measurement file to read.
    pub struct ProbeCsvInput {
        /// The machine (for the letters of K and M in the header).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// The file's text.
        pub csv: String = "csv" {
            label: "Measured sphere centres (CSV)",
            help: "One line per pose: K and M (deg), the measured centre X, Y, Z (mm or um), units in the header.",
            kind: Kind::Text { max_len: 1_000_000 },
        },
    }
}

impl crate::edge::Checked for ProbeCsvInput {}

/// One simulated pose.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct SimulatedPose {
    /// K, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m: f64,
    /// The centre the control expects (nominal kinematics): X, Y, Z, mm.
    pub expected: [f64; 3],
    /// The centre the probe measures on the machine with its errors (exact chain), mm.
    pub measured: [f64; 3],
    /// `measured − expected`, mm.
    pub deviation: [f64; 3],
    /// The first-order deviation `Σ (∂c/∂ε)·ε` of the machine's errors, mm.
    pub first_order: [f64; 3],
    /// Within the travel and the tilt limit.
    pub reachable: bool,
}

/// The sensitivity of the centres to one unknown.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct CentreSensitivity {
    /// ISO name, or `sphere_X` ….
    pub name: String,
    /// Per "mm" or per "deg".
    pub per: String,
    /// Per pose, `∂(X, Y, Z)/∂ε`: mm per mm, or mm per degree.
    pub rows: Vec<[f64; 3]>,
}

/// The simulated centres and their sensitivities.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct ProbeSimulation {
    /// The sphere's centre in the workpiece frame, mm.
    pub sphere: [f64; 3],
    /// Per pose.
    pub poses: Vec<SimulatedPose>,
    /// Per unknown (errors, then the sphere's position when fitted).
    pub sensitivities: Vec<CentreSensitivity>,
}

/// The poses to probe (simple and designed), NC blocks, and what a sphere cannot see.
pub fn design(i: &(ProbeInput, ProbeDesignInput)) -> Result<ProbeDesign> {
    let study = Study::new(&i.0)?;
    design::design(&study, &i.1)
}

/// The centres at the poses asked for: expected, measured on the machine with its errors
/// (exact chain), the first-order deviation, and the sensitivities (eq 2 of `probe`).
pub fn simulate(i: &(ProbeInput, ProbeSimulateInput)) -> Result<ProbeSimulation> {
    let study = Study::new(&i.0)?;
    let machine = &i.0.machine;
    let mut poses = Vec::with_capacity(i.1.k.len());
    let mut sens: Vec<Vec<[f64; 3]>> = vec![Vec::new(); study.unknowns.len()];
    for (&k, &m) in i.1.k.iter().zip(&i.1.m) {
        let e = study.expected(k, m)?;
        let c = study.measured(k, m)?;
        let s = study.sensitivities(k, m)?;
        let mut first = nalgebra::Vector3::zeros();
        for (u, v) in study.unknowns.iter().zip(&s) {
            if let super::Unknown::Error(d) = u {
                first += v * machine.errors.get(d.name);
            }
        }
        // Errors of the machine that are not unknowns still act on the centre.
        for d in machine.error_defs() {
            let value = machine.errors.get(d.name);
            if value != 0.0 && !study.names().iter().any(|n| n == d.name) {
                let one = Study {
                    unknowns: vec![super::Unknown::Error(d)],
                    ..study.clone()
                };
                first += one.sensitivities(k, m)?[0] * value;
            }
        }
        for (j, (u, v)) in study.unknowns.iter().zip(&s).enumerate() {
            let per = u.quantity().per_api_unit(1.0);
            sens[j].push([v[0] * per, v[1] * per, v[2] * per]);
        }
        let dev = c - e;
        poses.push(SimulatedPose {
            k,
            m,
            expected: [e[0], e[1], e[2]],
            measured: [c[0], c[1], c[2]],
            deviation: [dev[0], dev[1], dev[2]],
            first_order: [first[0], first[1], first[2]],
            reachable: study.reachable(k, m)?,
        });
    }
    Ok(ProbeSimulation {
        sphere: design::centre_of(&study.sphere),
        poses,
        sensitivities: study
            .unknowns
            .iter()
            .zip(sens)
            .map(|(u, rows)| CentreSensitivity {
                name: u.name().to_string(),
                per: u.quantity().api_unit().to_string(),
                rows,
            })
            .collect(),
    })
}

/// Reads a measurement file (module docs of `probe::measure`).
pub fn read_csv(i: &ProbeCsvInput) -> Result<Measurements> {
    measure::read(
        &i.csv,
        Some([i.machine.k().letter(), i.machine.m().letter()]),
    )
}

/// Identifies the rotary axes' errors from a measurement file.
pub fn identify(i: &(ProbeInput, ProbeIdentifyInput)) -> Result<ProbeIdentification> {
    let study = Study::new(&i.0)?;
    fit::identify_file(&study, &i.1)
}
