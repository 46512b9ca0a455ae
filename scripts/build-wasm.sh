#!/usr/bin/env bash
# `npm run build:wasm`: the engine's binding (wasm/) as WebAssembly, with its JavaScript glue and
# TypeScript types, in wasm/pkg/ (fiveaxis.js, fiveaxis.d.ts, fiveaxis_bg.wasm), which the page,
# the Node tests and the bench load. Three tools, each installed by scripts/setup.sh:
#   1. cargo builds wasm/ for wasm32-unknown-unknown (release profile: fat LTO, one codegen unit);
#   2. wasm-bindgen (the CLI at the exact version of the library in Cargo.lock) writes the glue
#      and the types for ES-module loading in the browser (`--target web`);
#   3. wasm-opt (npm package binaryen, node_modules/.bin) optimises the module (-O3).
# This is what `wasm-pack build --release --target web` did, without installing wasm-pack.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$PWD/node_modules/.bin:$HOME/.cargo/bin:$PATH"

out=wasm/pkg
target_dir=$(cargo metadata --format-version 1 --no-deps | node -e \
  'let s = ""; process.stdin.on("data", (d) => (s += d)).on("end", () => console.log(JSON.parse(s).target_directory))')

cargo build --release --target wasm32-unknown-unknown -p fiveaxis-wasm
mkdir -p "$out"
wasm-bindgen "$target_dir/wasm32-unknown-unknown/release/fiveaxis_wasm.wasm" \
  --target web --out-dir "$out" --out-name fiveaxis --typescript
wasm-opt -O3 "$out/fiveaxis_bg.wasm" -o "$out/fiveaxis_bg.wasm"
# wasm/pkg is build output: keep it out of git, as wasm-pack did.
printf '*\n' > "$out/.gitignore"
