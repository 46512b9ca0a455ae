//! # fiveaxis: the engine of the five-axis machine-tool accuracy calculator
//!
//! Plain Rust (nalgebra, `f64`); the only WebAssembly-specific code is the thin binding in
//! [`wasm`]. Inside the engine lengths are in mm and angles in radians; the binding converts
//! angles from and to degrees at the JavaScript edge.
//!
//! Studies, one module each, all built on [`geometry`], [`rotary`] and the kinematic chain with
//! geometric errors, [`chain`]:
//! * [`nonlinear`]: nonlinear error of rotary-axis interpolation (Geng, Wu & Qiu 2018).
//! * [`cubic`]: the cubic-machining test, 3 × 3 zone heights on a B/C tilting-rotary table
//!   (Li, Sato, Shirase & Sakamoto 2021).
//! * [`sshape`]: the S-shape test piece of ISO 10791-7 (Chanal, Duc & Chevalier 2022).

pub mod chain;
pub mod cubic;
pub mod error;
pub mod geometry;
pub mod nonlinear;
mod numeric;
pub mod rotary;
pub mod sshape;
pub mod wasm;

pub use error::{Error, Result};
