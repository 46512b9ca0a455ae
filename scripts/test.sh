#!/usr/bin/env bash
# `npm test`: every test there is, in order of speed. Installs what is missing first.
#   1. lint: rustfmt and clippy (native and wasm32)
#   2. native engine tests (cargo test)
#   3. the exported API as WebAssembly in headless Node (wasm-bindgen-test via wasm-pack)
#   4. build the page (engine to wasm, TypeScript check, Vite)
#   5. Node tests of the built JS API, and browser end-to-end tests in Debian's Chromium
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --test
export PATH="$PWD/node_modules/.bin:$HOME/.cargo/bin:$PATH"

step() { printf '\n== %s\n' "$*"; }

step "lint (rustfmt, clippy native and wasm32)"
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -q -- -D warnings
cargo clippy --workspace --target wasm32-unknown-unknown -q -- -D warnings

step "native engine tests"
cargo test --workspace --release -q

step "wasm tests in headless Node (wasm-bindgen-test)"
wasm-pack test --node wasm --test 'wasm_*'

step "build the page"
npm run --silent build

step "Node API tests and browser end-to-end tests"
node --test --test-reporter=spec tests/node/ tests/e2e/
