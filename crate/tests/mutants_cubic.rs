//! Tests written for mutants of `crate/src/cubic/mod.rs` that a sampled mutation run let survive
//! (`npm run mutants -- cubic`): the limits of the cut that the field table cannot check, each
//! at and just past its documented bound.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use fiveaxis::cubic::{CubicPiece, MAX_PASSES_PER_ZONE};
use fiveaxis::schema::Inputs;
use serde_json::json;

fn piece(zone: f64, radius: f64, pick: f64) -> CubicPiece {
    CubicPiece::from_value(
        &json!({ "zoneSize": zone, "toolRadius": radius, "pick": pick }),
        "",
    )
    .unwrap()
}

/// The pick feed must be less than the ball's diameter 2r: with r = 3 mm, 5.9 mm is accepted
/// and 6 mm refused.
#[test]
fn the_pick_must_be_less_than_the_ball_diameter() {
    assert!(piece(16.0, 3.0, 5.9).validate().is_ok());
    let e = piece(16.0, 3.0, 6.0).validate().unwrap_err();
    assert_eq!(e.field, "setup.pick");
    assert!(e.message.contains("diameter 6 mm"), "{}", e.message);
}

/// The pick feed may equal the zone size (one pass at each edge: 2 passes) but not exceed it.
#[test]
fn the_pick_may_equal_the_zone_but_not_exceed_it() {
    let at = piece(16.0, 10.0, 16.0);
    assert!(at.validate().is_ok());
    assert_eq!(at.passes_per_zone(), 2);
    let e = piece(16.0, 10.0, 17.0).validate().unwrap_err();
    assert!(e.message.contains("zone size 16 mm"), "{}", e.message);
}

/// `n = ⌈zone/pick⌉` intervals make n + 1 passes: exactly MAX_PASSES_PER_ZONE is accepted
/// (zone 20 mm, pick 20/19999 mm), one more (pick 0.001 mm: 20001 passes) refused.
#[test]
fn exactly_the_largest_number_of_passes_is_accepted() {
    let n = (MAX_PASSES_PER_ZONE - 1) as f64;
    let at = piece(20.0, 3.0, 20.0 / n);
    assert_eq!(at.passes_per_zone(), MAX_PASSES_PER_ZONE);
    assert!(at.validate().is_ok());
    let past = piece(20.0, 3.0, 0.001);
    assert_eq!(past.passes_per_zone(), 20_001);
    assert!(past
        .validate()
        .unwrap_err()
        .message
        .contains("passes per zone"));
}
