//! Siemens Sinumerik 840D blocks, read for a stated machine ([`super::nc`] moves the tool).
//! Cited: SINUMERIK ONE / 840D sl Programming Manual "NC programming" 12/2019
//! (6FC5398-2EP40-0BA0; CR= p.192, TRANS/ATRANS p.309, ROT/AROT pp.315–316, TRAORI p.666);
//! SINUMERIK 840D sl Programming Manual Job Planning 03/2006 (6FC5398-2BP10-1BA0; orientation
//! A3 B3 C3 p.7-20, TRAFOOF p.7-52); SINUMERIK 808D Programming Manual (Milling; `=AC()`, `=IC()`
//! p.53, `TRANS` alone p.56); SINUMERIK 828D Job Planning 07/2010 (`DEF` p.23); SINUMERIK 802D
//! sl (G70/G71 p.8-139); Function Manual K2 (MD10600, ROT's order p.56).
//!
//! # Read
//! * Blocks with optional `N` numbers, `;` comments, `MSG(…)` (skipped), labels `NAME:`.
//! * Words: an address and a number (`X10`, `G0X10`), or `address=value` (`X=10`, `X=R1`,
//!   `X=IC(5)`, `X=AC(5)`, `A=DC(90)`, `A=ACP(90)`, `CR=5`, `A3=0.5`). A value is a plain number
//!   or a variable the file defined earlier as a plain number (`R1=5`, `DEF REAL DEPTH=5`),
//!   with an optional sign; anything else (an expression, a variable computed by one, a system
//!   variable) is refused with its line.
//! * Motion `G0`–`G3` (arcs with `I J K`, incremental unless `=AC(…)`, or `CR=` positive up to
//!   half a turn, negative beyond; `TURN=` whole turns more), `G17`–`G19`, `G90`/`G91`.
//! * Units: `G70`/`G700` inches, `G71`/`G710` millimetres (from there on).
//! * `TRAORI` (tool-centre-point control: X Y Z the tool tip in the workpiece frame, the
//!   orientation by the rotary axes or the vector `A3 B3 C3`, which "points towards the tool
//!   adapter; the length is of no significance"), `TRAFOOF`.
//! * Frames, applied: `TRANS X Y Z` (absolute: replaces the programmable frame; alone it
//!   clears it), `ATRANS` (added in the current frame), `ROT X Y Z` (absolute; turns first
//!   about Z, then the new Y′, then X″, the default RPY order of MD10600), `ROT RPL=` (in the
//!   plane), `AROT` (added), `SCALE`/`MIRROR` alone (clear the frame).
//! * `SUPA`, `G53`, `G153` (machine coordinates, this block), `G74` (reference point
//!   approach): the axes named go where the file does not say; the path breaks until they are
//!   given again (a note).
//! * Work offsets `G54`–`G57`, `G505`–`G599`, `G500`: the first is the workpiece frame; another
//!   one later breaks the path (a note).
//! * `CYCLE800(…)` with all its offsets and angles 0 (a reset, as posts write it at the start):
//!   no frame.
//! * Drilling cycles called at positions (`MCALL CYCLE81(…)` … `MCALL`, `CYCLE81(…)`) and
//!   machining cycles (`POCKET3(…)`): the positions are read, their moves not drawn (a note).
//! * `M30`, `M2`, `M17`, `RET`: the end.
//!
//! # Skipped and counted
//! `F`, `S`, `T`, `D`, `M`-functions, `G4` (its `F` is a time), path and feed modes (`G60`,
//! `G64`, `G641`, `G642`, `G94`, `G95`, `SOFT`, `BRISK`, `FFWON`, `COMPCAD`, `CUT3DC`, `ORIWKS`,
//! `ORIAXES`, `UPATH` …), `CYCLE832(…)` (high-speed settings), `WORKPIECE(…)`, `STOPRE`,
//! `G40`, `G25`/`G26` limits, `MCALL` (its cycle is noted), variable definitions and assignments.
//!
//! # Refused, with the line and why
//! Expressions and undefined variables in values, control flow (`IF`, `GOTOF`, `GOTOB`,
//! `GOTO`, `WHILE`, `FOR`, `REPEAT`, `LOOP`, `CASE`), subprogram calls (`L100`, `NAME(…)`,
//! `CALL`, `PCALL`), `PROC` (a subprogram's values come from its caller), `CYCLE800` that
//! swivels, `RPL=` outside a `ROT`/`AROT` statement, polar coordinates
//! (`AP=`, `RP=`, `G110`–`G112`), `CIP`, `CT`, `SCALE`/`MIRROR` with values, orientation by
//! angles (`A2 B2 C2`, `LEAD`, `TILT`), a rotary word that is not one of the machine's.

use super::frame::Frame;
use super::lex::{number, shown, Loc, Seg};
use super::nc::{Block, Core, Mode, Plane, Way, Word};
use super::{LengthUnit, Log, NoteKind, Point};
use crate::error::{Error, Result};
use crate::geometry::{rotation, Axis};
use nalgebra::Vector3;
use std::collections::HashMap;

/// Keywords only Sinumerik uses, for [`super::Format::detect`].
const KEYWORDS: [&str; 22] = [
    "TRAORI",
    "TRAFOOF",
    "TRANS",
    "ATRANS",
    "AROT",
    "SUPA",
    "G500",
    "G642",
    "STOPRE",
    "MCALL",
    "CYCLE800",
    "CYCLE832",
    "ORIWKS",
    "ORIAXES",
    "ORIVECT",
    "COMPCAD",
    "FFWON",
    "SOFT",
    "WORKPIECE",
    "GOTOF",
    "GOTOB",
    "G710",
];

/// Whether a (trimmed) line holds something only Sinumerik writes, for
/// [`super::Format::detect`]: a keyword of [`KEYWORDS`], `DEF REAL`/`DEF INT`, `MSG(`, an R
/// parameter assignment (`R1=`), `%_N_`, or an address with `=` (`X=`, `CR=`).
pub(super) fn is_statement(l: &str) -> bool {
    if l.starts_with('(') {
        return false; // an ISO comment
    }
    // ISO comments `( … )` are not Siemens: a `(` that does not follow a name (`MSG(`,
    // `CYCLE800(`), such as one after a block number (`N1(File : test.nc)`).
    let mut kept = String::with_capacity(l.len());
    let mut depth = 0;
    // The letters and underscores the current run of name characters starts with.
    let mut run = 0;
    let mut head = 0;
    for c in l.chars() {
        if c == '(' && (depth > 0 || head < 2) {
            depth += 1;
        } else if c == ')' && depth > 0 {
            depth -= 1;
        } else if depth == 0 {
            kept.push(c);
        }
        if c.is_ascii_alphanumeric() || c == '_' {
            if run == head && (c.is_ascii_alphabetic() || c == '_') {
                head += 1;
            }
            run += 1;
        } else {
            (run, head) = (0, 0);
        }
    }
    let u = kept.to_ascii_uppercase();
    if u.starts_with("%_N_")
        || u.contains("DEF REAL")
        || u.contains("DEF INT")
        || u.contains("MSG(")
        || l.to_ascii_uppercase().contains("MSG (")
    {
        return true;
    }
    let code = u.split(';').next().unwrap_or("");
    for w in code.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
        if KEYWORDS.contains(&w) {
            return true;
        }
    }
    // R1=…, X=…, CR=… (ISO has no `=` after an address).
    let b = code.as_bytes();
    for (i, &c) in b.iter().enumerate() {
        if c == b'=' && i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b' ') {
            let before = code[..i].trim_end();
            let name: String = before
                .chars()
                .rev()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() && name.chars().last().is_some_and(|c| c.is_ascii_alphabetic()) {
                return true;
            }
        }
    }
    false
}

/// A variable's value: a plain number, or one computed (by an expression, a call).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Var {
    Number(f64),
    Computed(u32),
}

/// The Siemens reader's own state.
#[derive(Debug, Clone, Default)]
pub struct Siemens {
    vars: HashMap<String, Var>,
    /// The work offset in use.
    offset: Option<String>,
    /// A point has been written.
    any_point: bool,
}

/// One token of a block.
#[derive(Debug, Clone)]
enum Tok<'a> {
    /// `X10`, `G0`: an address letter and its number.
    Word {
        letter: char,
        value: f64,
        at: usize,
        num_at: usize,
    },
    /// `name=value`.
    Assign {
        name: String,
        value: &'a str,
        at: usize,
        value_at: usize,
    },
    /// `name(args)`.
    Call {
        name: String,
        args: &'a str,
        at: usize,
    },
    /// A bare keyword or name.
    Name { name: String, at: usize },
    /// `NAME:` at the start of a block.
    Label,
}

impl Siemens {
    pub(super) fn line(
        &mut self,
        core: &mut Core,
        text: &str,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let t = text.trim();
        if t.is_empty() || t.starts_with(';') {
            return Ok(());
        }
        if t.starts_with('%') {
            log.skip("program names (%_N_…)", no);
            return Ok(());
        }
        let segs = [Seg { start: 0, line: no }];
        let loc = Loc::line(text, &segs);
        // Program flow is refused at its keyword, before its condition is read as words.
        let (first, first_off) = first_word(text);
        let first = first.to_ascii_uppercase();
        if FLOW.contains(&first.as_str()) {
            return Err(loc.err(first_off, format!("{first} is program flow (a jump, loop or condition): the calculator reads the blocks in order; post the program with the moves written out")));
        }
        if matches!(first.as_str(), "CALL" | "PCALL" | "EXTCALL") {
            return Err(loc.err(first_off, format!("{first} calls a subprogram: the calculator reads one program without its subprograms; post the program with them written out")));
        }
        if first == "PROC" {
            return Err(loc.err(first_off, "PROC starts a subprogram whose values come from the program that calls it; read the program that calls it, posted with the moves written out"));
        }
        // DEF: variables (after a block number or a label, if any), read before the words: its
        // names are listed with commas, with or without a value (`DEF REAL _X_HOME, _Y_HOME`).
        if first == "DEF" {
            log.blocks += 1;
            self.def(&text[first_off..], no);
            return Ok(());
        }
        let toks = lex(text, &loc)?;
        if toks.is_empty() {
            return Ok(());
        }
        log.blocks += 1;
        let mut b = Block {
            at: first_at(&toks),
            ..Block::default()
        };
        let mut frame_stmt: Option<(String, usize)> = None;
        let mut frame_words: Vec<(char, f64, usize)> = Vec::new();
        let mut rpl: Option<f64> = None;
        let mut machine_coords = false;
        let mut home = false;
        let mut vector = [None::<f64>; 3];
        let mut home_words: Vec<(&str, &str, usize)> = Vec::new();
        for tok in &toks {
            match tok {
                Tok::Label => {}
                Tok::Word {
                    letter,
                    value,
                    at,
                    num_at,
                } => {
                    let (letter, value, at) = (*letter, *value, *at);
                    if frame_stmt.is_some() && "XYZ".contains(letter) {
                        frame_words.push((letter, value, at));
                        continue;
                    }
                    self.word(
                        core,
                        &mut b,
                        letter,
                        value,
                        at,
                        *num_at,
                        no,
                        &loc,
                        log,
                        &mut machine_coords,
                        &mut home,
                    )?;
                }
                Tok::Assign {
                    name,
                    value,
                    at,
                    value_at,
                } => {
                    let n = name.as_str();
                    if n == "RPL" && frame_stmt.is_some() {
                        rpl = Some(self.value(value, *value_at, &loc)?.0);
                        continue;
                    }
                    if frame_stmt.is_some() && matches!(n, "X" | "Y" | "Z") {
                        let (v, _) = self.value(value, *value_at, &loc)?;
                        frame_words.push((n.chars().next().unwrap_or('X'), v, *at));
                        continue;
                    }
                    match n {
                        "X" | "Y" | "Z" | "I" | "J" | "K" => {
                            let (v, mode) = self.value(value, *value_at, &loc)?;
                            let i = "XYZIJK".find(n).unwrap_or(0);
                            let w = Some(Word { value: v, at: *value_at });
                            if i < 3 {
                                b.axes[i] = w;
                                b.incremental[i] = mode;
                            } else {
                                b.centre[i - 3] = w;
                                if mode == Some(false) {
                                    b.centre_absolute = true;
                                }
                            }
                        }
                        "CR" => b.radius = Some(Word { value: self.value(value, *value_at, &loc)?.0, at: *value_at }),
                        "TURN" => b.turns = self.value(value, *value_at, &loc)?.0.max(0.0) as u32,
                        "A3" | "B3" | "C3" => {
                            let i = (n.as_bytes()[0] - b'A') as usize;
                            vector[i] = Some(self.value(value, *value_at, &loc)?.0);
                        }
                        "AP" | "RP" => return Err(loc.err(*at, "AP=/RP= are polar coordinates (angle and radius about a pole); the calculator reads X Y Z: post the program in Cartesian coordinates")),
                        "RPL" => return Err(loc.err(*at, "RPL= turns the plane in a ROT or AROT statement, and this block has none: write ROT RPL=… or AROT RPL=…")),
                        "AR" => return Err(loc.err(*at, "AR= gives an arc by its opening angle, which the reader does not read; post the arc with its centre (I J K) or radius (CR=)")),
                        "A2" | "B2" | "C2" | "LEAD" | "TILT" | "A4" | "B4" | "C4" | "A5" | "B5" | "C5" => {
                            return Err(loc.err(*at, format!("{n}= gives the orientation by angles or surface normals the reader does not read; post the program with the rotary axes or the vector A3 B3 C3")))
                        }
                        "F" | "S" | "T" | "D" | "FA" | "SF" | "OVR" => log.skip("feeds, speeds and tools (F, S, T, D)", no),
                        n if n.len() == 1 && "ABC".contains(n) => {
                            let letter = n.chars().next().unwrap_or('A');
                            let i = core.rotary_index(letter).ok_or_else(|| core.not_this_machine(&loc, *at, letter))?;
                            let (v, mode, way) = self.value_way(value, *value_at, &loc)?;
                            b.axes[i] = Some(Word { value: v, at: *value_at });
                            b.incremental[i] = mode;
                            b.way[i - 3] = way;
                        }
                        // `G74 X1=0 Z1=0`, `G75 FP=2 X1=0`: the machine axes to send to the
                        // reference or fixed point (read after the loop, whatever the order).
                        "X1" | "Y1" | "Z1" | "A1" | "B1" | "C1" | "FP" => home_words.push((n, value, *at)),
                        _ => self.assign(n, value, no, log),
                    }
                }
                Tok::Call { name, args, at } => self.call(core, name, args, *at, no, &loc, log)?,
                Tok::Name { name, at } => {
                    let n = name.as_str();
                    match n {
                        "TRAORI" => core.set_tcp(true, no, "TRAORI", log),
                        "TRAFOOF" => core.set_tcp(false, no, "TRAFOOF", log),
                        "TRANS" | "ATRANS" | "ROT" | "AROT" | "SCALE" | "ASCALE" | "MIRROR" | "AMIRROR" => {
                            frame_stmt = Some((n.to_string(), *at));
                        }
                        "SUPA" => machine_coords = true,
                        "MCALL" => log.skip("modal cycle calls (MCALL)", no),
                        "RET" => core.ended = true,
                        "STOPRE" | "SOFT" | "BRISK" | "FFWON" | "FFWOF" | "COMPCAD" | "COMPCURV" | "COMPSURF" | "COMPOF" | "CUT3DC" | "CUT3DF" | "CUT3DFS" | "CUT3DFF" | "ORIWKS" | "ORIMKS" | "ORIAXES" | "ORIVECT" | "ORIAXPOS" | "ORIPLANE" | "ORICONO" | "ORIPATH" | "ORIROTA" | "ORIROTR" | "ORIROTT" | "UPATH" | "SPATH" | "CFTCP" | "CFC" | "CFIN" | "FNORM" | "FLIN" | "FCUB" | "DYNNORM" | "DYNROUGH" | "DYNSEMIFIN" | "DYNFINISH" | "DYNPOS" | "SPOF" | "CPROTDEF" | "FGROUP" | "SOFTA" | "BRISKA" | "DRIVE" | "ACC" | "G642" | "G641" | "G645" | "G643" | "G644" | "G60" | "G64" => {
                            log.skip("path, feed and look-ahead modes (SOFT, COMPCAD, ORIWKS …)", no)
                        }
                        "IF" | "GOTOF" | "GOTOB" | "GOTO" | "GOTOC" | "GOTOS" | "WHILE" | "ENDWHILE" | "FOR" | "ENDFOR" | "REPEAT" | "UNTIL" | "LOOP" | "ENDLOOP" | "CASE" | "ELSE" | "ENDIF" => {
                            return Err(loc.err(*at, format!("{n} is program flow (a jump, loop or condition): the calculator reads the blocks in order; post the program with the moves written out")))
                        }
                        "CALL" | "PCALL" | "EXTCALL" => return Err(loc.err(*at, format!("{n} calls a subprogram: the calculator reads one program without its subprograms; post the program with them written out"))),
                        "PROC" => return Err(loc.err(*at, "PROC starts a subprogram whose values come from the program that calls it; read the program that calls it, posted with the moves written out")),
                        "CIP" => return Err(loc.err(*at, "CIP gives an arc through an intermediate point, which the reader does not read; post the arc with its centre (I J K) or radius (CR=)")),
                        "CT" => return Err(loc.err(*at, "CT gives a tangential arc, which the reader does not read; post the arc with its centre (I J K) or radius (CR=)")),
                        "G110" | "G111" | "G112" => return Err(loc.err(*at, format!("{n} sets a pole for polar coordinates; the calculator reads X Y Z: post the program in Cartesian coordinates"))),
                        _ => return Err(loc.err(*at, unknown(n))),
                    }
                }
            }
        }
        // The motion mode stays in force after a block that returns early (`G0 SUPA Z0`).
        if let Some(m) = b.mode {
            core.mode = m;
        }
        for (n, value, at) in home_words {
            if !home {
                self.assign(n, value, no, log);
            } else if n != "FP" {
                let letter = n.chars().next().unwrap_or('X');
                let w = Some(Word { value: 0.0, at });
                match "XYZ".find(letter) {
                    Some(i) => b.axes[i] = w,
                    None => {
                        let i = core
                            .rotary_index(letter)
                            .ok_or_else(|| core.not_this_machine(&loc, at, letter))?;
                        b.axes[i] = w; // the rotary axis's reference, 0°
                    }
                }
            }
        }
        if let Some((stmt, at)) = frame_stmt {
            return self.frame(core, &stmt, at, &frame_words, rpl, no, &loc, log);
        }
        if vector.iter().any(Option::is_some) {
            let v = Vector3::new(
                vector[0].unwrap_or(0.0),
                vector[1].unwrap_or(0.0),
                vector[2].unwrap_or(0.0),
            );
            b.vector = Some(
                super::lex::unit(&v)
                    .ok_or_else(|| loc.err(b.at, "the tool vector A3 B3 C3 must not be zero"))?,
            );
        }
        if home || machine_coords {
            let axes: Vec<usize> = (0..3).filter(|&i| b.axes[i].is_some()).collect();
            for i in 3..5 {
                if let Some(w) = b.axes[i] {
                    core.pos[i] = w.value;
                }
            }
            if !axes.is_empty() {
                core.forget(&axes);
                let what = if home {
                    "G74/G75 take"
                } else {
                    "a move in machine coordinates (SUPA, G53, G153) takes"
                };
                log.note("sie-machine", NoteKind::Break, no, || {
                    format!("line {no}: {what} {} where the file does not relate to the part: the path breaks until each is given again", axes.iter().map(|&i| ["X", "Y", "Z"][i]).collect::<Vec<_>>().join(", "))
                });
            }
            return Ok(());
        }
        let arc_block = matches!(b.mode.unwrap_or(core.mode), Mode::Cw | Mode::Ccw);
        if !arc_block {
            b.centre = [None; 3];
            b.radius = None;
        }
        let before = out.len();
        core.execute(&b, &loc, log, out)?;
        if out.len() > before {
            self.any_point = true;
        }
        Ok(())
    }

    /// An address word `letter value`.
    #[allow(clippy::too_many_arguments)]
    fn word(
        &mut self,
        core: &mut Core,
        b: &mut Block,
        letter: char,
        value: f64,
        at: usize,
        num_at: usize,
        no: u32,
        loc: &Loc,
        log: &mut Log,
        machine_coords: &mut bool,
        home: &mut bool,
    ) -> Result<()> {
        let w = Some(Word { value, at: num_at });
        match letter {
            'X' => b.axes[0] = w,
            'Y' => b.axes[1] = w,
            'Z' => b.axes[2] = w,
            'I' | 'J' | 'K' => b.centre[(letter as u8 - b'I') as usize] = w,
            'G' => {
                let code = (value * 10.0).round() as i64;
                match code {
                    0 => b.mode = Some(Mode::Rapid),
                    10 => b.mode = Some(Mode::Feed),
                    20 => b.mode = Some(Mode::Cw),
                    30 => b.mode = Some(Mode::Ccw),
                    170 => core.plane = Plane::Xy,
                    180 => core.plane = Plane::Zx,
                    190 => core.plane = Plane::Yz,
                    900 => core.absolute = true,
                    910 => core.absolute = false,
                    700 | 7000 => core.state_unit(LengthUnit::Inch, no, &format!("G{value}"), log),
                    710 | 7100 => core.state_unit(LengthUnit::Mm, no, &format!("G{value}"), log),
                    530 | 1530 => *machine_coords = true,
                    740 | 750 => *home = true,
                    410 | 420 => log.note("sie-cutcom", NoteKind::Partial, no, || {
                        format!("line {no}: G{value} offsets the path by the tool radius (radius compensation); the points are read as programmed")
                    }),
                    5000 | 540..=570 | 5050..=5990 => {
                        let name = format!("G{value}");
                        if self.offset.as_ref().is_some_and(|o| *o != name) && self.any_point {
                            core.break_next = true;
                            log.note("sie-offset", NoteKind::Break, no, || {
                                format!("line {no}: {name} selects another work offset, whose place the file does not state: the points after it are read in it, and the move into it is not analysed")
                            });
                        }
                        self.offset = Some(name);
                    }
                    40 => log.skip("dwells (G4)", no),
                    1100 | 1110 | 1120 => return Err(loc.err(at, format!("G{value} sets a pole for polar coordinates; the calculator reads X Y Z: post the program in Cartesian coordinates"))),
                    _ => log.skip("path, feed and look-ahead modes (G40, G64, G94 …)", no),
                }
            }
            'M' => match (value * 10.0).round() as i64 {
                20 | 300 | 170 => {
                    core.ended = true;
                    log.skip("program ends (M2, M17, M30)", no);
                }
                _ => log.skip("M-functions (spindle, coolant, tool change …)", no),
            },
            'L' => return Err(loc.err(at, format!("L{value} calls subprogram L{value}: the calculator reads one program without its subprograms; post the program with it written out"))),
            'N' => log.skip("block numbers (N)", no),
            'F' | 'S' | 'T' | 'D' | 'H' | 'E' => log.skip("feeds, speeds and tools (F, S, T, D)", no),
            'R' => {
                // `R1 5`? Siemens assigns with `=`; an R alone is not a word of a block.
                return Err(loc.err(at, format!("R{value} without = is not a block word; expected R{value}=value")));
            }
            l => {
                if let Some(i) = core.rotary_index(l) {
                    b.axes[i] = w;
                } else if "ABC".contains(l) {
                    return Err(core.not_this_machine(loc, at, l));
                } else {
                    return Err(loc.err(at, format!("{l} is not an address the reader knows in a Siemens block")));
                }
            }
        }
        Ok(())
    }

    /// A value: a plain number or a variable defined as one, optionally in `IC()`, `AC()`,
    /// `DC()`, `ACP()`, `ACN()`; with whether it is incremental (`IC`), absolute (`AC` …) or
    /// modal.
    fn value(&self, text: &str, at: usize, loc: &Loc) -> Result<(f64, Option<bool>)> {
        self.value_way(text, at, loc).map(|(v, inc, _)| (v, inc))
    }

    /// [`Siemens::value`] and, for a rotary axis, how it reaches the position: `DC` the
    /// shorter way, `ACP` turning positively, `ACN` negatively.
    fn value_way(
        &self,
        text: &str,
        at: usize,
        loc: &Loc,
    ) -> Result<(f64, Option<bool>, Option<Way>)> {
        let t = text.trim();
        let upper = t.to_ascii_uppercase();
        for (f, inc, way) in [
            ("IC(", Some(true), None),
            ("AC(", Some(false), Some(Way::Literal)),
            ("DC(", Some(false), Some(Way::Shortest)),
            ("ACP(", Some(false), Some(Way::Positive)),
            ("ACN(", Some(false), Some(Way::Negative)),
        ] {
            if upper.starts_with(f) && t.ends_with(')') {
                let inner = &t[f.len()..t.len() - 1];
                let v = self.plain(inner, at + f.len(), loc, t)?;
                return Ok((v, inc, way));
            }
        }
        Ok((self.plain(t, at, loc, t)?, None, None))
    }

    /// A plain number, or `[±]name` of a variable defined as a plain number.
    fn plain(&self, t: &str, at: usize, loc: &Loc, whole: &str) -> Result<f64> {
        let t = t.trim();
        if let Some(v) = number(t, true).filter(|v| v.is_finite()) {
            return Ok(v);
        }
        let (sign, name) = match t.strip_prefix('-') {
            Some(n) => (-1.0, n.trim()),
            None => (1.0, t.strip_prefix('+').unwrap_or(t).trim()),
        };
        let key = name.to_ascii_uppercase();
        let is_name = !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$')
            && !key.starts_with(|c: char| c.is_ascii_digit());
        if is_name {
            return match self.vars.get(&key) {
                Some(Var::Number(v)) => Ok(sign * v),
                Some(Var::Computed(line)) => Err(loc.err(at, format!("{} is computed on line {line} (by an expression or a call): the calculator reads plain numbers or variables defined as plain numbers; post the program with the values written out", shown(name)))),
                None => Err(loc.err(at, format!("{} uses {}, which the file does not define as a number (DEF or an R parameter); the calculator reads plain numbers", shown(whole), shown(name)))),
            };
        }
        Err(loc.err(at, format!("{} is an expression: the calculator reads plain numbers or variables defined earlier as plain numbers; post the program with the values written out", shown(whole))))
    }

    /// `name=value` of a variable (an R parameter, a user variable).
    fn assign(&mut self, name: &str, value: &str, no: u32, log: &mut Log) {
        let v = match number(value.trim(), true).filter(|v| v.is_finite()) {
            Some(x) => Var::Number(x),
            None => match self.vars.get(&value.trim().to_ascii_uppercase()) {
                Some(Var::Number(x)) => Var::Number(*x),
                _ => Var::Computed(no),
            },
        };
        self.vars.insert(name.to_ascii_uppercase(), v);
        log.skip("variable assignments (R1=…, DEF)", no);
    }

    /// `DEF type name[=value], …`: a name defined without a value is 0, the default value of
    /// the numeric types (828D Job Planning, `DEF` p.23).
    fn def(&mut self, text: &str, no: u32) {
        let code = text.split(';').next().unwrap_or("");
        let after = code.trim_start();
        let after = after.get(3..).unwrap_or("").trim_start(); // past DEF
        let rest = after.split_once(char::is_whitespace).map_or("", |(_, r)| r);
        for item in rest.split(',') {
            let (name, value) = match item.split_once('=') {
                Some((n, v)) => (n.trim(), Some(v.trim())),
                None => (item.trim(), None),
            };
            let name = name.split('[').next().unwrap_or(name).trim();
            if name.is_empty() {
                continue;
            }
            let v = match value {
                None => Var::Number(0.0),
                Some(v) => number(v, true)
                    .filter(|x| x.is_finite())
                    .map_or(Var::Computed(no), Var::Number),
            };
            self.vars.insert(name.to_ascii_uppercase(), v);
        }
    }

    /// `name(args)`.
    #[allow(clippy::too_many_arguments)]
    fn call(
        &mut self,
        core: &mut Core,
        name: &str,
        args: &str,
        at: usize,
        no: u32,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        match name {
            "MSG" | "WORKPIECE" | "CYCLE832" | "SETMS" | "SPOS" | "SPOSA" | "FGROUP" | "CPROT" | "TRAFOOF" | "SOFTA" | "BRISKA" | "G4" => {
                log.skip("messages and settings (MSG, WORKPIECE, CYCLE832 …)", no);
                Ok(())
            }
            "TRAORI" => {
                core.set_tcp(true, no, "TRAORI", log);
                Ok(())
            }
            "CYCLE800" => {
                let fields: Vec<&str> = args.split(',').map(str::trim).collect();
                // _FR,_TC,_ST,_MODE,_X0,_Y0,_Z0,_A,_B,_C,_X1,_Y1,_Z1,_DIR…: a reset when the
                // swivel data set is "0" or every offset and angle is 0.
                let deselect = fields.get(1).is_some_and(|tc| *tc == "\"0\"");
                let zero = (4..13).all(|i| fields.get(i).map_or(true, |f| f.is_empty() || number(f, true) == Some(0.0)));
                if deselect || zero {
                    log.skip("swivel resets (CYCLE800 with no rotation)", no);
                    return Ok(());
                }
                Err(loc.err(at, "CYCLE800 swivels the working plane by angles whose meaning depends on the machine's swivel data; the calculator needs the tool tip in workpiece coordinates: post the program with TRAORI (tool-centre-point output) or as CL data"))
            }
            n if n.starts_with("CYCLE8") || n.starts_with("CYCLE7") && n.len() == 7 => {
                log.note("sie-cycle", NoteKind::Partial, no, || {
                    format!("line {no}: drilling cycle {n}: it drills at the current position; its strokes are not drawn (the tool axis does not turn in them)")
                });
                Ok(())
            }
            n if n.starts_with("CYCLE") || n.starts_with("POCKET") || n.starts_with("SLOT") || n.starts_with("LONGHOLE") || n.starts_with("HOLES") => {
                log.note("sie-machining-cycle", NoteKind::Partial, no, || {
                    format!("line {no}: machining cycle {n}: its moves are computed by the control and are not drawn (the tool axis does not turn in them)")
                });
                Ok(())
            }
            _ => Err(loc.err(at, format!("{name}(…) calls a subprogram or a function the reader does not know: the calculator reads one program without its subprograms; post the program with the moves written out"))),
        }
    }

    /// A frame statement with its words.
    #[allow(clippy::too_many_arguments)]
    fn frame(
        &mut self,
        core: &mut Core,
        stmt: &str,
        at: usize,
        words: &[(char, f64, usize)],
        rpl: Option<f64>,
        no: u32,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let get = |l: char| words.iter().find(|w| w.0 == l).map(|w| w.1);
        // The programmable frame (TRANS, ROT …) is the reader's whole frame, kept in the
        // file's unit now.
        let current = core.frame;
        let frame = match stmt {
            "TRANS" | "ATRANS" => {
                let v = Vector3::new(
                    get('X').unwrap_or(0.0),
                    get('Y').unwrap_or(0.0),
                    get('Z').unwrap_or(0.0),
                );
                if stmt == "TRANS" {
                    Frame::shift(v)
                } else {
                    current.then(&Frame::shift(v))
                }
            }
            "ROT" | "AROT" => {
                let r = match rpl {
                    Some(a) => rotation(Axis::ALL[core.plane.normal()], a.to_radians()),
                    // RPY (MD10600 = 1): first about Z, then the new Y′, then X″.
                    None => {
                        rotation(Axis::Z, get('Z').unwrap_or(0.0).to_radians())
                            * rotation(Axis::Y, get('Y').unwrap_or(0.0).to_radians())
                            * rotation(Axis::X, get('X').unwrap_or(0.0).to_radians())
                    }
                };
                let f = Frame {
                    rotation: r,
                    origin: Vector3::zeros(),
                };
                if stmt == "ROT" {
                    f
                } else {
                    current.then(&f)
                }
            }
            _ => {
                if !words.is_empty() || rpl.is_some() {
                    return Err(loc.err(at, format!("{stmt} scales or mirrors the program's coordinates; the calculator reads them unscaled: post the program without scaling or mirroring")));
                }
                Frame::IDENTITY
            }
        };
        core.frame = frame;
        if !frame.is_identity() {
            let desc = frame.scaled(log.scale().0).describe();
            log.note("sie-frame", NoteKind::Frame, no, || {
                format!("line {no}: {stmt} sets the programmable frame to {desc}: applied to the points after it")
            });
        }
        Ok(())
    }
}

/// Keywords of program flow.
const FLOW: [&str; 17] = [
    "IF", "GOTOF", "GOTOB", "GOTO", "GOTOC", "GOTOS", "WHILE", "ENDWHILE", "FOR", "ENDFOR",
    "REPEAT", "UNTIL", "LOOP", "ENDLOOP", "CASE", "ELSE", "ENDIF",
];

/// The first word of a block after its skip mark, block number and label, and its byte offset.
fn first_word(text: &str) -> (&str, usize) {
    let b = text.as_bytes();
    let blanks = |mut i: usize| {
        while i < b.len() && matches!(b[i], b' ' | b'\t') {
            i += 1;
        }
        i
    };
    let word_end = |i: usize| {
        text[i..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .map_or(text.len(), |e| i + e)
    };
    let mut i = blanks(0);
    // A skip mark (`/`), a block number (`N10`), a label (`MARKE1:`).
    if b.get(i) == Some(&b'/') {
        i = blanks(i + 1);
    }
    if matches!(b.get(i), Some(b'N' | b'n')) && b.get(i + 1).is_some_and(u8::is_ascii_digit) {
        i += 1;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i = blanks(i);
    }
    let end = word_end(i);
    if end > i && b.get(end) == Some(&b':') {
        i = blanks(end + 1);
        return (&text[i..word_end(i)], i);
    }
    (&text[i..end], i)
}

/// The byte offset of the first token.
fn first_at(toks: &[Tok]) -> usize {
    match toks.first() {
        Some(
            Tok::Word { at, .. }
            | Tok::Assign { at, .. }
            | Tok::Call { at, .. }
            | Tok::Name { at, .. },
        ) => *at,
        _ => 0,
    }
}

/// The tokens of a Siemens block.
fn lex<'a>(line: &'a str, loc: &Loc) -> Result<Vec<Tok<'a>>> {
    let b = line.as_bytes();
    let mut toks = Vec::new();
    let mut i = 0;
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'$';
    while i < b.len() {
        let c = b[i];
        if c == b' ' || c == b'\t' {
            i += 1;
            continue;
        }
        if c == b';' {
            break;
        }
        if c == b'/' && toks.is_empty() {
            i += 1;
            continue;
        }
        if !(c.is_ascii_alphabetic() || c == b'_' || c == b'$') {
            let got: String = line[i..].chars().take(1).collect();
            return Err(loc.err(
                i,
                format!(
                    "expected a word (an address and a number, like X12.5, or X=…), got {}",
                    shown(&got)
                ),
            ));
        }
        let at = i;
        let mut j = i;
        while j < b.len() && ident(b[j]) {
            j += 1;
        }
        let id = &line[i..j];
        let mut k = j;
        while k < b.len() && matches!(b[k], b' ' | b'\t') {
            k += 1;
        }
        let after = b.get(k).copied();
        if after == Some(b'=') && b.get(k + 1) != Some(&b'=') {
            // name=value (`==` is a comparison): the value runs to a blank at depth 0.
            let mut v = k + 1;
            while v < b.len() && matches!(b[v], b' ' | b'\t') {
                v += 1;
            }
            let start = v;
            let (mut depth, mut quote) = (0i32, false);
            while v < b.len() {
                match b[v] {
                    b'"' => quote = !quote,
                    b'(' | b'[' if !quote => depth += 1,
                    b')' | b']' if !quote => depth -= 1,
                    b' ' | b'\t' if depth <= 0 && !quote => break,
                    b';' if !quote => break,
                    _ => {}
                }
                v += 1;
            }
            if v == start {
                return Err(loc.err(
                    at,
                    format!("{id}= has no value: expected a number or a variable after ="),
                ));
            }
            toks.push(Tok::Assign {
                name: id.to_ascii_uppercase(),
                value: &line[start..v],
                at,
                value_at: start,
            });
            i = v;
            continue;
        }
        if after == Some(b'(') && id.len() >= 2 {
            let start = k + 1;
            let mut v = start;
            let (mut depth, mut quote) = (1i32, false);
            while v < b.len() && depth > 0 {
                match b[v] {
                    b'"' => quote = !quote,
                    b'(' if !quote => depth += 1,
                    b')' if !quote => depth -= 1,
                    _ => {}
                }
                v += 1;
            }
            if depth > 0 {
                return Err(loc.err(at, format!("{id}( is not closed on its line: expected ')'")));
            }
            let args = &line[start..v - 1];
            toks.push(Tok::Call {
                name: id.to_ascii_uppercase(),
                args,
                at,
            });
            i = v;
            continue;
        }
        if after == Some(b':')
            && toks
                .iter()
                .all(|t| matches!(t, Tok::Word { letter: 'N', .. }))
        {
            toks.push(Tok::Label);
            i = k + 1;
            continue;
        }
        let letter = c.to_ascii_uppercase() as char;
        // An address is a letter with digits after it (`X10`, `G0X10`), or a letter alone with a
        // number after it, blanks between or not (`X-5.5`, `X 10`); any other identifier is a
        // name (`TRAORI`, `SUPA`, `$P_UIFR`, `_X`, an `X` without a number).
        let address = match id.as_bytes() {
            [_] => matches!(after, Some(b'0'..=b'9' | b'.' | b'-' | b'+')),
            [_, second, ..] => second.is_ascii_digit(),
            [] => false,
        };
        if !address {
            toks.push(Tok::Name {
                name: id.to_ascii_uppercase(),
                at,
            });
            i = j;
            continue;
        }
        // Letter + number.
        let mut n = i + 1;
        while n < b.len() && matches!(b[n], b' ' | b'\t') {
            n += 1;
        }
        let len = super::lex::number_len(&b[n..]);
        let tok = &line[n..n + len];
        let value = number(tok, false).ok_or_else(|| {
            loc.err(
                n,
                format!("expected a number after {letter}, got {}", shown(tok)),
            )
        })?;
        toks.push(Tok::Word {
            letter,
            value,
            at,
            num_at: n,
        });
        i = n + len;
    }
    Ok(toks)
}

/// The refusal of a name the reader does not know.
/// A letter alone is an address written without its number
/// (`G1 X F500`).
fn unknown(name: &str) -> String {
    if name.len() == 1 {
        format!("{name} has no number: expected a number after {name} (like {name}10 or {name}=10)")
    } else {
        format!("{} is not a word the reader knows; if it calls a subprogram, post the program with it written out", shown(name))
    }
}

fn _unused(_: Error) {}
