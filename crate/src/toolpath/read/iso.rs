//! ISO G-code blocks (Fanuc, Haas, and LinuxCNC's plain blocks), read for a stated machine
//! ([`super::nc`] moves the tool). Cited: FANUC Series 30i/300i-MODEL A Descriptions
//! (B-63942EN/02; G43.4/G43.5 p.411, G68.2 p.248); FANUC Series 15i-MB Connection manual
//! (B-63323EN-1/03, p.1053); Haas NGC Mill Operator's Manual (G234 TCPC, G254 DWO, G68); the
//! LinuxCNC G-code reference (`docs/src/gcode/g-code.adoc`, `o-code.adoc`, `overview.adoc`).
//!
//! # Read
//! * Words: a letter and a number (`X12.5`, `x-3`, `G1`, also `X 12.5` and `X=12.5`), run
//!   together or not (`G1X10Y20`); numbers have no exponent. Comments `( … )` and after `;`; a
//!   leading `/` (block delete: the block is read, as with the switch off); `N` block numbers.
//! * `%`: the tape's start and end. Text before the first `%` (a listing header, a program
//!   name) is skipped when it is not NC blocks; after the second `%` nothing is read. `O1000`
//!   and `:1000` program numbers are skipped. `M30`, `M2` and `M99` end the program.
//! * Motion: `G0` rapid, `G1` feed, `G2`/`G3` arcs with `I J K` (incremental from the start;
//!   absolute after `G90.1`) or `R` (LinuxCNC's `P` turns), in `G17`/`G18`/`G19`. Modal.
//! * `G90`/`G91`, `G20`/`G21` (the unit from there on), followed modally.
//! * Tool-centre-point control: `G43.4` (Fanuc type 1: rotary positions), `G43.5` (type 2:
//!   `I J K` the tool axis direction "as seen from the programming coordinate system", kept
//!   when all three are omitted, 0 when some are), Haas `G234` (TCPC) and `G254` (dynamic work
//!   offset: X Y Z follow the rotated table), `M128` (Heidenhain ISO); cancelled by `G49`,
//!   `G43`, `G255`, `M129`.
//! * Frames, applied: `G52 X Y Z` (local shift; `G52 X0 Y0 Z0` cancels), `G92 X Y Z` (the
//!   current position gets these coordinates; `G92.1` cancels), `G68` (rotation in the plane:
//!   `G17 G68 X Y R`, centre in the plane's axes, the current position when omitted, positive R
//!   counter-clockwise; with `I J K`, a rotation by R about that vector through X Y Z),
//!   `G68.2 X Y Z I J K` (tilted working plane: origin, then Euler angles Z, X′, Z″; the tool
//!   axis is the plane's z axis), all cancelled by `G69`.
//! * `G28`, `G30` (return through an intermediate point to the reference position), `G53`
//!   (machine coordinates, this block), `M91`/`M92` (Heidenhain ISO): the axes named go where
//!   the file does not say; the path breaks until they are given again (a note).
//! * Work offsets `G54`–`G59`, `G54.1 P…`, `G59.1`–`G59.3`, Haas `G110`–`G129`: the first is
//!   the workpiece frame; another one later breaks the path (its place is not in the file; a
//!   note).
//! * Drilling cycles `G73`, `G74`, `G76`, `G81`–`G89` (cancelled by `G80` or a `G0`–`G3`):
//!   each position is a rapid point, the strokes are not drawn (a note), `Z` and `R` are the
//!   cycle's.
//! * `G41`/`G42` (radius compensation): the path is read as programmed (a note).
//!
//! # Skipped and counted
//! Feeds (`F`, `E`), spindle (`S`, `M3`–`M5`), tools (`T`, `H`, `D`, `M6`), coolant, stops
//! (`M0`, `M1`), other M-functions, dwells (`G4`, whose `X`/`P` is a time), path and feed
//! modes (`G5.1`, `G61`, `G64`, `G187`, `G93`–`G95`, `G98`, `G99` …), `G10` tool data, `G53.1`
//! (after `G68.2`), `G40`, `G80`; G-codes the reader does not know are listed as such.
//!
//! # Refused, with the line and why
//! Macro variables and expressions (`#1`, `#<name>`, `[ … ]`), macro statements (`IF`,
//! `WHILE`, `GOTO`), LinuxCNC `o`-words (subroutines, loops, conditions), subprogram and macro
//! calls (`M98`, `M97`, `G65`, `G66`), polar coordinates (`G16`), scaling and mirroring (`G51`,
//! `G51.1`), `G10 L2`/`L20` (a work offset changed by the program), `G68.2` with `P` other
//! than 0 and `G68.3`/`G68.4`, `U V W` axes, a rotary word that is not one of the machine's,
//! an arc without centre or radius or whose end is off its circle, a keyword of another dialect
//! (`TRAORI`, `FMAX`).

use super::frame::Frame;
use super::lex::{number, number_len, shown, Loc, Seg};
use super::nc::{Block, Core, Mode, Plane, Word};
use super::{LengthUnit, Log, NoteKind, Point};
use crate::error::Result;
use crate::geometry::{rotation, Axis};
use nalgebra::{Rotation3, Unit, Vector3};

/// Lines held before the first `%` at most, while it is not known whether they are a leader.
const LEADER_LINES: usize = 200;

/// The ISO reader's own state.
#[derive(Debug, Clone, Default)]
pub struct Iso {
    /// Lines read before the first `%`, held until it is clear whether they are a tape leader.
    held: Vec<(u32, String)>,
    /// A `%` or a block has been read: no more holding.
    started: bool,
    /// `%` lines seen.
    percents: u32,
    /// The active drilling cycle, if any (its G code × 10).
    cycle: Option<i64>,
    /// The work offset in use (its G code × 10, and P for G54.1).
    offset: Option<(i64, i64)>,
    /// A point has been written (a new work offset then breaks the path).
    any_point: bool,
    /// The program's first block (other than comments) has been read: a later O and a letter
    /// is not its name.
    named: bool,
    /// G52 shift, G92 shift (mm: they stay where they are when the unit changes).
    local: Vector3<f64>,
    g92: Vector3<f64>,
    /// G68 rotation (mm).
    rotation: Option<Frame>,
    /// G68.2 tilted plane (mm).
    tilt: Option<Frame>,
    /// G90.1: arc centres absolute.
    centre_absolute: bool,
    /// G43.5: I J K are the tool axis.
    ijk_vector: bool,
    /// A HEIDENHAIN DIN/ISO program (`%NAME G71`): G70/G71 are units, G200… cycles.
    heidenhain: bool,
    /// DIN/ISO: the last arc centre (modal there).
    last_centre: [Option<Word>; 3],
    /// G99: a drilling cycle returns to its R plane (G98, the default: to the level it
    /// started from).
    to_r: bool,
    /// The drilling cycle's R plane, as last written (modal in the cycle).
    cycle_r: Option<f64>,
}

/// One word of a block.
#[derive(Debug, Clone, Copy)]
struct Tok {
    letter: char,
    value: f64,
    /// Byte offset of the letter.
    at: usize,
    /// Byte offset of the number.
    num_at: usize,
}

impl Iso {
    pub(super) fn line(
        &mut self,
        core: &mut Core,
        text: &str,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let t = text.trim();
        if self.percents >= 2 {
            if !t.is_empty() {
                log.skip("text after the end of the program", no);
            }
            return Ok(());
        }
        if t.starts_with('%') {
            if self.percents == 0 {
                self.heidenhain_header(core, t, no, log);
            }
            self.percents += 1;
            if !self.started {
                self.started = true;
                let held = std::mem::take(&mut self.held);
                // Blocks, the first of them (comments apart) perhaps the program's name.
                let first = held
                    .iter()
                    .position(|(_, l)| !l.trim_start().starts_with(['(', ';']));
                let block = |(i, (n, l)): (usize, &(u32, String))| {
                    lex(l, *n).is_ok() || Some(i) == first && program_name(l.trim_start())
                };
                if held.iter().enumerate().all(block) {
                    // The lines before are blocks: they are read, and this `%` is the end.
                    self.replay(core, held, log, out)?;
                    if !self.any_point && self.percents == 1 {
                        return Ok(()); // only settings before it: a start after all
                    }
                    self.percents = 2;
                } else {
                    for (n, _) in &held {
                        log.skip("text before the first % (a listing header)", *n);
                    }
                }
            }
            return Ok(());
        }
        if !self.started {
            if t.is_empty() {
                return Ok(());
            }
            self.held.push((no, text.to_string()));
            if self.held.len() >= LEADER_LINES {
                self.started = true;
                let held = std::mem::take(&mut self.held);
                self.replay(core, held, log, out)?;
            }
            return Ok(());
        }
        self.block(core, text, no, log, out)
    }

    /// `%NAME G71` (or `G70`) opens a HEIDENHAIN DIN/ISO program (TNC 640 DIN/ISO manual,
    /// "%NAME G71 *"): G71 is millimetres and G70 inches (not Fanuc's turning cycles), and an
    /// arc's I J K are its centre's absolute coordinates, as the TNC's CC.
    fn heidenhain_header(&mut self, core: &mut Core, t: &str, no: u32, log: &mut Log) {
        let words: Vec<&str> = t[1..].trim_end_matches('*').split_whitespace().collect();
        let unit = match words.as_slice() {
            [_, g] | [g] if g.eq_ignore_ascii_case("G71") => LengthUnit::Mm,
            [_, g] | [g] if g.eq_ignore_ascii_case("G70") => LengthUnit::Inch,
            _ => return,
        };
        self.heidenhain = true;
        self.centre_absolute = true;
        core.state_unit(
            unit,
            no,
            if unit == LengthUnit::Mm {
                "%… G71 (HEIDENHAIN DIN/ISO)"
            } else {
                "%… G70 (HEIDENHAIN DIN/ISO)"
            },
            log,
        );
        log.note("iso-heidenhain", NoteKind::Partial, no, || {
            format!("line {no}: a HEIDENHAIN DIN/ISO program: arc centres I J K are read as absolute coordinates, and the cycle definitions (G200 …, Q parameters) are skipped")
        });
    }

    pub(super) fn finish(
        &mut self,
        core: &mut Core,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let held = std::mem::take(&mut self.held);
        self.started = true;
        self.replay(core, held, log, out)
    }

    /// Reads the lines held before the first `%` as blocks.
    fn replay(
        &mut self,
        core: &mut Core,
        held: Vec<(u32, String)>,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        for (n, l) in held {
            if core.ended {
                log.skip("text after the end of the program", n);
                continue;
            }
            // The points carry their own lines; the parser counts them with the line that
            // released them.
            self.block(core, &l, n, log, out)?;
        }
        Ok(())
    }

    /// One block.
    fn block(
        &mut self,
        core: &mut Core,
        text: &str,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let segs = [Seg { start: 0, line: no }];
        let loc = Loc::line(text, &segs);
        if self.heidenhain {
            // DIN/ISO: a block ends with `*`; a cycle definition (`G200 DRILLING`) and its
            // parameter lines (`Q200=3.`) change no geometry.
            let code = text
                .split(';')
                .next()
                .unwrap_or("")
                .trim()
                .trim_end_matches('*')
                .trim();
            let body = code
                .trim_start_matches(|c: char| c == 'N' || c.is_ascii_digit())
                .trim_start();
            let is_q = body.starts_with(['Q', 'q']) && body.contains('=');
            // `G200 DRILLING`, or `G200` alone: G and three digits from 2 (read as bytes).
            let digits = body.as_bytes().get(1..4);
            let cycle = body.starts_with(['G', 'g'])
                && digits.is_some_and(|d| d[0] == b'2' && d.iter().all(u8::is_ascii_digit));
            if body.starts_with('%') {
                // `N99999999 %NAME G71 *`: the end of the program.
                core.ended = true;
                log.skip("program ends (M2, M30, M99)", no);
                return Ok(());
            }
            if is_q || cycle {
                log.blocks += 1;
                log.skip(
                    "cycle definitions and their Q parameters (G200 …, Q200=…)",
                    no,
                );
                return Ok(());
            }
            let toks = lex(code, no)?;
            return self.words(core, toks, &loc, no, log, out);
        }
        let t = text.trim_start();
        if !self.named && !t.is_empty() && !t.starts_with(['(', ';']) {
            self.named = true;
            if program_name(t) {
                log.blocks += 1;
                log.skip("program numbers and names (O)", no);
                return Ok(());
            }
        }
        let toks = lex(text, no)?;
        self.words(core, toks, &loc, no, log, out)
    }

    /// The words of one block. `M129` switches tool-centre-point control off at the end of its
    /// block (iTNC 530 DIN/ISO p.290): the block's own move is still under it.
    fn words(
        &mut self,
        core: &mut Core,
        toks: Vec<Tok>,
        loc: &Loc,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let m129 = toks.iter().any(|t| t.letter == 'M' && g10(t.value) == 1290);
        self.block_words(core, toks, loc, no, log, out)?;
        if m129 {
            core.set_tcp(false, no, "M129", log);
        }
        Ok(())
    }

    /// [`Iso::words`] but `M129`.
    fn block_words(
        &mut self,
        core: &mut Core,
        toks: Vec<Tok>,
        loc: &Loc,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        if toks.is_empty() {
            return Ok(());
        }
        log.blocks += 1;
        let gs: Vec<&Tok> = toks.iter().filter(|t| t.letter == 'G').collect();
        let has = |code: i64| gs.iter().any(|t| g10(t.value) == code);
        let word = |letter: char| toks.iter().find(|t| t.letter == letter).copied();
        let at0 = toks[0].at;

        // Refusals first.
        for t in &toks {
            let refuse = |msg: &str| Err(loc.err(t.at, msg.to_string()));
            let code = if matches!(t.letter, 'G' | 'M') {
                g10(t.value)
            } else {
                0
            };
            match (t.letter, code) {
                ('G', 160) => return refuse("G16 switches to polar coordinates (radius and angle); the calculator reads X Y Z: post the program in Cartesian coordinates"),
                ('G', 510) | ('G', 511) => return refuse("the program scales or mirrors its coordinates (G51, G51.1); the calculator reads them unscaled: post the program without scaling or mirroring"),
                ('G', 650) | ('G', 660) | ('G', 661) => return refuse("G65/G66 call a macro: the calculator reads one program as plain blocks; post it with the macro's moves written out"),
                ('G', 683) | ('G', 684) => return refuse("G68.3/G68.4 define the working plane from the tool axis the machine holds, which the file does not state; post the program with tool-centre-point output (G43.4) or as CL data"),
                ('M', 980) | ('M', 970) => return refuse(&format!("M{} calls a subprogram: the calculator reads one program without its subprograms; post the program with them written out", t.value)),
                ('U', _) | ('V', _) | ('W', _) => return refuse(&format!("{} is an axis the calculator does not read (a parallel or incremental axis); the program must move X, Y, Z and the machine's two rotary axes", t.letter)),
                ('A' | 'B' | 'C', _) if core.rotary_index(t.letter).is_none() => return Err(core.not_this_machine(loc, t.at, t.letter)),
                _ => {}
            }
        }
        for t in &toks {
            match t.letter {
                'N' => log.skip("block numbers (N)", no),
                'O' => log.skip("program numbers and names (O)", no),
                'F' | 'E' => log.skip("feeds (F)", no),
                'S' => log.skip("spindle speeds (S)", no),
                'T' | 'H' | 'D' => log.skip("tool numbers and offsets (T, H, D)", no),
                _ => {}
            }
        }

        if has(100) {
            let l = word('L').map(|w| w.value as i64);
            if matches!(l, Some(2) | Some(20)) {
                return Err(loc.err(at0, "G10 L2/L20 changes a work offset in the program: the points after it move by an amount the file does not state; set the offset at the machine and post the program without it"));
            }
            log.skip("tool data set in the program (G10)", no);
            return Ok(());
        }
        if has(40) {
            log.skip("dwells (G4)", no); // its X or P is a time
            return Ok(());
        }

        // Modal settings.
        let mut b = Block {
            at: at0,
            ..Block::default()
        };
        // Plane, unit and distance mode first: they apply to the whole block (`G28 G91 Z0`).
        // The motion mode too: it stays in force after a block whose non-modal code returns
        // early (`G53 G0 Z0`, `G0 G28 G91 Z0`).
        const SETTINGS: [i64; 13] = [0, 10, 20, 30, 170, 180, 190, 200, 210, 900, 910, 901, 911];
        for t in &gs {
            match g10(t.value) {
                0 => (b.mode, self.cycle) = (Some(Mode::Rapid), None),
                10 => (b.mode, self.cycle) = (Some(Mode::Feed), None),
                20 => (b.mode, self.cycle) = (Some(Mode::Cw), None),
                30 => (b.mode, self.cycle) = (Some(Mode::Ccw), None),
                170 => core.plane = Plane::Xy,
                180 => core.plane = Plane::Zx,
                190 => core.plane = Plane::Yz,
                200 => core.state_unit(LengthUnit::Inch, no, "G20", log),
                210 => core.state_unit(LengthUnit::Mm, no, "G21", log),
                900 => core.absolute = true,
                910 => core.absolute = false,
                901 => self.centre_absolute = true,
                911 => self.centre_absolute = false,
                _ => {}
            }
        }
        let mode = b.mode;
        let mut no_move = false;
        let keep_mode = |core: &mut Core| {
            if let Some(m) = mode {
                core.mode = m;
            }
        };
        for t in &gs {
            let code = g10(t.value);
            match code {
                c if SETTINGS.contains(&c) => {}
                434 => core.set_tcp(true, no, "G43.4", log),
                435 => {
                    core.set_tcp(true, no, "G43.5", log);
                    self.ijk_vector = true;
                }
                430 | 440 | 490 => {
                    core.set_tcp(false, no, &format!("G{}", t.value), log);
                    if self.ijk_vector {
                        core.vector = None;
                    }
                    self.ijk_vector = false;
                    log.skip("tool length offsets (G43, G49)", no);
                }
                2340 => core.set_tcp(true, no, "G234 (Haas TCPC)", log),
                2540 => core.set_tcp(true, no, "G254 (Haas dynamic work offset)", log),
                2550 => core.set_tcp(false, no, "G255", log),
                410 | 420 => {
                    log.note("iso-cutcom", NoteKind::Partial, no, || {
                        format!("line {no}: G{} offsets the path by the tool radius (cutter compensation); the points are read as programmed", t.value)
                    });
                }
                730 | 740 | 760 | 810..=890 => {
                    if code % 10 == 0 {
                        self.cycle = Some(code);
                        log.note("iso-cycle", NoteKind::Partial, no, || {
                            format!("line {no}: drilling cycle G{}: its positions are read as rapid points; its strokes are not drawn (the tool axis does not turn in them)", t.value)
                        });
                    }
                }
                800 => self.cycle = None,
                540..=593 | 1100..=1290 | 1540 => {
                    let p = if code == 541 || code == 1540 {
                        word('P').map_or(0, |w| w.value as i64)
                    } else {
                        0
                    };
                    self.work_offset(core, (code, p), t.value, no, log);
                }
                280 | 300 => {
                    let named: Vec<usize> = (0..3)
                        .filter(|&i| word(['X', 'Y', 'Z'][i]).is_some())
                        .collect();
                    let rotary: Vec<usize> =
                        (3..5).filter(|&i| word(core.name(i)).is_some()).collect();
                    let all = named.is_empty() && rotary.is_empty();
                    let axes = if all { vec![0, 1, 2] } else { named };
                    core.forget(&axes);
                    // A rotary axis returns to its reference position, 0°.
                    for i in if all { vec![3, 4] } else { rotary } {
                        core.pos[i] = 0.0;
                    }
                    keep_mode(core);
                    if !axes.is_empty() {
                        log.note("iso-home", NoteKind::Break, no, || {
                            format!("line {no}: G{} returns {} to the reference position, which the file does not state: the path breaks until each is given again (the move back is not analysed)", t.value, names(&axes))
                        });
                    }
                    return Ok(());
                }
                530 => {
                    keep_mode(core);
                    return self.machine_coordinates(core, &toks, "G53", no, log);
                }
                520 => {
                    keep_mode(core);
                    return self.local_shift(core, &toks, no, loc, log);
                }
                920 => {
                    keep_mode(core);
                    return self.g92(core, &toks, no, loc, log);
                }
                921 | 922 => {
                    self.g92 = Vector3::zeros();
                    self.update_frame(core, log);
                    keep_mode(core);
                    return Ok(());
                }
                680 => {
                    keep_mode(core);
                    return self.g68(core, &toks, no, loc, log);
                }
                682 => {
                    keep_mode(core);
                    return self.g68_2(core, &toks, no, loc, log);
                }
                690 => {
                    self.rotation = None;
                    self.tilt = None;
                    core.tilt_override = false;
                    self.update_frame(core, log);
                }
                531 | 536 => log.skip("tool axis direction control (G53.1, G53.6)", no),
                500 | 501 => {
                    // Its X Y Z name the axes whose mirroring ends: not a position.
                    no_move = true;
                    log.skip("scaling and mirroring cancels (G50, G50.1)", no);
                }
                980 | 990 => {
                    self.to_r = code == 990;
                    log.skip("cycle return levels (G98, G99)", no);
                }
                50..=90
                | 610
                | 611
                | 620
                | 630
                | 640
                | 1870
                | 930..=950
                | 400
                | 150
                | 960
                | 970 => log.skip(
                    "path, feed and look-ahead modes (G5.1, G61, G64, G94, G98 …)",
                    no,
                ),
                _ => {
                    log.skip(
                        "G-codes the reader does not know (read as settings without motion)",
                        no,
                    );
                    log.note("iso-unknown-g", NoteKind::Partial, no, || {
                        format!("line {no}: G{} is not a code the reader knows; it is read as a setting without motion (listed under Skipped)", t.value)
                    });
                }
            }
        }
        for t in toks.iter().filter(|t| t.letter == 'M') {
            match g10(t.value) {
                // DIN/ISO: M99 (and the modal M89) call the cycle defined last at the block's
                // end point.
                990 | 890 if self.heidenhain => {
                    log.note("iso-heidenhain-cycle", NoteKind::Partial, no, || {
                        format!("line {no}: M{} calls the cycle defined before it at the block's end point: its moves are not drawn (the tool axis does not turn in them)", t.value)
                    });
                }
                20 | 300 | 990 => {
                    core.ended = true;
                    log.skip("program ends (M2, M30, M99)", no);
                }
                1280 => core.set_tcp(true, no, "M128", log),
                1290 => {} // at the end of the block (`words`)
                // LinuxCNC's switchable-kinematics configurations (configs/sim/axis/vismach/
                // 5axis demos): `M428 ;TCP:xyzac`, `M429 ;Restore Trivkins`.
                4280 => core.set_tcp(
                    true,
                    no,
                    "M428 (LinuxCNC tool-centre-point kinematics)",
                    log,
                ),
                4290 => core.set_tcp(false, no, "M429", log),
                910 | 920 => {
                    keep_mode(core);
                    return self.machine_coordinates(
                        core,
                        &toks,
                        &format!("M{}", t.value),
                        no,
                        log,
                    );
                }
                30 | 40 | 50 | 190 => log.skip("spindle (M3, M4, M5)", no),
                60 => log.skip("tool changes (M6)", no),
                70 | 80 | 90 => log.skip("coolant (M7, M8, M9)", no),
                0 | 10 => log.skip("program stops (M0, M1)", no),
                _ => log.skip("other M-functions", no),
            }
        }
        if no_move {
            keep_mode(core);
            return Ok(());
        }
        // The move.
        if self.cycle.is_none() {
            self.cycle_r = None;
        }
        let in_cycle = self.cycle.is_some() && b.mode.is_none();
        for t in &toks {
            let w = Some(Word {
                value: t.value,
                at: t.num_at,
            });
            match t.letter {
                'X' => b.axes[0] = w,
                'Y' => b.axes[1] = w,
                'Z' => b.axes[2] = w,
                'I' | 'J' | 'K' => {
                    let i = (t.letter as u8 - b'I') as usize;
                    b.centre[i] = w;
                }
                'R' if !in_cycle => b.radius = w,
                'R' => self.cycle_r = Some(t.value),
                'P' if matches!(core.mode, Mode::Cw | Mode::Ccw)
                    || matches!(b.mode, Some(Mode::Cw | Mode::Ccw)) =>
                {
                    b.turns = (t.value.max(1.0) as u32).saturating_sub(1);
                }
                l => {
                    if let Some(i) = core.rotary_index(l) {
                        b.axes[i] = w;
                    }
                }
            }
        }
        let arc_block = matches!(b.mode.unwrap_or(core.mode), Mode::Cw | Mode::Ccw) && !in_cycle;
        if self.ijk_vector && !arc_block {
            let given: Vec<Option<Word>> = b.centre.to_vec();
            if given.iter().any(Option::is_some) {
                let v = Vector3::new(
                    given[0].map_or(0.0, |w| w.value),
                    given[1].map_or(0.0, |w| w.value),
                    given[2].map_or(0.0, |w| w.value),
                );
                let v = super::lex::unit(&v)
                    .ok_or_else(|| loc.err(at0, "the tool axis I J K of G43.5 must not be zero"))?;
                b.vector = Some(v);
            }
            b.centre = [None; 3];
        } else if !arc_block {
            b.centre = [None; 3];
            b.radius = None;
        }
        // DIN/ISO: the centre stays until another is given (the TNC's CC is modal).
        if self.heidenhain && arc_block {
            if b.centre.iter().any(Option::is_some) {
                self.last_centre = b.centre;
            } else if b.radius.is_none() && b.axes.iter().any(Option::is_some) {
                b.centre = self.last_centre;
            }
        }
        b.centre_absolute = self.centre_absolute;
        b.cycle = in_cycle;
        let before = out.len();
        core.execute(&b, loc, log, out)?;
        if out.len() > before {
            self.any_point = true;
            // G99: the cycle ends on its R plane, so the next move starts there.
            if let (true, true, true, Some(r)) = (in_cycle, self.to_r, core.absolute, self.cycle_r)
            {
                let mut up = Block {
                    at: at0,
                    rapid_once: true,
                    ..Block::default()
                };
                up.axes[2] = Some(Word { value: r, at: at0 });
                core.execute(&up, loc, log, out)?;
            }
        }
        Ok(())
    }

    /// A new work offset: the first is the workpiece frame, another breaks the path.
    fn work_offset(
        &mut self,
        core: &mut Core,
        code: (i64, i64),
        value: f64,
        no: u32,
        log: &mut Log,
    ) {
        if self.offset.is_some_and(|o| o != code) && self.any_point {
            core.break_next = true;
            log.note("iso-offset", NoteKind::Break, no, || {
                format!("line {no}: G{value} selects another work offset, whose place the file does not state: the points after it are read in it, and the move into it is not analysed")
            });
        }
        self.offset = Some(code);
    }

    /// `G53`, `M91`, `M92`: the axes of the block move in machine coordinates.
    fn machine_coordinates(
        &mut self,
        core: &mut Core,
        toks: &[Tok],
        what: &str,
        no: u32,
        log: &mut Log,
    ) -> Result<()> {
        let axes: Vec<usize> = (0..3)
            .filter(|&i| toks.iter().any(|t| t.letter == ['X', 'Y', 'Z'][i]))
            .collect();
        for t in toks {
            if let Some(i) = core.rotary_index(t.letter) {
                core.pos[i] = t.value; // rotary positions are the same in every frame
            }
        }
        if !axes.is_empty() {
            core.forget(&axes);
            log.note("iso-machine", NoteKind::Break, no, || {
                format!("line {no}: {what} moves {} in machine coordinates, which the file does not relate to the part: the path breaks until each is given again", names(&axes))
            });
        }
        Ok(())
    }

    /// `G52`: a local shift.
    fn local_shift(
        &mut self,
        core: &mut Core,
        toks: &[Tok],
        no: u32,
        _loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let mm = log.scale().0;
        for t in toks {
            if let Some(i) = "XYZ".find(t.letter) {
                self.local[i] = t.value * mm;
            }
        }
        self.update_frame(core, log);
        let s = self.local / mm;
        if s != Vector3::zeros() {
            log.note("iso-g52", NoteKind::Frame, no, || {
                format!("line {no}: G52 shifts the program's origin to ({}, {}, {}): applied to the points after it", s.x, s.y, s.z)
            });
        }
        Ok(())
    }

    /// `G92`: the current position gets the block's coordinates.
    fn g92(
        &mut self,
        core: &mut Core,
        toks: &[Tok],
        no: u32,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        for t in toks {
            if let Some(i) = "XYZ".find(t.letter) {
                if !core.known[i] {
                    return Err(loc.err(t.at, format!("G92 gives the tool's position a new value, but the file does not say where the tool is in {}", t.letter)));
                }
                // p_old = p_new + d, d = pos_old − value: the origin moves by d.
                let d = core.pos[i] - t.value;
                self.g92[i] += d * log.scale().0;
                core.pos[i] = t.value;
            } else if core.rotary_index(t.letter).is_some() {
                return Err(loc.err(t.at, "G92 on a rotary axis renumbers its angles: the commands after it no longer give the tool axis; post the program without it"));
            }
        }
        self.update_frame(core, log);
        let d = self.g92 / log.scale().0;
        log.note("iso-g92", NoteKind::Frame, no, || {
            format!("line {no}: G92 sets the current position: the program's origin moves by ({}, {}, {}); applied", d.x, d.y, d.z)
        });
        Ok(())
    }

    /// `G68`: rotation in the plane, or about `I J K`.
    fn g68(
        &mut self,
        core: &mut Core,
        toks: &[Tok],
        no: u32,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let get = |l: char| toks.iter().find(|t| t.letter == l).map(|t| t.value);
        let r = get('R').ok_or_else(|| {
            loc.err(toks[0].at, "G68 without R takes its angle from a setting of the control, which the file does not state; expected G68 X… Y… R…")
        })?;
        let cur = |i: usize| if core.known[i] { core.pos[i] } else { 0.0 };
        let centre = Vector3::new(
            get('X').unwrap_or(cur(0)),
            get('Y').unwrap_or(cur(1)),
            get('Z').unwrap_or(cur(2)),
        );
        let angle = r.to_radians();
        let (frame, about) = match (get('I'), get('J'), get('K')) {
            (None, None, None) => {
                let axis = Axis::ALL[core.plane.normal()];
                let mut c = centre;
                // Only the plane's two coordinates are the centre.
                c[core.plane.normal()] = 0.0;
                (
                    Frame::rotation_about(axis, angle, c),
                    format!(
                        "about {} through ({}, {}, {})",
                        axis.letter(),
                        c.x,
                        c.y,
                        c.z
                    ),
                )
            }
            (i, j, k) => {
                let v = Vector3::new(i.unwrap_or(0.0), j.unwrap_or(0.0), k.unwrap_or(0.0));
                let v = super::lex::unit(&v)
                    .ok_or_else(|| loc.err(toks[0].at, "G68's axis I J K must not be zero"))?;
                let rot = Rotation3::from_axis_angle(&Unit::new_unchecked(v), angle).into_inner();
                (
                    Frame {
                        rotation: rot,
                        origin: centre - rot * centre,
                    },
                    format!(
                        "about ({}, {}, {}) through ({}, {}, {})",
                        v.x, v.y, v.z, centre.x, centre.y, centre.z
                    ),
                )
            }
        };
        self.rotation = Some(frame.scaled(log.scale().0));
        self.update_frame(core, log);
        log.note("iso-g68", NoteKind::Frame, no, || {
            format!("line {no}: G68 turns the program by {r}° {about}: applied to the points after it (G69 cancels)")
        });
        Ok(())
    }

    /// `G68.2 X Y Z I J K`: the tilted working plane.
    fn g68_2(
        &mut self,
        core: &mut Core,
        toks: &[Tok],
        no: u32,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let get = |l: char| toks.iter().find(|t| t.letter == l).map(|t| t.value);
        if let Some(p) = get('P') {
            if p != 0.0 {
                return Err(loc.err(toks[0].at, format!("G68.2 P{p} defines the plane another way than by Euler angles (P0), which the reader does not read; post the program with tool-centre-point output (G43.4) or as CL data")));
            }
        }
        let o = Vector3::new(
            get('X').unwrap_or(0.0),
            get('Y').unwrap_or(0.0),
            get('Z').unwrap_or(0.0),
        );
        let (a, b, c) = (
            get('I').unwrap_or(0.0),
            get('J').unwrap_or(0.0),
            get('K').unwrap_or(0.0),
        );
        // Euler angles Z, X′, Z″ (FANUC 30i, 5.44): R = Rz(α)·Rx(β)·Rz(γ).
        let r = rotation(Axis::Z, a.to_radians())
            * rotation(Axis::X, b.to_radians())
            * rotation(Axis::Z, c.to_radians());
        self.tilt = Some(Frame {
            rotation: r,
            origin: o * log.scale().0,
        });
        core.tilt_override = false;
        self.update_frame(core, log);
        log.note("iso-g68.2", NoteKind::Frame, no, || {
            format!("line {no}: G68.2 tilts the working plane: origin ({}, {}, {}), Euler angles {a}°, {b}°, {c}° (Z, X′, Z″); the points after it are read in that plane and the tool axis is its z axis (G69 cancels)", o.x, o.y, o.z)
        });
        Ok(())
    }

    /// The frame of the active shifts, rotation and tilted plane.
    fn update_frame(&mut self, core: &mut Core, log: &Log) {
        let k = 1.0 / log.scale().0; // file units per mm
        let mut f = Frame::shift((self.local + self.g92) * k);
        if let Some(t) = self.tilt {
            f = f.then(&t.scaled(k));
        }
        if let Some(r) = self.rotation {
            f = f.then(&r.scaled(k));
        }
        core.frame = f;
        core.tilted = self.tilt.is_some();
    }
}

/// `G` or `M` code × 10, rounded (G43.4 → 434). Ties to even: a code has one decimal, so
/// `v × 10` is never halfway, and this rounding is one instruction in WebAssembly (`round`, ties
/// away from zero, is a library call there, and this runs for every word of every block).
fn g10(v: f64) -> i64 {
    (v * 10.0).round_ties_even() as i64
}

/// "X, Y and Z" of axis indices.
fn names(axes: &[usize]) -> String {
    let l: Vec<&str> = axes.iter().map(|&i| ["X", "Y", "Z"][i]).collect();
    match l.len() {
        0 => String::new(),
        1 => l[0].to_string(),
        n => format!("{} and {}", l[..n - 1].join(", "), l[n - 1]),
    }
}

/// The words of a block (comments, block delete and program numbers removed), or why the line
/// is not an ISO block.
fn lex(line: &str, no: u32) -> Result<Vec<Tok>> {
    let segs = [Seg { start: 0, line: no }];
    let loc = Loc::line(line, &segs);
    let b = line.as_bytes();
    let mut toks = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        match c {
            b' ' | b'\t' => i += 1,
            b'(' => {
                // A comment, to its matching `)` (posts nest them: `(#508= (NAME))`).
                let mut depth = 0;
                while i < b.len() {
                    match b[i] {
                        b'(' => depth += 1,
                        b')' => depth -= 1,
                        _ => {}
                    }
                    i += 1;
                    if depth == 0 {
                        break;
                    }
                }
            }
            b';' => break,
            b'/' if toks.is_empty() => i += 1,
            b':' if toks.is_empty() => break, // `:1000`, a program number
            b'#' => return Err(loc.err(i, "# marks a macro variable (#1, #<name>): the calculator reads plain numbers; post the program without macros or parameters")),
            b'[' => return Err(loc.err(i, "[ … ] is an expression: the calculator reads plain numbers; post the program without macros or parameters")),
            c if c.is_ascii_alphabetic() => {
                let run = b[i..].iter().take_while(|c| c.is_ascii_alphabetic()).count();
                let letter = c.to_ascii_uppercase() as char;
                if letter == 'O' && toks.is_empty() {
                    // O1000 (a program number) or a LinuxCNC o-word.
                    let rest = &line[i + 1..];
                    let rest_t = rest.trim_start();
                    if rest_t.starts_with('<') || rest_t.starts_with('[') {
                        return Err(o_word(&loc, i));
                    }
                    let n = number_len(rest_t.as_bytes());
                    let after = rest_t[n..].trim_start().to_ascii_lowercase();
                    const O_WORDS: [&str; 15] = ["sub", "endsub", "call", "do", "while", "endwhile", "if", "elseif", "else", "endif", "repeat", "endrepeat", "return", "break", "continue"];
                    if O_WORDS.iter().any(|w| after.starts_with(w) && !after[w.len()..].starts_with(|c: char| c.is_ascii_alphabetic())) {
                        return Err(o_word(&loc, i));
                    }
                    if run == 1 {
                        // A program number or name (`O1000`, `O1000 (NAME)`, a post's `O ENTER …`
                        // placeholder); the rest of the line is not read.
                        toks.push(Tok { letter: 'O', value: 0.0, at: i, num_at: i });
                        break;
                    }
                }
                if run >= 2 {
                    let word = line[i..i + run].to_ascii_uppercase();
                    let msg = if matches!(word.as_str(), "IF" | "WHILE" | "GOTO" | "DO" | "END" | "THEN" | "EQ" | "NE" | "GT" | "LT" | "GE" | "LE" | "AND" | "OR" | "SIN" | "COS" | "TAN" | "ATAN" | "SQRT" | "ABS" | "ROUND" | "FIX" | "FUP") {
                        format!("{word} is a macro statement (Fanuc Macro B, LinuxCNC): the calculator reads plain blocks; post the program without macros")
                    } else {
                        format!("{} is not ISO G-code (a keyword of another dialect, such as Siemens' TRAORI or Heidenhain's FMAX?): choose the file's dialect in the format field", shown(&line[i..i + run]))
                    };
                    return Err(loc.err(i, msg));
                }
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
                if b.get(i) == Some(&b'#') {
                    return Err(loc.err(i, "# marks a macro variable (#1, #<name>): the calculator reads plain numbers; post the program without macros or parameters"));
                }
                if b.get(i) == Some(&b'[') {
                    return Err(loc.err(i, "[ … ] is an expression: the calculator reads plain numbers; post the program without macros or parameters"));
                }
                let from = i;
                let n = number_len(&b[i..]);
                // A number followed by more number characters (`1.2.3`, `1,5`) is not one.
                let mut end = i + n;
                while end < b.len() && matches!(b[end], b'0'..=b'9' | b'.' | b',' | b'+' | b'-') {
                    end += 1;
                }
                let tok = &line[from..end];
                if tok.is_empty() {
                    let next = line[from..].split_whitespace().next();
                    let got = next.map_or("the end of the line".to_string(), shown);
                    return Err(loc.err(at, format!("expected a number after {letter}, got {got}")));
                }
                let value = number(tok, false).ok_or_else(|| {
                    loc.err(from, format!("expected a number after {letter}, got {}", shown(tok)))
                })?;
                i = end;
                toks.push(Tok { letter, value, at, num_at: from });
            }
            _ => {
                let got: String = line[i..].chars().take(1).collect();
                return Err(loc.err(
                    i,
                    format!("expected a word (a letter and a number, like X12.5), got {}", shown(&got)),
                ));
            }
        }
    }
    Ok(toks)
}

/// The program's first block may be its name where a control reads its O number: NX's Haas
/// posts write the part's name (`Omnf01_vx_0`, `OFinal ToolPath`). O and a letter there is a
/// name, not a word (an o-word has digits or `<` after the O).
fn program_name(t: &str) -> bool {
    t.starts_with(['O', 'o']) && t[1..].starts_with(|c: char| c.is_ascii_alphabetic())
}

/// The refusal of a LinuxCNC o-word.
fn o_word(loc: &Loc, at: usize) -> crate::error::Error {
    loc.err(
        at,
        "o-words (LinuxCNC subroutines, loops and conditions: o100 sub, o<name> call, o101 if) \
         are not read: the calculator reads plain blocks; post the program with them written out",
    )
}
