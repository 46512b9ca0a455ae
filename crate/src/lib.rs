//! # fiveaxis: the engine of the five-axis machine-tool accuracy calculator
//!
//! Plain Rust (nalgebra, `f64`), no WebAssembly in it: the JavaScript binding is its own crate
//! (`wasm/`, `fiveaxis-wasm`). Inside the engine lengths are in mm and angles in radians; at its
//! JSON edge ([`schema`]) angles are in degrees.
//!
//! * [`machine`]: the machine entered once: kind, rotary-axis type, linear axes, geometry,
//!   travel, and its ISO 230-1 errors ([`machine::errors`], one table for every study).
//! * [`chain`]: the one kinematic chain with errors that every study computes with.
//! * [`schema`]: inputs declared once ([`inputs!`]), read and checked in one place.
//! * [`identify`]: identification of the errors from a measured test piece (least squares,
//!   rank, family-wise decisions, goodness of fit), for every test piece.
//!
//! Studies, one module each, all on the machine:
//! * [`nonlinear`]: nonlinear error of rotary-axis interpolation (Geng, Wu & Qiu 2018).
//! * [`cubic`]: the cubic-machining test, 3 × 3 zone heights (Li, Sato, Shirase & Sakamoto 2021).
//! * [`sshape`]: the S-shape test piece of ISO 10791-7 (Chanal, Duc & Chevalier 2022).
//! * [`reversal`]: a rotary table's reversal with friction, as a ball bar sees it (Nishiguchi et al. 2017).
//! * [`toolpath`]: the customer's toolpath on the twelve rotary-axis types, ranked by nonlinear
//!   error, and refined to a tolerance.
//! * [`ballbar`]: a ball-bar circular test (ISO 230-4): G, H and the faults fitted from the trace.
//! * [`positioning`]: a positioning test of one axis (laser runs) evaluated as ISO 230-2 defines it.
//! * [`volumetric`]: the tool tip's deviation over the working volume from every location
//!   error and error motion, its budget, and Tan & Lim's RRTTT model beside it.
//! * [`probe`]: the rotary axes checked with a touch probe and a sphere (issue 31): poses,
//!   sensitivities, what a sphere cannot see, and the errors identified from measured centres.

pub mod schema;

pub mod api;
pub mod edge;

pub mod ballbar;
pub mod cache;
pub mod chain;
pub mod csv;
pub mod cubic;
pub mod error;
pub mod geometry;
pub mod identify;
pub mod machine;
pub mod nonlinear;

mod numeric;
pub mod positioning;
pub mod probe;
pub mod reversal;
pub mod rotary;
pub mod sshape;
pub mod toolpath;
pub mod volumetric;

pub use error::{Error, Result};
