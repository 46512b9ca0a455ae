//! Five-axis toolpaths in workpiece coordinates: a streaming parser of three text formats
//! ([`Parser`], [`parse`]) and their writers ([`write()`]).
//!
//! # A point
//! Every format gives a sequence of [`Point`]s: the **tool tip** `(x, y, z)` in mm and the
//! **tool axis** `(i, j, k)`, a unit vector pointing from the tip towards the spindle, both in
//! workpiece coordinates (the frame the part is programmed in, the frame of
//! [`crate::rotary::RotaryType::tool_vector`]). A vector of any non-zero length is accepted
//! and normalised on reading. NC blocks also keep their commanded rotary angles.
//!
//! # CSV
//! One point a line, `x,y,z,i,j,k`. Fields are separated by semicolons, else by commas (then
//! spaces around them are ignored), else by spaces and tabs. In a line separated by semicolons
//! or holding a tab, a comma is a **decimal comma** (`1,5;2;3;0;0;1`, `1,5<tab>2<tab>…`), as
//! European measuring software writes it, the same rule as [`crate::csv`]. One trailing
//! separator is allowed (`1,2,3,0,0,1,`). Blank lines and lines starting with `#` are skipped;
//! the first other line is a header, and skipped, when none of its fields is a number.
//!
//! # APT CL data
//! Statements, one a line, case-insensitive:
//! * `GOTO/x,y,z,i,j,k`: a point with its tool axis (five-axis, as written under `MULTAX` or
//!   `MULTAX/ON`); the axis is remembered.
//! * `GOTO/x,y,z`: a point with the last tool axis: of the last six-number `GOTO` or
//!   `TLAXIS/i,j,k`, `(0, 0, 1)` before either.
//! * `TLAXIS/i,j,k`: sets the tool axis.
//! * `FINI`: the end of the program; the rest of the file is not read.
//! * Any other statement that starts with a word (`PARTNO …`, `MULTAX/ON`, `MULTAX/OFF`,
//!   `CUTTER/…`, `FEDRAT/…`, `RAPID`, `LOADTL/…`, `SPINDL/…`, `COOLNT/…`, …) is skipped.
//!   Which `GOTO`s are five-axis is read from their count of numbers, not from `MULTAX`.
//!
//! `$$` starts a comment. A line ending with `$` (after removing the comment and trailing
//! spaces; `$$` is a comment, not a continuation) continues on the next line: the text before
//! the `$` and the next line make one statement, whose point carries the line of its start.
//!
//! # NC blocks
//! ISO (G-code) blocks for a stated [`Machine`], written for the control with tool-centre-point
//! control on (`G43.4`, `TRAORI`, `M128`): `X Y Z` are the tool tip in workpiece coordinates
//! (mm) and the machine's two rotary letters ([`crate::machine::Model::letters`], K then M, e.g.
//! `C` and `A`) the **commanded** angles in degrees. The tool axis is the machine's forward
//! kinematics of the orientation, `V = R_K(θk)·R_M(θm)·e_H` with `θ = factor·command`
//! (`factor = −1` for an axis marked reversed, [`crate::chain::RotaryLayout`]). Forward
//! kinematics is defined everywhere: a singular orientation (tool along K) is no special case
//! here. The tip is taken as written: with tool-centre-point control the control, not the
//! program, accounts for the rotary axes' offsets and the tool length.
//! * A word is a letter and a number (`X12.5`, `x-3`, `G1`, also `X 12.5` and `X=12.5`);
//!   numbers have no exponent (`X1E5` is `X1` and an `E5` word). Words may be run together
//!   (`G1X10Y20`).
//! * Modal: a coordinate or angle missing from a block keeps its value (all start at 0).
//! * A block without an `X`, `Y`, `Z` or rotary word (`G90`, `N10 G1 F1000`, `T1 M6`, `M30`)
//!   gives no point. Lines starting with `%` (tape start, Siemens program names) are skipped,
//!   as are comments in parentheses `( … )` and after `;`, and a leading `/` (block delete).
//! * `G90`/`G91` (absolute/incremental) and `G20`/`G21` (inch/mm) are followed, modally
//!   (start `G90 G21`). A block with `G10`, `G28`, `G30` or `G53` (data setting, reference
//!   return, machine coordinates) gives no point and leaves the positions as they were; `G52`
//!   or `G92` with axis words (a shift of the workpiece frame) is an error. Other words
//!   (`N G F S T M H D O` …) are read and ignored, frame rotations (`G68`, `G68.2`) included:
//!   the coordinates are taken as workpiece coordinates. `G2`/`G3` arcs give their end points
//!   only.
//! * A run of two or more letters is a control keyword (`TRAORI`, `TRAFOOF`, `CYCLE800`,
//!   `FMAX`) and is skipped with the digits and `_` that follow it.
//! * A rotary word that is not one of the machine's letters (`B10` on a C/A machine) is an error.
//!
//! # Limits and errors
//! Numbers are `[+-]digits[.digits]` or `[+-].digits`, with an exponent `e±n` in CSV and APT
//! (`1`, `-1.5`, `.5`, `1.`, `+2`, `1e-3`); `1.2.3`, `1,5` in one field, `nan` and `inf` are
//! not numbers. Coordinates must lie within ±[`MAX_COORDINATE`] mm, NC angles within
//! ±[`MAX_ANGLE`]° (for `G91` and `G20` the position reached, in mm); a tool axis must be
//! finite and non-zero (a huge or tiny one is fine: only its direction counts). A bad line is an
//! [`Error`] on the field [`FIELD`] whose message starts `line L, column C:` (both 1-based, the
//! column counted in characters at the offending token) and says what was expected. A file
//! without points is an error, and so is an APT continuation `$` on the last line. After an
//! error the parser's state is undefined: drop it.
//!
//! # Streaming
//! [`Parser::feed`] takes the text in chunks split anywhere (inside a number, between the `\r`
//! and `\n` of a line end); only the incomplete last line (or APT statement) is carried over,
//! and a line may be at most [`MAX_LINE`] bytes. Lines end with `\n`, `\r\n` or `\r`; a UTF-8
//! byte-order mark at the start is skipped. A [`Point`] takes 80 bytes, so 10⁶ points (a
//! normal file) take 80 MB; a caller that needs less drains `out` after each chunk.

use crate::error::{Error, Result};
use crate::machine::Machine;
use crate::rotary::{Pose, RotaryType};
use nalgebra::Vector3;
use std::fmt::{self, Write as _};
use std::str::FromStr;

/// The field every toolpath error names.
pub const FIELD: &str = "toolpath";
/// Largest coordinate accepted, mm (absolute value).
pub const MAX_COORDINATE: f64 = 1e5;
/// Largest NC rotary angle accepted, degrees (absolute value).
pub const MAX_ANGLE: f64 = 3600.0;
/// Longest line (or continued APT statement) the parser carries over between chunks, bytes.
pub const MAX_LINE: usize = 1 << 20;

/// Decimals written for lengths in CSV and APT (1 nm).
const LENGTH_DECIMALS: usize = 6;
/// Decimals written for tool-axis components in CSV and APT.
const VECTOR_DECIMALS: usize = 9;
/// Decimals written for NC words, lengths (0.1 µm) and angles (0.0001°): what controls take.
const NC_DECIMALS: usize = 4;
/// APT lines longer than this are continued with `$` by the writer.
const APT_WIDTH: usize = 72;

/// APT major words that [`Format::detect`] recognises at the start of a line.
const APT_WORDS: [&str; 20] = [
    "GOTO", "TLAXIS", "MULTAX", "PARTNO", "CUTTER", "FEDRAT", "RAPID", "LOADTL", "SPINDL",
    "COOLNT", "FINI", "UNITS", "MACHIN", "PPRINT", "INTOL", "OUTTOL", "FROM", "GODLTA", "CIRCLE",
    "CLPRNT",
];

/// A toolpath text format (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// `x,y,z,i,j,k` lines.
    Csv,
    /// APT CL data: `GOTO/…`, `TLAXIS/…`.
    Apt,
    /// NC blocks of a stated machine with tool-centre-point control on.
    Nc,
}

impl Format {
    /// The three formats.
    pub const ALL: [Format; 3] = [Format::Csv, Format::Apt, Format::Nc];

    /// `"csv"`, `"apt"` or `"nc"`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Apt => "apt",
            Format::Nc => "nc",
        }
    }

    /// Guesses the format from the first text of a file (a few lines are enough), reading it
    /// line by line and deciding at the first telling one:
    /// * a `$$` comment, or an APT word (`GOTO`, `TLAXIS`, `MULTAX`, `PARTNO`, `FINI`, …)
    ///   followed by `/`, by nothing, or (`PARTNO`, `PPRINT`) by text: [`Format::Apt`];
    /// * a line starting with `%`, `(` or `;`, or with one letter and a number (`N10`, `G90`,
    ///   `X1.5`, `O1000`): [`Format::Nc`];
    /// * a line starting with a digit, sign or point: [`Format::Csv`].
    ///
    /// Blank lines, `#` comments, headers (`x,y,z,i,j,k`) and other words (`TRAORI`) decide
    /// nothing; without a telling line the answer is [`Format::Csv`].
    pub fn detect(first_text: &str) -> Format {
        for raw in first_text.split(['\n', '\r']) {
            let l = raw.trim_start_matches('\u{feff}').trim();
            if l.is_empty() || l.starts_with('#') {
                continue;
            }
            if l.starts_with("$$") {
                return Format::Apt;
            }
            if l.starts_with(['%', '(', ';']) {
                return Format::Nc;
            }
            let word_len = l
                .find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(l.len());
            let after = l[word_len..].trim_start();
            if word_len >= 2 {
                let word = l[..word_len].to_ascii_uppercase();
                if APT_WORDS.contains(&word.as_str())
                    && (after.is_empty()
                        || after.starts_with('/')
                        || word == "PARTNO"
                        || word == "PPRINT")
                {
                    return Format::Apt;
                }
                continue;
            }
            if word_len == 1 {
                let value = after.strip_prefix('=').unwrap_or(after).trim_start();
                if value.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.')) {
                    return Format::Nc;
                }
                continue;
            }
            if l.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.')) {
                return Format::Csv;
            }
        }
        Format::Csv
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = Error;

    /// `"csv"`, `"apt"` or `"nc"`, case-insensitive; an error on the field `"format"` else.
    fn from_str(s: &str) -> Result<Self> {
        Format::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| {
                Error::field(
                    "format",
                    format!("expected csv, apt or nc, got {}", shown(s)),
                )
            })
    }
}

/// One point of a toolpath, in workpiece coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Tool tip, mm.
    pub tip: Vector3<f64>,
    /// Tool axis, unit, from the tip towards the spindle.
    pub axis: Vector3<f64>,
    /// 1-based line of the file the point was read from (of the statement's first line for a
    /// continued APT statement); 0 for a point not read from a file.
    pub line: u32,
    /// NC only: the commanded K and M angles, degrees, as written (after `G91` increments).
    pub angles: Option<[f64; 2]>,
}

/// Parses a whole text: [`Parser::new`], one [`Parser::feed`], [`Parser::finish`].
pub fn parse(text: &str, format: Format, machine: Option<&Machine>) -> Result<Vec<Point>> {
    let mut parser = Parser::new(format, machine)?;
    let mut out = Vec::new();
    parser.feed(text, &mut out)?;
    parser.finish(&mut out)?;
    Ok(out)
}

/// A streaming toolpath parser (module docs): feed it the text in chunks, then finish.
#[derive(Debug, Clone)]
pub struct Parser {
    state: State,
    /// The incomplete last line of the text fed so far.
    carry: String,
    /// The last chunk ended with `\r`: a `\n` starting the next one belongs to that line end.
    after_cr: bool,
    /// Lines read so far.
    line: u32,
    /// Points produced so far.
    points: u64,
}

#[derive(Debug, Clone)]
enum State {
    Csv { started: bool },
    Apt(Apt),
    Nc(Box<Nc>),
}

impl Parser {
    /// A parser of `format`. [`Format::Nc`] needs the `machine` (its letters and kinematics; it
    /// is built, so an invalid machine is its own error); the other formats ignore it.
    pub fn new(format: Format, machine: Option<&Machine>) -> Result<Self> {
        let state = match format {
            Format::Csv => State::Csv { started: false },
            Format::Apt => State::Apt(Apt {
                axis: Vector3::z(),
                stmt: String::new(),
                segs: Vec::new(),
                dollar: (0, 0),
                fini: false,
            }),
            Format::Nc => {
                let machine = machine.ok_or_else(|| {
                    Error::field(
                        "machine",
                        "NC blocks need the machine: its rotary letters and kinematics give the \
                         tool axis",
                    )
                })?;
                let model = machine.build()?;
                State::Nc(Box::new(Nc {
                    rtype: model.layout.rtype,
                    factors: [model.layout.k_factor, model.layout.m_factor],
                    letters: model.letters(),
                    pos: [0.0; 5],
                    absolute: true,
                    inch: false,
                }))
            }
        };
        Ok(Self {
            state,
            carry: String::new(),
            after_cr: false,
            line: 0,
            points: 0,
        })
    }

    /// The format being read.
    pub fn format(&self) -> Format {
        match self.state {
            State::Csv { .. } => Format::Csv,
            State::Apt(_) => Format::Apt,
            State::Nc(_) => Format::Nc,
        }
    }

    /// Lines read so far (complete lines; the progress of a long file).
    pub fn lines(&self) -> u32 {
        self.line
    }

    /// Reads the next `chunk` of the text, appending the points of its complete lines to `out`.
    /// A chunk may end anywhere; its incomplete last line waits for the next chunk or
    /// [`Parser::finish`].
    pub fn feed(&mut self, chunk: &str, out: &mut Vec<Point>) -> Result<()> {
        let mut rest = chunk;
        if self.after_cr && !rest.is_empty() {
            self.after_cr = false;
            rest = rest.strip_prefix('\n').unwrap_or(rest);
        }
        while let Some(pos) = rest.find(['\n', '\r']) {
            let cr = rest.as_bytes()[pos] == b'\r';
            let (line, tail) = (&rest[..pos], &rest[pos + 1..]);
            if self.carry.is_empty() {
                self.line(line, out)?;
            } else {
                let mut carried = std::mem::take(&mut self.carry);
                carried.push_str(line);
                self.line(&carried, out)?;
                carried.clear();
                self.carry = carried;
            }
            rest = tail;
            if cr {
                if rest.is_empty() {
                    self.after_cr = true;
                } else {
                    rest = rest.strip_prefix('\n').unwrap_or(rest);
                }
            }
        }
        if self.carry.len() + rest.len() > MAX_LINE {
            return Err(too_long(self.line.saturating_add(1)));
        }
        self.carry.push_str(rest);
        Ok(())
    }

    /// Reads the last line (if the text does not end with a line end) and ends the file: an
    /// APT statement still waiting for its continuation, or a file without any point, is an
    /// error.
    pub fn finish(&mut self, out: &mut Vec<Point>) -> Result<()> {
        if !self.carry.is_empty() {
            let last = std::mem::take(&mut self.carry);
            self.line(&last, out)?;
        }
        if let State::Apt(apt) = &self.state {
            if !apt.segs.is_empty() && !apt.fini {
                let (l, c) = apt.dollar;
                return Err(Error::field(
                    FIELD,
                    format!(
                        "line {l}, column {c}: the statement continues with $ but the file \
                         ends; expected its next line"
                    ),
                ));
            }
        }
        if self.points == 0 {
            let what = match self.format() {
                Format::Csv => "lines x,y,z,i,j,k",
                Format::Apt => "GOTO/x,y,z,i,j,k statements",
                Format::Nc => "blocks with X, Y, Z or rotary words",
            };
            return Err(Error::field(
                FIELD,
                format!("the file has no points; expected {what}"),
            ));
        }
        Ok(())
    }

    /// One complete line, without its line end.
    fn line(&mut self, text: &str, out: &mut Vec<Point>) -> Result<()> {
        self.line = self.line.saturating_add(1);
        let line = self.line;
        if text.len() > MAX_LINE {
            return Err(too_long(line));
        }
        let text = if line == 1 {
            text.strip_prefix('\u{feff}').unwrap_or(text)
        } else {
            text
        };
        let before = out.len();
        match &mut self.state {
            State::Csv { started } => csv_line(text, line, started, out)?,
            State::Apt(apt) => apt.line(text, line, out)?,
            State::Nc(nc) => nc.line(text, line, out)?,
        }
        self.points += (out.len() - before) as u64;
        Ok(())
    }
}

/// The error of a line longer than [`MAX_LINE`], whether it came whole or in pieces.
fn too_long(line: u32) -> Error {
    Error::field(
        FIELD,
        format!(
            "line {line}, column 1: expected a line of at most {MAX_LINE} bytes, got a longer one"
        ),
    )
}

// ---------------------------------------------------------------------------------------------
// Positions and numbers

/// A piece of a statement's text that starts at column 1 of line `line`.
#[derive(Debug, Clone, Copy)]
struct Seg {
    /// Byte offset of the piece in the statement.
    start: usize,
    line: u32,
}

/// A statement's text and where its pieces come from, to report errors at a line and column.
struct Loc<'a> {
    text: &'a str,
    segs: &'a [Seg],
}

impl Loc<'_> {
    /// Line and 1-based column (in characters) of byte `off` of the text.
    fn at(&self, off: usize) -> (u32, usize) {
        let seg = self
            .segs
            .iter()
            .rev()
            .find(|s| s.start <= off)
            .copied()
            .unwrap_or(Seg { start: 0, line: 0 });
        let col = self
            .text
            .get(seg.start..off)
            .map_or(0, |s| s.chars().count());
        (seg.line, col + 1)
    }

    /// The line of byte `off`.
    fn line(&self, off: usize) -> u32 {
        self.at(off).0
    }

    /// An error at byte `off`.
    fn err(&self, off: usize, msg: impl fmt::Display) -> Error {
        let (l, c) = self.at(off);
        Error::field(FIELD, format!("line {l}, column {c}: {msg}"))
    }
}

/// A token as shown in a message: quoted, at most 40 characters ([`crate::error::quote`]).
fn shown(tok: &str) -> String {
    crate::error::quote(tok)
}

/// Reads a number of the module's grammar (`exponent`: an `e±n` may follow); `None` if `tok`
/// is not one. The value may be infinite when the exponent overflows.
fn number(tok: &str, exponent: bool) -> Option<f64> {
    let b = tok.as_bytes();
    let digits = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let int_end = digits(i);
    let mut count = int_end - i;
    i = int_end;
    if b.get(i) == Some(&b'.') {
        let frac_end = digits(i + 1);
        count += frac_end - i - 1;
        i = frac_end;
    }
    if count == 0 {
        return None;
    }
    if exponent && matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let end = digits(i);
        if end == i {
            return None;
        }
        i = end;
    }
    if i != b.len() {
        return None;
    }
    tok.parse().ok()
}

/// Names of the six numbers of a point.
const NAMES: [&str; 6] = ["x", "y", "z", "i", "j", "k"];

/// Six numbers of a point read from a statement: values, byte offsets, tokens.
struct Fields<'a> {
    vals: [f64; 6],
    offs: [usize; 6],
    toks: [&'a str; 6],
}

/// A coordinate `v` (token `tok` at `off`, named `name`) checked against [`MAX_COORDINATE`].
fn coordinate(loc: &Loc, off: usize, name: &str, tok: &str, v: f64) -> Result<f64> {
    if v.abs() <= MAX_COORDINATE {
        Ok(v)
    } else {
        Err(loc.err(
            off,
            format!(
                "expected {name} within ±{MAX_COORDINATE} mm, got {}",
                shown(tok)
            ),
        ))
    }
}

/// The tip from fields 0..3.
fn tip(loc: &Loc, f: &Fields) -> Result<Vector3<f64>> {
    let mut p = Vector3::zeros();
    for n in 0..3 {
        p[n] = coordinate(loc, f.offs[n], NAMES[n], f.toks[n], f.vals[n])?;
    }
    Ok(p)
}

/// The unit tool axis from fields 3..6 (i, j, k).
fn unit_axis(loc: &Loc, f: &Fields) -> Result<Vector3<f64>> {
    let from = 3;
    let mut v = Vector3::zeros();
    for n in 0..3 {
        let x = f.vals[from + n];
        if !x.is_finite() {
            return Err(loc.err(
                f.offs[from + n],
                format!(
                    "expected a finite number for {}, got {}",
                    NAMES[3 + n],
                    shown(f.toks[from + n])
                ),
            ));
        }
        v[n] = x;
    }
    // Scaled first so that neither tiny nor huge components under- or overflow.
    let scale = v.amax();
    if scale == 0.0 {
        return Err(loc.err(
            f.offs[from],
            format!(
                "expected a non-zero tool axis (i, j, k), got ({}, {}, {})",
                f.toks[from],
                f.toks[from + 1],
                f.toks[from + 2]
            ),
        ));
    }
    let v = v / scale;
    Ok(v / v.norm())
}

// ---------------------------------------------------------------------------------------------
// CSV

/// How a CSV line is separated (module docs).
#[derive(Clone, Copy, PartialEq)]
enum CsvSep {
    /// `;`; a comma is a decimal comma.
    Semicolon,
    /// `,` (and `;` is absent).
    Comma,
    /// Spaces and tabs; with a tab in the line a comma is a decimal comma.
    Blank { decimal_comma: bool },
}

impl CsvSep {
    fn of(line: &str) -> CsvSep {
        if line.contains(';') {
            CsvSep::Semicolon
        } else if line.contains('\t') {
            CsvSep::Blank {
                decimal_comma: true,
            }
        } else if line.contains(',') {
            CsvSep::Comma
        } else {
            CsvSep::Blank {
                decimal_comma: false,
            }
        }
    }

    fn splits(self, c: char) -> bool {
        match self {
            CsvSep::Semicolon => c == ';',
            CsvSep::Comma => c == ',',
            CsvSep::Blank { .. } => c.is_whitespace(),
        }
    }

    /// The number in a field: with a decimal comma `1,5` is 1.5.
    fn number(self, tok: &str) -> Option<f64> {
        let decimal_comma = matches!(
            self,
            CsvSep::Semicolon
                | CsvSep::Blank {
                    decimal_comma: true
                }
        );
        if decimal_comma && tok.contains(',') {
            // One comma at most: `1,5` is a number, `1,5,2` is not.
            if tok.matches(',').count() > 1 || tok.contains('.') {
                return None;
            }
            number(&tok.replace(',', "."), true)
        } else {
            number(tok, true)
        }
    }
}

/// The fields of a CSV line: byte offset and trimmed text of each (module docs).
fn csv_fields(line: &str) -> impl Iterator<Item = (usize, &str)> + '_ {
    let sep = CsvSep::of(line);
    let delimited = !matches!(sep, CsvSep::Blank { .. });
    let mut body = line.trim_end();
    if delimited {
        body = body.strip_suffix(|c: char| sep.splits(c)).unwrap_or(body);
    }
    let base = body.as_ptr() as usize;
    body.split(move |c: char| sep.splits(c))
        .filter(move |p| delimited || !p.is_empty())
        .map(move |p| {
            let t = p.trim();
            let off = if t.is_empty() {
                p.as_ptr() as usize - base
            } else {
                t.as_ptr() as usize - base
            };
            (off, t)
        })
}

fn csv_line(line: &str, no: u32, started: &mut bool, out: &mut Vec<Point>) -> Result<()> {
    let t = line.trim();
    if t.is_empty() || t.starts_with('#') {
        return Ok(());
    }
    let sep = CsvSep::of(line);
    if !*started {
        *started = true;
        if !csv_fields(line).any(|(_, tok)| sep.number(tok).is_some()) {
            return Ok(()); // the header
        }
    }
    let segs = [Seg { start: 0, line: no }];
    let loc = Loc {
        text: line,
        segs: &segs,
    };
    let mut f = Fields {
        vals: [0.0; 6],
        offs: [0; 6],
        toks: [""; 6],
    };
    let mut n = 0;
    for (off, tok) in csv_fields(line) {
        if n == 6 {
            let count = csv_fields(line).count();
            return Err(loc.err(off, format!("expected 6 numbers x,y,z,i,j,k, got {count}")));
        }
        f.vals[n] = sep.number(tok).ok_or_else(|| {
            loc.err(
                off,
                format!("expected a number for {}, got {}", NAMES[n], shown(tok)),
            )
        })?;
        f.offs[n] = off;
        f.toks[n] = tok;
        n += 1;
    }
    if n < 6 {
        let mut end = line.trim_end();
        end = end.strip_suffix(|c: char| sep.splits(c)).unwrap_or(end);
        return Err(loc.err(
            end.len(),
            format!("expected 6 numbers x,y,z,i,j,k, got {n}"),
        ));
    }
    out.push(Point {
        tip: tip(&loc, &f)?,
        axis: unit_axis(&loc, &f)?,
        line: no,
        angles: None,
    });
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// APT

#[derive(Debug, Clone)]
struct Apt {
    /// The current tool axis (unit).
    axis: Vector3<f64>,
    /// A statement continued with `$`, so far (without the `$`s).
    stmt: String,
    /// Where the pieces of `stmt` come from; empty when no statement is pending.
    segs: Vec<Seg>,
    /// Line and column of the last continuation `$`.
    dollar: (u32, usize),
    /// `FINI` was read.
    fini: bool,
}

impl Apt {
    fn line(&mut self, line: &str, no: u32, out: &mut Vec<Point>) -> Result<()> {
        if self.fini {
            return Ok(());
        }
        let code = line.find("$$").map_or(line, |p| &line[..p]);
        let body = code.trim_end();
        if let Some(piece) = body.strip_suffix('$') {
            if self.stmt.len() + piece.len() > MAX_LINE {
                return Err(Error::field(
                    FIELD,
                    format!(
                        "line {no}, column 1: the continued statement is longer than \
                         {MAX_LINE} bytes"
                    ),
                ));
            }
            self.segs.push(Seg {
                start: self.stmt.len(),
                line: no,
            });
            self.stmt.push_str(piece);
            self.dollar = (no, piece.chars().count() + 1);
            return Ok(());
        }
        if self.segs.is_empty() {
            return self.statement(code, &[Seg { start: 0, line: no }], out);
        }
        self.segs.push(Seg {
            start: self.stmt.len(),
            line: no,
        });
        self.stmt.push_str(code);
        let (mut stmt, mut segs) = (
            std::mem::take(&mut self.stmt),
            std::mem::take(&mut self.segs),
        );
        let result = self.statement(&stmt, &segs, out);
        stmt.clear();
        segs.clear();
        (self.stmt, self.segs) = (stmt, segs);
        result
    }

    /// One whole statement (comments and continuations removed).
    fn statement(&mut self, text: &str, segs: &[Seg], out: &mut Vec<Point>) -> Result<()> {
        let loc = Loc { text, segs };
        let Some(start) = text.find(|c: char| !c.is_whitespace()) else {
            return Ok(());
        };
        let rest = &text[start..];
        let word_len = rest
            .find(|c: char| !c.is_ascii_alphanumeric())
            .unwrap_or(rest.len());
        let word = &rest[..word_len];
        if !word.starts_with(|c: char| c.is_ascii_alphabetic()) {
            let tok = rest
                .split(|c: char| c.is_whitespace() || c == ',' || c == '/')
                .next()
                .unwrap_or("");
            return Err(loc.err(
                start,
                format!(
                    "expected an APT statement such as GOTO/x,y,z,i,j,k, got {}",
                    shown(tok)
                ),
            ));
        }
        if word.eq_ignore_ascii_case("FINI") {
            self.fini = true;
            return Ok(());
        }
        let goto = word.eq_ignore_ascii_case("GOTO");
        if !goto && !word.eq_ignore_ascii_case("TLAXIS") {
            return Ok(()); // any other statement is skipped
        }
        let name = if goto { "GOTO" } else { "TLAXIS" };
        let after = &rest[word_len..];
        let slash = start + word_len + (after.len() - after.trim_start().len());
        if !text[slash..].starts_with('/') {
            let got = text[slash..].split_whitespace().next().unwrap_or("");
            return Err(loc.err(
                slash,
                format!("expected / after {name}, got {}", shown(got)),
            ));
        }
        let max = if goto { 6 } else { 3 };
        let mut f = Fields {
            vals: [0.0; 6],
            offs: [0; 6],
            toks: [""; 6],
        };
        // Offsets of the first 7 fields, to point at the first one that does not fit.
        let mut all_offs = [0usize; 7];
        let mut n = 0;
        let mut piece_start = slash + 1;
        for piece in text[slash + 1..].split(',') {
            let lead = piece.len() - piece.trim_start().len();
            let (off, tok) = (piece_start + lead, piece.trim());
            piece_start += piece.len() + 1;
            if n < max {
                f.vals[n] = number(tok, true).ok_or_else(|| {
                    loc.err(
                        off,
                        format!("expected a number after {name}/, got {}", shown(tok)),
                    )
                })?;
                f.offs[n] = off;
                f.toks[n] = tok;
            }
            if n < all_offs.len() {
                all_offs[n] = off;
            }
            n += 1;
        }
        let line = loc.line(start);
        if goto && (n == 3 || n == 6) {
            let tip = tip(&loc, &f)?;
            if n == 6 {
                self.axis = unit_axis(&loc, &f)?;
            }
            out.push(Point {
                tip,
                axis: self.axis,
                line,
                angles: None,
            });
            return Ok(());
        }
        if !goto && n == 3 {
            // Named i, j, k: shift the fields into place.
            let g = Fields {
                vals: [0.0, 0.0, 0.0, f.vals[0], f.vals[1], f.vals[2]],
                offs: [0, 0, 0, f.offs[0], f.offs[1], f.offs[2]],
                toks: ["", "", "", f.toks[0], f.toks[1], f.toks[2]],
            };
            self.axis = unit_axis(&loc, &g)?;
            return Ok(());
        }
        let off = if n < 3 {
            text.trim_end().len() // where the next number should be
        } else if goto && n < 6 {
            all_offs[3] // 4 or 5 numbers: the 4th is the first that does not fit
        } else {
            all_offs[max]
        };
        let expected = if goto {
            "3 numbers (x, y, z) or 6 (x, y, z, i, j, k)"
        } else {
            "3 numbers (i, j, k)"
        };
        Err(loc.err(off, format!("expected {expected} after {name}/, got {n}")))
    }
}

// ---------------------------------------------------------------------------------------------
// NC

#[derive(Debug, Clone)]
struct Nc {
    rtype: RotaryType,
    /// θ = factor·command for K and M.
    factors: [f64; 2],
    /// K's and M's letters.
    letters: [char; 2],
    /// Modal X, Y, Z (mm), K, M (degrees).
    pos: [f64; 5],
    /// G90 (true) or G91.
    absolute: bool,
    /// G20 (true) or G21.
    inch: bool,
}

/// An axis word of a block: its value as written, the byte offset and text of its number.
#[derive(Clone, Copy)]
struct Word<'a> {
    value: f64,
    at: usize,
    tok: &'a str,
}

impl Nc {
    fn line(&mut self, line: &str, no: u32, out: &mut Vec<Point>) -> Result<()> {
        if line.trim_start().starts_with('%') {
            return Ok(());
        }
        let segs = [Seg { start: 0, line: no }];
        let loc = Loc {
            text: line,
            segs: &segs,
        };
        let [kl, ml] = self.letters;
        let b = line.as_bytes();
        let mut words: [Option<Word>; 5] = [None; 5];
        let (mut absolute, mut inch) = (self.absolute, self.inch);
        let mut no_motion = false;
        let mut shift = None;
        let mut any_word = false;
        let mut i = 0;
        while i < b.len() {
            let c = b[i];
            match c {
                b' ' | b'\t' => i += 1,
                b'(' => match line[i..].find(')') {
                    Some(p) => i += p + 1,
                    None => break,
                },
                b';' => break,
                b'/' if !any_word => i += 1,
                c if c.is_ascii_alphabetic() => {
                    let run = b[i..]
                        .iter()
                        .take_while(|c| c.is_ascii_alphabetic())
                        .count();
                    if run >= 2 {
                        // A control keyword (TRAORI, CYCLE800): skipped.
                        i += run;
                        while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                            i += 1;
                        }
                        continue;
                    }
                    any_word = true;
                    let letter = c.to_ascii_uppercase() as char;
                    let at = i;
                    i += 1;
                    while i < b.len() && matches!(b[i], b' ' | b'\t') {
                        i += 1;
                    }
                    if b.get(i) == Some(&b'=') {
                        i += 1;
                        while i < b.len() && matches!(b[i], b' ' | b'\t') {
                            i += 1;
                        }
                    }
                    let from = i;
                    while i < b.len() && matches!(b[i], b'0'..=b'9' | b'.' | b',' | b'+' | b'-') {
                        i += 1;
                    }
                    let tok = &line[from..i];
                    if tok.is_empty() {
                        let next = line[from..].split_whitespace().next();
                        let got = next.map_or("the end of the line".to_string(), shown);
                        return Err(
                            loc.err(at, format!("expected a number after {letter}, got {got}"))
                        );
                    }
                    let value = number(tok, false).ok_or_else(|| {
                        loc.err(
                            from,
                            format!("expected a number after {letter}, got {}", shown(tok)),
                        )
                    })?;
                    let word = Some(Word {
                        value,
                        at: from,
                        tok,
                    });
                    match letter {
                        'X' => words[0] = word,
                        'Y' => words[1] = word,
                        'Z' => words[2] = word,
                        l if l == kl => words[3] = word,
                        l if l == ml => words[4] = word,
                        'A' | 'B' | 'C' => {
                            return Err(loc.err(
                                at,
                                format!(
                                    "expected a rotary axis of this machine ({kl} or {ml}), \
                                     got {letter}"
                                ),
                            ))
                        }
                        'G' => match (value * 10.0).round() as i64 {
                            900 => absolute = true,
                            910 => absolute = false,
                            200 => inch = true,
                            210 => inch = false,
                            100 | 280 | 300 | 530 => no_motion = true,
                            520 | 920 => shift = Some((at, value)),
                            _ => {}
                        },
                        _ => {}
                    }
                }
                _ => {
                    let got: String = line[i..].chars().take(1).collect();
                    return Err(loc.err(
                        i,
                        format!(
                            "expected a word (a letter and a number, like X12.5), got {}",
                            shown(&got)
                        ),
                    ));
                }
            }
        }
        self.absolute = absolute;
        self.inch = inch;
        if words.iter().all(Option::is_none) {
            return Ok(());
        }
        if let Some((at, g)) = shift {
            return Err(loc.err(
                at,
                format!("expected no shift of the workpiece frame, got G{g} with axis words"),
            ));
        }
        if no_motion {
            return Ok(());
        }
        let names = ['X', 'Y', 'Z', kl, ml];
        for (n, w) in words.iter().enumerate() {
            let Some(w) = w else { continue };
            let (value, limit, unit) = if n < 3 {
                let scale = if inch { 25.4 } else { 1.0 };
                (w.value * scale, MAX_COORDINATE, " mm")
            } else {
                (w.value, MAX_ANGLE, "°")
            };
            let new = if absolute { value } else { self.pos[n] + value };
            if new.abs() > limit {
                let got = if absolute && !inch {
                    shown(w.tok)
                } else {
                    format!("{new}{unit}")
                };
                return Err(loc.err(
                    w.at,
                    format!("expected {} within ±{limit}{unit}, got {got}", names[n]),
                ));
            }
            self.pos[n] = new;
        }
        let [x, y, z, k, m] = self.pos;
        let pose = Pose::new(
            self.factors[0] * k.to_radians(),
            self.factors[1] * m.to_radians(),
        );
        out.push(Point {
            tip: Vector3::new(x, y, z),
            axis: self.rtype.tool_vector(pose),
            line: no,
            angles: Some([k, m]),
        });
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Writers

/// Appends `x` with `decimals` decimals, trailing zeros dropped (keeping one after the point
/// when `keep_point`), and no sign on a zero.
fn push_num(out: &mut String, x: f64, decimals: usize, keep_point: bool) {
    let start = out.len();
    let _ = write!(out, "{x:.decimals$}");
    if out[start..].contains('.') {
        let kept = out[start..].trim_end_matches('0').len();
        out.truncate(start + kept);
        if out.ends_with('.') {
            if keep_point {
                out.push('0');
            } else {
                out.pop();
            }
        }
    } else if keep_point {
        out.push_str(".0");
    }
    if out[start..].starts_with('-') && out[start + 1..].bytes().all(|c| c == b'0' || c == b'.') {
        out.remove(start);
    }
}

/// Writes `points` in `format`, so that [`parse`] reads them back equal within the written
/// precision: lengths with 6 decimals (1 nm) and axis components with 9 in CSV and APT; NC
/// words with 4 decimals (0.1 µm, 0.0001°; what controls accept), always with a decimal point
/// (`X10.0`: some controls read `X10` in their least increment). A point with a coordinate,
/// axis component or angle that is not finite is an error.
/// * CSV: a `#` comment, the header `x,y,z,i,j,k`, one line a point.
/// * APT: two `$$` comment lines, `PARTNO TOOLPATH`, `MULTAX/ON`, a `GOTO/x,y,z,i,j,k` a point
///   (continued with `$` after z when longer than 72 characters), `FINI`.
/// * NC: `%`, comments, `G90 G21`, then `X Y Z` and the two rotary words `letters` (K then M)
///   from each point's `angles`, `M30`, `%`. It needs the letters and every point's angles (the
///   axis is not written: the machine gives it), else an error. Switching tool-centre-point
///   control on is left to the user (a comment says so).
pub fn write(format: Format, points: &[Point], letters: Option<[char; 2]>) -> Result<String> {
    for (n, p) in points.iter().enumerate() {
        let angles = p.angles.unwrap_or_default();
        if !p
            .tip
            .iter()
            .chain(p.axis.iter())
            .chain(&angles)
            .all(|v| v.is_finite())
        {
            return Err(Error::field(
                FIELD,
                format!(
                    "point {} (line {}) is not finite: tip {:?}, axis {:?}, angles {:?}",
                    n + 1,
                    p.line,
                    p.tip.as_slice(),
                    p.axis.as_slice(),
                    p.angles
                ),
            ));
        }
    }
    let mut s = String::with_capacity(64 * points.len() + 256);
    match format {
        Format::Csv => {
            s.push_str(
                "# five-axis toolpath, workpiece coordinates: tool tip x, y, z (mm), tool axis \
                 i, j, k (unit, from the tip towards the spindle)\nx,y,z,i,j,k\n",
            );
            for p in points {
                for (n, v) in p.tip.iter().chain(p.axis.iter()).enumerate() {
                    if n > 0 {
                        s.push(',');
                    }
                    let d = if n < 3 {
                        LENGTH_DECIMALS
                    } else {
                        VECTOR_DECIMALS
                    };
                    push_num(&mut s, *v, d, false);
                }
                s.push('\n');
            }
        }
        Format::Apt => {
            s.push_str(
                "$$ five-axis toolpath, workpiece coordinates: GOTO/x,y,z,i,j,k,\n$$ tool tip \
                 in mm, tool axis from the tip towards the spindle\nPARTNO TOOLPATH\nMULTAX/ON\n",
            );
            let mut xyz = String::new();
            let mut ijk = String::new();
            for p in points {
                xyz.clear();
                ijk.clear();
                for (n, v) in p.tip.iter().enumerate() {
                    if n > 0 {
                        xyz.push(',');
                    }
                    push_num(&mut xyz, *v, LENGTH_DECIMALS, false);
                }
                for (n, v) in p.axis.iter().enumerate() {
                    if n > 0 {
                        ijk.push(',');
                    }
                    push_num(&mut ijk, *v, VECTOR_DECIMALS, false);
                }
                s.push_str("GOTO/");
                s.push_str(&xyz);
                if 5 + xyz.len() + 1 + ijk.len() > APT_WIDTH {
                    s.push_str(",$\n");
                } else {
                    s.push(',');
                }
                s.push_str(&ijk);
                s.push('\n');
            }
            s.push_str("FINI\n");
        }
        Format::Nc => {
            let [kl, ml] = letters.ok_or_else(|| {
                Error::field(
                    FIELD,
                    "NC blocks need the machine's rotary letters (K and M)",
                )
            })?;
            let _ = write!(
                s,
                "%\n(five-axis toolpath: X Y Z tool tip in workpiece coordinates, mm; {kl} {ml} \
                 commanded angles, degrees)\n(tool centre point control must be on: G43.4, \
                 TRAORI or M128)\nG90 G21\n"
            );
            for (n, p) in points.iter().enumerate() {
                let [k, m] = p.angles.ok_or_else(|| {
                    Error::field(
                        FIELD,
                        format!(
                            "point {} (line {}) has no rotary angles; NC blocks need each \
                             point's {kl} and {ml} commands",
                            n + 1,
                            p.line
                        ),
                    )
                })?;
                for (letter, v) in [
                    ('X', p.tip.x),
                    ('Y', p.tip.y),
                    ('Z', p.tip.z),
                    (kl, k),
                    (ml, m),
                ] {
                    if letter != 'X' {
                        s.push(' ');
                    }
                    s.push(letter);
                    push_num(&mut s, v, NC_DECIMALS, true);
                }
                s.push('\n');
            }
            s.push_str("M30\n%\n");
        }
    }
    Ok(s)
}
