//! The binding's tests, run as WebAssembly in Node by wasm-bindgen's test runner (`cargo test
//! --target wasm32-unknown-unknown -p fiveaxis-wasm --test wasm`, scripts/test.sh): one test
//! binary, so one link and one wasm-bindgen pass for all of them. Natively it is empty.
#![cfg(target_arch = "wasm32")]

mod common;

mod exports_units;
mod inputs;
mod output;
mod reversal;
mod studies;
mod units;
