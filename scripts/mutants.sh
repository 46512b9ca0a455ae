#!/usr/bin/env bash
# `npm run mutants`: mutation testing of the engine with cargo-mutants (installed when missing,
# like scripts/setup.sh installs its cargo tools). Not part of `npm test`: it is slow.
#
#   npm run mutants                       the default scopes: chain, edge
#   npm run mutants -- chain sshape       named scopes (list below)
#   npm run mutants -- all                every scope, one after the other (many hours)
#   npm run mutants -- resume cubic       go on where a stopped run of the scope left off
#   npm run mutants -- chain -- --shard 1/4 --baseline skip
#                                         anything after a second `--` goes to cargo-mutants
#                                         (not --cargo-test-arg: this script's filters for the
#                                         test binary come after cargo's `--`, and a cargo test
#                                         option after them would reach the binary)
#
# A scope is a module of the engine (its source files) and the tests named for it, run against
# each of its mutants in two passes (see `quick` below): every mutant against the scope's quick tests, then the
# survivors against every test. Run one scope at a time: two runs side by side on two cores
# take longer than the same runs one after the other.
#
# Results: each cargo-mutants run writes mutants.out/<scope>/mutants.out/ (outcomes.json, a
# log per mutant); mutants.out/<scope>/ledger.json keeps every mutant's latest outcome over the
# passes and resumed runs (scripts/mutants-ledger.mjs); the ledgers are committed (.gitignore
# keeps them), so that a run stopped on one machine resumes on another. `resume` first drops the ledger's
# mutants the tree no longer has (a name carries its line and column: after an edit, those of
# the edited lines and of every line it shifted are new names, tested again).
#
# The summary counts each scope's missed mutants that are listed in mutants-equivalent.txt (one
# line per mutant exactly as cargo-mutants prints it, then ` # why it is equivalent`), and exits
# non-zero when a missed mutant is neither killed nor listed there. A mutant that times out (a
# test hangs with it) is counted apart as detected.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
say() { printf '[mutants] %s\n' "$*"; }

cargo_install() {
  cargo install --locked "$@" || { say "retrying without --locked"; cargo install "$@"; }
}
if ! cargo mutants --version >/dev/null 2>&1; then
  say "installing cargo-mutants; this takes a few minutes"
  cargo_install cargo-mutants
fi

equivalents=mutants-equivalent.txt

# A scope is a module of the engine, named by its path under crate/src: `chain` is
# crate/src/chain.rs, `cubic` every file under crate/src/cubic/, `sshape/overcut`
# crate/src/sshape/overcut.rs (a module inside a study: after an edit, run the file's module
# again rather than the whole study). The scopes are read from the tree, so a new module is a
# scope without an edit here. (The binding, wasm/src, has no scope: it holds no mathematics,
# only the conversion of JavaScript values, which runs under WebAssembly alone and is tested
# there: wasm/tests, tests/node.)
files() {
  [[ "$1" =~ ^[a-z_0-9]+(/[a-z_0-9]+)*$ ]] || return 1
  if [ -f "crate/src/$1.rs" ]; then echo "crate/src/$1.rs"
  elif [ -d "crate/src/$1" ]; then echo "crate/src/$1/**/*.rs"
  else return 1
  fi
}
# Two passes per scope. The first runs every mutant against the scope's own tests: the unit tests
# of its module and the integration tests named for it (the engine's one test binary,
# crate/tests/engine.rs, mirrors crate/src: crate/tests/chain/model.rs tests chain.rs as
# `chain::model::…`, crate/tests/machine/travel.rs machine/ as `machine::travel::…`), chosen by
# libtest's name filter `<scope>::`, so a new test file (declared in engine.rs) joins its scope
# by where it is. libtest's filter matches anywhere in a name: `machine::` also runs
# `sshape::machine::…`, more tests than the scope's own, never fewer. The
# second (`--re`, by name from the ledger) runs the first pass's survivors again, except those
# listed as equivalent, against every test of the crate: a mutant survives only when no test
# kills it.
# Slow test files (`slow_files` below) run only in the second pass, and only for the scopes whose code
# they reach: reversal::fit (≈ 30 s) for reversal, ballbar::rotary_identify_monte_carlo (≈ 10 s,
# of a mutant's 15) for ballbar, nonlinear::fast_peak and nonlinear::paper (≈ 7 s and 5 s: the
# rotary-axis types and the chain) for nonlinear, rotary and chain. (No unit test of crate/src
# has these names.)
slow_files="reversal::fit=reversal ballbar::rotary_identify_monte_carlo=ballbar nonlinear::fast_peak=nonlinear,rotary,chain nonlinear::paper=nonlinear,rotary,chain"
# The test binary's arguments for each pass, one per line: name filters and `--skip`s. A nested
# scope (`sshape/overcut`) runs the tests of its study (`sshape::`).
quick() {
  local f
  echo "${1%%/*}::"
  # The edge's tests are those of its one caller, api.rs's table: crate/tests/api/.
  [ "${1%%/*}" = edge ] && echo "api::"
  for f in $slow_files; do printf -- '--skip\n%s::\n' "${f%%=*}"; done
}
every() {
  local f
  for f in $slow_files; do
    case ",${f#*=}," in *",${1%%/*},"*) ;; *) printf -- '--skip\n%s::\n' "${f%%=*}" ;; esac
  done
}
# cargo-mutants options naming mutants of the ledger exactly: `regexes --exclude-re done`
# leaves out the settled ones, `regexes --re survivors` selects the unexplained survivors.
regexes() {
  node scripts/mutants-ledger.mjs list "$out" "$2" "$equivalents" | while IFS= read -r m; do
    printf -- '%s\n^%s$\n' "$1" "$(printf '%s' "$m" | sed 's/[][\\.^$*+?(){}|]/\\&/g')"
  done
}
# Every module of crate/src but the crate's root (lib.rs) and the edge's declarations (api.rs:
# a macro's list, tested by crate/tests/api/call.rs and the wasm and Node suites).
all_scopes=$(for f in crate/src/*; do n=$(basename "$f" .rs); case "$n" in lib | api) ;; *) printf '%s ' "$n" ;; esac; done)
scopes=()
extra=()
resume=0
while [ $# -gt 0 ]; do
  case "$1" in
    --) shift; extra=("$@"); break ;;
    resume) resume=1 ;;
    all) read -r -a scopes <<<"$all_scopes" ;;
    *) files "$1" >/dev/null || { echo "[mutants] unknown scope '$1' (known: $all_scopes, all)" >&2; exit 2; }
       scopes+=("$1") ;;
  esac
  shift
done
[ "${#scopes[@]}" -gt 0 ] || scopes=(chain edge)

# Its own target directory, so that a run does not wait on the lock of the tree's builds; the
# dependencies are built once and kept there (MUTANTS_TARGET_DIR chooses another).
export CARGO_TARGET_DIR="${MUTANTS_TARGET_DIR:-$PWD/target/mutants-run}"
jobs="${MUTANTS_JOBS:-1}"

status=0
summary=()
for s in "${scopes[@]}"; do
  out="mutants.out/${s//\//.}" # sshape/overcut → mutants.out/sshape.overcut
  say "scope $s: $(files "$s")"
  mkdir -p "$out"
  args=(--package fiveaxis --output "$out" -j "$jobs" --no-shuffle)
  # The pattern goes to cargo-mutants as it is (quoted): cargo-mutants reads `**` as any depth,
  # where bash, without globstar, would expand it to one level of subfolders only (ballbar's
  # rotary/ without ballbar's own files).
  args+=(--file "$(files "$s")")
  resumed=()
  # A run stopped part-way (the machine reset, a kill) left its outcomes in
  # $out/mutants.out/outcomes.json, unmerged: merged first, or the next run, which moves that
  # folder aside, would test them again. (That file is always the latest run's, so merging it
  # again after a finished run changes nothing.)
  if [ "$resume" = 1 ] && [ -f "$out/mutants.out/outcomes.json" ]; then
    node scripts/mutants-ledger.mjs merge "$out"
  fi
  if [ "$resume" = 1 ] && [ -f "$out/ledger.json" ]; then
    cargo mutants --list "${args[@]}" >"$out/names.txt"
    node scripts/mutants-ledger.mjs prune "$out" "$out/names.txt"
    mapfile -t resumed < <(regexes --exclude-re done)
    say "scope $s: resuming ($(($(printf '%s\n' "${resumed[@]}" | grep -c '^\^' || true))) mutants settled before are left out)"
  else
    rm -f "$out/ledger.json"
  fi
  failed=0
  for pass in quick every; do
    # The unit tests and the engine's test binary (not the doctests, nor the binding's tests),
    # with the pass's filters after cargo's `--`.
    targs=(--cargo-arg=--lib --cargo-arg=--test --cargo-arg=engine --cargo-test-arg=--)
    while IFS= read -r a; do [ -n "$a" ] && targs+=("--cargo-test-arg=$a"); done < <($pass "$s")
    more=("${resumed[@]}")
    if [ $pass = every ]; then
      mapfile -t more < <(regexes --re survivors)
      [ "${#more[@]}" -gt 0 ] || break
      say "scope $s: second pass, $((${#more[@]} / 2)) survivors against every test"
    fi
    set +e
    nice -n 10 cargo mutants "${args[@]}" "${targs[@]}" "${more[@]}" "${extra[@]}"
    rc=$?
    set -e
    node scripts/mutants-ledger.mjs merge "$out"
    # cargo-mutants: 0 all caught, 2 some missed, 3 some timed out; anything else is a failure.
    case $rc in 0 | 2 | 3) ;; *) say "cargo mutants failed ($rc) in scope $s"; failed=1; break ;; esac
  done
  [ $failed = 0 ] || { status=1; continue; }
  set +e
  line=$(node scripts/mutants-ledger.mjs summary "$out" "$s" "$equivalents")
  [ $? = 0 ] || status=1
  set -e
  printf '%s\n' "$line" | grep '^\[mutants\]' || true
  summary+=("$(printf '%s\n' "$line" | tail -n 1)")
done

printf '\n== mutation testing summary\n'
printf '%s\n' "${summary[@]}"
exit $status
