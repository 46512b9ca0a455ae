//! Tests written for mutants of `crate/src/toolpath/mod.rs` that a sampled mutation run let
//! survive (`npm run mutants -- toolpath`): the case layer the exports read (file format, `L`,
//! the ranking), checked against the documented meaning of each input.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use fiveaxis::rotary::RotaryType;
use fiveaxis::toolpath::parse::Format;
use fiveaxis::toolpath::{ToolpathCase, ToolpathReadInput};
use nalgebra::Vector3;
use serde_json::json;

/// Each named format is the parser's format of that name; `auto` leaves it to detection.
#[test]
fn each_file_format_names_its_parser() {
    let format = |f: &str| {
        ToolpathReadInput::read(&json!({ "format": f }))
            .unwrap()
            .format
            .format()
    };
    assert_eq!(format("auto"), None);
    assert_eq!(format("csv"), Some(Format::Csv));
    assert_eq!(format("apt"), Some(Format::Apt));
    assert_eq!(format("nc"), Some(Format::Nc));
}

/// `L` as given; left out, a head's pivot length plus tool length (the README's definition:
/// 250 + 120 = 370 mm).
#[test]
fn the_swing_length_is_the_given_one_or_pivot_plus_tool() {
    let head =
        json!({ "kind": "head-table", "geometry": { "pivotLength": 250, "toolLength": 120 } });
    let given = ToolpathCase::read(&json!({ "machine": head, "length": 80 })).unwrap();
    assert_eq!(given.length().unwrap(), 80.0);
    let machine = ToolpathCase::read(&json!({ "machine": head })).unwrap();
    assert_eq!(machine.length().unwrap(), 370.0);
}

/// A ranking has one row per type asked for, each of that type, each over every segment of the
/// path (n points: n − 1 segments).
#[test]
fn the_ranking_has_one_row_per_type_over_every_segment() {
    let case = ToolpathCase::read(&json!({ "length": 100 })).unwrap();
    let axes: Vec<Vector3<f64>> = (0..5)
        .map(|i| {
            let a = 0.2 * f64::from(i);
            Vector3::new(a.sin(), 0.3 * a.sin(), a.cos()).normalize()
        })
        .collect();
    let types = [RotaryType::ALL[0], RotaryType::ALL[5], RotaryType::ALL[11]];
    let rows = case.compare(&axes, &types).unwrap();
    assert_eq!(rows.len(), types.len());
    for r in &rows {
        assert!(types.contains(&r.rtype));
        assert_eq!(r.segments, axes.len() - 1);
    }
}
