//! A file's bytes as the page hands them over, piece by piece (`Parser::feed_bytes`,
//! `fiveaxis::toolpath::read::bytes`): UTF-8, else Windows-1252 from the first byte that is not,
//! with a note at that byte's line; what the file is decided by its first bytes alone.

#![allow(clippy::unwrap_used)]
use fiveaxis::toolpath::read::{Format, Note, Parser, Point, Report};

/// Reads `pieces` one after the other as a CSV file: the points and the report.
fn read_pieces(pieces: &[&[u8]]) -> (Vec<Point>, Report) {
    let mut parser = Parser::new(Format::Csv, None, Default::default()).unwrap();
    let mut out = Vec::new();
    for piece in pieces {
        parser.feed_bytes(piece, &mut out).unwrap();
    }
    let report = parser.finish(&mut out).unwrap();
    (out, report)
}

/// The note that the file is read as Windows-1252.
fn legacy_note(r: &Report) -> &Note {
    let notes: Vec<&Note> = r
        .notes
        .iter()
        .filter(|n| n.text.contains("read as Windows-1252"))
        .collect();
    assert_eq!(notes.len(), 1, "{:#?}", r.notes);
    notes[0]
}

/// The note names the line of the first byte that is not UTF-8, in whichever piece it comes:
/// here line 4 (`# Abweichung µm`, µ the byte 0xB5), in the second piece, after two lines of the
/// first and one of its own. (From a mutant that counted the piece's lines from the start of
/// the file.)
#[test]
fn the_note_names_the_line_of_the_first_byte_that_is_not_utf8() {
    let (p, r) = read_pieces(&[
        b"# Messung\n0,0,0,0,0,1\n",
        b"1,0,0,0,0,1\n# Abweichung \xb5m\n2,0,0,0,0,1\n",
    ]);
    assert_eq!(p.len(), 3);
    assert_eq!(p[2].tip.x, 2.0);
    let n = legacy_note(&r);
    assert_eq!(n.line, 4);
    assert!(n.text.starts_with("line 4: "), "{}", n.text);
    // The byte right after a line end is on the next line: the header `µm-Werte` is line 2.
    // (From a mutant that put it one byte early, before that line end.)
    let (_, r) = read_pieces(&[b"# Messung\n\xb5m-Werte\n0,0,0,0,0,1\n"]);
    assert_eq!(legacy_note(&r).line, 2);
}

/// Only the file's first bytes say what it is: a text whose comment holds the bytes that start
/// a GIF image (`GIF89a`) or a PDF (`%PDF`) reads the same wherever the page's pieces are cut,
/// a piece starting with those bytes included. (From the mutant that checked every piece.)
#[test]
fn only_the_first_bytes_say_what_the_file_is() {
    let text: &[u8] = b"# logo GIF89a, drawing %PDF\n0,0,0,0,0,1\n1,2,3,0,0,1\n";
    let (whole, _) = read_pieces(&[text]);
    assert_eq!(whole.len(), 2);
    for cut in 1..text.len() {
        let (p, _) = read_pieces(&[&text[..cut], &text[cut..]]);
        assert_eq!(p, whole, "cut at byte {cut}");
    }
}

/// Lines end with `\n` (Unix), `\r\n` (Windows) or `\r` alone (classic Mac OS), and the note
/// counts them as the reader does: `# Abweichung µm` is line 3 with each, also when a piece is
/// cut between the `\r` and the `\n` of a line end.
#[test]
fn the_line_of_the_note_is_counted_with_any_line_end() {
    for end in [&b"\n"[..], b"\r\n", b"\r"] {
        let mut bytes = Vec::new();
        for line in [
            &b"# Messung"[..],
            b"0,0,0,0,0,1",
            b"# Abweichung \xb5m",
            b"1,0,0,0,0,1",
        ] {
            bytes.extend_from_slice(line);
            bytes.extend_from_slice(end);
        }
        let (p, r) = read_pieces(&[&bytes]);
        assert_eq!(p.len(), 2, "{end:?}");
        assert_eq!(legacy_note(&r).line, 3, "{end:?}");
    }
    let (_, r) = read_pieces(&[b"# Messung\r", b"\n0,0,0,0,0,1\r\n# Abweichung \xb5m\r\n"]);
    assert_eq!(legacy_note(&r).line, 3);
}

/// A file in Windows-1252 whose last byte is `é` (0xE9), with no line end after it: in UTF-8
/// that byte starts a three-byte sequence, which the end of the file cuts. It is read as
/// Windows-1252, and the note names the last line. (From the mutant of `Decoder::finish`
/// returning nothing.)
#[test]
fn a_file_that_ends_inside_a_utf8_sequence_is_windows_1252() {
    let (p, r) = read_pieces(&[b"0,0,0,0,0,1\n# Caf\xe9"]);
    assert_eq!(p.len(), 1);
    assert_eq!(legacy_note(&r).line, 2);
}
