//! Heidenhain conversational (Klartext) programs, read for a stated machine ([`super::nc`]
//! moves the tool). Cited: HEIDENHAIN TNC 620 Conversational Programming User's Manual
//! 10/2017 (BEGIN PGM p.154, PLANE p.540, PLANE VECTOR p.548); iTNC 530 User's Manual (340 422;
//! CR p.239, PLANE SPATIAL pp.456–460, FUNCTION TCPM p.457, LN p.491); iTNC 530 DIN/ISO
//! (340 49x; M128 p.290); TNC 620 DIN/ISO 5/2013 (PLANE EULER p.322); TNC 320 (L p.128); TNC
//! 410 (C p.79); TNC 426/430 (CP p.153); TNC7 User's Manual (81762x-17, FUNCTION TCPM, Q
//! parameters).
//!
//! The whole program is read first (each block checked as it comes), then run from its first
//! block, so that `CALL LBL` finds labels written after `M30`, as the control does.
//!
//! # Read
//! * Blocks: a block number, a statement, `;` comments; `*` comment lines; `~` at the end of a
//!   line continues the block (cycle parameters); `/` block skip (the block is read).
//! * `BEGIN PGM name MM|INCH`: the unit of the whole program. `END PGM`, `M30`, `M2`: the end.
//! * `L X+… Y… Z… A… B… C… R0 F…|FMAX M…`: a straight move (`IX` incremental, `FMAX` or `F MAX`
//!   this block at rapid); `LN … TX TY TZ`: with the tool vector.
//! * Arcs about the pole `CC X Y` (absolute, or `IX IY` from the last position; its two axes
//!   give the plane: X Y, Z X or Y Z; without coordinates the current position): `C X Y DR±`
//!   (`DR+` counter-clockwise, `DR−` clockwise, end = start a full circle), `CR X Y R± DR±` (R+
//!   up to half a turn, R− beyond), `CT X Y` (tangential to the move before), `CP IPA± [IZ…]
//!   DR±` (polar arc or helix about CC; `PA` absolute). Cut into chords within the tolerance.
//! * Q parameters assigned a plain number (`FN 0: Q1 = +5`, `Q1 = 5`) may stand in a
//!   coordinate (`X+Q1`, `X-Q1`); `Q120`–`Q122` are the rotary angles a `PLANE … STAY` leaves
//!   for the program, solved on the machine as the control does (the smallest tilt; `SEQ+`/
//!   `SEQ−` the sign of the tilting axis).
//! * `M128`/`FUNCTION TCPM` switch tool-centre-point control on, `M129`/`FUNCTION RESET TCPM`
//!   off.
//! * Frames, applied: `CYCL DEF 7 DATUM SHIFT` (`7.1 X…` … absolute from the preset, `IX`
//!   from the last shift), `TRANS DATUM AXIS X… Y… Z…` / `TRANS DATUM RESET`, `CYCL DEF 10
//!   ROTATION` (`10.1 ROT±a` about the tool axis through the datum, `IROT` incremental), and the
//!   tilted working plane `PLANE SPATIAL SPA SPB SPC` (about the fixed X, then Y, then Z: "first
//!   around the A axis, then B, and then C"), `PLANE EULER EULPR EULNU EULROT` (Z, X′, Z″),
//!   `PLANE VECTOR BX BY BZ NX NY NZ` (base vector the x axis, normal the tool axis),
//!   `PLANE RELATIV SPA|SPB|SPC` (one more turn about the tilted axis), `PLANE RESET`. In a tilted
//!   plane the tool axis is its z axis. `PLANE RESET MOVE` or `TURN` turns the rotary axes back
//!   to 0° (`STAY` leaves them).
//! * `M91`/`M92` (machine coordinates) and `M140` (retract along the tool axis): the axes go
//!   where the file does not say; the path breaks until they are given again (a note).
//! * `CALL LBL n` (a subprogram up to `LBL 0`) and `CALL LBL n REP m` (repeats the part from
//!   `LBL n` to the call; a label after the call is run once, as a subprogram), 8 deep at most.
//! * Cycles called at positions (`CYCL CALL`, `CYCL CALL POS`, `M99`, `M89`): the positions are
//!   read, the cycle's own moves are not drawn (a note).
//!
//! # Skipped and counted
//! `TOOL CALL`, `TOOL DEF`, `BLK FORM`, feeds, M-functions, radius compensation `RL`/`RR` (a
//! note), cycle definitions and their `Q` parameter lines, `CYCL DEF 32` (tolerance), `LBL`,
//! `STOP`, `FUNCTION` settings, `SEL`, `DECLARE`, `SPEC`, `PATTERN`, other Q-parameter
//! assignments. `PRESET SELECT`, `COPY`, `SET` and `CORRECT` change the preset by values the
//! file does not state: the path breaks there (a note).
//!
//! # Refused, with the line and why (when the block is run)
//! `APPR`/`DEP` (approach contours the control builds), `RND`/`CHF` (corner roundings),
//! FK free contours (`FPOL`, `FL`, `FC` …), `LP`/`CTP` polar moves, `CYCL DEF 19` (its angles
//! depend on the machine's configuration), `CYCL DEF 8`, `11`, `26` (mirror, scaling),
//! `PLANE PROJECTED`, `POINTS`, `AXIAL`, `CALL PGM`, `FN 9`–`FN 12` jumps, coordinates from Q
//! parameters that are computed or undefined, a rotary word that is not one of the machine's,
//! a datum shift of a rotary axis (`CYCL DEF 7.1 C+90`, `TRANS DATUM AXIS C+90`),
//! another `PRESET` function, and any other statement.

use super::frame::Frame;
use super::lex::{number, shown, Loc, Seg};
use super::nc::{Block, Core, Mode, Plane, Word};
use super::{LengthUnit, Log, NoteKind, Point};
use crate::error::{Error, Result};
use crate::geometry::{rotation, Axis};
use crate::machine::BranchRule;
use nalgebra::{Matrix3, Vector3};
use std::collections::HashMap;

/// Deepest nesting of label calls.
const MAX_DEPTH: usize = 8;
/// Most repeats of a label section (the TNC's own limit, `REP` 65 534).
const MAX_REP: f64 = 65_534.0;
/// Most blocks run (repeats included), a guard against a label that calls itself.
const MAX_RUN: u64 = 50_000_000;

/// Whether a (trimmed) line is a Heidenhain statement, for [`super::Format::detect`]: `BEGIN
/// PGM`, or a block number followed by `L`, `C`, `CC`, `CR`, `CT`, `CP`, `LN`, `TOOL CALL`,
/// `CYCL DEF`, `PLANE`, `LBL`, `FN`, `BLK FORM`, or a line with `FMAX`, `TOOL CALL` or
/// `CYCL DEF`.
pub(super) fn is_statement(l: &str) -> bool {
    // Comments are not statements: an ISO `(TOOL CALL T1)` or a Siemens `;TOOL CALL` is not
    // Heidenhain.
    let code = strip_comment(l);
    let u = code
        .split('(')
        .next()
        .unwrap_or("")
        .trim()
        .to_ascii_uppercase();
    let rest = u
        .trim_start_matches(|c: char| c.is_ascii_digit())
        .trim_start();
    if u.contains("BEGIN PGM")
        || rest.starts_with("TOOL CALL")
        || rest.starts_with("CYCL DEF")
        || u.contains("FMAX") && !code.contains('(')
    {
        return true;
    }
    let rest = u.trim_start_matches(|c: char| c.is_ascii_digit());
    if rest.len() == u.len() || !rest.starts_with(' ') {
        return false;
    }
    let first = rest.split_whitespace().next().unwrap_or("");
    matches!(
        first,
        "L" | "C"
            | "CC"
            | "CR"
            | "CT"
            | "CP"
            | "LN"
            | "PLANE"
            | "LBL"
            | "FN"
            | "BLK"
            | "M128"
            | "FUNCTION"
    )
}

/// A Q parameter's value: a plain number, or computed on a line.
#[derive(Debug, Clone, Copy)]
enum Q {
    Number(f64),
    Computed(u32),
}

/// The Heidenhain reader: the program's blocks, then its run.
#[derive(Debug, Clone, Default)]
pub struct Heidenhain {
    /// Each block: its first line and its text (continuations joined, comments removed).
    blocks: Vec<(u32, String)>,
    /// A block continued with `~`, so far.
    pending: Option<(u32, String)>,
    /// Labels: name → index of the `LBL` block.
    labels: HashMap<String, usize>,
    // The run's state.
    q: HashMap<u32, Q>,
    /// The pole CC (program frame), and the plane its axes give.
    pole: Option<(Vector3<f64>, Plane)>,
    /// The tool axis of TOOL CALL: its plane.
    tool_plane: Option<Plane>,
    /// The datum shift programmed outside a tilted plane (workpiece axes).
    datum: Vector3<f64>,
    /// The datum shift programmed in the tilted plane (along its axes: the TNC's
    /// transformations after `PLANE` act in the working-plane system).
    datum_tilted: Vector3<f64>,
    rot10: f64,
    tilt: Option<Matrix3<f64>>,
    /// Cycle being defined (number) and the one last defined.
    cycle: Option<(u32, String)>,
    run: u64,
}

impl Heidenhain {
    pub(super) fn line(
        &mut self,
        _core: &mut Core,
        text: &str,
        no: u32,
        log: &mut Log,
        _out: &mut [Point],
    ) -> Result<()> {
        // `~` continues the block on the next line; the TNC writes it after the line's
        // comment too (`Q240=0 ;TUNING MODE~`).
        let raw = text.trim_end();
        let (more, raw) = match raw.strip_suffix('~') {
            Some(r) => (true, r),
            None => (false, raw),
        };
        let code = strip_comment(raw);
        let t = code.trim_end();
        let t = t.strip_suffix('~').unwrap_or(t);
        match self.pending.take() {
            Some((first, mut acc)) => {
                acc.push(' ');
                acc.push_str(t.trim());
                if more {
                    self.pending = Some((first, acc));
                } else {
                    self.push(first, acc, log);
                }
            }
            None => {
                if t.trim().is_empty() {
                    return Ok(()); // blank, or a lone `~`: a block starts with its words
                }
                if more {
                    self.pending = Some((no, t.to_string()));
                } else {
                    self.push(no, t.to_string(), log);
                }
            }
        }
        Ok(())
    }

    /// Keeps a block (and notes a label's place).
    fn push(&mut self, no: u32, text: String, log: &mut Log) {
        let body = block_body(&text);
        if body.is_empty() || body.starts_with('*') {
            return;
        }
        log.blocks += 1;
        let u = body.to_ascii_uppercase();
        if let Some(rest) = u.strip_prefix("LBL ") {
            let name = label_name(rest);
            if name != "0" {
                self.labels.entry(name).or_insert(self.blocks.len());
            }
        }
        self.blocks.push((no, text));
    }

    pub(super) fn finish(
        &mut self,
        core: &mut Core,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        if let Some((no, acc)) = self.pending.take() {
            self.push(no, acc, log);
        }
        let blocks = std::mem::take(&mut self.blocks);
        let r = self.run_from(core, &blocks, 0, None, 0, log, out);
        self.blocks = blocks;
        r
    }

    /// Runs blocks from `start` until the end of the program, or (a subprogram) `LBL 0`, or
    /// (a repeat) the block `until`.
    #[allow(clippy::too_many_arguments)]
    fn run_from(
        &mut self,
        core: &mut Core,
        blocks: &[(u32, String)],
        start: usize,
        until: Option<usize>,
        depth: usize,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let mut i = start;
        while i < blocks.len() && !core.ended {
            if until == Some(i) {
                return Ok(());
            }
            self.count_run(blocks[i].0, out.len())?;
            let (no, text) = (&blocks[i].0, &blocks[i].1);
            let segs = [Seg {
                start: 0,
                line: *no,
            }];
            let loc = Loc::line(text, &segs);
            let body_at = text.len() - block_body(text).len();
            let body = &text[body_at..];
            let u = body.to_ascii_uppercase();
            if u.starts_with("LBL") {
                if depth > 0
                    && until.is_none()
                    && label_name(u.trim_start_matches("LBL").trim()) == "0"
                {
                    return Ok(()); // the end of a subprogram
                }
                log.skip("labels (LBL)", *no);
                i += 1;
                continue;
            }
            if let Some(rest) = u.strip_prefix("CALL LBL") {
                let (name, rep) = match rest.find(" REP") {
                    Some(p) => {
                        // `REP 2` or, as the TNC stores it, `REP 2/2` (remaining/total).
                        let words = rest[p + 4..].trim_start();
                        let n = words.split(['/', ' ']).next().unwrap_or("");
                        let Some(m) = number(n, false).filter(|m| m.fract() == 0.0 && *m >= 0.0)
                        else {
                            return Err(loc.err(body_at + "CALL LBL".len() + p + 1, format!("REP must be followed by the number of repeats (REP 2 or REP 2/2), not {:?}", words)));
                        };
                        (label_name(rest[..p].trim()), Some(m.min(MAX_REP)))
                    }
                    None => (label_name(rest.trim()), None),
                };
                let Some(&at) = self.labels.get(&name) else {
                    return Err(loc.err(
                        body_at,
                        format!("CALL LBL {name}: the program has no label {name}"),
                    ));
                };
                if depth >= MAX_DEPTH {
                    return Err(loc.err(
                        body_at,
                        format!(
                            "CALL LBL {name}: labels call each other more than {MAX_DEPTH} deep"
                        ),
                    ));
                }
                match rep {
                    Some(m) if at < i => {
                        for _ in 0..(m as u64) {
                            self.count_run(blocks[i].0, out.len())?; // a pass counts, even an empty one
                            self.run_from(core, blocks, at + 1, Some(i), depth + 1, log, out)?;
                        }
                    }
                    _ => self.run_from(core, blocks, at + 1, None, depth + 1, log, out)?,
                }
                i += 1;
                continue;
            }
            self.block(core, *no, body, body_at, &loc, log, out)?;
            i += 1;
        }
        Ok(())
    }

    /// Counts one block (or one pass of a repeat) run, against [`MAX_RUN`], and the points so
    /// far against [`super::MAX_POINTS`].
    fn count_run(&mut self, line: u32, points: usize) -> Result<()> {
        super::within_points(points as u64, line)?;
        self.run += 1;
        if self.run > MAX_RUN {
            return Err(Error::field(super::FIELD, format!("line {line}: the program runs more than {MAX_RUN} blocks (a label calling itself?)")));
        }
        Ok(())
    }

    /// One block's statement.
    #[allow(clippy::too_many_arguments)]
    fn block(
        &mut self,
        core: &mut Core,
        no: u32,
        body: &str,
        at: usize,
        loc: &Loc,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let u = body.to_ascii_uppercase();
        let words: Vec<&str> = body.split_whitespace().collect();
        let first = words
            .first()
            .map(|w| w.to_ascii_uppercase())
            .unwrap_or_default();
        let refuse = |msg: String| -> Result<()> { Err(loc.err(at, msg)) };
        match first.as_str() {
            "BEGIN" => {
                let unit = if u.contains(" INCH") { LengthUnit::Inch } else { LengthUnit::Mm };
                core.state_unit(unit, no, if unit == LengthUnit::Inch { "BEGIN PGM … INCH" } else { "BEGIN PGM … MM" }, log);
                Ok(())
            }
            "END" => {
                core.ended = true;
                Ok(())
            }
            "BLK" => {
                log.skip("workpiece blank (BLK FORM)", no);
                Ok(())
            }
            "TOOL" => {
                if u.starts_with("TOOL CALL") {
                    // The tool axis: the letter after the tool number or name.
                    for w in words.iter().skip(2) {
                        match w.to_ascii_uppercase().as_str() {
                            "X" => self.tool_plane = Some(Plane::Yz),
                            "Y" => self.tool_plane = Some(Plane::Zx),
                            "Z" => self.tool_plane = Some(Plane::Xy),
                            _ => continue,
                        }
                        break;
                    }
                }
                log.skip("tool calls (TOOL CALL, TOOL DEF)", no);
                Ok(())
            }
            "STOP" => {
                log.skip("program stops (STOP)", no);
                Ok(())
            }
            "L" | "LN" => self.linear(core, no, body, at, loc, log, out, first == "LN"),
            "CC" => self.pole(core, no, body, at, loc),
            "C" | "CR" | "CT" | "CP" => self.arc(core, no, body, at, loc, log, out, &first),
            "LP" | "CTP" | "CPP" => refuse(format!("{first} moves in polar coordinates, which the reader does not read; post the program in Cartesian coordinates")),
            "RND" | "CHF" => refuse(format!("{first} rounds or chamfers the corner between two blocks; the control computes it. Post the program with the corner written as moves")),
            "APPR" | "DEP" => refuse(format!("{first} approaches or leaves the contour along moves the control builds; post the program with them written as L and C blocks")),
            "FPOL" | "FL" | "FLT" | "FC" | "FCT" | "FSELECT" => refuse(format!("{first} is free contour programming (FK): the control computes the contour; post the program with L and C blocks")),
            "CYCL" => self.cycl(core, no, body, at, &u, loc, log, out),
            "TRANS" if u.starts_with("TRANS DATUM") => {
                if u.contains("TABLE") {
                    return refuse("TRANS DATUM TABLE shifts the datum by a line of a datum table, which the file does not state; post the program with the shift written out".into());
                }
                if u.contains("RESET") {
                    self.datum = Vector3::zeros();
                    self.datum_tilted = Vector3::zeros();
                    self.update_frame(core);
                    return Ok(());
                }
                let shifts = self.datum_words(&words[2..], "TRANS DATUM", loc, at)?;
                self.shift_datum(core, &shifts, "TRANS DATUM", no, log);
                Ok(())
            }
            "PLANE" => self.plane(core, no, body, at, &u, loc, log),
            "FUNCTION" => {
                if u.contains("RESET TCPM") {
                    core.set_tcp(false, no, "FUNCTION RESET TCPM", log);
                } else if u.contains("TCPM") {
                    if u.contains("AXIS SPAT") {
                        return refuse("FUNCTION TCPM … AXIS SPAT makes A, B, C spatial angles, not the rotary axes' positions, which the reader does not read; post the program with AXIS POS, with vectors (LN … TX TY TZ) or as CL data".into());
                    }
                    core.set_tcp(true, no, "FUNCTION TCPM", log);
                } else {
                    log.skip("FUNCTION settings", no);
                }
                Ok(())
            }
            "FN" => self.fn_statement(no, body, at, &u, loc, log),
            "CALL" => refuse(format!("{} calls another program: the calculator reads one program; post it with the called moves written out", shown(body))),
            "TCH" => {
                log.note("hei-probe", NoteKind::Partial, no, || format!("line {no}: a touch-probe cycle: its probing moves are not drawn"));
                Ok(())
            }
            // The NC functions of the preset table: SELECT activates a row, COPY copies one
            // (and may activate it), SET writes one, CORRECT offsets the active one ("offsets
            // the entered value against the actual table value", TNC7 manual 81762x-17). Each
            // may move the datum by values the file does not state: the path breaks there.
            "PRESET" => {
                let what = words.get(1).map(|w| w.to_ascii_uppercase()).unwrap_or_default();
                if !matches!(what.as_str(), "SELECT" | "COPY" | "SET" | "CORRECT") {
                    return refuse(format!("{} is not a preset function the reader knows (SELECT, COPY, SET, CORRECT)", shown(body)));
                }
                core.break_next = true;
                log.note("hei-preset", NoteKind::Break, no, || format!("line {no}: PRESET {what} selects or changes a preset, whose place the file does not state: the path breaks there"));
                Ok(())
            }
            "SEL" | "DECLARE" | "SPEC" | "PATTERN" => {
                log.skip("settings (SEL, DECLARE, SPEC, PATTERN)", no);
                Ok(())
            }
            f if f.starts_with('Q') && u.contains('=') => {
                self.assign_q(no, body, &u, log);
                Ok(())
            }
            f if f.starts_with('M') => self.m_only(core, no, &words, at, loc, log),
            _ => refuse(format!("{} is not a Heidenhain statement the reader knows", shown(words.first().copied().unwrap_or(body)))),
        }
    }

    /// `FN n: …`.
    fn fn_statement(
        &mut self,
        no: u32,
        body: &str,
        at: usize,
        u: &str,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let n = u[2..].trim_start().split(':').next().unwrap_or("").trim();
        match n {
            "0" => {
                let rest = body.split_once(':').map_or("", |(_, r)| r);
                self.assign_q(no, rest, &rest.to_ascii_uppercase(), log);
                Ok(())
            }
            "9" | "10" | "11" | "12" => Err(loc.err(at, format!("FN {n} jumps on a condition: the calculator reads the blocks in order; post the program with the moves written out"))),
            _ => {
                // A computation: the parameter it writes is computed.
                if let Some(q) = q_target(body.split_once(':').map_or("", |(_, r)| r)) {
                    self.q.insert(q, Q::Computed(no));
                }
                log.skip("Q-parameter functions (FN)", no);
                Ok(())
            }
        }
    }

    /// `Qn = value`.
    fn assign_q(&mut self, no: u32, text: &str, _u: &str, log: &mut Log) {
        if let Some((lhs, rhs)) = text.split_once('=') {
            if let Some(q) = q_target(lhs) {
                let rhs = rhs.trim();
                let v = match number(rhs, false) {
                    Some(x) => Q::Number(x),
                    None => match self.q_value(rhs) {
                        Some(x) => Q::Number(x),
                        None => Q::Computed(no),
                    },
                };
                self.q.insert(q, v);
            }
        }
        log.skip("Q-parameter assignments", no);
    }

    /// The value of `[±]Qn` when it is a plain number.
    fn q_value(&self, t: &str) -> Option<f64> {
        let (sign, rest) = match t.strip_prefix('-') {
            Some(r) => (-1.0, r),
            None => (1.0, t.strip_prefix('+').unwrap_or(t)),
        };
        let n: u32 = rest.strip_prefix(['Q', 'q'])?.parse().ok()?;
        match self.q.get(&n) {
            Some(Q::Number(v)) => Some(sign * v),
            _ => None,
        }
    }

    /// An axis word: `X+10`, `IX-5`, `X+Q1`: (index 0..5 for X Y Z and the machine's rotary
    /// axes, 5.. for others, incremental, value). `None` when `w` is not an axis word.
    fn axis_value(&self, w: &str, loc: &Loc, at: usize) -> Result<Option<(usize, bool, f64)>> {
        let uw = w.to_ascii_uppercase();
        let (inc, rest) = match uw.strip_prefix('I') {
            Some(r) if r.starts_with(['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W']) => (true, r),
            _ => (false, uw.as_str()),
        };
        let Some(letter) = rest.chars().next() else {
            return Ok(None);
        };
        let idx = match letter {
            'X' => 0,
            'Y' => 1,
            'Z' => 2,
            'A' | 'B' | 'C' => 5 + (letter as u8 - b'A') as usize,
            'U' | 'V' | 'W' => 9,
            _ => return Ok(None),
        };
        let val = &rest[1..];
        if val.is_empty()
            || !(val.starts_with(['+', '-', '.', 'Q'])
                || val.starts_with(|c: char| c.is_ascii_digit()))
        {
            return Ok(None);
        }
        let v = match number(val, false) {
            Some(v) => v,
            None => {
                let q = val.trim_start_matches(['+', '-']);
                if q.starts_with('Q') {
                    self.q_value(val).ok_or_else(|| {
                        let n: u32 = q[1..].parse().unwrap_or(0);
                        match self.q.get(&n) {
                            Some(Q::Computed(l)) => loc.err(at, format!("{w} takes {q}, computed on line {l} by a formula: the calculator reads plain numbers or Q parameters set to one; post the program with the values written out")),
                            _ => loc.err(at, format!("{w} takes {q}, which the program does not set to a number; post the program with the values written out")),
                        }
                    })?
                } else {
                    return Err(loc.err(
                        at,
                        format!("expected a number after {letter}, got {}", shown(val)),
                    ));
                }
            }
        };
        if idx == 9 {
            return Err(loc.err(at, format!("{letter} is an axis the calculator does not read; the program must move X, Y, Z and the machine's two rotary axes")));
        }
        Ok(Some((idx, inc, v)))
    }

    /// Reads the axis words of a block into `b` (rotary letters checked).
    fn axes(&self, core: &Core, words: &[&str], b: &mut Block, loc: &Loc, at: usize) -> Result<()> {
        for w in words {
            if let Some((i, inc, v)) = self.axis_value(w, loc, at)? {
                let idx = if i < 3 {
                    i
                } else {
                    let letter = (b'A' + (i - 5) as u8) as char;
                    core.rotary_index(letter)
                        .ok_or_else(|| core.not_this_machine(loc, at, letter))?
                };
                b.axes[idx] = Some(Word { value: v, at });
                b.incremental[idx] = Some(inc);
            }
        }
        Ok(())
    }

    /// `L` and `LN` blocks.
    #[allow(clippy::too_many_arguments)]
    fn linear(
        &mut self,
        core: &mut Core,
        no: u32,
        body: &str,
        at: usize,
        loc: &Loc,
        log: &mut Log,
        out: &mut Vec<Point>,
        ln: bool,
    ) -> Result<()> {
        let words: Vec<&str> = body.split_whitespace().skip(1).collect();
        let mut b = Block {
            at,
            mode: Some(Mode::Feed),
            ..Block::default()
        };
        self.axes(core, &words, &mut b, loc, at)?;
        let mut tv = [None::<f64>; 3];
        let mut machine = false;
        let mut retract = false;
        let mut cycle_call = false;
        let mut tcp_off = false;
        let mut prev = "";
        for w in &words {
            let uw = w.to_ascii_uppercase();
            match uw.as_str() {
                "FMAX" => b.rapid_once = true,
                "MAX" if prev.eq_ignore_ascii_case("F") => b.rapid_once = true,
                "RL" | "RR" => log.note("hei-cutcom", NoteKind::Partial, no, || format!("line {no}: {uw} offsets the path by the tool radius (radius compensation); the points are read as programmed")),
                _ => {}
            }
            if ln {
                for (i, n) in ["TX", "TY", "TZ"].iter().enumerate() {
                    if let Some(v) = uw.strip_prefix(n) {
                        tv[i] = Some(number(v, false).ok_or_else(|| {
                            loc.err(at, format!("expected a number after {n}, got {}", shown(v)))
                        })?);
                    }
                }
            }
            if let Some(m) = uw.strip_prefix('M').and_then(|m| m.parse::<u32>().ok()) {
                match m {
                    91 | 92 => machine = true,
                    140 => retract = true,
                    99 | 89 => cycle_call = true,
                    126 => core.shortest = true,
                    127 => core.shortest = false,
                    128 => core.set_tcp(true, no, "M128", log),
                    129 => tcp_off = true, // M129 acts at the end of its block
                    30 | 2 => core.ended = true,
                    _ => log.skip("M-functions", no),
                }
            }
            if uw.starts_with('F') && uw != "FMAX" && uw != "F" {
                log.skip("feeds (F)", no);
            }
            prev = w;
        }
        if tv.iter().any(Option::is_some) {
            let v = Vector3::new(
                tv[0].unwrap_or(0.0),
                tv[1].unwrap_or(0.0),
                tv[2].unwrap_or(0.0),
            );
            b.vector = Some(
                super::lex::unit(&v)
                    .ok_or_else(|| loc.err(at, "the tool vector TX TY TZ must not be zero"))?,
            );
        }
        if machine || retract {
            let axes: Vec<usize> = if retract {
                vec![0, 1, 2]
            } else {
                (0..3).filter(|&i| b.axes[i].is_some()).collect()
            };
            for i in 3..5 {
                if let Some(w) = b.axes[i] {
                    core.pos[i] = if b.incremental[i] == Some(true) {
                        core.pos[i] + w.value
                    } else {
                        w.value
                    };
                }
            }
            if !axes.is_empty() {
                core.forget(&axes);
                let what = if retract {
                    "M140 retracts the tool along its axis"
                } else {
                    "M91/M92 move in machine coordinates"
                };
                log.note("hei-machine", NoteKind::Break, no, || format!("line {no}: {what}, to positions the file does not relate to the part: the path breaks until each axis is given again"));
            }
        } else {
            core.execute(&b, loc, log, out)?;
        }
        if tcp_off {
            core.set_tcp(false, no, "M129", log);
        }
        if cycle_call {
            self.cycle_called(no, log, " at the block's end point");
        }
        Ok(())
    }

    /// A block of M-functions only.
    fn m_only(
        &mut self,
        core: &mut Core,
        no: u32,
        words: &[&str],
        at: usize,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let mut retract = false;
        for w in words {
            let uw = w.to_ascii_uppercase();
            // M140's own words: `MB MAX`, `MB+10`.
            if retract && (uw.starts_with("MB") || uw == "MAX") {
                continue;
            }
            // A feed: `M128 F25000` gives the largest feed of M128's compensating moves.
            if uw.len() > 1 && uw.starts_with('F') {
                log.skip("feeds (F)", no);
                continue;
            }
            let Some(m) = uw.strip_prefix('M').and_then(|m| m.parse::<u32>().ok()) else {
                return Err(loc.err(
                    at,
                    format!(
                        "{} is not a Heidenhain statement the reader knows",
                        shown(w)
                    ),
                ));
            };
            match m {
                128 => core.set_tcp(true, no, "M128", log),
                129 => core.set_tcp(false, no, "M129", log),
                126 => core.shortest = true,
                127 => core.shortest = false,
                30 | 2 => core.ended = true,
                99 | 89 => self.cycle_called(no, log, " at the current position"),
                140 => retract = true,
                _ => log.skip("M-functions", no),
            }
        }
        if retract {
            core.forget(&[0, 1, 2]);
            log.note("hei-machine", NoteKind::Break, no, || format!("line {no}: M140 retracts the tool along its axis, to positions the file does not relate to the part: the path breaks until each axis is given again"));
        }
        Ok(())
    }

    /// The cycle last defined is called (`at`: where, in words).
    fn cycle_called(&mut self, no: u32, log: &mut Log, at: &str) {
        let name = self
            .cycle
            .as_ref()
            .map_or_else(|| "a cycle".to_string(), |(n, t)| format!("cycle {n} {t}"));
        log.note("hei-cycle", NoteKind::Partial, no, || format!("line {no}: {name} is called{at}: its moves are not drawn (the tool axis does not turn in them)"));
    }

    /// `CC`.
    fn pole(&mut self, core: &Core, _no: u32, body: &str, at: usize, loc: &Loc) -> Result<()> {
        let words: Vec<&str> = body.split_whitespace().skip(1).collect();
        let mut c = Vector3::new(core.pos[0], core.pos[1], core.pos[2]);
        let mut given = Vec::new();
        for w in &words {
            if let Some((i, inc, v)) = self.axis_value(w, loc, at)? {
                if i < 3 {
                    c[i] = if inc { core.pos[i] + v } else { v };
                    given.push(i);
                }
            }
        }
        let plane = match (given.contains(&0), given.contains(&1), given.contains(&2)) {
            (true, true, _) => Plane::Xy,
            (true, false, true) => Plane::Zx,
            (false, true, true) => Plane::Yz,
            _ => self.tool_plane.unwrap_or(Plane::Xy),
        };
        self.pole = Some((c, plane));
        Ok(())
    }

    /// `C`, `CR`, `CT`, `CP`.
    #[allow(clippy::too_many_arguments)]
    fn arc(
        &mut self,
        core: &mut Core,
        no: u32,
        body: &str,
        at: usize,
        loc: &Loc,
        log: &mut Log,
        out: &mut Vec<Point>,
        kind: &str,
    ) -> Result<()> {
        let words: Vec<&str> = body.split_whitespace().skip(1).collect();
        let mut b = Block {
            at,
            ..Block::default()
        };
        self.axes(core, &words, &mut b, loc, at)?;
        let mut dr: Option<bool> = None;
        let mut radius = None;
        let mut ipa = None;
        let mut pa = None;
        let mut tcp_off = false;
        let mut prev = "";
        for w in &words {
            let uw = w.to_ascii_uppercase();
            match uw.as_str() {
                "DR+" => dr = Some(true),
                "DR-" => dr = Some(false),
                "FMAX" => b.rapid_once = true,
                "MAX" if prev.eq_ignore_ascii_case("F") => b.rapid_once = true,
                _ => {}
            }
            if kind == "CR"
                && uw.starts_with('R')
                && uw.len() > 1
                && !matches!(uw.as_str(), "RL" | "RR" | "R0")
            {
                radius = Some(number(&uw[1..], false).ok_or_else(|| {
                    loc.err(
                        at,
                        format!("expected the radius after R, got {}", shown(&uw[1..])),
                    )
                })?);
            }
            if let Some(v) = uw.strip_prefix("IPA") {
                ipa = Some(number(v, false).ok_or_else(|| {
                    loc.err(at, format!("expected an angle after IPA, got {}", shown(v)))
                })?);
            } else if let Some(v) = uw.strip_prefix("PA") {
                pa = Some(number(v, false).ok_or_else(|| {
                    loc.err(at, format!("expected an angle after PA, got {}", shown(v)))
                })?);
            }
            if uw.starts_with("PR") || uw.starts_with("IPR") {
                return Err(loc.err(at, format!("{kind} with a polar radius ({uw}) is not read; post the arc with its end point")));
            }
            if let Some(m) = uw.strip_prefix('M').and_then(|m| m.parse::<u32>().ok()) {
                match m {
                    128 => core.set_tcp(true, no, "M128", log),
                    129 => tcp_off = true, // M129 acts at the end of its block
                    30 | 2 => core.ended = true,
                    _ => log.skip("M-functions", no),
                }
            }
            prev = w;
        }
        let plane_of_pole = self.pole.map(|p| p.1);
        match kind {
            "C" | "CP" => {
                let (centre, plane) = self.pole.ok_or_else(|| {
                    loc.err(
                        at,
                        format!("{kind} turns about the pole CC, but no CC comes before it"),
                    )
                })?;
                core.plane = plane;
                let ccw = dr.ok_or_else(|| loc.err(at, format!("{kind} needs its direction, DR+ (counter-clockwise) or DR− (clockwise)")))?;
                b.mode = Some(if ccw { Mode::Ccw } else { Mode::Cw });
                b.centre = [0, 1, 2].map(|i| {
                    Some(Word {
                        value: centre[i],
                        at,
                    })
                });
                b.centre_absolute = true;
                if kind == "CP" {
                    let sweep = match (ipa, pa) {
                        (Some(a), _) => a,
                        (None, Some(a)) => {
                            let (u, v) = plane_axes(plane);
                            let now = (core.pos[v] - centre[v])
                                .atan2(core.pos[u] - centre[u])
                                .to_degrees();
                            let mut d = a - now;
                            if ccw {
                                d = d.rem_euclid(360.0)
                            } else {
                                d = -(-d).rem_euclid(360.0)
                            }
                            d
                        }
                        _ => return Err(loc.err(at, "CP needs its angle, IPA (incremental) or PA")),
                    };
                    if (sweep > 0.0) != ccw || sweep == 0.0 {
                        return Err(loc.err(
                            at,
                            format!(
                                "CP's angle {sweep}° and its direction {} disagree",
                                if ccw { "DR+" } else { "DR−" }
                            ),
                        ));
                    }
                    // The plane's two axes come from the rotation; only the third may be given.
                    let n = plane.normal();
                    for i in 0..3 {
                        if i != n {
                            b.axes[i] = None;
                        }
                    }
                    b.sweep = Some(sweep);
                }
            }
            "CR" => {
                let r = radius.ok_or_else(|| {
                    loc.err(
                        at,
                        "CR needs its radius, R+ (up to half a turn) or R− (more)",
                    )
                })?;
                let ccw = dr.ok_or_else(|| {
                    loc.err(
                        at,
                        "CR needs its direction, DR+ (counter-clockwise) or DR− (clockwise)",
                    )
                })?;
                core.plane = plane_of_arc(&b, plane_of_pole.or(self.tool_plane));
                b.mode = Some(if ccw { Mode::Ccw } else { Mode::Cw });
                b.radius = Some(Word { value: r, at });
            }
            _ => {
                // CT: tangential to the move before.
                let t = core.tangent.ok_or_else(|| {
                    loc.err(
                        at,
                        "CT continues tangentially from the move before, but there is none, or it started \
                         where the tool's position is not known (after M91, M92 or M140)",
                    )
                })?;
                let plane = plane_of_arc(&b, plane_of_pole.or(self.tool_plane));
                core.plane = plane;
                let n = Vector3::ith(plane.normal(), 1.0);
                let s = Vector3::new(core.pos[0], core.pos[1], core.pos[2]);
                let mut e = s;
                for i in 0..3 {
                    if let Some(w) = b.axes[i] {
                        e[i] = if b.incremental[i] == Some(true) {
                            s[i] + w.value
                        } else {
                            w.value
                        };
                    }
                }
                let mut d = e - s;
                d -= n * n.dot(&d);
                let t = (t - n * n.dot(&t)).try_normalize(1e-12).ok_or_else(|| {
                    loc.err(at, "CT: the move before is normal to the plane of the arc")
                })?;
                let left = n.cross(&t);
                let k = left.dot(&d);
                if k.abs() < 1e-9 * d.norm().max(1.0) {
                    b.mode = Some(Mode::Feed); // the end lies on the tangent: a straight move
                } else {
                    let rho = d.norm_squared() / (2.0 * k);
                    let c = s + left * rho;
                    b.mode = Some(if rho > 0.0 { Mode::Ccw } else { Mode::Cw });
                    b.centre = [0, 1, 2].map(|i| Some(Word { value: c[i], at }));
                    b.centre_absolute = true;
                }
            }
        }
        core.execute(&b, loc, log, out)?;
        if tcp_off {
            core.set_tcp(false, no, "M129", log);
        }
        Ok(())
    }

    /// `CYCL DEF …`, `CYCL CALL …`.
    #[allow(clippy::too_many_arguments)]
    fn cycl(
        &mut self,
        core: &mut Core,
        no: u32,
        body: &str,
        at: usize,
        u: &str,
        loc: &Loc,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        if let Some(rest) = u.strip_prefix("CYCL CALL") {
            if rest.trim_start().starts_with("POS") {
                // `CYCL CALL POS X Y Z FMAX|F`: a positioning move there (drawn as a rapid, the
                // tool axis does not turn), then the cycle; its words are those after POS.
                let words = body.split_whitespace().skip(3).collect::<Vec<_>>();
                self.linear(
                    core,
                    no,
                    &format!("L {} FMAX", words.join(" ")),
                    at,
                    loc,
                    log,
                    out,
                    false,
                )?;
                self.cycle_called(no, log, " at the position the block gives");
            } else {
                self.cycle_called(no, log, " at the current position");
            }
            return Ok(());
        }
        let rest = u.strip_prefix("CYCL DEF").unwrap_or("").trim();
        let num = rest.split_whitespace().next().unwrap_or("");
        let (major, minor) = num.split_once('.').unwrap_or((num, "0"));
        let major: u32 = major.parse().map_err(|_| {
            loc.err(
                at,
                format!("expected a cycle number after CYCL DEF, got {}", shown(num)),
            )
        })?;
        let words: Vec<&str> = body.split_whitespace().skip(3).collect();
        match major {
            7 => {
                if minor == "0" {
                    return Ok(());
                }
                if words.iter().any(|w| w.starts_with('#')) {
                    return Err(loc.err(at, "CYCL DEF 7 with a datum table line (#) shifts by values the file does not state; post the program with the shift written out"));
                }
                let shifts = self.datum_words(&words, "CYCL DEF 7 DATUM SHIFT", loc, at)?;
                self.shift_datum(core, &shifts, "CYCL DEF 7 DATUM SHIFT", no, log);
                Ok(())
            }
            10 => {
                if minor == "0" {
                    return Ok(());
                }
                for w in &words {
                    let uw = w.to_ascii_uppercase();
                    if let Some(v) = uw.strip_prefix("IROT") {
                        self.rot10 += number(v, false).ok_or_else(|| loc.err(at, format!("expected an angle after IROT, got {}", shown(v))))?;
                    } else if let Some(v) = uw.strip_prefix("ROT") {
                        self.rot10 = number(v, false).ok_or_else(|| loc.err(at, format!("expected an angle after ROT, got {}", shown(v))))?;
                    }
                }
                self.update_frame(core);
                let r = self.rot10;
                if r != 0.0 {
                    log.note("hei-rot", NoteKind::Frame, no, || format!("line {no}: CYCL DEF 10 ROTATION turns the program by {r}° about the tool axis through the datum: applied to the points after it"));
                }
                Ok(())
            }
            19 => {
                // 19.0 names the cycle; 19.1 gives its angles. With none, or all 0, it tilts
                // nothing: the reset a post writes before it starts (iTNC 530 User's Manual:
                // cycle 19 reset by programming it again with every rotary angle 0).
                if minor == "0" {
                    return Ok(());
                }
                // Anything but rotary angles of 0 (an angle, a feed F for the automatic
                // positioning of the rotary axes) is refused.
                let zero = |w: &&str| {
                    w.starts_with(['A', 'B', 'C', 'a', 'b', 'c'])
                        && number(&w[1..], false) == Some(0.0)
                };
                if !words.iter().all(zero) {
                    return Err(loc.err(at, "CYCL DEF 19 WORKING PLANE tilts by angles that mean machine axes or spatial angles depending on the machine's configuration; post the program with PLANE SPATIAL, M128/FUNCTION TCPM or as CL data"));
                }
                log.skip("working plane resets (CYCL DEF 19 with no angle)", no);
                Ok(())
            }
            8 | 11 | 26 => Err(loc.err(at, format!("CYCL DEF {major} mirrors or scales the program's coordinates; the calculator reads them unscaled: post the program without it"))),
            247 => {
                core.break_next = true;
                log.note("hei-preset", NoteKind::Break, no, || format!("line {no}: CYCL DEF 247 DATUM SETTING selects another preset, whose place the file does not state: the path breaks there"));
                Ok(())
            }
            9 | 32 | 332 | 392 => {
                log.skip("settings cycles (CYCL DEF 9, 32 TOLERANCE …)", no);
                Ok(())
            }
            _ => {
                if minor == "0" {
                    let name = body
                        .split_whitespace()
                        .skip(3)
                        .take_while(|w| !w.contains('=')) // up to the first parameter, `Q200=2`
                        .collect::<Vec<_>>()
                        .join(" ");
                    self.cycle = Some((major, name));
                }
                log.skip("cycle definitions (CYCL DEF)", no);
                Ok(())
            }
        }
    }

    /// `PLANE …`.
    #[allow(clippy::too_many_arguments)]
    fn plane(
        &mut self,
        core: &mut Core,
        no: u32,
        body: &str,
        at: usize,
        u: &str,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let words: Vec<&str> = u.split_whitespace().collect();
        let kind = words.get(1).copied().unwrap_or("");
        let get = |name: &str| -> Result<Option<f64>> {
            for w in &words[2..] {
                if let Some(v) = w.strip_prefix(name) {
                    if v.starts_with(['+', '-', '.']) || v.starts_with(|c: char| c.is_ascii_digit())
                    {
                        return number(v, false).map(Some).ok_or_else(|| {
                            loc.err(
                                at,
                                format!("expected a number after {name}, got {}", shown(v)),
                            )
                        });
                    }
                }
            }
            Ok(None)
        };
        let need = |name: &str| -> Result<f64> {
            get(name)?.ok_or_else(|| loc.err(at, format!("PLANE {kind} needs {name}")))
        };
        let deg = |x: f64| x.to_radians();
        let r = match kind {
            "RESET" => {
                if words.iter().any(|w| matches!(*w, "MOVE" | "TURN")) {
                    core.pos[3] = 0.0;
                    core.pos[4] = 0.0;
                }
                None
            }
            "SPATIAL" => {
                let (a, b, c) = (need("SPA")?, need("SPB")?, need("SPC")?);
                Some(rotation(Axis::Z, deg(c)) * rotation(Axis::Y, deg(b)) * rotation(Axis::X, deg(a)))
            }
            "EULER" => {
                let (p, n, r) = (need("EULPR")?, need("EULNU")?, need("EULROT")?);
                Some(rotation(Axis::Z, deg(p)) * rotation(Axis::X, deg(n)) * rotation(Axis::Z, deg(r)))
            }
            "VECTOR" => {
                let bv = Vector3::new(need("BX")?, need("BY")?, need("BZ")?);
                let nv = Vector3::new(need("NX")?, need("NY")?, need("NZ")?);
                let z = super::lex::unit(&nv).ok_or_else(|| loc.err(at, "PLANE VECTOR's normal NX NY NZ must not be zero"))?;
                let y = z.cross(&bv).try_normalize(1e-12).ok_or_else(|| loc.err(at, "PLANE VECTOR's base vector must not be parallel to its normal"))?;
                let x = y.cross(&z);
                Some(Matrix3::from_columns(&[x, y, z]))
            }
            "RELATIV" => {
                let cur = self.tilt.unwrap_or_else(Matrix3::identity);
                let turn = match (get("SPA")?, get("SPB")?, get("SPC")?) {
                    (Some(a), None, None) => rotation(Axis::X, deg(a)),
                    (None, Some(b), None) => rotation(Axis::Y, deg(b)),
                    (None, None, Some(c)) => rotation(Axis::Z, deg(c)),
                    _ => return Err(loc.err(at, "PLANE RELATIV needs one angle, SPA, SPB or SPC")),
                };
                Some(cur * turn)
            }
            _ => return Err(loc.err(at, format!("PLANE {kind} defines the plane in a way the reader does not read; post the program with PLANE SPATIAL, M128/FUNCTION TCPM or as CL data"))),
        };
        // A shift programmed in the plane before stays where it is (in workpiece axes).
        if let Some(t) = self.tilt {
            if self.datum_tilted != Vector3::zeros() {
                self.datum += t * self.datum_tilted;
                self.datum_tilted = Vector3::zeros();
                log.note("hei-datum-fold", NoteKind::Frame, no, || format!("line {no}: a new working plane while a datum shift programmed in the tilted plane is active: the datum is kept where it is"));
            }
        }
        self.tilt = r.filter(|m| (m - Matrix3::identity()).amax() > 1e-12);
        core.tilt_override = false;
        self.update_frame(core);
        if let Some(m) = r {
            if u.contains("STAY") {
                self.stay_angles(core, &m, u, no);
            }
            if self.tilt.is_none() {
                log.note("hei-plane-none", NoteKind::Frame, no, || format!("line {no}: PLANE {kind} with zero angles: no tilt, the working plane is the workpiece's"));
            }
            if self.tilt.is_some() {
                let text = body
                    .split_whitespace()
                    .take(5)
                    .collect::<Vec<_>>()
                    .join(" ");
                let z: Vector3<f64> = m.column(2).into();
                log.note("hei-plane", NoteKind::Frame, no, || format!("line {no}: {text} tilts the working plane (tool axis ({:.6}, {:.6}, {:.6})): the points after it are read in it and the tool axis is its z axis (PLANE RESET cancels)", z.x, z.y, z.z));
            }
        }
        Ok(())
    }

    /// `PLANE … STAY`: the control leaves the rotary angles in Q120 (A), Q121 (B), Q122 (C);
    /// solved on the machine (the smallest tilt; `SEQ+`/`SEQ−` the tilting axis's sign).
    fn stay_angles(&mut self, core: &Core, m: &Matrix3<f64>, u: &str, no: u32) {
        let dir: Vector3<f64> = m.column(2).into();
        let Ok(o) = core
            .model
            .orientations(&dir, BranchRule::SmallestTilt, None)
        else {
            return;
        };
        let seq = if u.contains("SEQ-") {
            Some(false)
        } else if u.contains("SEQ+") {
            Some(true)
        } else {
            None
        };
        let pick = o
            .solutions
            .iter()
            .filter(|c| c.in_travel)
            .find(|c| seq.map_or(true, |pos| (c.m >= -1e-12) == pos))
            .or_else(|| o.chosen.map(|i| &o.solutions[i]));
        for q in [120, 121, 122] {
            self.q.insert(q, Q::Computed(no));
        }
        if let Some(c) = pick {
            for (i, v) in [(0, c.k), (1, c.m)] {
                let letter = core.letters[i];
                let q = 120 + (letter as u8 - b'A') as u32;
                self.q.insert(q, Q::Number(v.to_degrees()));
            }
        }
    }

    /// The shifts a datum shift's words give: `(axis 0..3 for X Y Z, incremental, value)`. A
    /// shift of a rotary axis (`C+90`: the control turns the axis's zero) is refused, not
    /// dropped: the reader moves the workpiece frame along X, Y and Z only. (A parallel axis,
    /// U V W, is refused by [`Self::axis_value`].)
    fn datum_words(
        &self,
        words: &[&str],
        what: &str,
        loc: &Loc,
        at: usize,
    ) -> Result<Vec<(usize, bool, f64)>> {
        let mut shifts = Vec::new();
        for w in words {
            if let Some((i, inc, v)) = self.axis_value(w, loc, at)? {
                // X Y Z are 0 1 2; the rotary axes come after.
                if i > 2 {
                    return Err(loc.err(at, format!("{what} {} shifts a rotary axis, which the reader does not apply; post the program with that axis's positions written with the shift", shown(w))));
                }
                shifts.push((i, inc, v));
            }
        }
        Ok(shifts)
    }

    /// A datum shift (`TRANS DATUM`, cycle 7): each `(axis, incremental, value)`. Programmed in
    /// a tilted plane it is along the plane's axes, else along the workpiece's.
    fn shift_datum(
        &mut self,
        core: &mut Core,
        shifts: &[(usize, bool, f64)],
        what: &str,
        no: u32,
        log: &mut Log,
    ) {
        let tilted = self.tilt.is_some();
        let d = if tilted {
            &mut self.datum_tilted
        } else {
            &mut self.datum
        };
        for &(i, inc, v) in shifts {
            d[i] = if inc { d[i] + v } else { v };
        }
        let d = *d;
        self.update_frame(core);
        if d != Vector3::zeros() {
            let along = if tilted {
                "along the tilted plane's axes"
            } else {
                "along the workpiece's axes"
            };
            log.note("hei-datum", NoteKind::Frame, no, || format!("line {no}: {what} moves the datum by ({}, {}, {}) {along}: applied to the points after it", d.x, d.y, d.z));
        }
    }

    /// The frame of the datum shift, the tilted plane, the shift programmed in it and the
    /// rotation: `p ↦ datum + T·(datum_tilted + R₁₀·p)`.
    fn update_frame(&mut self, core: &mut Core) {
        let mut f = Frame::shift(self.datum);
        if let Some(t) = self.tilt {
            f = f.then(&Frame {
                rotation: t,
                origin: t * self.datum_tilted,
            });
        }
        if self.rot10 != 0.0 {
            let axis = match self.tool_plane.unwrap_or(Plane::Xy) {
                Plane::Xy => Axis::Z,
                Plane::Zx => Axis::Y,
                Plane::Yz => Axis::X,
            };
            f = f.then(&Frame {
                rotation: rotation(axis, self.rot10.to_radians()),
                origin: Vector3::zeros(),
            });
        }
        core.frame = f;
        core.tilted = self.tilt.is_some();
    }
}

/// The plane of an arc: from its end words (two of X, Y, Z), else `default`, else XY.
fn plane_of_arc(b: &Block, default: Option<Plane>) -> Plane {
    match (
        b.axes[0].is_some(),
        b.axes[1].is_some(),
        b.axes[2].is_some(),
    ) {
        (true, true, false) => Plane::Xy,
        (true, false, true) => Plane::Zx,
        (false, true, true) => Plane::Yz,
        _ => default.unwrap_or(Plane::Xy),
    }
}

/// The plane's first and second axes (the polar angle runs from the first towards the second).
fn plane_axes(p: Plane) -> (usize, usize) {
    match p {
        Plane::Xy => (0, 1),
        Plane::Zx => (2, 0),
        Plane::Yz => (1, 2),
    }
}

/// The text of a line without its `;` comment (outside quotes).
fn strip_comment(text: &str) -> &str {
    let mut quote = false;
    for (i, c) in text.char_indices() {
        match c {
            '"' => quote = !quote,
            ';' if !quote => return &text[..i],
            _ => {}
        }
    }
    text
}

/// A block's statement: without its block number and a leading `/`.
fn block_body(text: &str) -> &str {
    let t = text.trim_start();
    let t = t.strip_prefix('/').unwrap_or(t).trim_start();
    let t = t.trim_start_matches(|c: char| c.is_ascii_digit());
    t.trim()
}

/// A label's name: a number or a quoted name.
fn label_name(rest: &str) -> String {
    let r = rest.trim();
    if let Some(q) = r.strip_prefix('"') {
        return q.split('"').next().unwrap_or("").to_string();
    }
    r.split_whitespace().next().unwrap_or("").to_string()
}

/// The Q parameter a statement assigns (`Q12 = …`).
fn q_target(lhs: &str) -> Option<u32> {
    let t = lhs.trim();
    let t = t.strip_prefix(['Q', 'q'])?;
    let n: String = t.chars().take_while(|c| c.is_ascii_digit()).collect();
    n.parse().ok()
}
