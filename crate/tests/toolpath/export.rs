//! The toolpath exports as the page calls them (`fiveaxis::toolpath::export`): a file read in
//! pieces, a path written back, the twelve types ranked, one type's analysis and the refined
//! path.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::tilted;
use fiveaxis::toolpath::export::{analyse, compare, refine, write_path, PathInput, Reading};
use fiveaxis::toolpath::read::Motion;
use fiveaxis::toolpath::{ToolpathCase, ToolpathReadInput};
use nalgebra::Vector3;
use serde_json::{json, Value};

/// A C-A fork head (head-head CAZ).
fn options(format: &str) -> ToolpathReadInput {
    ToolpathReadInput::read(&json!({ "machine": { "kind": "head-head", "type": "CAZ" },
                                     "format": format }))
    .unwrap()
}

/// A path of tips and tool axes, each point reached as `motions` says.
fn path(points: &[([f64; 3], Vector3<f64>)], motions: &[Motion]) -> PathInput {
    PathInput {
        tips: points.iter().map(|(t, _)| Vector3::from(*t)).collect(),
        axes: points.iter().map(|(_, a)| *a).collect(),
        motions: Some(motions.to_vec()),
        commands: None,
    }
}

/// Each piece read says how many whole lines are read so far (the page's progress): a line cut
/// by the end of a piece waits for the next one, text or bytes alike.
#[test]
fn a_file_read_in_pieces_counts_the_lines_read() {
    let mut r = Reading::new(options("nc"));
    assert_eq!(r.feed("G0 X0 Y0 Z0 C0 A0\nG1 X1").unwrap(), 1);
    assert_eq!(r.feed("0 Y0\nG1 X20 C10\n").unwrap(), 3);
    let parsed = r.finish().unwrap();
    assert_eq!((parsed.count, parsed.lines_read), (3, 3));
    assert_eq!(parsed.lines, [1.0, 2.0, 3.0]);
    let mut r = Reading::new(options("nc"));
    assert_eq!(r.feed_bytes(b"G0 X0 Y0 Z0\r\n(\xb5m)\r\nG1 X1").unwrap(), 2);
    assert_eq!(r.feed_bytes(b"0\r\n").unwrap(), 3);
    assert_eq!(r.finish().unwrap().count, 2);
}

/// A path is written as the format chosen and reads back: CSV and APT without the machine's
/// commands, NC blocks only with them; "auto" is no format to write.
#[test]
fn a_path_is_written_in_the_format_chosen() {
    let p = path(
        &[
            ([0.0, 0.0, 5.0], Vector3::z()),
            ([10.0, -2.5, 5.0], tilted(30.0, 0.0)),
        ],
        &[Motion::Rapid, Motion::Feed],
    );
    let csv = write_path(&options("csv"), &p).unwrap();
    let mut r = Reading::new(options("csv"));
    r.feed(&csv).unwrap();
    let back = r.finish().unwrap().path.points;
    assert_eq!(back[..3], [0.0, 0.0, 5.0]);
    assert_eq!(back[6..9], [10.0, -2.5, 5.0]);
    let e = write_path(&options("nc"), &p).unwrap_err();
    assert_eq!(e.field, "angles");
    let e = write_path(&options("auto"), &p).unwrap_err();
    assert_eq!(e.field, "format");
    let with_commands = PathInput {
        commands: Some((
            vec![[0.0, 0.0], [90.0, 30.0]],
            fiveaxis::rotary::RotaryType::parse("CAZ").unwrap(),
        )),
        ..p
    };
    let nc = write_path(&options("nc"), &with_commands).unwrap();
    assert!(nc.contains("G0 X0.0 Y0.0 Z5.0 C0.0 A0.0\n"), "{nc}");
    assert!(nc.contains("G1 X10.0 Y-2.5 Z5.0 C90.0 A30.0\n"), "{nc}");
}

/// The ranking has a row for each type asked for, the twelve when none is named.
#[test]
fn the_ranking_has_a_row_per_type() {
    let case = ToolpathCase::read(&json!({})).unwrap();
    let p = path(
        &[
            ([0.0, 0.0, 0.0], tilted(10.0, 0.0)),
            ([5.0, 0.0, 0.0], tilted(20.0, 30.0)),
        ],
        &[Motion::Feed, Motion::Feed],
    );
    assert_eq!(compare(&case, &p, &Value::Null).unwrap().len(), 12);
    let rows = compare(&case, &p, &json!(["CAZ", "ABX"])).unwrap();
    let mut names: Vec<String> = rows.iter().map(|r| r.rtype.name()).collect();
    names.sort_unstable();
    assert_eq!(names, ["ABX", "CAZ"]);
}

/// A segment through the pole of a C-A head whose A stays at 0° or above: C must turn 180°
/// while the tool turns 10°, a flip (more than 30° of the axes, and more than ten times the
/// tool's turn). It is listed as a pole passage and a flip when it cuts, and as a rapid, neither
/// a pole passage nor a flip, when it is reached at rapid. Refining puts points into the cutting one, each marked as inserted (-1),
/// between the original points 0 and 1; the rapid is left as it is.
#[test]
fn a_pole_passage_at_rapid_is_a_rapid() {
    let case = ToolpathCase::read(&json!({ "machine": { "kind": "head-head", "type": "CAZ",
                                                        "rotary": { "mFrom": 0, "mTo": 110 } } }))
    .unwrap();
    let points = [
        ([0.0, 0.0, 0.0], tilted(5.0, 0.0)),
        ([5.0, 0.0, 0.0], tilted(5.0, 180.0)),
        ([10.0, 0.0, 0.0], tilted(6.0, 180.0)),
    ];
    let cutting = path(&points, &[Motion::Feed, Motion::Feed, Motion::Feed]);
    let a = analyse(&case, &cutting).unwrap();
    assert_eq!((a.poles, a.flips, a.rapids), (vec![0], vec![0], vec![]));
    let r = refine(&case, &cutting).unwrap();
    assert!(r.added > 0);
    let n = r.source.len();
    assert_eq!(n, 3 + r.added);
    assert_eq!(
        (r.source[0], r.source[n - 2], r.source[n - 1]),
        (0.0, 1.0, 2.0)
    );
    assert!(r.source[1..n - 2].iter().all(|&s| s == -1.0));
    let at_rapid = path(&points, &[Motion::Feed, Motion::Rapid, Motion::Feed]);
    let a = analyse(&case, &at_rapid).unwrap();
    assert_eq!((a.poles, a.flips, a.rapids), (vec![], vec![], vec![0]));
    let r = refine(&case, &at_rapid).unwrap();
    assert_eq!((r.added, r.source), (0, vec![0.0, 1.0, 2.0]));
}
