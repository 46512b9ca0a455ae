//! NC blocks: what the three dialects share. Each dialect ([`super::iso`], [`super::siemens`],
//! [`super::heidenhain`]) reads its own syntax into a [`Block`] (axis words, motion, arc centre
//! or radius, a tool vector) and sets the modal state it owns (units, frames, tool-centre-point
//! control); [`Core::execute`] then moves the tool the way a control does and writes the points.
//!
//! # The tool tip and the tool axis
//! NC blocks are read for a stated machine: `X Y Z` are the tool tip and the machine's two
//! rotary letters ([`crate::machine::Model::letters`], K then M) the **commanded** angles in
//! degrees. The tool axis is the machine's forward kinematics of the orientation,
//! `V = R_K(θk)·R_M(θm)·e_H` with `θ = factor·command` (`factor = −1` for an axis marked
//! reversed), in the workpiece frame. With tool-centre-point control on (`G43.4`, `G234`,
//! `TRAORI`, `M128`, `FUNCTION TCPM`) that is what the control does: it keeps the programmed
//! tip on the part whatever the rotary axes do. Without it, `X Y Z` of a block that turns the
//! rotary axes are the machine's axis positions, not the tip on the part, and so are those after
//! the control is switched off (`G49`, `M129`, `TRAFOOF` …) with the axes turned: the reader
//! says so in a note at the first point reached that way, unless the axes are back at 0° there
//! (whole turns included), where the machine's frame is the workpiece's. The ranking needs the
//! tool axes only, so it holds either way.
//!
//! Where the dialect tilts the working plane (`G68.2`, `PLANE SPATIAL`) the tool axis is the
//! tilted frame's z axis (the control turns the rotary axes to it), and the point carries no
//! commanded angles, until a block under tool-centre-point control gives rotary words or a tool
//! vector (5-axis moves in a tilted plane): from there those give the tool axis, as the control
//! does, and a note says so; the next tilt statement returns to the plane's z. A tool vector
//! written in the block (Siemens `A3 B3 C3`, Heidenhain `LN … TX TY TZ`) is the tool axis,
//! turned by the active frame.
//!
//! # Positions
//! * Modal: a coordinate missing from a block keeps its value. A linear axis is **unknown**
//!   until the program gives it an absolute value (and again after a reference return or a move
//!   in machine coordinates: `G28`, `G53`, `G153`, `SUPA`, `M91`); a block that leaves one
//!   unknown gives no point, and the move to the next point known is a rapid (the path breaks
//!   there, and a note says where). A rotary axis not yet commanded is at 0°.
//! * Positions are kept in the file's unit; the unit and the active frame are applied to each
//!   point written: `tip = s·(origin + R·p)` with `s` mm per file unit.
//! * A drilling cycle's position block gives a rapid point; its strokes are not drawn (a note
//!   says so): the tool axis does not turn in a cycle.
//!
//! # Arcs
//! `G2` (clockwise) and `G3` (counter-clockwise) as seen from the positive end of the axis
//! normal to the plane (`G17` XY about +Z, `G18` ZX about +Y, `G19` YZ about +X), with their
//! centre (`I J K`, incremental from the start unless the dialect says absolute) or radius
//! (`R`, `CR=`: positive up to half a turn, negative beyond), are cut into chords within the
//! chord tolerance ([`super::frame::arc`]); a coordinate along the normal moves in proportion
//! (a helix), and rotary axes in the block move in proportion to the arc's fraction, as the
//! control interpolates them.

use super::frame::{arc, ArcError, Frame};
use super::lex::{shown, Loc, MAX_ANGLE, MAX_COORDINATE};
use super::{heidenhain, iso, siemens, Format, Log, Motion, NoteKind, Point};
use crate::error::{Error, Result};
use crate::machine::Model;
use crate::rotary::{Pose, RotaryType};
use nalgebra::Vector3;

/// A number word of a block: its value as written (file unit, degrees) and the byte offset of
/// its number (for messages).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Word {
    pub value: f64,
    pub at: usize,
}

/// The modal motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Mode {
    Rapid,
    Feed,
    Cw,
    Ccw,
}

/// How a rotary axis reaches an absolute command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Way {
    /// As far as the numbers say.
    Literal,
    /// The shorter way round: the equivalent angle (modulo 360°) nearest the current one;
    /// half a turn exactly turns positively.
    Shortest,
    /// Turning positively (Siemens `ACP`).
    Positive,
    /// Turning negatively (Siemens `ACN`).
    Negative,
}

impl Way {
    /// The position reached from `current` by a command `value` (degrees).
    pub fn reach(self, value: f64, current: f64) -> f64 {
        match self {
            Way::Literal => value,
            Way::Shortest => value + 360.0 * ((current - value) / 360.0 + 0.5).floor(),
            Way::Positive => value + 360.0 * ((current - value) / 360.0).ceil(),
            Way::Negative => value + 360.0 * ((current - value) / 360.0).floor(),
        }
    }
}

/// The working plane of arcs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Plane {
    /// G17: XY, normal +Z.
    Xy,
    /// G18: ZX, normal +Y.
    Zx,
    /// G19: YZ, normal +X.
    Yz,
}

impl Plane {
    /// The index of the axis normal to the plane.
    pub fn normal(self) -> usize {
        match self {
            Plane::Xy => 2,
            Plane::Zx => 1,
            Plane::Yz => 0,
        }
    }
}

/// One block, as a dialect read it.
#[derive(Debug, Clone, Default)]
pub(super) struct Block {
    /// X, Y, Z, K, M as written.
    pub axes: [Option<Word>; 5],
    /// Per word: incremental (`Some(true)`), absolute (`Some(false)`), or as the modal state
    /// says (`None`).
    pub incremental: [Option<bool>; 5],
    /// Per rotary word (K, M): how it reaches an absolute command, when the word says
    /// (Siemens `DC`, `ACP`, `ACN`).
    pub way: [Option<Way>; 2],
    /// A change of the modal motion.
    pub mode: Option<Mode>,
    /// This block alone at rapid (Heidenhain `FMAX`).
    pub rapid_once: bool,
    /// The arc's centre `I J K` (one per linear axis).
    pub centre: [Option<Word>; 3],
    /// The centre is absolute (Heidenhain `CC`, Siemens `I=AC(…)`, `G90.1`), not incremental
    /// from the start.
    pub centre_absolute: bool,
    /// The arc's radius (`R`, `CR=`).
    pub radius: Option<Word>,
    /// Whole turns more (a helix, Siemens `TURN=`).
    pub turns: u32,
    /// An arc of this many degrees about the centre (Heidenhain `CP IPA`), the end computed.
    pub sweep: Option<f64>,
    /// A tool vector written in the block.
    pub vector: Option<Vector3<f64>>,
    /// A drilling cycle's position: the `Z` word is the cycle's depth, not a position, and the
    /// move is a rapid.
    pub cycle: bool,
    /// Where the block starts (for messages about the block as a whole).
    pub at: usize,
}

impl Block {
    /// True when the block moves the tool.
    pub fn moves(&self) -> bool {
        self.axes.iter().any(Option::is_some) || self.vector.is_some() || self.sweep.is_some()
    }
}

/// The modal state of NC blocks and the kinematics that turn commands into tool axes.
#[derive(Debug, Clone)]
pub(super) struct Core {
    pub rtype: RotaryType,
    /// θ = factor·command for K and M.
    pub factors: [f64; 2],
    /// K's and M's letters.
    pub letters: [char; 2],
    /// The machine (the Heidenhain reader solves `PLANE … STAY`'s axis angles with it).
    pub model: Box<Model>,
    /// X, Y, Z (file unit) and K, M (degrees).
    pub pos: [f64; 5],
    /// X, Y, Z known.
    pub known: [bool; 3],
    pub mode: Mode,
    pub plane: Plane,
    /// G90 (true) or G91.
    pub absolute: bool,
    /// Program coordinates to workpiece coordinates (file unit).
    pub frame: Frame,
    /// The frame tilts the working plane: the tool axis is its z axis.
    pub tilted: bool,
    /// In the tilted plane, a block under tool-centre-point control gave rotary words or a
    /// vector: they give the tool axis, not the plane's z (reset by the next tilt statement).
    pub tilt_override: bool,
    /// Tool-centre-point control is on.
    pub tcp: bool,
    /// A tool vector programmed (Siemens `A3 B3 C3`, Heidenhain `TX TY TZ`), modal.
    pub vector: Option<Vector3<f64>>,
    /// The next point is reached across unknown positions: a rapid.
    pub break_next: bool,
    /// The program has ended (`M30`, `M2`, `END PGM`): the rest is not read.
    pub ended: bool,
    /// The last move's direction at its end (program frame; none from an unknown start), for CT.
    pub tangent: Option<Vector3<f64>>,
    /// K and M reach absolute commands the shorter way round: the machine's rollover for K;
    /// Heidenhain's M126 for both.
    pub rollover: [bool; 2],
    /// Heidenhain M126 is on.
    pub shortest: bool,
    /// Why the next point reached without tool-centre-point control may be the machine's
    /// position and not the tip on the part, until a point is reached outside a tilted plane
    /// (then the reader says so, when the rotary axes are turned there or an arc turns them on
    /// its way) or the control is switched on first.
    pub untracked: Option<Untracked>,
}

/// Why X Y Z may be the machine's axis positions and not the tool tip on the part.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Untracked {
    /// The rotary axes turned on this line without tool-centre-point control.
    Turned(u32),
    /// The statement (`M129`, `G49`, `TRAFOOF` …) switched tool-centre-point control off on
    /// this line with the rotary axes turned to these commanded angles (K, M; degrees).
    Off(u32, String, [f64; 2]),
}

/// Whether commanded angles `k`, `m` (degrees) turn the machine away from its zero pose, where
/// the workpiece frame is the machine's (whole turns are the zero pose; 10⁻⁹° is rounding).
pub(super) fn turned(k: f64, m: f64) -> bool {
    [k, m].iter().any(|a| {
        let r = a.rem_euclid(360.0);
        r > 1e-9 && r < 360.0 - 1e-9
    })
}

/// The NC reader: the shared state and the dialect's own.
#[derive(Debug, Clone)]
pub struct Nc {
    core: Core,
    dialect: Dialect,
}

#[derive(Debug, Clone)]
enum Dialect {
    Iso(iso::Iso),
    Siemens(siemens::Siemens),
    Heidenhain(heidenhain::Heidenhain),
}

impl Nc {
    /// A reader of `format` (one of the NC dialects) for the machine `model`.
    pub(super) fn new(format: Format, model: &Model) -> Self {
        let dialect = match format {
            Format::Siemens => Dialect::Siemens(siemens::Siemens::default()),
            Format::Heidenhain => Dialect::Heidenhain(heidenhain::Heidenhain::default()),
            _ => Dialect::Iso(iso::Iso::default()),
        };
        Nc {
            core: Core {
                rtype: model.layout.rtype,
                factors: [model.layout.k_factor, model.layout.m_factor],
                letters: model.letters(),
                model: Box::new(model.clone()),
                pos: [0.0; 5],
                known: [false; 3],
                mode: Mode::Rapid,
                plane: Plane::Xy,
                absolute: true,
                frame: Frame::IDENTITY,
                tilted: false,
                tilt_override: false,
                tcp: false,
                vector: None,
                break_next: false,
                ended: false,
                tangent: None,
                rollover: [model.machine.rotary.k_rollover, false],
                shortest: false,
                untracked: None,
            },
            dialect,
        }
    }

    /// One line of the file.
    pub(super) fn line(
        &mut self,
        text: &str,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        // After the end (`M30`, `M2`, `RET`) nothing is read; Heidenhain runs its blocks at the
        // end of the file and ends there.
        if self.core.ended && !matches!(self.dialect, Dialect::Heidenhain(_)) {
            if !text.trim().is_empty() {
                log.skip("text after the end of the program", no);
            }
            return Ok(());
        }
        match &mut self.dialect {
            Dialect::Iso(d) => d.line(&mut self.core, text, no, log, out),
            Dialect::Siemens(d) => d.line(&mut self.core, text, no, log, out),
            Dialect::Heidenhain(d) => d.line(&mut self.core, text, no, log, out),
        }
    }

    /// The end of the file.
    pub(super) fn finish(&mut self, log: &mut Log, out: &mut Vec<Point>) -> Result<()> {
        match &mut self.dialect {
            Dialect::Iso(d) => d.finish(&mut self.core, log, out),
            Dialect::Siemens(_) => Ok(()),
            Dialect::Heidenhain(d) => d.finish(&mut self.core, log, out),
        }
    }
}

impl Core {
    /// The letter of position index `n` (0..5).
    pub fn name(&self, n: usize) -> char {
        ['X', 'Y', 'Z', self.letters[0], self.letters[1]][n]
    }

    /// Index 3 or 4 of a rotary letter of this machine.
    pub fn rotary_index(&self, letter: char) -> Option<usize> {
        self.letters
            .iter()
            .position(|&l| l == letter)
            .map(|i| i + 3)
    }

    /// The error of a rotary word that is not one of the machine's.
    pub fn not_this_machine(&self, loc: &Loc, at: usize, letter: char) -> Error {
        let [kl, ml] = self.letters;
        loc.err(
            at,
            format!(
                "expected a rotary axis of this machine ({kl} or {ml}), got {letter}: the program \
                 is for another machine; choose the machine it was written for above"
            ),
        )
    }

    /// Linear axes `axes` go to positions the file does not state (a reference return, a move
    /// in machine coordinates): they are unknown until given again.
    pub fn forget(&mut self, axes: &[usize]) {
        for &a in axes {
            if a < 3 {
                self.known[a] = false;
            }
        }
        self.break_next = true;
    }

    /// The file states `unit` (`what` on `line`): the positions held are written in the new
    /// unit, so that an axis not in the next block stays where it physically is.
    pub fn state_unit(&mut self, unit: super::LengthUnit, line: u32, what: &str, log: &mut Log) {
        let before = log.scale().0;
        log.state_unit(unit, line, what);
        let k = before / log.scale().0;
        if k != 1.0 {
            for p in &mut self.pos[..3] {
                *p *= k;
            }
            self.frame.origin *= k;
        }
    }

    /// Switches tool-centre-point control on or off (`what` on `line`, for the report and the
    /// notes). Switched off with the rotary axes turned, the points after it (outside a tilted
    /// working plane) are the machine's positions until the control is on again or the axes
    /// are back at 0°: the first one reached that way is noted.
    pub fn set_tcp(&mut self, on: bool, line: u32, what: &str, log: &mut Log) {
        if on && !self.tcp && log.tcp.is_none() {
            log.tcp = Some(format!("{what} on line {line}"));
        }
        if on {
            self.untracked = None;
        } else if self.tcp && turned(self.pos[3], self.pos[4]) {
            let angles = [self.pos[3], self.pos[4]];
            self.untracked = Some(Untracked::Off(line, what.to_string(), angles));
        }
        self.tcp = on;
    }

    /// Moves the tool as block `b` says (module docs), appending its points to `out`.
    pub fn execute(
        &mut self,
        b: &Block,
        loc: &Loc,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        if let Some(m) = b.mode {
            self.mode = m;
        }
        let arc_mode = matches!(self.mode, Mode::Cw | Mode::Ccw) && !b.rapid_once && !b.cycle;
        let full_circle =
            arc_mode && !b.moves() && b.centre.iter().any(Option::is_some) && b.radius.is_none();
        if !b.moves() && !full_circle {
            return Ok(());
        }
        let start = self.pos;
        let start_known = self.known;
        let mut new = self.pos;
        let mut known = self.known;
        for n in 0..5 {
            let Some(w) = b.axes[n] else { continue };
            if n == 2 && b.cycle {
                continue; // the cycle's depth
            }
            let incremental = b.incremental[n].unwrap_or(!self.absolute);
            let value = if incremental {
                new[n] + w.value
            } else if n >= 3 {
                let way = b.way[n - 3].unwrap_or(if self.rollover[n - 3] || self.shortest {
                    Way::Shortest
                } else {
                    Way::Literal
                });
                way.reach(w.value, new[n])
            } else {
                w.value
            };
            if n < 3 && ((value * log.scale().0).abs() > MAX_COORDINATE || value.is_nan()) {
                let got = if incremental || log.scale().0 != 1.0 {
                    format!("{} mm", value * log.scale().0)
                } else {
                    shown(&format!("{}", w.value))
                };
                return Err(loc.err(
                    w.at,
                    format!(
                        "expected {} within ±{MAX_COORDINATE} mm, got {got}",
                        self.name(n)
                    ),
                ));
            }
            if n >= 3 && value.abs() > MAX_ANGLE {
                let got = if incremental {
                    format!("{value}°")
                } else {
                    shown(&format!("{}", w.value))
                };
                return Err(loc.err(
                    w.at,
                    format!("expected {} within ±{MAX_ANGLE}°, got {got}", self.name(n)),
                ));
            }
            new[n] = value;
            if n < 3 && !incremental {
                known[n] = true;
            }
        }
        let rotary_moves = new[3] != start[3] || new[4] != start[4];
        self.pos = new;
        self.known = known;
        if b.vector.is_some() {
            self.vector = b.vector;
        } else if b.axes[3].is_some() || b.axes[4].is_some() {
            self.vector = None;
        }
        let orients = b.vector.is_some() || b.axes[3].is_some() || b.axes[4].is_some();
        if self.tilted && self.tcp && orients && !self.tilt_override {
            self.tilt_override = true;
            let line = loc.line_of(b.at);
            log.note("tilt-tcp", NoteKind::Tcp, line, || {
                format!("line {line}: in the tilted working plane, under tool-centre-point control, the block's rotary axes (or tool vector) give the tool axis from here, not the plane's z axis")
            });
        }
        if rotary_moves && !self.tcp && !self.tilted {
            self.untracked
                .get_or_insert(Untracked::Turned(loc.line_of(b.at)));
        }
        if !known.iter().all(|&k| k) {
            self.break_next = true;
            return Ok(());
        }
        // A rotary turn matters to the points only when one is reached before tool-centre-point
        // control is on, with the axes still turned: a post turns the table, then switches the
        // control on (`G0 B-22.2 C1.05` then `G234`), with X Y Z not yet given; at 0° the
        // machine's frame is the workpiece's. In a tilted working plane the points are in the
        // plane's frame, and the turn its setting.
        // An arc's chords carry angles between its ends: one that turns is noted even when it
        // ends at 0°. In the tilted plane the pending note waits for the plane's cancel.
        let reached = if self.tilted {
            None
        } else {
            self.untracked
                .take()
                .filter(|_| turned(new[3], new[4]) || (arc_mode && rotary_moves))
        };
        let [kl, ml] = self.letters;
        let then =
            "X Y Z are then the machine's axis positions, not the tool tip on the part. The \
                    ranking uses the rotary commands only and holds; the path drawn is the \
                    machine's.";
        match reached {
            Some(Untracked::Turned(line)) => log.note("no-tcp", NoteKind::Tcp, line, || {
                format!(
                    "line {line}: the rotary axes ({kl}, {ml}) turn while tool-centre-point \
                     control is off (G43.4, G43.5, G234, TRAORI, M128, FUNCTION TCPM … switch it on): \
                     {then}"
                )
            }),
            Some(Untracked::Off(line, what, [k, m])) => {
                let moved = loc.line_of(b.at);
                log.note("tcp-off", NoteKind::Tcp, line, || {
                    format!(
                        "line {line}: {what} switches tool-centre-point control off with the \
                         rotary axes turned ({kl} {}°, {ml} {}°), and line {moved} moves with \
                         the control off and the axes turned: {then}",
                        round(k),
                        round(m)
                    )
                })
            }
            None => {}
        }
        let cutting = !(b.rapid_once || b.cycle || self.mode == Mode::Rapid);
        let k_turn = (new[3] - start[3]).abs();
        if cutting && k_turn > 180.0 && !self.rollover[0] && !self.shortest {
            let line = loc.line_of(b.at);
            let kl = self.letters[0];
            log.note("k-jump", NoteKind::Rotary, line, || {
                format!(
                    "line {line}: the program turns {kl} from {}° to {}° ({}°) in one cutting \
                     block; read as written the machine swings {kl} that far while cutting. If \
                     the control takes the shorter way round (rollover), tick '{kl} takes the \
                     shorter way round' in the machine",
                    round(start[3]),
                    round(new[3]),
                    round(new[3] - start[3])
                )
            });
        }
        let motion = if b.rapid_once || b.cycle || self.mode == Mode::Rapid {
            Motion::Rapid
        } else if arc_mode {
            Motion::Arc
        } else {
            Motion::Feed
        };
        let (line, from_known) = (loc.line_of(b.at), start_known.iter().all(|&k| k));
        let p0 = Vector3::new(start[0], start[1], start[2]);
        let mut p1 = Vector3::new(new[0], new[1], new[2]);
        if motion != Motion::Arc {
            if !from_known || (p1 - p0).norm() > 0.0 {
                self.tangent = from_known.then(|| (p1 - p0).normalize());
            }
            return self.emit(&p1, [new[3], new[4]], motion, line, log, out);
        }
        if !start_known.iter().all(|&k| k) {
            return Err(loc.err(
                b.at,
                "the arc starts where the tool's position is not known (after a reference \
                 return or a move in machine coordinates); expected a straight move to a known \
                 position first",
            ));
        }
        let ccw = self.mode == Mode::Ccw;
        let nz = self.plane.normal();
        let normal = Vector3::ith(nz, 1.0);
        let (scale, _) = log.scale();
        let centre =
            match (b.radius, b.centre.iter().any(Option::is_some)) {
                (Some(r), _) => radius_centre(&p0, &p1, r.value, &normal, ccw)
                    .map_err(|msg| loc.err(r.at, msg))?,
                (None, true) => {
                    let mut c = if b.centre_absolute {
                        Vector3::zeros()
                    } else {
                        p0
                    };
                    for (i, w) in b.centre.iter().enumerate() {
                        match w {
                            Some(w) => {
                                c[i] = if b.centre_absolute {
                                    w.value
                                } else {
                                    p0[i] + w.value
                                }
                            }
                            None if b.centre_absolute => c[i] = p0[i],
                            None => {}
                        }
                    }
                    c
                }
                (None, false) => return Err(loc.err(
                    b.at,
                    "an arc needs its centre (I, J, K or CC) or its radius (R or CR=); the block \
                     gives neither",
                )),
            };
        if let Some(sweep) = b.sweep {
            // The end is the start turned about the centre (Heidenhain CP IPA).
            let rot =
                Frame::rotation_about(crate::geometry::Axis::ALL[nz], sweep.to_radians(), centre);
            let along = p1[nz];
            p1 = rot.apply(&Vector3::new(p0[0], p0[1], p0[2]));
            p1[nz] = along;
            for i in 0..3 {
                self.pos[i] = p1[i];
            }
        }
        let tol = log.arc_tolerances();
        // A sweep of more than a turn ends where a smaller one does: the whole turns are added.
        let turns = b.turns
            + b.sweep
                .map_or(0, |s| ((s.abs() - 1e-9) / 360.0).floor().max(0.0) as u32);
        // Would I J K read as absolute coordinates fit (Heidenhain's ISO programs write them so)?
        let absolute_fits = !b.centre_absolute && b.radius.is_none() && {
            let mut c = p0;
            for (i, w) in b.centre.iter().enumerate() {
                if let Some(w) = w {
                    c[i] = w.value;
                }
            }
            arc(&p0, &p1, &c, &normal, ccw, turns, (f64::INFINITY, tol.1)).is_ok()
        };
        let points = arc(&p0, &p1, &centre, &normal, ccw, turns, tol).map_err(|e| match e {
            ArcError::Radii(r0, r1) => loc.err(
                b.at,
                format!(
                    "the arc's end is not on its circle: {} mm from the centre at the start, {} \
                     mm at the end{}",
                    round(r0 * scale),
                    round(r1 * scale),
                    if absolute_fits {
                        "; read as absolute coordinates (as Heidenhain's ISO programs write I J K) \
                         the centre fits: add G90.1 before the arcs if that is what the program means"
                    } else {
                        ""
                    }
                ),
            ),
            ArcError::NoRadius => loc.err(
                b.at,
                "the arc starts or ends on its centre: expected a centre away from both ends",
            ),
        })?;
        let sign = if ccw { 1.0 } else { -1.0 };
        let radial = p1 - centre - normal * normal.dot(&(p1 - centre));
        self.tangent = normal.cross(&radial).try_normalize(0.0).map(|t| t * sign);
        for (p, u) in points {
            let k = start[3] + (new[3] - start[3]) * u;
            let m = start[4] + (new[4] - start[4]) * u;
            self.emit(&p, [k, m], Motion::Arc, line, log, out)?;
        }
        Ok(())
    }

    /// Writes the point at program coordinates `p` (file unit) with commanded angles `angles`
    /// (degrees).
    fn emit(
        &mut self,
        p: &Vector3<f64>,
        angles: [f64; 2],
        motion: Motion,
        line: u32,
        log: &Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        let (scale, _) = log.scale();
        let tip = self.frame.apply(p) * scale;
        if let Some(i) = (0..3).find(|&i| tip[i].abs() > MAX_COORDINATE || tip[i].is_nan()) {
            return Err(Error::field(
                super::FIELD,
                format!(
                    "line {line}: the tool tip reaches {} = {} mm in the workpiece frame, beyond \
                     ±{MAX_COORDINATE} mm",
                    ['x', 'y', 'z'][i],
                    tip[i]
                ),
            ));
        }
        let (axis, angles) = if self.tilted && !self.tilt_override {
            (self.frame.direction(&Vector3::z()), None)
        } else if let Some(v) = self.vector {
            (self.frame.direction(&v), None)
        } else {
            let pose = Pose::new(
                self.factors[0] * angles[0].to_radians(),
                self.factors[1] * angles[1].to_radians(),
            );
            (self.rtype.tool_vector(pose), Some(angles))
        };
        let motion = if self.break_next {
            Motion::Rapid
        } else {
            motion
        };
        self.break_next = false;
        out.push(Point {
            tip,
            axis: axis.normalize(),
            line,
            motion,
            angles,
        });
        Ok(())
    }
}

/// The centre of the arc from `p0` to `p1` of radius `r` (positive: at most half a turn;
/// negative: more) turning about `normal` counter-clockwise when `ccw`, in the plane normal to
/// `normal` (the coordinate along it is ignored).
fn radius_centre(
    p0: &Vector3<f64>,
    p1: &Vector3<f64>,
    r: f64,
    normal: &Vector3<f64>,
    ccw: bool,
) -> std::result::Result<Vector3<f64>, String> {
    let mut d = p1 - p0;
    d -= normal * normal.dot(&d);
    let chord = d.norm();
    if chord < 1e-9 {
        return Err(
            "an arc given by its radius needs an end away from its start (a full circle \
                    needs its centre)"
                .into(),
        );
    }
    let half = chord / 2.0;
    // The radius may fall short of half the chord by rounding of the written numbers.
    if r.abs() < half - (1e-3 * half).max(0.005) {
        return Err(format!(
            "the radius {} is shorter than half the distance to the end ({}): no arc joins them",
            round(r.abs()),
            round(half)
        ));
    }
    let h = (r * r - half * half).max(0.0).sqrt();
    let left = normal.cross(&(d / chord));
    let side = if ccw == (r > 0.0) { 1.0 } else { -1.0 };
    let mid = (p0 + p1) / 2.0;
    Ok(mid + left * (side * h))
}

/// `x` to 6 decimals, for messages.
fn round(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}
