#!/usr/bin/env bash
# Installs whatever the build and the tests need and is not already present.
# Idempotent: every step first checks, then installs only what is missing.
#
#   scripts/setup.sh           toolchain for building the engine and the page
#   scripts/setup.sh --test    also the headless browser for the end-to-end tests
#
# What it may install (and how):
#   - the wasm32-unknown-unknown target       (rustup)
#   - wasm-bindgen-cli at the exact version of wasm-bindgen in Cargo.lock (cargo install --debug)
#   - wasm-opt comes from the npm package binaryen (node_modules/.bin, on PATH in npm scripts):
#     Debian's binaryen 108 corrupts the externref table that wasm-bindgen 0.2.130 emits.
#   - chromium, with --test                    (Debian package chromium)
#   - gs, with --test                          (Debian package ghostscript: the report test reads its PDF)
#   - the npm packages of package-lock.json   (npm ci)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

want_browser=0
[ "${1:-}" = "--test" ] && want_browser=1

say() { printf '[setup] %s\n' "$*"; }

# cargo install with the crate's own lock file; when the registry mirror lacks a locked
# version (seen: a mirror a few days behind crates.io), resolve afresh instead.
cargo_install() {
  cargo install --locked "$@" || { say "retrying without --locked"; cargo install "$@"; }
}

command -v cargo >/dev/null || { echo "[setup] cargo not found: install Rust with rustup first (https://rustup.rs)" >&2; exit 1; }
command -v node >/dev/null || { echo "[setup] node not found: install Node.js 20 or newer first" >&2; exit 1; }

# The downloads and unpacking (Debian packages, npm packages) run in the background while
# cargo compiles wasm-bindgen-cli: one waits on the network and the disk, the other on the
# processors (on a fresh two-core machine, 2026-11-28: 95 s for all of it, wasm-bindgen-cli's
# compilation 86 s of them). Each writes to its own log, shown when it has finished.
bg=()
background() { # name, command…
  local log
  log=$(mktemp)
  say "$1 (in the background)"
  ("${@:2}") >"$log" 2>&1 &
  bg+=("$!|$1|$log")
}
wait_background() {
  local failed=0 job pid name log
  for job in "${bg[@]}"; do
    IFS='|' read -r pid name log <<<"$job"
    if wait "$pid"; then
      sed 's/^/  /' "$log"
    else
      echo "[setup] failed: $name" >&2
      cat "$log" >&2
      failed=1
    fi
    rm -f "$log"
  done
  return $failed
}

# 1. Debian packages: for the tests, chromium and Ghostscript.
apt_pkgs=()
if [ "$want_browser" = 1 ] && [ ! -x /usr/bin/chromium ]; then apt_pkgs+=(chromium); fi
if [ "$want_browser" = 1 ] && ! command -v gs >/dev/null; then apt_pkgs+=(ghostscript); fi
if [ "${#apt_pkgs[@]}" -gt 0 ]; then
  apt_install() {
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >/dev/null
  }
  if [ "$(id -u)" = 0 ]; then
    background "installing Debian packages: ${apt_pkgs[*]}" apt_install "${apt_pkgs[@]}"
  else
    # sudo may ask for a password: in the foreground.
    say "installing Debian packages: ${apt_pkgs[*]}"
    sudo apt-get update -qq
    sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${apt_pkgs[@]}" >/dev/null
  fi
fi

# 2. npm packages, when node_modules is missing or older than the lock file.
if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  background "installing npm packages (npm ci)" npm ci --no-audit --no-fund
fi

# 3. The wasm32 target.
if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  say "adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

# 4. wasm-bindgen-cli at the version the lock file pins (the CLI and the library must agree exactly).
bindgen_version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
if [ -z "$bindgen_version" ]; then
  echo "[setup] could not read the wasm-bindgen version from Cargo.lock" >&2; exit 1
fi
have_bindgen=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have_bindgen" != "$bindgen_version" ]; then
  # Unoptimised and without debug information: it compiled in 75 s where an optimised build
  # took 178 s (opt-level 1) to 242 s (release, beside the other installs), and the slower tool
  # costs little where it runs: 1.1 s instead of 0.25 on the page's wasm, 4.5 s instead of 1.8 for
  # the wasm tests' runner.
  say "installing wasm-bindgen-cli $bindgen_version (have: ${have_bindgen:-none}); this takes a minute or two"
  CARGO_PROFILE_DEV_DEBUG=false cargo_install --debug wasm-bindgen-cli --version "=$bindgen_version" --force
fi

# (No wasm-pack: scripts/build-wasm.sh runs cargo, wasm-bindgen and wasm-opt itself, and the
# wasm tests run under cargo test with wasm-bindgen's test runner. Installing it took minutes.)

wait_background
say "toolchain ready"
