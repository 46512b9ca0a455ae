//! Reading the customer's toolpath file: CSV, APT CL data and the NC dialects machines run (ISO
//! G-code for Fanuc and Haas controls, Siemens Sinumerik 840D, Heidenhain conversational), read
//! the way the machine would read them: each point knows how it was reached ([`Motion`]), arcs
//! are cut into chords within a tolerance, and every frame and unit the file states is applied
//! or refused with its line, never skipped. What does not change the geometry (feeds, spindle,
//! coolant, tool calls, cycle parameters) is skipped and counted in the [`Report`].
//!
//! # A point
//! Every format gives a sequence of [`Point`]s: the **tool tip** `(x, y, z)` in mm and the
//! **tool axis** `(i, j, k)`, a unit vector from the tip towards the spindle, both in
//! **workpiece coordinates** (the frame in which the machine's kinematics
//! ([`crate::rotary::RotaryType::tool_vector`]) give the tool axis), the line of the file, the
//! [`Motion`] that reached it (the segment from the previous point moves that way) and, for NC
//! blocks, the commanded rotary angles.
//!
//! # The readers
//! * CSV ([`csv`]): `x,y,z,i,j,k` lines, every point a feed move.
//! * APT CL data ([`apt`]): `GOTO/`, `RAPID`, `CIRCLE/`, `MSYS/`, `CSYS/`, `UNITS/` … from NX,
//!   CATIA, SolidWorks CAM, Mastercam and other CAM systems.
//! * NC blocks ([`nc`]) in three dialects, each from its manual: ISO ([`iso`]: Fanuc, Haas,
//!   LinuxCNC's plain G-code), Siemens ([`siemens`]) and Heidenhain ([`heidenhain`]). NC
//!   blocks are read for a stated machine: its two rotary letters and their commands give the
//!   tool axis.
//!
//! Each reader's module says what it reads, applies, skips and refuses.
//!
//! # Units
//! A unit the file states (`UNITS/INCHES`, `G20`, `G70`, `BEGIN PGM … INCH`) is applied from
//! where it is stated. Where the file states none, the unit of [`ReadOptions::unit`] is used:
//! [`UnitChoice::Auto`] takes a unit the file implies (an APT feed in inches per minute,
//! `FEDRAT/IPM`), else millimetres; [`UnitChoice::Mm`] and [`UnitChoice::Inch`] are the user's
//! pick. The [`Report`] says which unit was used and why. Points read before a later hint
//! changes the choice are scaled in [`Parser::finish`], so a caller that drains its output
//! between chunks must pick the unit.
//!
//! # Limits and errors
//! Coordinates must lie within ±[`MAX_COORDINATE`] mm and NC angles within ±[`MAX_ANGLE`]° (the
//! position reached); a tool axis must be finite and non-zero. A bad line is an [`Error`] on the
//! field [`FIELD`] whose message starts `line L, column C:` (both 1-based, the column counted in
//! characters) and says in a plain sentence what was expected or why the file cannot be read
//! right. A file without points is an error. After an error the parser's state is undefined:
//! drop it.
//!
//! # Streaming
//! [`Parser::feed`] takes the text in chunks split anywhere (inside a number, between the `\r`
//! and `\n` of a line end); only the incomplete last line is carried over, and a line may be at
//! most [`MAX_LINE`] bytes. Lines end with `\n`, `\r\n` or `\r`; a UTF-8 byte-order mark at the
//! start is skipped. A [`Point`] takes 88 bytes, so 10⁶ points take 88 MB.

pub mod apt;
mod bytes;
pub mod csv;
pub mod frame;
pub mod heidenhain;
pub mod iso;
mod lex;
pub mod nc;
pub mod siemens;

pub use frame::Frame;
pub use lex::{MAX_ANGLE, MAX_COORDINATE};

use crate::error::{Error, Result};
use crate::machine::Machine;
use nalgebra::Vector3;
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

/// The field every toolpath error names.
pub const FIELD: &str = "toolpath";
/// Longest line (or continued APT statement) the parser carries over between chunks, bytes.
pub const MAX_LINE: usize = 1 << 20;
/// The rounding allowed between an arc's start and end radii, mm (at least; 10⁻⁴ of the radius
/// on large arcs): what controls accept from numbers written to a few decimals.
pub const ARC_ROUNDING_MM: f64 = 0.01;
/// Most points a file may give (arcs and repeats included), about 400 MB: a guard against a
/// program that repeats without end.
pub const MAX_POINTS: u64 = 5_000_000;
/// One inch, mm.
pub const INCH: f64 = 25.4;
/// Lines [`Format::detect`] reads at most: a file with no telling line among them is CSV.
pub const DETECT_LINES: usize = 2000;

/// A toolpath text format: the reader that reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub enum Format {
    /// `x,y,z,i,j,k` lines.
    Csv,
    /// APT CL data.
    Apt,
    /// ISO G-code (Fanuc, Haas, LinuxCNC) of a stated machine.
    Nc,
    /// Siemens Sinumerik 840D blocks of a stated machine.
    Siemens,
    /// Heidenhain conversational blocks of a stated machine.
    Heidenhain,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 5] = [
        Format::Csv,
        Format::Apt,
        Format::Nc,
        Format::Siemens,
        Format::Heidenhain,
    ];

    /// `"csv"`, `"apt"`, `"nc"`, `"siemens"` or `"heidenhain"`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Apt => "apt",
            Format::Nc => "nc",
            Format::Siemens => "siemens",
            Format::Heidenhain => "heidenhain",
        }
    }

    /// The format in words, as the page shows it.
    pub fn label(self) -> &'static str {
        match self {
            Format::Csv => "CSV (x, y, z, i, j, k)",
            Format::Apt => "APT CL data",
            Format::Nc => "ISO G-code (Fanuc, Haas)",
            Format::Siemens => "Siemens Sinumerik 840D",
            Format::Heidenhain => "Heidenhain conversational",
        }
    }

    /// NC blocks of a machine (the three dialects).
    pub fn is_nc(self) -> bool {
        matches!(self, Format::Nc | Format::Siemens | Format::Heidenhain)
    }

    /// Recognises the format from the first text of a file (the first chunk; its first
    /// [`DETECT_LINES`] lines decide). Lines are read in order:
    /// * the first telling line decides between APT, NC and CSV: a `$$` comment or an APT
    ///   statement (a word of two or more letters, spaces allowed, followed by `/`: `GOTO/`,
    ///   `TOOL PATH/`; or `RAPID`, `FINI`, `MULTAX` alone, `PARTNO`, `PPRINT` or `REMARK` and
    ///   any text) is APT; a line starting with `%`, `(`, `;`, a block number or a letter and a
    ///   number (`N10`, `G90`, `O1000`) is NC; a line starting with a digit, sign or point is
    ///   CSV, unless it is a Heidenhain block (`0 BEGIN PGM`, `12 L X+10 FMAX`);
    /// * NC text is then Heidenhain when any line is a Heidenhain statement (`BEGIN PGM`,
    ///   `TOOL CALL`, `CYCL DEF`, an `L`, `C`, `CC` or `CR` block, `FMAX`), Siemens when any line
    ///   holds a keyword only Sinumerik uses (`TRAORI`, `TRAFOOF`, `DEF REAL`, `R1=`, `MSG(`,
    ///   `CYCLE800(`, `AROT`, `G500`, `%_N_`, `X=` assignments …), else ISO.
    ///
    /// Blank lines, `#` comments and CSV headers decide nothing; without a telling line the
    /// answer is [`Format::Csv`]. A line ends at `\n` or `\r`, and a `\r` followed by `\n` is
    /// one end, as the readers count lines.
    pub fn detect(first_text: &str) -> Format {
        let mut nc = false;
        let lines = first_text
            .split('\n')
            .flat_map(|l| l.strip_suffix('\r').unwrap_or(l).split('\r'));
        for (n, raw) in lines.enumerate() {
            let l = raw.trim_start_matches('\u{feff}').trim();
            if n >= DETECT_LINES {
                break;
            }
            if l.is_empty() || (l.starts_with('#') && !nc) {
                continue;
            }
            if heidenhain::is_statement(l) {
                return Format::Heidenhain;
            }
            if nc {
                if siemens::is_statement(l) {
                    return Format::Siemens;
                }
                continue;
            }
            if apt::is_statement(l) {
                return Format::Apt;
            }
            if l.starts_with(['%', '(', ';']) {
                if l.starts_with("%_N_") {
                    return Format::Siemens;
                }
                nc = true;
                continue;
            }
            let letters = l
                .find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(l.len());
            let after = l[letters..].trim_start();
            let after = after.strip_prefix('=').unwrap_or(after).trim_start();
            let numeric = |s: &str| {
                s.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.'))
            };
            if letters == 1 && numeric(after) {
                nc = true;
                if siemens::is_statement(l) {
                    return Format::Siemens;
                }
                continue;
            }
            if letters >= 2 {
                if siemens::is_statement(l) {
                    return Format::Siemens;
                }
                continue; // a header (x,y,z,i,j,k) or a keyword
            }
            if numeric(l) {
                return Format::Csv;
            }
        }
        if nc {
            Format::Nc
        } else {
            Format::Csv
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = Error;

    /// A format's name ([`Format::name`]), case-insensitive; an error on the field `"format"`.
    fn from_str(s: &str) -> Result<Self> {
        Format::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| {
                Error::field(
                    "format",
                    format!(
                        "expected csv, apt, nc, siemens or heidenhain, got {}",
                        lex::shown(s)
                    ),
                )
            })
    }
}

/// How a point was reached: the motion of the segment from the previous point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub enum Motion {
    /// Rapid traverse (`G0`, APT `RAPID`, Heidenhain `FMAX`): positioning, no cutting.
    Rapid,
    /// A straight feed move (`G1`, `GOTO`, `L … F`).
    Feed,
    /// A chord of an arc (`G2`/`G3`, APT `CIRCLE`, Heidenhain `C`/`CR`): cutting.
    Arc,
}

impl Motion {
    /// The code of the API: 0 rapid, 1 feed, 2 arc.
    pub fn code(self) -> u8 {
        match self {
            Motion::Rapid => 0,
            Motion::Feed => 1,
            Motion::Arc => 2,
        }
    }

    /// The motion of an API code (see [`Motion::code`]).
    pub fn from_code(c: f64) -> Option<Motion> {
        [Motion::Rapid, Motion::Feed, Motion::Arc]
            .into_iter()
            .find(|m| f64::from(m.code()) == c)
    }

    /// Rapids do not cut.
    pub fn cuts(self) -> bool {
        self != Motion::Rapid
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
    /// How the point was reached from the previous one.
    pub motion: Motion,
    /// NC only: the commanded K and M angles, degrees, as the program gives them (after `G91`
    /// increments); `None` where the tool axis does not come from them (a tilted working plane).
    pub angles: Option<[f64; 2]>,
}

crate::choices! {
    /// The length unit a file without a statement of its own is read in.
    pub enum UnitChoice {
        /// What the file implies, else mm.
        Auto = "auto" {
            label: "As the file says (else mm)",
            help: "A unit the file states (G20/G21, UNITS/, BEGIN PGM … INCH) is always used. Where it states none, a feed in inches per minute (FEDRAT/IPM) means inches; otherwise millimetres.",
        },
        /// Millimetres where the file states no unit.
        Mm = "mm" {
            label: "Millimetres where the file does not say",
            help: "For a file that states no unit: its numbers are millimetres. A unit the file states is still used.",
        },
        /// Inches where the file states no unit.
        Inch = "inch" {
            label: "Inches where the file does not say",
            help: "For a file that states no unit: its numbers are inches (25.4 mm). A unit the file states is still used.",
        },
    }
}

/// A length unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub enum LengthUnit {
    /// Millimetres.
    Mm,
    /// Inches, 25.4 mm.
    Inch,
}

impl LengthUnit {
    /// mm per unit.
    pub fn mm(self) -> f64 {
        match self {
            LengthUnit::Mm => 1.0,
            LengthUnit::Inch => INCH,
        }
    }

    /// `"millimetres"` or `"inches"`.
    pub fn words(self) -> &'static str {
        match self {
            LengthUnit::Mm => "millimetres",
            LengthUnit::Inch => "inches",
        }
    }
}

crate::choices! {
    /// How APT points are read when the file states an output frame (`MSYS/`).
    pub enum AptFrameChoice {
        /// The points are in the MSYS frame; turned into the frame MSYS is written in.
        Apply = "apply" {
            label: "Apply it: GOTOs are in the MSYS frame (NX)",
            help: "The reading NX documents: MSYS/ gives the machine coordinate system (origin, x axis, y axis) in the part's absolute frame, and the GOTO/ points that follow are written in it. Each point p is read as origin + R·p.",
        },
        /// The points are already in the machine's frame; MSYS is only shown.
        Ignore = "ignore" {
            label: "Leave GOTOs as written (machine frame)",
            help: "When the CAM system wrote the points in the frame the machine runs in and MSYS/ only records where that frame is.",
        },
    }
}

/// How to read a file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReadOptions {
    /// The unit where the file states none.
    pub unit: UnitChoice,
    /// Largest distance of an arc from its chords, mm.
    pub chord_tolerance: f64,
    /// How an APT `MSYS/` is read.
    pub apt_frame: AptFrameChoice,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            unit: UnitChoice::Auto,
            chord_tolerance: DEFAULT_CHORD_TOLERANCE,
            apt_frame: AptFrameChoice::Apply,
        }
    }
}

/// Default largest distance of an arc from its chords, mm (1 µm).
pub const DEFAULT_CHORD_TOLERANCE: f64 = 0.001;

/// What a note of the [`Report`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub enum NoteKind {
    /// A frame (shift, rotation, tilted plane, output frame) found and applied or shown.
    Frame,
    /// Tool-centre-point control switched on or off, or missing.
    Tcp,
    /// The path breaks: positions unknown (reference return, machine coordinates), another
    /// work offset.
    Break,
    /// Something the control does that the reader draws only in part (a drilling cycle's
    /// strokes, radius compensation).
    Partial,
    /// How the rotary axes are read (a turn of more than half a turn in a cutting block).
    Rotary,
}

/// Something the file does that the reader applied or read in part, and the user should know.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct Note {
    /// What it is about.
    pub kind: NoteKind,
    /// The first line it happens on.
    pub line: u32,
    /// How often it happens.
    pub count: u32,
    /// In words, of its first occurrence.
    pub text: String,
}

/// A kind of statement or word skipped because it does not change the geometry.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct Skipped {
    /// What was skipped, in words ("feeds (F)").
    pub what: String,
    /// How many times.
    pub count: u32,
    /// The first line.
    pub first_line: u32,
}

/// A frame the file states, how it was read, and the reading chosen (an APT `MSYS/`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct FrameFound {
    /// The statement (`"MSYS/"`).
    pub statement: String,
    /// Its line.
    pub line: u32,
    /// The frame in words ([`Frame::describe`]).
    pub frame: String,
    /// The reading used.
    pub reading: AptFrameChoice,
}

/// What a reader found in the file besides its points: its dialect, the unit and why, the
/// frames, tool-centre-point control, and what it skipped.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct Report {
    /// The format read.
    pub format: Format,
    /// The format in words ([`Format::label`]).
    pub dialect: String,
    /// Lines read.
    pub lines: u32,
    /// Statements or blocks with something in them.
    pub blocks: u32,
    /// The unit the points were read in (the last one stated, else the one chosen).
    pub unit: LengthUnit,
    /// Why: `"inches: G20 on line 14"`, `"millimetres: the file states no unit"`.
    pub unit_reason: String,
    /// Tool-centre-point control: where it was switched on (`"G43.4 on line 12"`), or `None`.
    pub tcp: Option<String>,
    /// Rapid moves (into each point after the first: the moves between the points).
    pub rapids: usize,
    /// Straight feed moves.
    pub feeds: usize,
    /// Chords of arcs.
    pub arc_points: usize,
    /// Frames, breaks and partial readings, in the order first met.
    pub notes: Vec<Note>,
    /// The kinds skipped, in the order first met.
    pub skipped: Vec<Skipped>,
    /// An output frame the user may read another way (APT `MSYS/`).
    pub frame_choice: Option<FrameFound>,
}

/// What the readers share while reading: the notes, the skips and the unit.
#[derive(Debug, Clone)]
pub(crate) struct Log {
    notes: Vec<(&'static str, Note)>,
    skipped: Vec<Skipped>,
    pub(crate) blocks: u32,
    units: Units,
    pub(crate) tcp: Option<String>,
    pub(crate) frame_choice: Option<FrameFound>,
    pub(crate) options: ReadOptions,
    /// The format has unit hints (APT's `FEDRAT/IPM`): an unstated unit may change later.
    hints: bool,
    /// Frames noted while the file's unit was not stated ([`Log::frame_note`]).
    unstated_frames: Vec<UnstatedFrame>,
}

/// A frame noted in a unit not yet decided: the frame in the file's unit, and its note's text
/// before and after the frame's description.
#[derive(Debug, Clone)]
struct UnstatedFrame {
    frame: frame::Frame,
    key: &'static str,
    before: String,
    after: String,
}

impl Log {
    fn new(options: ReadOptions, format: Format) -> Self {
        Log {
            notes: Vec::new(),
            skipped: Vec::new(),
            blocks: 0,
            units: Units::default(),
            tcp: None,
            frame_choice: None,
            options,
            hints: format == Format::Apt,
            unstated_frames: Vec::new(),
        }
    }

    /// Records a note under `key` (one entry per key: the first text, counted).
    pub(crate) fn note(
        &mut self,
        key: &'static str,
        kind: NoteKind,
        line: u32,
        text: impl FnOnce() -> String,
    ) {
        match self.notes.iter_mut().find(|(k, _)| *k == key) {
            Some((_, n)) => n.count = n.count.saturating_add(1),
            None => self.notes.push((
                key,
                Note {
                    kind,
                    line,
                    count: 1,
                    text: text(),
                },
            )),
        }
    }

    /// Records the note `key` on `line`: `before`, the description of `frame` (file unit) in
    /// mm, `after`. While the file states no unit, that description assumes the unit chosen so
    /// far, which a later hint may change (APT's `FEDRAT/IPM`): if the file never states one,
    /// the note is written again at the end in the unit decided then. The description is
    /// returned.
    pub(crate) fn frame_note(
        &mut self,
        key: &'static str,
        line: u32,
        frame: &frame::Frame,
        before: String,
        after: String,
    ) -> String {
        let (scale, stated) = self.scale();
        let desc = frame.scaled(scale).describe();
        if !stated && !self.notes.iter().any(|(k, _)| *k == key) {
            self.unstated_frames.push(UnstatedFrame {
                frame: *frame,
                key,
                before: before.clone(),
                after: after.clone(),
            });
        }
        self.note(key, NoteKind::Frame, line, || {
            format!("{before}{desc}{after}")
        });
        desc
    }

    /// The frame notes again in mm per file unit `now`, the unit decided at the end, when the
    /// file stated none ([`Log::frame_note`]); the frame choice with the output frame's.
    fn describe_frames_again(&mut self, now: f64) {
        if self.units.stated.is_some() {
            return;
        }
        for f in std::mem::take(&mut self.unstated_frames) {
            let desc = f.frame.scaled(now).describe();
            if let Some((_, n)) = self.notes.iter_mut().find(|(k, _)| *k == f.key) {
                n.text = format!("{}{desc}{}", f.before, f.after);
            }
            if let Some(c) = self.frame_choice.as_mut().filter(|_| f.key == "apt-frame") {
                c.frame = desc;
            }
        }
    }

    /// Counts a skipped kind `what` (a few dozen kinds at most: found by comparing).
    pub(crate) fn skip(&mut self, what: &str, line: u32) {
        match self.skipped.iter_mut().find(|s| s.what == what) {
            Some(s) => s.count = s.count.saturating_add(1),
            None => self.skipped.push(Skipped {
                what: what.to_string(),
                count: 1,
                first_line: line,
            }),
        }
    }

    /// The unit stated by `what` on `line` applies from here.
    pub(crate) fn state_unit(&mut self, unit: LengthUnit, line: u32, what: &str) {
        if self.units.stated.map(|(u, _)| u) != Some(unit) {
            self.units.statements.push((unit, line, what.to_string()));
        }
        self.units.stated = Some((unit, line));
    }

    /// The file implies `unit` (a feed unit) on `line`, `what` says by what; used only where
    /// it states none. Only the first hint counts (`what` is not even made after it).
    pub(crate) fn hint_unit(&mut self, unit: LengthUnit, line: u32, what: impl FnOnce() -> String) {
        if self.units.hint.is_none() {
            self.units.hint = Some((unit, line, what()));
        }
    }

    /// mm per file unit now, and whether that unit is stated (an unstated one may still change:
    /// [`Log::unstated_mm`] decides it at the end).
    pub(crate) fn scale(&self) -> (f64, bool) {
        match self.units.stated {
            Some((u, _)) => (u.mm(), true),
            None => (self.unstated().mm(), false),
        }
    }

    /// The arc tolerances in the file's unit now: the chord's sagitta (the option, mm) and the
    /// rounding allowed between an arc's two radii (0.01 mm). While an APT file states no unit
    /// and no hint has decided it yet, so that a later hint may still make it inches, both take the
    /// stricter case (the chord for inches, the rounding for millimetres): the points are
    /// scaled only at the end.
    pub(crate) fn arc_tolerances(&self) -> (f64, f64) {
        let tol = self.options.chord_tolerance;
        let undecided = self.hints
            && self.units.stated.is_none()
            && self.units.hint.is_none()
            && self.options.unit == UnitChoice::Auto;
        if undecided {
            (
                tol / LengthUnit::Inch.mm(),
                ARC_ROUNDING_MM / LengthUnit::Mm.mm(),
            )
        } else {
            let mm = self.scale().0;
            (tol / mm, ARC_ROUNDING_MM / mm)
        }
    }

    /// The unit used where the file states none ([`Log::unstated_unit`] without its reason:
    /// asked for every point).
    fn unstated(&self) -> LengthUnit {
        match (self.options.unit, &self.units.hint) {
            (UnitChoice::Mm, _) | (UnitChoice::Auto, None) => LengthUnit::Mm,
            (UnitChoice::Inch, _) => LengthUnit::Inch,
            (UnitChoice::Auto, Some((u, _, _))) => *u,
        }
    }

    /// The unit used where the file states none, and why.
    fn unstated_unit(&self) -> (LengthUnit, String) {
        match (self.options.unit, &self.units.hint) {
            (UnitChoice::Mm, _) => (LengthUnit::Mm, "the unit chosen for a file that states none".into()),
            (UnitChoice::Inch, _) => (LengthUnit::Inch, "the unit chosen for a file that states none".into()),
            (UnitChoice::Auto, Some((u, line, what))) => (
                *u,
                format!("{what} on line {line} (the file states no length unit; change it beside the file if this is wrong)"),
            ),
            (UnitChoice::Auto, None) => (
                LengthUnit::Mm,
                "the file states no unit (change it beside the file if this is wrong)".into(),
            ),
        }
    }

    /// Marks points `from..to` (indices of every point read) as read where no unit is stated,
    /// at `mm` per file unit.
    fn unstated_points(&mut self, from: u64, to: u64, mm: f64) {
        match self.units.unstated.last_mut() {
            Some(r) if r.1 == from && r.2 == mm => r.1 = to,
            _ => self.units.unstated.push((from, to, mm)),
        }
    }

    /// The unit of the report and its reason.
    fn unit_report(&self, any_unstated: bool) -> (LengthUnit, String) {
        let s = &self.units.statements;
        if s.is_empty() {
            let (u, why) = self.unstated_unit();
            return (u, format!("{}: {why}", u.words()));
        }
        let stated: Vec<String> = s
            .iter()
            .map(|(u, line, what)| format!("{} from {what} on line {line}", u.words()))
            .collect();
        let last = s[s.len() - 1].0;
        let mut why = if s.len() == 1 {
            format!("{}: {} on line {}", last.words(), s[0].2, s[0].1)
        } else {
            format!("{}: {}", last.words(), stated.join(", "))
        };
        if any_unstated {
            let (u, reason) = self.unstated_unit();
            why.push_str(&format!("; before that, {}: {reason}", u.words()));
        }
        (last, why)
    }
}

#[derive(Debug, Clone, Default)]
struct Units {
    /// The unit stated now and the line.
    stated: Option<(LengthUnit, u32)>,
    /// Every change of the stated unit: unit, line, statement.
    statements: Vec<(LengthUnit, u32, String)>,
    /// A unit the file implies (a feed unit), the first one.
    hint: Option<(LengthUnit, u32, String)>,
    /// Ranges of points (indices of all points read) read where no unit was stated, and the mm
    /// per file unit they were read at.
    unstated: Vec<(u64, u64, f64)>,
}

/// Parses a whole text with the default options: [`Parser::new`], one [`Parser::feed`],
/// [`Parser::finish`].
pub fn parse(text: &str, format: Format, machine: Option<&Machine>) -> Result<Vec<Point>> {
    Ok(read(text, format, machine, ReadOptions::default())?.0)
}

/// Parses a whole text: the points and the report ([`read_bytes`] of its UTF-8).
pub fn read(
    text: &str,
    format: Format,
    machine: Option<&Machine>,
    options: ReadOptions,
) -> Result<(Vec<Point>, Report)> {
    read_bytes(text.as_bytes(), format, machine, options)
}

/// Parses a whole file's bytes ([`Parser::feed_bytes`]): the points and the report.
pub fn read_bytes(
    bytes: &[u8],
    format: Format,
    machine: Option<&Machine>,
    options: ReadOptions,
) -> Result<(Vec<Point>, Report)> {
    let mut parser = Parser::new(format, machine, options)?;
    let mut out = Vec::new();
    parser.feed_bytes(bytes, &mut out)?;
    let report = parser.finish(&mut out)?;
    Ok((out, report))
}

/// A streaming toolpath reader (module docs): feed it the text in chunks, then finish.
#[derive(Debug, Clone)]
pub struct Parser {
    reader: Reader,
    log: Log,
    format: Format,
    /// The incomplete last line of the text fed so far.
    carry: String,
    /// The last chunk ended with `\r`: a `\n` starting the next one belongs to that line end.
    after_cr: bool,
    /// Lines read so far.
    line: u32,
    /// Points produced so far.
    points: u64,
    /// Moves of each motion so far (into the points after the first): rapid, feed, arc.
    motions: [usize; 3],
    /// Bytes to text, for [`Parser::feed_bytes`].
    decoder: bytes::Decoder,
}

#[derive(Debug, Clone)]
enum Reader {
    Csv(csv::Csv),
    Apt(Box<apt::Apt>),
    Nc(Box<nc::Nc>),
}

impl Parser {
    /// A reader of `format`. The NC formats need the `machine` (its letters and kinematics;
    /// it is built, so an invalid machine is its own error); the others ignore it.
    pub fn new(format: Format, machine: Option<&Machine>, options: ReadOptions) -> Result<Self> {
        crate::error::check_positive("chordTolerance", options.chord_tolerance, 1.0, "mm")?;
        let reader = match format {
            Format::Csv => Reader::Csv(csv::Csv::default()),
            Format::Apt => Reader::Apt(Box::default()),
            Format::Nc | Format::Siemens | Format::Heidenhain => {
                let machine = machine.ok_or_else(|| {
                    Error::field(
                        "machine",
                        "NC blocks need the machine: its rotary letters and kinematics give the \
                         tool axis",
                    )
                })?;
                Reader::Nc(Box::new(nc::Nc::new(format, &machine.build()?)))
            }
        };
        Ok(Self {
            reader,
            log: Log::new(options, format),
            format,
            carry: String::new(),
            after_cr: false,
            line: 0,
            points: 0,
            motions: [0; 3],
            decoder: bytes::Decoder::default(),
        })
    }

    /// The format being read.
    pub fn format(&self) -> Format {
        self.format
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
        // Bytes, not chars: a line end is one byte in UTF-8, and a byte loop is what WebAssembly
        // runs fast (a char-set search decodes every character).
        while let Some(pos) = rest.bytes().position(|b| b == b'\n' || b == b'\r') {
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

    /// Reads the next piece of the file's bytes ([`Parser::feed`] of their text): UTF-8, else
    /// Windows-1252 from the first byte that is not (a note says from which line); a file that
    /// is not text (an image, a PDF, an archive, UTF-16) is refused by its first bytes.
    pub fn feed_bytes(&mut self, chunk: &[u8], out: &mut Vec<Point>) -> Result<()> {
        let piece = self.decoder.decode(chunk)?;
        if let Some(at) = piece.legacy_from {
            // The line of the first byte that is not UTF-8: the lines before this piece, and
            // the line ends of the piece's UTF-8 part, counted as `feed` counts them (`\r`,
            // `\n`, or both as one).
            let head = &piece.text.as_bytes()[..at];
            let mut after_cr = self.after_cr;
            let mut ends = 0u32;
            for &b in head {
                ends += u32::from(b == b'\r' || b == b'\n' && !after_cr);
                after_cr = b == b'\r';
            }
            self.note_legacy(self.line + 1 + ends);
        }
        self.feed(&piece.text, out)
    }

    /// The note of a file read as Windows-1252 from `line`.
    fn note_legacy(&mut self, line: u32) {
        self.log.note("encoding", NoteKind::Partial, line, || {
            format!("line {line}: the file is not UTF-8 text; it is read as Windows-1252 from here (µ as the byte 0xB5), as Windows editors write it")
        });
    }

    /// Reads the last line (if the text does not end with a line end) and ends the file: the
    /// report. A statement still waiting for its continuation, or a file without any point, is
    /// an error. Points read where the file states no unit are scaled to the unit decided now
    /// (module docs): `out` must still hold them (points handed on before stay as read).
    pub fn finish(&mut self, out: &mut Vec<Point>) -> Result<Report> {
        let tail = self.decoder.finish();
        if !tail.is_empty() {
            self.note_legacy(self.line + 1);
            self.feed(&tail, out)?;
        }
        if !self.carry.is_empty() {
            let last = std::mem::take(&mut self.carry);
            self.line(&last, out)?;
        }
        let before = out.len();
        match &mut self.reader {
            Reader::Csv(_) => {}
            Reader::Apt(apt) => apt.finish(&mut self.log, out)?,
            Reader::Nc(nc) => nc.finish(&mut self.log, out)?,
        }
        self.count(before, out)?;
        if self.points == 0 {
            let what = match self.format {
                Format::Csv => "lines x,y,z,i,j,k",
                Format::Apt => "GOTO/x,y,z or GOTO/x,y,z,i,j,k statements",
                _ => "blocks that move the tool to a known position",
            };
            return Err(Error::field(
                FIELD,
                format!("the file has no points; expected {what}"),
            ));
        }
        // Points read where no unit was stated: scaled when the unit decided differs from the
        // one they were read in (a later hint).
        let any_unstated = !self.log.units.unstated.is_empty();
        let now_unit = self.log.unstated();
        let now = now_unit.mm();
        let first = self.points - out.len() as u64;
        for &(from, to, read_in) in &self.log.units.unstated {
            let k = now / read_in;
            if k != 1.0 {
                for i in from.max(first)..to {
                    let p = &mut out[(i - first) as usize];
                    p.tip *= k;
                    if p.tip.amax() > MAX_COORDINATE {
                        return Err(Error::field(FIELD, format!("line {}: expected coordinates within ±{MAX_COORDINATE} mm, got {} mm once read in {}", p.line, p.tip.amax(), now_unit.words())));
                    }
                }
            }
        }
        self.log.describe_frames_again(now);
        let (unit, unit_reason) = self.log.unit_report(any_unstated);
        let notes = self.log.notes.iter().map(|(_, n)| n.clone()).collect();
        let skipped = self.log.skipped.clone();
        Ok(Report {
            format: self.format,
            dialect: self.format.label().to_string(),
            lines: self.line,
            blocks: self.log.blocks,
            unit,
            unit_reason,
            tcp: self.log.tcp.clone(),
            rapids: self.motions[0],
            feeds: self.motions[1],
            arc_points: self.motions[2],
            notes,
            skipped,
            frame_choice: self.log.frame_choice.clone(),
        })
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
        match &mut self.reader {
            Reader::Csv(c) => c.line(text, line, &mut self.log, out)?,
            Reader::Apt(apt) => apt.line(text, line, &mut self.log, out)?,
            Reader::Nc(nc) => nc.line(text, line, &mut self.log, out)?,
        }
        self.count(before, out)
    }

    /// Counts the points appended since `before`, checks their range, and notes those read
    /// where no unit is stated.
    fn count(&mut self, before: usize, out: &[Point]) -> Result<()> {
        let new = out.len() - before;
        if new == 0 {
            return Ok(());
        }
        // The moves: into every point but the file's first.
        for (i, p) in out[before..].iter().enumerate() {
            if self.points + i as u64 > 0 {
                self.motions[usize::from(p.motion.code())] += 1;
            }
        }
        let from = self.points;
        self.points += new as u64;
        within_points(self.points, self.line)?;
        let (mm, stated) = self.log.scale();
        if !stated {
            self.log.unstated_points(from, self.points, mm);
        }
        Ok(())
    }
}

/// Refuses a file at `line` once it has given `points` points, more than [`MAX_POINTS`] (the
/// one limit of every reader: the parser's count, and a reader's own while it runs repeats).
pub(super) fn within_points(points: u64, line: u32) -> Result<()> {
    if points > MAX_POINTS {
        return Err(Error::field(
            FIELD,
            format!("line {line}: the file gives more than {MAX_POINTS} points (with its arcs and repeats); read a part of the program at a time"),
        ));
    }
    Ok(())
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
