// `node scripts/api-doc.mjs`: writes docs/api.md, the API reference of the JavaScript module,
// generated from the engine's own declarations and nothing else:
//   - schema() (called through wasm/pkg/fiveaxis.js): every export's inputs with their quantity,
//     unit, limits, default and help, the machine's fields, the error table and error motions;
//   - wasm/pkg/fiveaxis.d.ts (written by wasm-bindgen and tsify from the Rust doc comments): each
//     exported function's signature and doc comment, and the result types field by field.
// The output depends only on those two, so it is deterministic; tests/node/docs.test.mjs
// regenerates it in memory and fails when docs/api.md is stale.
import { readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const root = new URL('../', import.meta.url);

// ---------------------------------------------------------------------------------------------
// The .d.ts: doc comments and the declarations they belong to.

/** Parses the declarations of a wasm-bindgen `.d.ts`: functions, classes, interfaces, types. */
export function parseDts(text) {
  const lines = text.split('\n');
  const decls = new Map();
  let doc = null;
  let pending = [];
  const docText = (block) =>
    block
      .map((l) => l.replace(/^\s*\/\*\*\s?/, '').replace(/\s*\*\/\s*$/, '').replace(/^\s*\*\s?/, ''))
      .join('\n')
      .trim();
  for (let i = 0; i < lines.length; i++) {
    const line = lines[i];
    const t = line.trim();
    if (t.startsWith('/**')) {
      pending = [line];
      while (!lines[i].includes('*/')) pending.push(lines[++i]);
      doc = docText(pending);
      continue;
    }
    let m;
    if ((m = t.match(/^export (?:default )?function\s+(\w+)\s*\((.*)\)\s*:\s*(.+);$/))) {
      decls.set(m[1], { kind: 'function', name: m[1], params: m[2], returns: m[3], doc: doc ?? '' });
    } else if ((m = t.match(/^export type (\w+) = (.+);$/))) {
      decls.set(m[1], { kind: 'type', name: m[1], value: m[2], doc: doc ?? '' });
    } else if ((m = t.match(/^export (interface|class) (\w+)(?: extends ([\w, ]+))? \{$/))) {
      const d = { kind: m[1], name: m[2], extends: m[3] ? m[3].split(',').map((s) => s.trim()) : [], doc: doc ?? '', members: [] };
      let mdoc = null;
      for (i++; lines[i].trim() !== '}'; i++) {
        const u = lines[i].trim();
        if (u.startsWith('/**')) {
          const block = [lines[i]];
          while (!lines[i].includes('*/')) block.push(lines[++i]);
          mdoc = docText(block);
          continue;
        }
        let f;
        if ((f = u.match(/^(readonly )?(\w+)(\?)?: (.+);$/))) {
          d.members.push({ name: f[2], optional: !!f[3], type: f[4], doc: mdoc ?? '' });
        } else if ((f = u.match(/^(constructor|\w+)\((.*)\)(?:: (.+))?;$/)) && f[1] !== 'free') {
          d.members.push({ name: f[1], method: true, params: f[2], type: f[3] ?? '', doc: mdoc ?? '' });
        }
        mdoc = null;
      }
      decls.set(d.name, d);
    }
    if (t !== '') doc = null;
  }
  return decls;
}

// ---------------------------------------------------------------------------------------------
// Markdown helpers.

const cell = (s) => String(s).replace(/\|/g, '\\|').replace(/\s*\n\s*/g, ' ');
const code = (s) => '`' + String(s).replace(/`/g, "'") + '`';
const num = (x) => (Number.isInteger(x) ? String(x) : String(x));

function range(f) {
  const parts = [];
  if (f.list) {
    const { minLen, maxLen, nonzero } = f.list;
    parts.push(minLen === maxLen ? `${minLen} values` : `${minLen} to ${maxLen} values`);
    if (nonzero) parts.push('none zero');
  }
  if (f.kind === 'text') {
    if (f.max != null) parts.push(`at most ${num(f.max)} bytes`);
  } else if (f.min != null || f.max != null) {
    const lo = f.min == null ? '(−∞' : `${f.exclusiveMin ? '(' : '['}${num(f.min)}`;
    const hi = f.max == null ? '∞)' : `${num(f.max)}]`;
    parts.push(`${lo}, ${hi}`);
  }
  if (f.kind === 'count') parts.push('whole number');
  return parts.join('; ');
}

function what(f) {
  let s = f.label;
  if (f.help) s += `: ${f.help}`;
  if (!/[.!?)]$/.test(s)) s += '.';
  if (f.choices.length) s += ` Choices: ${f.choices.map((c) => `${code(c.value)} (${c.label}${c.help ? `: ${c.help}` : ''})`).join(', ')}.`;
  if (f.kinds.length) s += ` Only for ${f.kinds.join(', ')}.`;
  if (!f.shown) s += ' Not on the page.';
  return s;
}

function fieldTable(fields) {
  const out = ['| input | kind, quantity | unit | range | default | required | what it is |', '|---|---|---|---|---|---|---|'];
  for (const f of fields) {
    const kind = f.quantity ? `${f.kind}, ${f.quantity}` : f.kind;
    const dflt = f.default == null ? '' : code(JSON.stringify(f.default));
    out.push(`| ${code(f.path)} | ${kind} | ${f.unit} | ${cell(range(f))} | ${cell(dflt)} | ${f.optional ? '' : 'yes'} | ${cell(what(f))} |`);
  }
  return out.join('\n');
}

function memberTable(d) {
  const out = ['| field | type | what it is |', '|---|---|---|'];
  for (const m of d.members) {
    const name = m.method ? `${m.name}(${m.params})` : m.name + (m.optional ? '?' : '');
    out.push(`| ${cell(code(name))} | ${cell(code(m.type || '—'))} | ${cell(m.doc)} |`);
  }
  return out.join('\n');
}

// Types have headings `type Name` (anchor `#type-name`), apart from the exports' headings.
const typeLink = (name) => `[${code(name)}](#type-${name.toLowerCase()})`;

// The type names a TypeScript type expression refers to that are declared in the .d.ts.
const refs = (expr, decls) => [...new Set((expr.match(/[A-Za-z_]\w*/g) ?? []).filter((w) => decls.has(w) && decls.get(w).kind !== 'function'))];

// ---------------------------------------------------------------------------------------------
// The document.

// Exports grouped by study, in the order a newcomer meets them; anything not matched falls into
// "Other", so that a new export is never left out.
const GROUPS = [
  ['Machine', /^(schema|rotaryTypes|machine\w*|toolVector)$/],
  ['Nonlinear error', /^nonlinear/],
  ['Toolpath comparison', /^(toolpath\w*|ToolpathReader)$/],
  ['Volumetric error', /^volumetric/],
  ['Cubic-machining test', /^cubic/],
  ['S-shape test piece', /^sshape/],
  ['Rotary-axis reversal', /^reversal/],
  ['Probe and sphere', /^probe/],
  ['Ball-bar circular test (ISO 230-4)', /^ballbar/],
  ['Laser positioning (ISO 230-2)', /^positioning/],
  ['Other', /./],
];
const SKIP = new Set(['initSync', '__wbg_init']);

/** The text of docs/api.md from a schema() value and the .d.ts text. */
export function apiDoc(schema, dtsText) {
  const decls = parseDts(dtsText);
  const exported = [...decls.values()].filter((d) => (d.kind === 'function' || d.kind === 'class') && !SKIP.has(d.name));
  const out = [];
  const p = (...l) => out.push(...l);
  p(
    '# API reference',
    '',
    '<!-- Generated by `node scripts/api-doc.mjs` from the engine\'s `schema()` and',
    '     wasm/pkg/fiveaxis.d.ts. Do not edit: change the Rust doc comments or the inputs!',
    '     declarations, rebuild the wasm package, and run the script again. -->',
    '',
    'Every function of `wasm/pkg/fiveaxis.js`, as the engine declares it. Inputs come from',
    '`schema()`: each field\'s path in the input object, its quantity and API unit (lengths in',
    '`mm`, angles in `deg`), the accepted range (`[` inclusive, `(` exclusive), the default, and',
    'the help the page shows (`{K}`, `{M}` in a label stand for the machine\'s rotary axes,',
    '`{U}`, `{V}` for the face\'s axes). Fields of the `machine` object, taken by most exports, are listed',
    'once under [The machine](#the-machine). Results are the TypeScript types of the `.d.ts`, with',
    'their doc comments; the types they refer to are under [Types](#types). How to call the',
    'engine, what its errors look like and worked examples: [using.md](using.md).',
    '',
    '## Contents',
    '',
  );
  const grouped = GROUPS.map(([title, re]) => [title, exported.filter((d) => re.test(d.name) && !GROUPS.slice(0, GROUPS.findIndex(([t]) => t === title)).some(([, r]) => r.test(d.name)))]);
  const anchor = (s) => s.toLowerCase().replace(/[^a-z0-9 -]/g, '').replace(/ /g, '-');
  p('- [The machine](#the-machine)');
  for (const [title, ds] of grouped) {
    if (!ds.length) continue;
    p(`- [${title}](#${anchor(title)}): ${ds.map((d) => `[${code(d.name)}](#${d.name.toLowerCase()})`).join(', ')}`);
  }
  p('- [Types](#types)', '');

  // The machine.
  p('## The machine', '', 'The `machine` object every study takes (`schema().machine`); every field may be left out.', '', fieldTable(schema.machine), '');
  p('### Location errors (`machine.errors`)', '', 'ISO 230-1 names (`schema().errors`): a position in mm or an orientation in degrees, each within ±`limit`. Aliases are the symbols of a paper, refused with the ISO name and sign to use.', '');
  const errRows = (list) => {
    const rows = ['| name | axis | quantity | limit | label | what it is | aliases (sign) |', '|---|---|---|---|---|---|---|'];
    for (const e of list) {
      const al = e.aliases.map((a) => `${a.symbol} (${a.sign > 0 ? '+' : '−'}, ${a.source})`).join('; ');
      rows.push(`| ${code(e.name)} | ${e.axis} | ${e.quantity} | ${num(e.limit)} | ${cell(e.label)} | ${cell(e.description)} | ${cell(al)} |`);
    }
    return rows.join('\n');
  };
  p(errRows(schema.errors), '');
  p('### Error motions (`machine.motions`)', '', 'Errors that change along an axis (`schema().motions`): each a number, `{ poly: [c0, c1, …] }` or a measured table `{ position: [...], value: [...] }` (see `ErrorFunction`).', '');
  p(errRows(schema.motions), '');

  // The exports.
  for (const [title, ds] of grouped) {
    if (!ds.length) continue;
    p(`## ${title}`, '');
    for (const d of ds) {
      p(`### ${d.name}`, '');
      if (d.kind === 'class') {
        const ctor = d.members.find((m) => m.name === 'constructor');
        p('```ts', `new ${d.name}(${ctor ? ctor.params : ''})`, '```', '');
        if (d.doc) p(d.doc, '');
        if (ctor?.doc) p(`Constructor: ${ctor.doc}`, '');
        p(memberTable({ members: d.members.filter((m) => m.method && m !== ctor) }), '');
      } else {
        p('```ts', `${d.name}(${d.params}): ${d.returns}`, '```', '');
        if (d.doc) p(d.doc, '');
      }
      const fields = schema.exports[d.name];
      if (fields) {
        const own = fields.filter((f) => !f.path.startsWith('machine.'));
        const takesMachine = own.length < fields.length;
        p(`**Inputs** (\`schema().exports.${d.name}\`)${takesMachine ? ': `machine` (see [The machine](#the-machine))' : ''}${own.length ? (takesMachine ? ' and' : ':') : '.'}`, '');
        if (own.length) p(fieldTable(own), '');
      }
      if (d.kind === 'function') {
        const res = refs(d.returns, decls);
        if (res.length) p(`**Result**: ${res.map(typeLink).join(', ')}.`, '');
      }
    }
  }

  // Types reachable from the exports, alphabetically.
  const seen = new Set();
  const queue = [];
  const visit = (names) => names.forEach((n) => { if (!seen.has(n)) { seen.add(n); queue.push(n); } });
  for (const d of exported) {
    if (d.kind === 'function') visit(refs(`${d.params} ${d.returns}`, decls));
    else d.members.forEach((m) => visit(refs(`${m.params ?? ''} ${m.type}`, decls)));
  }
  while (queue.length) {
    const t = decls.get(queue.shift());
    if (t.kind === 'interface') {
      visit(t.extends.filter((e) => decls.has(e)));
      t.members.forEach((m) => visit(refs(m.type, decls)));
    } else if (t.kind === 'type') visit(refs(t.value, decls));
  }
  p('## Types', '');
  for (const name of [...seen].filter((n) => decls.get(n).kind !== 'class').sort()) {
    const t = decls.get(name);
    p(`### type ${name}`, '');
    if (t.kind === 'type') {
      p('```ts', `type ${name} = ${t.value}`, '```', '');
      if (t.doc) p(t.doc, '');
    } else {
      if (t.doc) p(t.doc, '');
      if (t.extends.length) p(`Extends ${t.extends.map((e) => (decls.has(e) ? typeLink(e) : code(e))).join(', ')}.`, '');
      p(memberTable(t), '');
    }
  }
  return out.join('\n').replace(/\n+$/, '\n');
}

/** The names the JS module exports, from the .d.ts (functions and classes). */
export function exportedNames(dtsText) {
  return [...parseDts(dtsText).values()].filter((d) => d.kind === 'function' || d.kind === 'class').map((d) => d.name);
}

/** docs/api.md as the current wasm package gives it. */
export async function generate() {
  const mod = await import(new URL('wasm/pkg/fiveaxis.js', root));
  mod.initSync({ module: readFileSync(new URL('wasm/pkg/fiveaxis_bg.wasm', root)) });
  return apiDoc(mod.schema(), readFileSync(new URL('wasm/pkg/fiveaxis.d.ts', root), 'utf8'));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const text = await generate();
  writeFileSync(new URL('docs/api.md', root), text);
  console.log(`docs/api.md: ${text.split('\n').length - 1} lines`);
}
