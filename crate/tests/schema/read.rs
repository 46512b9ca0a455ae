//! How the engine reads an input object (`fiveaxis::schema::read`): what its messages say.
//! An export whose inputs are two structs (the cubic height map: the test piece and the grid)
//! refuses a key neither declares with the keys of both; a value of the wrong kind is named in
//! the message, a long text as "a text" rather than all of it.
// Found by cargo-mutants: `==` as `!=` in `read_split`'s key test, and the 40-character guard of
// `what`, changed no outcome of the tests before this file.
#![allow(clippy::unwrap_used)]

use fiveaxis::api::call;
use serde_json::json;

#[test]
fn an_unknown_key_of_a_two_part_input_is_refused_with_the_keys_of_both_parts() {
    let e = call("cubicHeightMap", &json!({ "nx": 11, "bogus": 1 })).unwrap_err();
    assert_eq!(e.field, "bogus", "{e:?}");
    // "nx" is the grid's, "machine" the test piece's.
    assert!(e.message.contains("\"nx\""), "{}", e.message);
    assert!(e.message.contains("\"machine\""), "{}", e.message);
    // A key of either part is read by its part.
    assert!(call("cubicHeightMap", &json!({ "nx": 11, "ny": 11 })).is_ok());
}

#[test]
fn a_value_of_the_wrong_kind_is_named_and_a_long_text_is_not_repeated() {
    let short = call("nonlinearMove", &json!({ "length": "ten" })).unwrap_err();
    assert!(short.message.contains("\"ten\""), "{}", short.message);
    let long = "x".repeat(41);
    let e = call("nonlinearMove", &json!({ "length": long })).unwrap_err();
    assert!(e.message.contains("a text"), "{}", e.message);
    assert!(!e.message.contains(&long), "{}", e.message);
    // 40 characters are still quoted.
    let forty = "y".repeat(40);
    let e = call("nonlinearMove", &json!({ "length": forty })).unwrap_err();
    assert!(e.message.contains(&format!("\"{forty}\"")), "{}", e.message);
}

#[test]
fn a_null_value_is_a_value_left_out() {
    // (The binding turns JavaScript's `undefined` into null: `{ length: undefined }` must read
    // as the default, not as "expected a number, got null".)
    let with_null = call(
        "nonlinearMove",
        &json!({ "length": null, "tolerance": null }),
    )
    .unwrap();
    let without = call("nonlinearMove", &json!({})).unwrap();
    assert_eq!(with_null, without);
}

#[test]
fn a_misspelt_key_is_answered_with_the_one_nearest_key_or_none() {
    use fiveaxis::schema::closest;
    assert_eq!(closest("lenght", &["length", "width"]), Some("length"));
    assert_eq!(closest("LENGTH", &["length", "width"]), Some("length"));
    // Two at the same distance: no guess.
    assert_eq!(closest("ab", &["ac", "ad"]), None);
    assert_eq!(closest("ab", &["ac", "xyz", "ad"]), None);
    // The nearer wins wherever it is in the list.
    assert_eq!(closest("abc", &["axx", "abd"]), Some("abd"));
    assert_eq!(closest("abc", &["abd", "axx"]), Some("abd"));
    // Further than 2 edits: no guess (4 letters before the key are 4 edits).
    assert_eq!(closest("speed", &["length"]), None);
    assert_eq!(closest("zzzzlength", &["length"]), None);
    assert_eq!(closest("zzlength", &["length"]), Some("length"));
}

#[test]
fn a_count_takes_a_whole_number_within_its_limits() {
    for bad in [json!(10.5), json!(0), json!(-3), json!(1e9)] {
        let e = call("cubicHeightMap", &json!({ "nx": bad })).unwrap_err();
        assert_eq!(e.field, "nx", "{e:?}");
        assert!(e.message.contains("whole number"), "{}", e.message);
    }
    assert!(call("cubicHeightMap", &json!({ "nx": 11 })).is_ok());
}

#[test]
fn a_list_left_out_is_an_empty_list() {
    // The rotary ball-bar's tests, left out: the one default test.
    let r = call("ballbarRotarySimulate", &json!({})).unwrap();
    assert_eq!(r["tests"].as_array().unwrap().len(), 1);
}

#[test]
fn a_text_longer_than_its_limit_is_refused_with_its_length() {
    // A rotary ball-bar test's name takes at most 40 bytes.
    let long = "n".repeat(41);
    let e = call(
        "ballbarRotarySimulate",
        &json!({ "tests": [{ "name": long }] }),
    )
    .unwrap_err();
    assert_eq!(e.field, "tests[0].name", "{e:?}");
    assert!(
        e.message.contains("41 bytes long; at most 40"),
        "{}",
        e.message
    );
    assert!(call(
        "ballbarRotarySimulate",
        &json!({ "tests": [{ "name": "n".repeat(40) }] })
    )
    .is_ok());
    let e = call(
        "ballbarRotarySimulate",
        &json!({ "tests": [{ "name": 7 }] }),
    )
    .unwrap_err();
    assert!(
        e.message.contains("expected a text, got 7"),
        "{}",
        e.message
    );
}

#[test]
fn a_list_of_numbers_of_the_wrong_length_is_refused_with_the_count_it_takes() {
    for bad in [json!([1, 0]), json!([1, 0, 0, 0])] {
        let e = call("machineInverse", &json!({ "vector": bad })).unwrap_err();
        assert_eq!(e.field, "vector", "{e:?}");
        assert!(e.message.contains("expected 3 values"), "{}", e.message);
    }
    assert!(call("machineInverse", &json!({ "vector": [0, 0, 1] })).is_ok());
}
