// The ledger of `npm run mutants` (scripts/mutants.sh): every cargo-mutants run of a scope (the
// first pass, the second pass, a run resumed after a stop) writes its own outcomes.json; the
// ledger keeps each mutant's latest outcome, so that the counts are those of all runs together.
//
//   node scripts/mutants-ledger.mjs merge <scope dir>      add <scope dir>/mutants.out/outcomes.json
//   node scripts/mutants-ledger.mjs summary <scope dir> <scope> <equivalents file>
//   node scripts/mutants-ledger.mjs list <scope dir> done|survivors <equivalents file>
//   node scripts/mutants-ledger.mjs prune <scope dir> <names file>
//
// `list done` prints the mutants whose outcome is settled (caught, unviable, timed out, or
// missed but listed as equivalent), `list survivors` the missed ones not listed: the mutants a
// resumed first pass leaves out, and those a second pass runs again.
//
// `prune` drops from the ledger the mutants the tree no longer has (the names file is
// `cargo mutants --list` of the scope now): a name carries its line and column, so after an
// edit the mutants of the edited lines, and those of every line it shifted, get new names and
// a resumed run tests them again, and the old names are not counted.
//
// `summary` prints the scope's counts and each survivor that mutants-equivalent.txt does not
// explain, and exits 1 when there is one. A timeout (the mutant made a test run past
// cargo-mutants' limit, e.g. an SVD of NaNs that never converges) is detected, not a survivor:
// the suite does not pass with it.
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const [cmd, dir, scope, equivalentsFile] = process.argv.slice(2);
// `list` takes (dir, which, equivalents) and `prune` (dir, names file): `scope` holds the second there.
const ledgerPath = join(dir, 'ledger.json');
const ledger = existsSync(ledgerPath) ? JSON.parse(readFileSync(ledgerPath, 'utf8')) : {};

const explainedIn = (file) =>
  new Set(
    (file && existsSync(file) ? readFileSync(file, 'utf8') : '')
      .split('\n')
      .filter((l) => /^[a-z]/.test(l) && l.includes(' # '))
      .map((l) => l.slice(0, l.indexOf(' # '))),
  );

if (cmd === 'list') {
  const explained = explainedIn(equivalentsFile);
  const want = scope; // `done` or `survivors`
  for (const [name, summary] of Object.entries(ledger)) {
    const survivor = summary === 'MissedMutant' && !explained.has(name);
    if ((want === 'survivors') === survivor) console.log(name);
  }
} else if (cmd === 'merge') {
  const outcomes = join(dir, 'mutants.out', 'outcomes.json');
  if (existsSync(outcomes)) {
    for (const o of JSON.parse(readFileSync(outcomes, 'utf8')).outcomes) {
      const name = o.scenario?.Mutant?.name;
      if (name) ledger[name] = o.summary;
    }
    writeFileSync(ledgerPath, JSON.stringify(ledger, null, 1));
  }
} else if (cmd === 'prune') {
  const now = new Set(readFileSync(scope, 'utf8').split('\n').filter(Boolean));
  const gone = Object.keys(ledger).filter((name) => !now.has(name));
  for (const name of gone) delete ledger[name];
  writeFileSync(ledgerPath, JSON.stringify(ledger, null, 1));
  console.log(`[mutants] ${gone.length} mutants of the ledger are no longer in the tree (edited or moved lines): tested again`);
} else if (cmd === 'summary') {
  const explained = explainedIn(equivalentsFile);
  const by = { CaughtMutant: 0, MissedMutant: 0, Unviable: 0, Timeout: 0 };
  const unexplained = [];
  let equivalent = 0;
  for (const [name, summary] of Object.entries(ledger)) {
    by[summary] = (by[summary] ?? 0) + 1;
    if (summary !== 'MissedMutant') continue;
    if (explained.has(name)) equivalent++;
    else unexplained.push(name);
  }
  for (const m of unexplained.sort()) console.log(`[mutants]   unexplained survivor: ${m}`);
  console.log(
    `${scope}: ${Object.keys(ledger).length} mutants: caught ${by.CaughtMutant}, missed ${by.MissedMutant} ` +
      `(equivalent ${equivalent}, unexplained ${unexplained.length}), unviable ${by.Unviable}, timeout ${by.Timeout}`,
  );
  process.exit(unexplained.length === 0 ? 0 : 1);
} else {
  console.error('usage: mutants-ledger.mjs merge <dir> | summary <dir> <scope> <equivalents> | list <dir> done|survivors <equivalents> | prune <dir> <names file>');
  process.exit(2);
}
