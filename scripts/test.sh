#!/usr/bin/env bash
# `npm test`: every test there is, in order of speed. Installs what is missing first.
#   1. lint: rustfmt and clippy (native and wasm32)
#   2. native engine tests (cargo test)
#   3. the exported API as WebAssembly in headless Node (wasm-bindgen-test: cargo test for
#      wasm32 with wasm-bindgen's test runner)
#   4. build the page (engine to wasm, TypeScript check, Vite): started beside step 1, in a
#      target directory of its own, waited for here
#   5. Node tests of the built JS API, and browser end-to-end tests in Debian's Chromium (one
#      Chromium for all of them, three test files at a time: tests/run.mjs)
set -euo pipefail
cd "$(dirname "$0")/.."

# Each step's time is printed when the next one starts, and all of them at the end.
START=$(date +%s)
LAST=$START
LAST_NAME="install what is missing (scripts/setup.sh)"
TIMES=""
lap() {
  local now
  now=$(date +%s)
  TIMES="${TIMES}$(printf '%5d s  %s' $((now - LAST)) "$LAST_NAME")"$'\n'
  LAST=$now
}
step() {
  lap
  LAST_NAME="$*"
  printf '\n== %s\n' "$*"
}
finish() {
  local rc=${1:-$?}
  lap
  printf '\n== time per step (exit %d)\n%s%5d s  in all\n' "$rc" "$TIMES" $(($(date +%s) - START))
}
trap finish EXIT

bash scripts/setup.sh --test
export PATH="$PWD/node_modules/.bin:$HOME/.cargo/bin:$PATH"

# The page's build runs beside steps 1-3. Most of its time uses one core (the wasm's fat-LTO
# link, wasm-opt, tsc, Vite) while the lint and the native tests keep both busy only part of
# theirs. Its own target directory: two cargo runs in one directory wait on each other's lock.
page_log=$(mktemp)
page_start=$(date +%s)
CARGO_TARGET_DIR="$PWD/target/page" setsid npm run --silent build >"$page_log" 2>&1 &
page_pid=$!
# On the way out of a failed step, the build is stopped with everything it started (and waited
# for, so that nothing writes to target/page or wasm/pkg after this script).
stop_page() {
  if [ -n "$page_pid" ]; then
    kill -- -"$page_pid" 2>/dev/null || true
    wait "$page_pid" 2>/dev/null || true
  fi
  rm -f "$page_log"
}
trap 'rc=$?; stop_page; finish "$rc"' EXIT

step "lint (rustfmt, clippy native and wasm32)"
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -q -- -D warnings
cargo clippy --workspace --target wasm32-unknown-unknown -q -- -D warnings

step "native engine tests"
cargo test --workspace --profile test-opt -q

step "wasm tests in headless Node (wasm-bindgen-test)"
WASM_BINDGEN_TEST_ONLY_NODE=1 CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
  cargo test --profile test-opt --target wasm32-unknown-unknown -p fiveaxis-wasm --test wasm

step "build the page (the rest of it: started with the lint)"
page_ok=0
wait "$page_pid" || page_ok=$?
page_pid=
if [ "$page_ok" = 0 ]; then
  sed 's/^/  /' "$page_log"
  printf '  (the build took %d s from its start beside the lint)\n' $(($(date +%s) - page_start))
else
  cat "$page_log" >&2
  echo "the page's build failed (log above)" >&2
  exit 1
fi

step "Node API tests and browser end-to-end tests"
node tests/run.mjs
