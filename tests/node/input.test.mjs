// How every export reads the JavaScript value it is given (the binding's rules, `json` in wasm/src/lib.rs
// and the README's conventions): `undefined` and `null` are absent; numbers must be finite;
// typed arrays are lists; functions, symbols and big integers are refused; a property whose
// getter throws is refused; nothing is nested deeper than 16 levels; every refusal starts with
// the path of the value. Texts and keys outside ASCII (one and two UTF-16 units) arrive whole:
// the engine's own refusal names them back.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

/** The message the S-shape defects export refuses `input` with, or 'accepted'. */
const refusal = (input) => {
  try {
    fa.sshapeDefects(input);
    return 'accepted';
  } catch (e) {
    assert.ok(e instanceof Error);
    return e.message;
  }
};

test('a value JavaScript cannot give as JSON is refused at its path', () => {
  const errors = (E_X0B) => ({ machine: { errors: { E_X0B } } });
  const thrower = { machine: { errors: { get E_X0B() { throw new Error('no'); } } } };
  assert.match(refusal(thrower), /^machine\.errors\.E_X0B: cannot be read/);
  for (const bad of [1n, Symbol('s'), () => 1]) {
    assert.match(refusal(errors(bad)), /^machine\.errors\.E_X0B: expected a number, a text, a list or an object/, typeof bad);
  }
  for (const x of [NaN, Infinity, -Infinity]) {
    assert.match(refusal(errors(x)), new RegExp(`^machine\\.errors\\.E_X0B: must be a finite number, got (NaN|inf|-inf)`), String(x));
  }
  const motion = { machine: { motions: { E_XZ: { position: [-300, 0, 300], value: [0, NaN, 0] } } } };
  assert.match(refusal(motion), /^machine\.motions\.E_XZ\.value\[1\]: must be a finite number/);
});

test('nothing deeper than 16 levels: the refusal names the path down to the 17th', () => {
  let deep = 1;
  for (let i = 0; i < 20; i++) deep = { a: deep };
  const m = refusal({ machine: { geometry: deep } });
  // input (0) → machine (1) → geometry (2) → a (3) … a (17): fifteen a's.
  assert.equal(m, `machine.geometry${'.a'.repeat(15)}: nested too deeply`);
});

test('undefined and null are absent, typed arrays are lists', () => {
  assert.equal(refusal({ machine: undefined, tool: null }), 'accepted');
  const map = (position, value) =>
    fa.volumetricMap({
      machine: { motions: { E_XZ: { position, value } } },
      region: { plane: 'XY', uFrom: -100, uTo: 100, vFrom: -100, vTo: 100, at: 50, k: 0, m: 0, steps: 5 },
    });
  const typed = map(new Float64Array([-300, 300]), new Float32Array([0, 0.5]));
  const listed = map([-300, 300], [0, 0.5]);
  assert.deepEqual(typed, listed);
  // And the motion is in it: the same map without it differs.
  assert.notDeepEqual(listed, map([-300, 300], [0, 0]));
});

test('keys and texts outside ASCII arrive whole, and so do the keys and texts after them', () => {
  assert.match(refusal({ 'µ€𝜀': 1, machine: {} }), /^µ€𝜀: unknown input/);
  assert.match(refusal({ machine: { errors: { 'E_𝜀X': 1 } } }), /^machine\.errors\.E_𝜀X: unknown error name/);
  assert.match(refusal({ machine: { errors: { E_X0B: 0.001, E_Y0B: '𝜀Ω' } } }), /^machine\.errors\.E_Y0B: expected a number of mm, got "𝜀Ω"/);
  // A text of two-unit characters, then a key and a text read after it.
  assert.match(refusal({ model: '𝜀𝜀Ω', tool: 'xyz' }), /^tool: expected an object, got "xyz"/);
  // A lone half of a surrogate pair is no character: it arrives as U+FFFD, as the browser's
  // TextEncoder writes it (the WHATWG Encoding standard), and the text around it whole.
  assert.match(refusal({ tool: 'a\uD800b€' }), /^tool: expected an object, got "a\uFFFDb€"/);
});
