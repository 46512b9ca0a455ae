//! A result into JavaScript in one crossing. The result is serialized into a tape in
//! WebAssembly's memory: `ops` (what comes next: null, a boolean, a number, a text, a list, an
//! object, a `Float64Array`), `nums` (the numbers, in order) and `text` (every text and key, one
//! string, each addressed by its UTF-16 offsets); one JavaScript function (`fiveaxisBuild`
//! below) then builds the objects from it. Writing each field across the boundary (an object,
//! a `Reflect.set`, a `TextDecoder` call per text) was a third of a cubic identification's time
//! under WebAssembly.
//!
//! What becomes what: `None` and `()` → `null`; structs and maps → objects (map keys texts or
//! numbers); enums as serde writes them (a unit variant → its name, the others
//! `{ variant: … }`); integers → numbers; a series (`fiveaxis::edge::SERIES`) → `Float64Array`.

use fiveaxis::edge::SERIES;
use serde::ser::{self, Serialize};
use std::collections::HashMap;
use std::fmt::Display;
use std::hash::{BuildHasherDefault, Hasher};
use wasm_bindgen::prelude::*;

// The op codes, as `fiveaxisBuild` reads them.
const NULL: u32 = 0;
const TRUE: u32 = 1;
const FALSE: u32 = 2;
/// The next number of `nums`.
const NUM: u32 = 3;
/// Then its start and end in `text`.
const STR: u32 = 4;
/// Then its length and its items.
const LIST: u32 = 5;
/// Then its length and its (key, value) pairs. A key is `2i` for the `i`-th key written before
/// in this result, or `1` then its start and end in `text` (a new key, numbered next).
const OBJECT: u32 = 6;
/// Then its length; its numbers are the next of `nums`.
const FLOAT64: u32 = 7;

#[wasm_bindgen(inline_js = r#"
export function fiveaxisBuild(ops, nums, text) {
  let o = 0;
  let n = 0;
  // Each key is read from the text once per result: V8 then finds the same key and the same
  // object shape again (a key sliced anew for every object costs a lookup per field).
  const keys = [];
  function value() {
    switch (ops[o++]) {
      case 0: return null;
      case 1: return true;
      case 2: return false;
      case 3: return nums[n++];
      case 4: { const s = text.slice(ops[o], ops[o + 1]); o += 2; return s; }
      case 5: {
        const len = ops[o++];
        const out = [];
        for (let i = 0; i < len; i++) out.push(value());
        return out;
      }
      case 6: {
        const len = ops[o++];
        const out = {};
        for (let i = 0; i < len; i++) {
          const k = ops[o++];
          let key;
          if (k === 1) {
            key = text.slice(ops[o], ops[o + 1]);
            o += 2;
            keys.push(key);
          } else {
            key = keys[k >> 1];
          }
          out[key] = value();
        }
        return out;
      }
      case 7: {
        const len = ops[o++];
        const out = nums.slice(n, n + len);
        n += len;
        return out;
      }
      default: throw new Error('fiveaxis: unreadable result (op ' + ops[o - 1] + ')');
    }
  }
  return value();
}
"#)]
extern "C" {
    #[wasm_bindgen(js_name = fiveaxisBuild)]
    fn build(ops: &[u32], nums: &[f64], text: &str) -> JsValue;
}

/// Writes a result as a JavaScript value (module docs): what every export returns.
pub fn output<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    let mut tape = Tape::default();
    value.serialize(&mut tape).map_err(crate::js_error)?;
    Ok(build(&tape.ops, &tape.nums, &tape.text))
}

#[derive(Default)]
struct Tape {
    ops: Vec<u32>,
    nums: Vec<f64>,
    text: String,
    /// Length of `text` in UTF-16 units (JavaScript's string offsets).
    utf16: u32,
    /// Inside a series: numbers go to `nums` alone.
    series: bool,
    /// The struct field names written so far, by address (they are `&'static str`), with their
    /// number in `fiveaxisBuild`'s key list.
    keys: HashMap<usize, u32, BuildHasherDefault<Address>>,
    /// Keys written out so far (the length of `fiveaxisBuild`'s key list).
    named: u32,
}

/// A hasher of addresses (a struct field name's): the address times a large odd constant
/// (Fibonacci hashing), so that the high bits the table also uses vary.
#[derive(Default)]
struct Address(u64);

impl Hasher for Address {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = self.0.rotate_left(8) ^ u64::from(*b);
        }
    }
    fn write_usize(&mut self, i: usize) {
        self.0 = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

impl Tape {
    /// `text` appended; its start and end in UTF-16 units.
    fn text(&mut self, s: &str) -> [u32; 2] {
        let start = self.utf16;
        self.text.push_str(s);
        let len = if s.is_ascii() {
            s.len()
        } else {
            s.encode_utf16().count()
        };
        self.utf16 += len as u32;
        [start, self.utf16]
    }

    /// An object's key that is a struct field's or a variant's name: numbered once per result
    /// (by its address), then written as its number.
    fn name(&mut self, name: &'static str) {
        if let Some(&i) = self.keys.get(&(name.as_ptr() as usize)) {
            self.ops.push(2 * i);
        } else {
            self.keys.insert(name.as_ptr() as usize, self.named);
            self.key(name);
        }
    }

    /// An object's key written out (numbered all the same by `fiveaxisBuild`).
    fn key(&mut self, key: &str) {
        let at = self.text(key);
        self.ops.push(1);
        self.ops.extend(at);
        self.named += 1;
    }

    fn str(&mut self, s: &str) {
        let at = self.text(s);
        self.ops.push(STR);
        self.ops.extend(at);
    }

    /// Opens a list or an object whose length is written by [`Compound::end`].
    fn open(&mut self, op: u32) -> Compound<'_> {
        self.ops.extend([op, 0]);
        let at = self.ops.len() - 1;
        Compound {
            at,
            len: 0,
            ends_series: false,
            tape: self,
        }
    }

    /// Opens `{ variant: <op> }` (a tuple or struct variant).
    fn variant(&mut self, variant: &'static str, op: u32) -> Compound<'_> {
        self.ops.extend([OBJECT, 1]);
        self.name(variant);
        self.open(op)
    }

    fn num(&mut self, v: f64) -> Result<(), Error> {
        if !self.series {
            self.ops.push(NUM);
        }
        self.nums.push(v);
        Ok(())
    }

    /// Refuses anything but a number in a series.
    fn plain(&self) -> Result<(), Error> {
        if self.series {
            return Err(ser::Error::custom("a series holds numbers only"));
        }
        Ok(())
    }

    fn op(&mut self, op: u32) -> Result<(), Error> {
        self.plain()?;
        self.ops.push(op);
        Ok(())
    }
}

/// A result that cannot be written (a series holding something else than numbers, a map key
/// that is not a text or a number).
#[derive(Debug)]
struct Error(String);

impl Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the result cannot be written: {}", self.0)
    }
}

impl std::error::Error for Error {}

impl ser::Error for Error {
    fn custom<T: Display>(msg: T) -> Self {
        Error(msg.to_string())
    }
}

/// A list or an object being written: where its length goes, and how many items it has.
struct Compound<'a> {
    tape: &'a mut Tape,
    at: usize,
    len: u32,
    /// A series' list: the tape's series mode is left at its end.
    ends_series: bool,
}

impl Compound<'_> {
    fn item<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Error> {
        self.len += 1;
        value.serialize(&mut *self.tape)
    }

    fn field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), Error> {
        self.tape.name(key);
        self.item(value)
    }

    fn end(self) -> Result<(), Error> {
        self.tape.ops[self.at] = self.len;
        if self.ends_series {
            self.tape.series = false;
        }
        Ok(())
    }
}

/// Every number is a JavaScript number (integers beyond 2⁵³ rounded, as `JSON.parse` would).
macro_rules! numbers {
    ($($method:ident : $t:ty),*) => { $(
        fn $method(self, v: $t) -> Result<(), Error> {
            self.num(v as f64)
        }
    )* };
}

impl<'a> ser::Serializer for &'a mut Tape {
    type Ok = ();
    type Error = Error;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    fn serialize_bool(self, v: bool) -> Result<(), Error> {
        self.op(if v { TRUE } else { FALSE })
    }
    numbers!(
        serialize_i8: i8,
        serialize_i16: i16,
        serialize_i32: i32,
        serialize_i64: i64,
        serialize_u8: u8,
        serialize_u16: u16,
        serialize_u32: u32,
        serialize_u64: u64,
        serialize_f32: f32,
        serialize_f64: f64
    );
    fn serialize_char(self, v: char) -> Result<(), Error> {
        self.serialize_str(v.encode_utf8(&mut [0; 4]))
    }
    fn serialize_str(self, v: &str) -> Result<(), Error> {
        self.plain()?;
        self.str(v);
        Ok(())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<(), Error> {
        let mut list = self.serialize_seq(Some(v.len()))?;
        for b in v {
            list.item(b)?;
        }
        list.end()
    }
    fn serialize_none(self) -> Result<(), Error> {
        self.op(NULL)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), Error> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), Error> {
        self.op(NULL)
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<(), Error> {
        self.op(NULL)
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<(), Error> {
        self.serialize_str(variant)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        name: &'static str,
        value: &T,
    ) -> Result<(), Error> {
        if name == SERIES && !self.series {
            // The series' list, then its numbers alone (`Compound::end` leaves the mode).
            self.series = true;
        }
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), Error> {
        self.op(OBJECT)?;
        self.ops.push(1);
        self.name(variant);
        value.serialize(self)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Compound<'a>, Error> {
        if self.series {
            self.nums.reserve(len.unwrap_or(0));
            let mut list = self.open(FLOAT64);
            list.ends_series = true;
            return Ok(list);
        }
        Ok(self.open(LIST))
    }
    fn serialize_tuple(self, len: usize) -> Result<Compound<'a>, Error> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(self, _: &'static str, len: usize) -> Result<Compound<'a>, Error> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Error> {
        self.plain()?;
        Ok(self.variant(variant, LIST))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, Error> {
        self.plain()?;
        Ok(self.open(OBJECT))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Error> {
        self.serialize_map(None)
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Error> {
        self.plain()?;
        Ok(self.variant(variant, OBJECT))
    }
}

/// The serde traits of a list's items and of a struct's fields, all written by [`Compound`].
macro_rules! items {
    ($($trait:ident :: $method:ident),*) => { $(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = Error;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Error> {
                self.item(value)
            }
            fn end(self) -> Result<(), Error> {
                Compound::end(self)
            }
        }
    )* };
}
macro_rules! fields {
    ($($trait:ident),*) => { $(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = Error;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), Error> {
                self.field(key, value)
            }
            fn end(self) -> Result<(), Error> {
                Compound::end(self)
            }
        }
    )* };
}
items!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);
fields!(SerializeStruct, SerializeStructVariant);

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = Error;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), Error> {
        // A key written on a tape of its own: a text, or a number written as JavaScript would.
        let mut own = Tape::default();
        key.serialize(&mut own)?;
        let name = match (own.ops.as_slice(), own.nums.as_slice()) {
            ([STR, ..], _) => own.text,
            ([NUM], [v]) => v.to_string(),
            _ => return Err(ser::Error::custom("a map key must be a text or a number")),
        };
        self.tape.key(&name);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Error> {
        self.item(value)
    }
    fn end(self) -> Result<(), Error> {
        Compound::end(self)
    }
}
