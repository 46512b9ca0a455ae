//! APT CL data, as NX (CLSF), CATIA, SolidWorks CAM, Mastercam, Creo and other CAM systems
//! write it. Statements, one a line (`$` at the end continues one on the next line, `$$`
//! starts a comment; a comment line ending in `$` continues on the lines of numbers after it,
//! as Creo writes `$$-> CSYS / …, $`), a major word, `/` and comma-separated numbers and minor
//! words, case-insensitive.
//!
//! No public text of ISO 4343 or ANSI X3.37 was at hand; each statement is read as the CAM
//! system that writes it documents it, cited below as: CATIA, "Syntax of Generated APT
//! Instructions" (Dassault Systèmes, NC Generation user guide); Creo, "CL Output for Circular
//! Interpolation" (PTC help); ICAM Post help library, vocabulary "MSYS" and "Matrix functions"
//! (ICAM Technologies, hosted by CGTech); NX GRIP reference, "Transformation matrix"
//! (Siemens). Where no documentation was found, the reading of public CL files and readers is
//! named as such.
//!
//! # Read
//! * `GOTO/x,y,z` and `GOTO/x,y,z,i,j,k` (CATIA): the tool tip, and the tool axis from the tip
//!   towards the spindle; a 3-number `GOTO` keeps the last axis (of a 6-number `GOTO`,
//!   `TLAXIS/i,j,k` or `FROM/`; `(0, 0, 1)` before any). A feed move, or a rapid after
//!   `RAPID` (one-shot: NX, CATIA and SolidWorks CAM write `RAPID` before each rapid `GOTO`).
//! * `FROM/x,y,z[,i,j,k]` (CATIA): the start position, a rapid point.
//! * `GODLTA/dx,dy,dz[,i,j,k]` (CATIA): a move by the increments; `GODLTA/d`: by `d` along the
//!   tool axis.
//! * `CIRCLE/xc,yc,zc,i,j,k,r` (Creo; NX writes 4 more numbers, ignored; 6 numbers: the
//!   radius is the start's distance from the axis; 4 numbers `xc,yc,zc,r`: about the tool
//!   axis): the centre, the axis and the radius of the arc that the next `GOTO`s follow, each
//!   on the circle (a `GOTO` off it is a straight move and ends the arc). The arc is cut into
//!   chords within the chord tolerance, the tool axis turning on its great circle in
//!   proportion. Direction: counter-clockwise about `(i, j, k)` (Creo: "(0,0,1) is
//!   counter-clockwise"), except in NX CLSF (recognised by `TOOL PATH/`, `TLDATA/`, `MSYS/` or
//!   `PAINT/`), whose arcs turn clockwise about it (NX Post Builder: "UG arc axis is opposite of
//!   ISO standard"; the public NX sample arcs are clockwise about (0, 0, 1)).
//! * `UNITS/MM`, `UNITS/INCHES` (CATIA), `UNIT/MM` (SolidWorks CAM): the unit from there on.
//!   `FEDRAT/…,IPM` or `IPR` (either order, CATIA) imply inches where no unit is stated,
//!   `MMPM`, `MMPR` millimetres ([`super::UnitChoice::Auto`]).
//! * Output frames, read as [`super::AptFrameChoice`] says (applied by default: the points
//!   that follow are written in the frame, `p ↦ origin + R·p`):
//!   - `MSYS/x0,y0,z0,xi,xj,xk,yi,yj,yk` (NX): the origin, then the x and y axes (z = x × y)
//!     of the machine coordinate system in the part's absolute frame. No Siemens text was
//!     found; the reading is that of the public NX sample CLSF (its GOTOs are local to the
//!     MSYS origin) and of public CLSF readers.
//!   - `MSYS/` with 12 numbers, `CSYS/` (SolidWorks CAM) and `TRACUT/` with 12 numbers: the
//!     APT matrix `a1 … a12`, rows of `[R | t]` (ICAM "Matrix functions"; NX GRIP: "elements
//!     4, 8 and 12 are the translation"). `TRACUT/NOMORE` cancels `TRACUT`. The matrix must
//!     be a proper rotation.
//!   - CATIA's machining axis system, `$$*CATIA0`, a name line, then three `$$` lines of
//!     `a11 a12 a13 t1` ("in absolute axis").
//! * `CYCLE/…` … `CYCLE/OFF`: each `GOTO` between them is a hole position, read as a rapid
//!   point; the drilling strokes are not drawn (a note says so).
//! * `FINI`: the end; the rest of the file is not read.
//!
//! # Skipped and counted
//! `PARTNO`, `PPRINT`, `INSERT`, `REMARK` (a comment: Creo writes its header in them),
//! `CUTTER`, `TLDATA`, `LOADTL`, `LOAD/TOOL`, `SELECT/TOOL`, `SPINDL`, `COOLNT`, `FEDRAT`,
//! `MULTAX`, `PAINT`, `TOOL PATH`, `END-OF-PATH`, `MACHIN`, `CLPRNT`, `INTOL`, `OUTTOL`,
//! `TOLER`, `PPWORD` (Creo's post-processor vocabulary table), `DELAY`, `OPSTOP`, `STOP`,
//! `AUXFUN`, `PREFUN`, `SEQNO`, `CUTCOM` (radius compensation, noted), SolidWorks' `CSI_…`,
//! `TRNTYP`. Any other statement is skipped and listed as not known to the reader.
//!
//! # Refused
//! `NURBS/` (a spline the control interpolates); `GOTO` with other than 3 or 6 numbers (no
//! documentation defines them); `ROTABL`, `ROTATE` (the table turns: the points after it are
//! in a frame the file does not state); APT part-program (source) language (`INDIRV`, `TLON`,
//! `GOFWD`, `GOLFT`, `GORGT`, `GOBACK`, `GOUP`, `GODOWN`, `PSIS`); `MSYS/`, `CSYS/` or `TRACUT/`
//! whose numbers are not a frame; a continuation `$` on the last line.

use super::frame::{arc, ArcError, Frame};
use super::lex::{shown, unit, unit_axis, Fields, Loc, Seg, MAX_COORDINATE, NAMES};
use super::{
    AptFrameChoice, FrameFound, LengthUnit, Log, Motion, NoteKind, Point, FIELD, MAX_LINE,
};
use crate::error::{Error, Result};
use crate::toolpath::slerp;
use nalgebra::Vector3;

/// Whether a (trimmed) line is an APT statement, for [`super::Format::detect`]: a `$$`
/// comment, a major word of two or more letters (spaces and `-` allowed) followed by `/`, or a
/// word that stands alone in APT (`RAPID`, `FINI` or `MULTAX`, and `PARTNO`, `PPRINT` or
/// `REMARK`, alone or followed by text).
pub(super) fn is_statement(l: &str) -> bool {
    if l.starts_with("$$") {
        return true;
    }
    if let Some(slash) = l.find('/') {
        let major = l[..slash].trim();
        if major.len() >= 2
            && major.starts_with(|c: char| c.is_ascii_alphabetic())
            && major
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == ' ' || c == '-' || c == '_')
            && major.chars().filter(|c| c.is_ascii_alphabetic()).count() >= 2
        {
            return true;
        }
    }
    let word: String = l
        .chars()
        .take_while(|c| c.is_ascii_alphabetic())
        .collect::<String>()
        .to_ascii_uppercase();
    let rest = l[word.len()..].trim();
    matches!(word.as_str(), "RAPID" | "FINI" | "MULTAX") && rest.is_empty()
        || matches!(word.as_str(), "PARTNO" | "PPRINT" | "REMARK")
            && (rest.is_empty() || l[word.len()..].starts_with(' '))
}

/// Points of an arc and their tool axes.
type Chords = Vec<(Vector3<f64>, Vector3<f64>)>;

/// The arc that `GOTO`s follow after a `CIRCLE/` (file unit, the statement's own frame).
#[derive(Debug, Clone, Copy)]
struct Circle {
    centre: Vector3<f64>,
    normal: Vector3<f64>,
    /// `None`: the start's distance from the axis.
    radius: Option<f64>,
}

/// A CATIA matrix being read from `$$` lines.
#[derive(Debug, Clone)]
struct CatiaMatrix {
    line: u32,
    /// `$$` lines still to skip before the rows (the name line).
    name_pending: bool,
    rows: Vec<[f64; 4]>,
}

/// The APT reader.
#[derive(Debug, Clone)]
pub struct Apt {
    /// The current tool axis (unit, the statements' own frame).
    axis: Vector3<f64>,
    /// A statement continued with `$`, so far (without the `$`s).
    stmt: String,
    /// Where the pieces of `stmt` come from; empty when no statement is pending.
    segs: Vec<Seg>,
    /// Line and column of the last continuation `$`.
    dollar: (u32, usize),
    /// `FINI` was read.
    fini: bool,
    /// The last position (file unit, the statements' own frame).
    pos: Option<Vector3<f64>>,
    /// The FROM/ point (GOHOME returns to it).
    home: Option<Vector3<f64>>,
    /// The next motion is a rapid.
    rapid_next: bool,
    /// The arc the next `GOTO`s follow.
    circle: Option<Circle>,
    /// A drilling cycle is on: its name.
    cycle: Option<String>,
    /// The output frame (MSYS/, CSYS/, CATIA's matrix).
    output: Frame,
    /// TRACUT's matrix.
    tracut: Frame,
    /// NX CLSF recognised: arcs turn clockwise about their axis.
    nx: bool,
    /// CATIA's matrix being read.
    catia: Option<CatiaMatrix>,
    /// The last line was a `$$` comment ending in `$`: a next line of numbers is more of it.
    comment_continues: bool,
}

impl Default for Apt {
    fn default() -> Self {
        Apt {
            axis: Vector3::z(),
            stmt: String::new(),
            segs: Vec::new(),
            dollar: (0, 0),
            fini: false,
            pos: None,
            home: None,
            rapid_next: false,
            circle: None,
            cycle: None,
            output: Frame::IDENTITY,
            tracut: Frame::IDENTITY,
            nx: false,
            catia: None,
            comment_continues: false,
        }
    }
}

/// Statements skipped because they change no geometry: major word and the kind it is counted
/// under.
const SKIPPED: [(&str, &str); 30] = [
    (
        "PARTNO",
        "names and comments (PARTNO, PPRINT, INSERT, REMARK)",
    ),
    (
        "PPRINT",
        "names and comments (PARTNO, PPRINT, INSERT, REMARK)",
    ),
    (
        "INSERT",
        "names and comments (PARTNO, PPRINT, INSERT, REMARK)",
    ),
    (
        "REMARK",
        "names and comments (PARTNO, PPRINT, INSERT, REMARK)",
    ),
    (
        "CUTTER",
        "tool data and tool changes (CUTTER, TLDATA, LOAD/TOOL …)",
    ),
    (
        "TLDATA",
        "tool data and tool changes (CUTTER, TLDATA, LOAD/TOOL …)",
    ),
    (
        "LOADTL",
        "tool data and tool changes (CUTTER, TLDATA, LOAD/TOOL …)",
    ),
    (
        "LOAD",
        "tool data and tool changes (CUTTER, TLDATA, LOAD/TOOL …)",
    ),
    (
        "SELECT",
        "tool data and tool changes (CUTTER, TLDATA, LOAD/TOOL …)",
    ),
    ("SPINDL", "spindle and coolant (SPINDL, COOLNT)"),
    ("COOLNT", "spindle and coolant (SPINDL, COOLNT)"),
    ("FEDRAT", "feeds (FEDRAT)"),
    ("MULTAX", "MULTAX (the GOTOs' count of numbers says it)"),
    ("PAINT", "display (PAINT)"),
    ("TOOL PATH", "operations (TOOL PATH, END-OF-PATH)"),
    ("END-OF-PATH", "operations (TOOL PATH, END-OF-PATH)"),
    (
        "MACHIN",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    (
        "CLPRNT",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    (
        "INTOL",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    (
        "OUTTOL",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    (
        "TOLER",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    (
        "TRNTYP",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    (
        "PPWORD",
        "post-processor and tolerance settings (MACHIN, INTOL, OUTTOL …)",
    ),
    ("DELAY", "stops and dwells (DELAY, OPSTOP, STOP)"),
    ("OPSTOP", "stops and dwells (DELAY, OPSTOP, STOP)"),
    ("STOP", "stops and dwells (DELAY, OPSTOP, STOP)"),
    ("AUXFUN", "machine functions (AUXFUN, PREFUN, SEQNO)"),
    ("PREFUN", "machine functions (AUXFUN, PREFUN, SEQNO)"),
    ("SEQNO", "machine functions (AUXFUN, PREFUN, SEQNO)"),
    ("END", "operations (TOOL PATH, END-OF-PATH)"),
];

/// APT part-program (source) words: not CL data.
const SOURCE: [&str; 9] = [
    "INDIRV", "TLON", "GOFWD", "GOLFT", "GORGT", "GOBACK", "GOUP", "GODOWN", "PSIS",
];

impl Apt {
    pub(super) fn line(
        &mut self,
        line: &str,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        if self.fini {
            return Ok(());
        }
        // A comment line ending in `$` continues on the lines of numbers after it: Creo writes
        // `$$-> CSYS / 1.0, 0.0, 0.0, 0.0,  $` and two more lines of four numbers. A line that
        // starts otherwise (a statement, another comment) is read as it is.
        if std::mem::take(&mut self.comment_continues) {
            let t = line.trim_ascii();
            if t.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.')) {
                self.comment_continues = continues(t);
                return Ok(());
            }
        }
        let comment = comment_start(line);
        if let Some(p) = comment {
            self.comment(&line[p + 2..], no, log)?;
            if line[..p].trim().is_empty() && self.segs.is_empty() {
                self.comment_continues = continues(line[p + 2..].trim_ascii());
                return Ok(());
            }
        }
        let code = comment.map_or(line, |p| &line[..p]);
        let body = code.trim_ascii_end();
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
            return self.statement(code, &[Seg { start: 0, line: no }], log, out);
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
        let result = self.statement(&stmt, &segs, log, out);
        stmt.clear();
        segs.clear();
        (self.stmt, self.segs) = (stmt, segs);
        result
    }

    pub(super) fn finish(&mut self, _log: &mut Log, _out: &mut [Point]) -> Result<()> {
        if !self.segs.is_empty() && !self.fini {
            let (l, c) = self.dollar;
            return Err(Error::field(
                FIELD,
                format!(
                    "line {l}, column {c}: the statement continues with $ but the file ends; \
                     expected its next line"
                ),
            ));
        }
        if let Some(m) = &self.catia {
            return Err(Error::field(
                FIELD,
                format!(
                    "line {}: CATIA's machining axis system ($$*CATIA0) has {} of its 3 rows \
                     when the file ends",
                    m.line,
                    m.rows.len()
                ),
            ));
        }
        Ok(())
    }

    /// A `$$` comment: CATIA's matrix is read from them.
    fn comment(&mut self, text: &str, no: u32, log: &mut Log) -> Result<()> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("*CATIA0") {
            self.catia = Some(CatiaMatrix {
                line: no,
                name_pending: true,
                rows: Vec::new(),
            });
            return Ok(());
        }
        let Some(m) = &mut self.catia else {
            return Ok(());
        };
        if m.name_pending {
            m.name_pending = false;
            return Ok(());
        }
        let nums: Vec<f64> = t
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .filter_map(|s| super::lex::number(s, true))
            .collect();
        if nums.len() != 4 {
            return Err(Error::field(
                FIELD,
                format!(
                    "line {no}: expected a row of CATIA's machining axis system ($$*CATIA0 on \
                     line {}): four numbers a b c t, got {}",
                    m.line,
                    shown(t)
                ),
            ));
        }
        m.rows.push([nums[0], nums[1], nums[2], nums[3]]);
        if m.rows.len() == 3 {
            let r = &m.rows;
            let line = m.line;
            let frame = Frame::from_matrix(
                [
                    [r[0][0], r[0][1], r[0][2]],
                    [r[1][0], r[1][1], r[1][2]],
                    [r[2][0], r[2][1], r[2][2]],
                ],
                Vector3::new(r[0][3], r[1][3], r[2][3]),
            )
            .ok_or_else(|| {
                Error::field(
                    FIELD,
                    format!(
                        "line {line}: CATIA's machining axis system ($$*CATIA0) is not a \
                         rotation: its rows must be perpendicular unit vectors"
                    ),
                )
            })?;
            self.catia = None;
            self.set_output(frame, "$$*CATIA0", line, log);
        }
        Ok(())
    }

    /// A new output frame (`what` on `line`).
    fn set_output(&mut self, frame: Frame, what: &str, line: u32, log: &mut Log) {
        let reading = log.options.apt_frame;
        if frame.is_identity() {
            log.note("apt-frame-identity", NoteKind::Frame, line, || {
                format!("line {line}: {what} states the identity frame (the output frame is the workpiece's): nothing to apply")
            });
        } else {
            let applied = match reading {
                AptFrameChoice::Apply => "the points after it are read in it (origin + R·p)",
                AptFrameChoice::Ignore => {
                    "shown only: the points are left as written (your choice beside the file)"
                }
            };
            let desc = log.frame_note(
                "apt-frame",
                line,
                &frame,
                format!("line {line}: {what} states the output frame "),
                format!("; {applied}"),
            );
            if log.frame_choice.is_none() {
                log.frame_choice = Some(FrameFound {
                    statement: what.to_string(),
                    line,
                    frame: desc,
                    reading,
                });
            }
        }
        if reading == AptFrameChoice::Apply {
            self.output = frame;
        }
    }

    /// One whole statement (comments and continuations removed).
    fn statement(
        &mut self,
        text: &str,
        segs: &[Seg],
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let loc = Loc { text, segs };
        let Some(start) = text.bytes().position(|c| !c.is_ascii_whitespace()) else {
            return Ok(());
        };
        let no = loc.line_of(start);
        log.blocks += 1;
        let rest = &text[start..];
        let slash = rest.find('/');
        let major_text = slash.map_or(rest, |s| &rest[..s]).trim_ascii();
        if !major_text.starts_with(|c: char| c.is_ascii_alphabetic()) {
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
        // In upper case without allocating for the usual short words (a statement a line, 10⁴
        // to 10⁶ of them).
        let mut buf = [0u8; 32];
        let owned;
        let major: &str = if major_text.len() <= buf.len() && major_text.is_ascii() {
            for (b, c) in buf.iter_mut().zip(major_text.bytes()) {
                *b = c.to_ascii_uppercase();
            }
            std::str::from_utf8(&buf[..major_text.len()]).unwrap_or("")
        } else {
            owned = major_text.to_ascii_uppercase();
            &owned
        };
        // The word alone (PARTNO text, PPRINT text): the first run of letters.
        let first_len = major
            .bytes()
            .position(|c| !(c.is_ascii_alphanumeric() || c == b'_' || c == b'-'))
            .unwrap_or(major.len());
        let first = &major[..first_len];
        // The statements that take numbers need their `/` right after the word.
        if matches!(
            first,
            "GOTO"
                | "FROM"
                | "GODLTA"
                | "TLAXIS"
                | "CIRCLE"
                | "MSYS"
                | "CSYS"
                | "TRACUT"
                | "UNITS"
                | "UNIT"
        ) {
            let after = &rest[first.len()..];
            let at = start + first.len() + (after.len() - after.trim_start().len());
            if !text[at..].starts_with('/') {
                let got = text[at..].split_whitespace().next().unwrap_or("");
                return Err(loc.err(at, format!("expected / after {first}, got {}", shown(got))));
            }
        }
        let args_at = start + slash.map_or(rest.len(), |s| s + 1);
        let args = &text[args_at..];
        if !self.nx && matches!(major, "TOOL PATH" | "TLDATA" | "MSYS" | "PAINT") {
            self.nx = true;
        }
        match first {
            "FINI" => {
                self.fini = true;
                Ok(())
            }
            "GOTO" | "FROM" | "GODLTA" => self.goto(first, args, args_at, no, &loc, log, out),
            "GOHOME" => {
                // Back to the FROM/ point at rapid; without one, to a place the file does not
                // state: the path breaks.
                match self.home {
                    Some(h) => {
                        self.pos = Some(h);
                        self.circle = None;
                        let a = self.axis;
                        self.emit(&h, &a, Motion::Rapid, no, log, out)
                    }
                    None => {
                        self.pos = None;
                        self.rapid_next = true;
                        log.note("apt-gohome", NoteKind::Break, no, || format!("line {no}: GOHOME returns to the FROM/ point, which the file does not give: the path breaks until the next GOTO/"));
                        Ok(())
                    }
                }
            }
            "TLAXIS" => {
                let f = numbers(args, args_at, &loc, "TLAXIS", 0, 3)?;
                if f.1 != 3 {
                    let off = if f.1 < 3 {
                        args_at + args.trim_end().len()
                    } else {
                        field_offsets(args, args_at)[3]
                    };
                    return Err(loc.err(
                        off,
                        format!("expected 3 numbers (i, j, k) after TLAXIS/, got {}", f.1),
                    ));
                }
                let g = shift_axis(&f);
                self.axis = unit_axis(&loc, &g)?;
                Ok(())
            }
            "RAPID" => {
                self.rapid_next = true;
                Ok(())
            }
            "CIRCLE" => self.circle(args, args_at, &loc),
            "UNITS" | "UNIT" => {
                let w = args.trim().to_ascii_uppercase();
                let unit = match w.as_str() {
                    "MM" | "MILLIMETERS" | "MILLIMETRES" => LengthUnit::Mm,
                    "INCHES" | "INCH" | "IN" => LengthUnit::Inch,
                    _ => {
                        return Err(loc.err(
                            args_at,
                            format!(
                                "expected UNITS/MM or UNITS/INCHES, got {}",
                                shown(args.trim())
                            ),
                        ))
                    }
                };
                let before = log.scale().0;
                log.state_unit(unit, no, &format!("{first}/{w}"));
                // What is held stays where it physically is, written in the new unit.
                let k = before / log.scale().0;
                if k != 1.0 {
                    self.pos = self.pos.map(|p| p * k);
                    self.home = self.home.map(|p| p * k);
                    if let Some(c) = &mut self.circle {
                        c.centre *= k;
                        c.radius = c.radius.map(|r| r * k);
                    }
                    self.output = self.output.scaled(k);
                    self.tracut = self.tracut.scaled(k);
                }
                Ok(())
            }
            "FEDRAT" => {
                for w in args.split(',').map(str::trim) {
                    let is = |u: &str| w.eq_ignore_ascii_case(u);
                    let unit = if is("IPM") || is("IPR") {
                        Some((LengthUnit::Inch, "inches"))
                    } else if is("MMPM") || is("MMPR") {
                        Some((LengthUnit::Mm, "millimetres"))
                    } else {
                        None
                    };
                    if let Some((u, words)) = unit {
                        log.hint_unit(u, no, || {
                            format!("FEDRAT/{} (a feed in {words})", w.to_ascii_uppercase())
                        });
                    }
                }
                log.skip("feeds (FEDRAT)", no);
                Ok(())
            }
            "MSYS" | "CSYS" | "TRACUT" => self.matrix(first, args, args_at, &loc, log),
            "CYCLE" => {
                let kind = args
                    .split(',')
                    .next()
                    .unwrap_or("")
                    .trim()
                    .to_ascii_uppercase();
                if kind == "OFF" {
                    self.cycle = None;
                } else {
                    log.note("apt-cycle", NoteKind::Partial, no, || {
                        format!(
                            "line {no}: CYCLE/{kind}: the hole positions that follow are read as \
                             rapid points; the drilling strokes are not drawn (the tool axis does \
                             not turn in them)"
                        )
                    });
                    self.cycle = Some(kind);
                }
                Ok(())
            }
            "CUTCOM" => {
                let w = args
                    .split(',')
                    .next()
                    .unwrap_or("")
                    .trim()
                    .to_ascii_uppercase();
                if matches!(w.as_str(), "LEFT" | "RIGHT") {
                    log.note("apt-cutcom", NoteKind::Partial, no, || {
                        format!(
                            "line {no}: CUTCOM/{w}: the control offsets the path by the tool \
                             radius; the points are read as written"
                        )
                    });
                }
                log.skip("radius compensation (CUTCOM)", no);
                Ok(())
            }
            "NURBS" => Err(loc.err(
                start,
                "NURBS/ is a spline the control interpolates; the calculator reads straight moves \
                 and arcs: post the path with GOTO/ points",
            )),
            "ROTABL" | "ROTATE" => Err(loc.err(
                start,
                format!(
                    "{first}/ turns the table: the points after it are in a frame the file does \
                     not state; post the path in one frame with the tool axis in GOTO/x,y,z,i,j,k"
                ),
            )),
            w if SOURCE.contains(&w) => Err(loc.err(
                start,
                format!(
                    "{w} is APT part-program (source) language, not CL data: the calculator \
                     reads the cutter locations (GOTO/) the CAM system writes"
                ),
            )),
            w if w.starts_with("CSI_") => {
                log.skip("SolidWorks CAM settings (CSI_…)", no);
                Ok(())
            }
            _ => {
                if let Some((_, kind)) = SKIPPED.iter().find(|(k, _)| major == *k || first == *k) {
                    log.skip(kind, no);
                } else {
                    log.skip(
                        &format!(
                            "{major}: a statement the reader does not know (no geometry assumed)"
                        ),
                        no,
                    );
                    log.note("apt-unknown", NoteKind::Partial, no, || {
                        format!(
                            "line {no}: {major} is not a statement the reader knows; it and any \
                             other such statement are skipped as changing no geometry (each is \
                             listed by name under Skipped)"
                        )
                    });
                }
                Ok(())
            }
        }
    }

    /// `GOTO/`, `FROM/`, `GODLTA/` of the statement starting on line `no`.
    #[allow(clippy::too_many_arguments)]
    fn goto(
        &mut self,
        word: &str,
        args: &str,
        args_at: usize,
        no: u32,
        loc: &Loc,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let (p, axis) = if word == "GODLTA" {
            let f = numbers(args, args_at, loc, word, 1, 6)?;
            let n = f.1;
            let from = self.pos.ok_or_else(|| {
                loc.err(
                    args_at,
                    "GODLTA/ moves from the last position, but there is none yet",
                )
            })?;
            match n {
                1 => (from + self.axis * f.0.vals[0], None),
                3 | 6 => (
                    from + Vector3::new(f.0.vals[0], f.0.vals[1], f.0.vals[2]),
                    (n == 6).then(|| unit_axis(loc, &f.0)).transpose()?,
                ),
                _ => {
                    return Err(loc.err(
                        f.0.offs[n.min(5)],
                        format!("expected 1, 3 or 6 numbers after GODLTA/, got {n}"),
                    ))
                }
            }
        } else {
            let f = numbers(args, args_at, loc, word, 0, 6)?;
            let n = f.1;
            if n != 3 && n != 6 {
                // Where it goes wrong: the end when too few, else the first field too many.
                let offs = field_offsets(args, args_at);
                let off = if n < 3 {
                    args_at + args.trim_end().len()
                } else if n < 6 {
                    offs[3]
                } else {
                    offs[6]
                };
                let why = if n == 5 || n == 8 {
                    ": no documentation defines that form"
                } else {
                    ""
                };
                return Err(loc.err(
                    off,
                    format!("expected 3 numbers (x, y, z) or 6 (x, y, z, i, j, k) after {word}/, got {n}{why}"),
                ));
            }
            let p = super::lex::tip(loc, &f.0)?;
            (p, (n == 6).then(|| unit_axis(loc, &f.0)).transpose()?)
        };
        let a0 = self.axis;
        if let Some(a) = axis {
            self.axis = a;
        }
        let motion = if word == "FROM" || self.rapid_next || self.cycle.is_some() {
            Motion::Rapid
        } else {
            Motion::Feed
        };
        self.rapid_next = false;
        let start = self.pos;
        self.pos = Some(p);
        if word == "FROM" {
            self.home = Some(p);
        }
        // An arc: the GOTO on the circle from a known start.
        if let (Some(c), Some(p0), Motion::Feed) = (self.circle, start, motion) {
            match self.arc_to(&c, &p0, &p, &a0, loc, args_at, log)? {
                Some(points) => {
                    for (q, a) in points {
                        self.emit(&q, &a, Motion::Arc, no, log, out)?;
                    }
                    if self.nx {
                        self.circle = None; // NX writes one CIRCLE/ per arc
                    }
                    return Ok(());
                }
                None => self.circle = None, // off the circle: a straight move, the arc done
            }
        } else {
            self.circle = None;
        }
        let a = self.axis;
        self.emit(&p, &a, motion, no, log, out)
    }

    /// The chords of the arc of `c` from `p0` to `p1`, with the tool axis turning from `a0` to
    /// the current one; `None` when `p1` is not on the circle.
    #[allow(clippy::too_many_arguments)]
    fn arc_to(
        &self,
        c: &Circle,
        p0: &Vector3<f64>,
        p1: &Vector3<f64>,
        a0: &Vector3<f64>,
        loc: &Loc,
        at: usize,
        log: &Log,
    ) -> Result<Option<Chords>> {
        let radial = |p: &Vector3<f64>| {
            let d = p - c.centre;
            (d - c.normal * c.normal.dot(&d)).norm()
        };
        let (r0, r1) = (radial(p0), radial(p1));
        let r = c.radius.unwrap_or(r0);
        let tol = (1e-3 * r).max(0.01);
        if (r1 - r).abs() > tol {
            return Ok(None);
        }
        if (r0 - r).abs() > tol {
            return Err(loc.err(
                at,
                format!(
                    "the arc of the CIRCLE/ before starts {} from its axis, not on its radius {}",
                    r0, r
                ),
            ));
        }
        let tol = log.arc_tolerances();
        let ccw = !self.nx;
        let pts = arc(p0, p1, &c.centre, &c.normal, ccw, 0, tol).map_err(|e| match e {
            ArcError::Radii(a, b) => loc.err(
                at,
                format!("the arc's end is not on its circle ({a} and {b} from its axis)"),
            ),
            ArcError::NoRadius => loc.err(at, "the arc starts or ends on its axis"),
        })?;
        let a1 = self.axis;
        Ok(Some(
            pts.into_iter()
                .map(|(q, u)| (q, slerp(a0, &a1, u)))
                .collect(),
        ))
    }

    /// `CIRCLE/`: the arc the next GOTOs follow.
    fn circle(&mut self, args: &str, args_at: usize, loc: &Loc) -> Result<()> {
        // NX's `CIRCLE/…,TIMES,n`: a helix of several turns to the next GOTO.
        if let Some(i) = args.to_ascii_uppercase().find("TIMES") {
            return Err(loc.err(
                args_at + i,
                "CIRCLE/ … TIMES,n turns n times round (NX: a circle or a helix of several \
                 turns), which the reader does not read: it reads one turn at most; post the \
                 moves as GOTO points",
            ));
        }
        let (f, n, extra) = all_numbers(args, args_at, loc, "CIRCLE")?;
        let centre = Vector3::new(
            f[0],
            f.get(1).copied().unwrap_or(0.0),
            f.get(2).copied().unwrap_or(0.0),
        );
        let (normal, radius) = match n {
            4 => (Some(self.axis), Some(f[3])),
            6 => (axis_of(&f[3..6]), None),
            7 | 11 | 12 => (axis_of(&f[3..6]), Some(f[6])),
            _ => {
                return Err(loc.err(
                    extra.unwrap_or(args_at),
                    format!(
                        "expected CIRCLE/ with 4 numbers (centre, radius), 6 (centre, axis) or 7 \
                         and more (centre, axis, radius), got {n}"
                    ),
                ))
            }
        };
        let normal = normal
            .ok_or_else(|| loc.err(args_at, "the CIRCLE/ axis (i, j, k) must not be zero"))?;
        if let Some(r) = radius {
            if !(r > 0.0 && r.is_finite()) {
                return Err(loc.err(
                    args_at,
                    format!("expected a CIRCLE/ radius above 0, got {r}"),
                ));
            }
        }
        if centre.iter().any(|v| v.abs() > MAX_COORDINATE) {
            return Err(loc.err(
                args_at,
                format!("expected the CIRCLE/ centre within ±{MAX_COORDINATE} mm"),
            ));
        }
        self.circle = Some(Circle {
            centre,
            normal,
            radius,
        });
        Ok(())
    }

    /// `MSYS/`, `CSYS/`, `TRACUT/`.
    fn matrix(
        &mut self,
        word: &str,
        args: &str,
        args_at: usize,
        loc: &Loc,
        log: &mut Log,
    ) -> Result<()> {
        let no = loc.line_of(args_at);
        if word == "TRACUT" && args.trim().eq_ignore_ascii_case("NOMORE") {
            self.tracut = Frame::IDENTITY;
            return Ok(());
        }
        if word == "MSYS" && args.trim().to_ascii_uppercase().starts_with("LAST") {
            return Err(loc.err(args_at, "MSYS/LAST refers to a frame the file does not state; expected MSYS/ with its 9 or 12 numbers"));
        }
        let (f, n, _) = all_numbers(args, args_at, loc, word)?;
        let frame = match (word, n) {
            ("MSYS", 9) => Frame::from_axes(
                Vector3::new(f[0], f[1], f[2]),
                Vector3::new(f[3], f[4], f[5]),
                Vector3::new(f[6], f[7], f[8]),
            ),
            (_, 12) => Frame::from_matrix(
                [[f[0], f[1], f[2]], [f[4], f[5], f[6]], [f[8], f[9], f[10]]],
                Vector3::new(f[3], f[7], f[11]),
            ),
            _ => {
                let counts = if word == "MSYS" {
                    "9 numbers (origin, x axis, y axis) or 12 (a matrix)"
                } else {
                    "12 numbers (a matrix, rows of [R | t])"
                };
                return Err(loc.err(args_at, format!("expected {word}/ with {counts}, got {n}")));
            }
        }
        .ok_or_else(|| {
            loc.err(
                args_at,
                format!(
                    "{word}/ is not a frame: its axes must be perpendicular unit vectors (a \
                     rotation, not a mirror)"
                ),
            )
        })?;
        if word == "TRACUT" {
            let reading = log.options.apt_frame;
            let (before, after) = match reading {
                AptFrameChoice::Apply => (
                    format!("line {no}: TRACUT/ moves the points after it by "),
                    ": applied".to_string(),
                ),
                AptFrameChoice::Ignore => (
                    format!("line {no}: TRACUT/ ("),
                    ") shown only: the points are left as written".to_string(),
                ),
            };
            log.frame_note("apt-tracut", no, &frame, before, after);
            if reading == AptFrameChoice::Apply {
                self.tracut = frame;
            }
            return Ok(());
        }
        self.set_output(frame, &format!("{word}/"), no, log);
        Ok(())
    }

    /// Writes the point `p` (file unit) with axis `a`, both in the statements' own frame.
    fn emit(
        &mut self,
        p: &Vector3<f64>,
        a: &Vector3<f64>,
        motion: Motion,
        line: u32,
        log: &Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let (scale, _) = log.scale();
        let f = if self.tracut.is_identity() {
            self.output
        } else {
            self.output.then(&self.tracut)
        };
        let tip = f.apply(p) * scale;
        if let Some(i) = (0..3).find(|&i| tip[i].abs() > MAX_COORDINATE || tip[i].is_nan()) {
            return Err(Error::field(
                FIELD,
                format!(
                    "line {line}: expected {} within ±{MAX_COORDINATE} mm, got {} mm",
                    NAMES[i], tip[i]
                ),
            ));
        }
        out.push(Point {
            tip,
            axis: f.direction(a).normalize(),
            line,
            motion,
            angles: None,
        });
        Ok(())
    }
}

/// The axis `(i, j, k)` of a statement, unit; `None` when zero.
fn axis_of(v: &[f64]) -> Option<Vector3<f64>> {
    unit(&Vector3::new(v[0], v[1], v[2]))
}

/// Fields `i, j, k` moved to places 3..6 (TLAXIS).
fn shift_axis<'a>(f: &(Fields<'a>, usize)) -> Fields<'a> {
    Fields {
        vals: [0.0, 0.0, 0.0, f.0.vals[0], f.0.vals[1], f.0.vals[2]],
        offs: [0, 0, 0, f.0.offs[0], f.0.offs[1], f.0.offs[2]],
        toks: ["", "", "", f.0.toks[0], f.0.toks[1], f.0.toks[2]],
    }
}

/// The numbers after `word/` (at most 6 kept, counted all): `(fields, count)`. Fewer than
/// `min` is an error, and so is a field that is not a number (a minor word among the first
/// `max`).
fn numbers<'a>(
    args: &'a str,
    at: usize,
    loc: &Loc,
    word: &str,
    min: usize,
    max: usize,
) -> Result<(Fields<'a>, usize)> {
    let mut f = Fields::new();
    let mut n = 0;
    let mut piece_start = at;
    for piece in fields(args) {
        let lead = piece.len() - piece.trim_ascii_start().len();
        let (off, tok) = (piece_start + lead, piece.trim_ascii());
        piece_start += piece.len() + 1;
        if n < 6 {
            let v = super::lex::number(tok, true).ok_or_else(|| {
                loc.err(
                    off,
                    format!("expected a number after {word}/, got {}", shown(tok)),
                )
            })?;
            if n < max {
                f.vals[n] = v;
                f.offs[n] = off;
                f.toks[n] = tok;
            }
        }
        n += 1;
    }
    if args.trim_ascii().is_empty() {
        n = 0;
    }
    if n < min {
        return Err(loc.err(
            at + args.trim_end().len(),
            format!("expected at least {min} numbers after {word}/, got {n}"),
        ));
    }
    Ok((f, n))
}

/// Where a `$$` comment starts in `line` (a byte loop: the reader's hottest search).
fn comment_start(line: &str) -> Option<usize> {
    let b = line.as_bytes();
    let mut i = 0;
    while let Some(p) = b[i..].iter().position(|&c| c == b'$') {
        let at = i + p;
        if b.get(at + 1) == Some(&b'$') {
            return Some(at);
        }
        i = at + 1;
    }
    None
}

/// Whether a (trimmed) comment text ends in one `$`, continuing on the next line (`$$` at the
/// end, as in a banner `$$ ---- $$`, does not).
fn continues(t: &str) -> bool {
    t.ends_with('$') && !t.ends_with("$$")
}

/// The comma-separated fields of `args` (a byte loop, as [`comment_start`]).
fn fields(args: &str) -> impl Iterator<Item = &str> {
    let mut rest = Some(args);
    std::iter::from_fn(move || {
        let r = rest?;
        match r.bytes().position(|c| c == b',') {
            Some(p) => {
                rest = Some(&r[p + 1..]);
                Some(&r[..p])
            }
            None => {
                rest = None;
                Some(r)
            }
        }
    })
}

/// The byte offset of each comma-separated field of `args` (starting at `at`), at its first
/// character that is not blank.
fn field_offsets(args: &str, at: usize) -> Vec<usize> {
    let mut offs = Vec::new();
    let mut start = at;
    for piece in args.split(',') {
        offs.push(start + piece.len() - piece.trim_start().len());
        start += piece.len() + 1;
    }
    offs
}

/// Every number after `word/` (a statement of up to 12): values, count, and the offset of the
/// 13th field when there are more.
fn all_numbers(
    args: &str,
    at: usize,
    loc: &Loc,
    word: &str,
) -> Result<(Vec<f64>, usize, Option<usize>)> {
    let mut v = Vec::new();
    let mut piece_start = at;
    let mut extra = None;
    for piece in args.split(',') {
        let lead = piece.len() - piece.trim_start().len();
        let (off, tok) = (piece_start + lead, piece.trim());
        piece_start += piece.len() + 1;
        if v.len() == 12 {
            extra = Some(off);
        }
        let x = super::lex::number(tok, true)
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                loc.err(
                    off,
                    format!("expected a number after {word}/, got {}", shown(tok)),
                )
            })?;
        v.push(x);
    }
    let n = v.len();
    Ok((v, n, extra))
}
