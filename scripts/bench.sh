#!/usr/bin/env bash
# `npm run bench`: installs what is missing, builds the release wasm package, then compares.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export PATH="$PWD/node_modules/.bin:$HOME/.cargo/bin:$PATH"
npm run --silent build
node scripts/bench.mjs
node scripts/bench-page.mjs
