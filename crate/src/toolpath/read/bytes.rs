//! A file's bytes as text, piece by piece: UTF-8 (a sequence split between two pieces waits for
//! the next one), and where the bytes are not UTF-8, Windows-1252 (what Windows editors and older
//! CAM systems write: `µ` as the byte 0xB5) from that byte on. A file that is not text at all (an
//! image, a PDF, an archive, UTF-16) is refused by its first bytes, with what it looks like.

use super::FIELD;
use crate::error::{Error, Result};
use std::borrow::Cow;

/// The characters of the bytes 0x80–0x9F in Windows-1252 (the others are Latin-1's: the byte's
/// value; the five undefined bytes map to the C1 controls, as browsers decode them).
const CP1252_80: [char; 32] = [
    '€', '\u{81}', '‚', 'ƒ', '„', '…', '†', '‡', 'ˆ', '‰', 'Š', '‹', 'Œ', '\u{8d}', 'Ž', '\u{8f}',
    '\u{90}', '‘', '’', '“', '”', '•', '–', '—', '˜', '™', 'š', '›', 'œ', '\u{9d}', 'ž', 'Ÿ',
];

/// A byte in Windows-1252.
fn cp1252(b: u8) -> char {
    match b {
        0x80..=0x9f => CP1252_80[usize::from(b - 0x80)],
        _ => char::from(b),
    }
}

/// What a file's first bytes say it is, when it is not text.
fn not_text(head: &[u8]) -> Option<&'static str> {
    const SIGNATURES: [(&[u8], &str); 12] = [
        (b"\x89PNG", "a PNG image"),
        (b"\xff\xd8\xff", "a JPEG image"),
        (b"GIF8", "a GIF image"),
        (b"%PDF", "a PDF document"),
        (b"PK\x03\x04", "a ZIP archive (or an Office document)"),
        (b"\x1f\x8b", "a gzip archive"),
        (b"7z\xbc\xaf", "a 7-Zip archive"),
        (b"Rar!", "a RAR archive"),
        (b"II*\x00", "a TIFF image"),
        (b"MM\x00*", "a TIFF image"),
        (b"\xff\xfe", "UTF-16 text: save it as UTF-8 (or ANSI) text"),
        (b"\xfe\xff", "UTF-16 text: save it as UTF-8 (or ANSI) text"),
    ];
    if let Some((_, what)) = SIGNATURES.iter().find(|(s, _)| head.starts_with(s)) {
        return Some(what);
    }
    // NUL bytes in the first kilobyte: a binary file.
    head.iter()
        .take(1024)
        .any(|&b| b == 0)
        .then_some("a binary file")
}

/// A piece of a file's text.
#[derive(Debug)]
pub(super) struct Piece<'a> {
    pub text: Cow<'a, str>,
    /// The byte of `text` from which it is read as Windows-1252, when the bytes stopped being
    /// UTF-8 in this piece (`text[..i]` is the piece's UTF-8 part).
    pub legacy_from: Option<usize>,
}

/// A streaming decoder (module docs).
#[derive(Debug, Clone, Default)]
pub(super) struct Decoder {
    /// The first bytes have been checked.
    checked: bool,
    /// Bytes of a UTF-8 sequence split at the end of the last piece.
    pending: Vec<u8>,
    /// The bytes stopped being UTF-8: reading as Windows-1252.
    legacy: bool,
}

impl Decoder {
    /// The text of the next piece of bytes.
    pub fn decode<'a>(&mut self, bytes: &'a [u8]) -> Result<Piece<'a>> {
        if !self.checked && !bytes.is_empty() {
            self.checked = true;
            if let Some(what) = not_text(bytes) {
                return Err(Error::field(
                    FIELD,
                    format!("the file is {what}, not a toolpath: expected text (CL data, NC blocks or CSV)"),
                ));
            }
        }
        if self.pending.is_empty() {
            return Ok(self.decode_slice(bytes));
        }
        let mut joined = std::mem::take(&mut self.pending);
        joined.extend_from_slice(bytes);
        let piece = self.decode_slice(&joined);
        Ok(Piece {
            text: Cow::Owned(piece.text.into_owned()),
            legacy_from: piece.legacy_from,
        })
    }

    /// [`Decoder::decode`] of bytes that start where the last piece ended.
    fn decode_slice<'b>(&mut self, data: &'b [u8]) -> Piece<'b> {
        if self.legacy {
            return Piece {
                text: Cow::Owned(data.iter().map(|&b| cp1252(b)).collect()),
                legacy_from: None,
            };
        }
        match std::str::from_utf8(data) {
            Ok(s) => Piece {
                text: Cow::Borrowed(s),
                legacy_from: None,
            },
            Err(e) => {
                let valid = e.valid_up_to();
                let head = std::str::from_utf8(&data[..valid]).unwrap_or("");
                match e.error_len() {
                    // A sequence cut at the end of the piece: it waits for the next one.
                    None => {
                        self.pending = data[valid..].to_vec();
                        Piece {
                            text: Cow::Borrowed(head),
                            legacy_from: None,
                        }
                    }
                    // Not UTF-8: Windows-1252 from here on.
                    Some(_) => {
                        self.legacy = true;
                        let mut s = head.to_owned();
                        s.extend(data[valid..].iter().map(|&b| cp1252(b)));
                        Piece {
                            text: Cow::Owned(s),
                            legacy_from: Some(valid),
                        }
                    }
                }
            }
        }
    }

    /// The end of the file: the bytes of a sequence still cut, which are not UTF-8, in
    /// Windows-1252 (empty when none is).
    pub fn finish(&mut self) -> String {
        let s = self.pending.iter().map(|&b| cp1252(b)).collect();
        self.pending.clear();
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::unwrap_used)]
    fn utf8_split_anywhere_and_windows_1252_and_binary_files() {
        // "Ø6 µm" in UTF-8, split inside Ø (C3 98) and inside µ (C2 B5).
        let text = "(Ø6 µm)\n".as_bytes();
        let mut d = Decoder::default();
        let mut got = String::new();
        for piece in [&text[..2], &text[2..6], &text[6..]] {
            let p = d.decode(piece).unwrap();
            assert_eq!(p.legacy_from, None);
            got.push_str(&p.text);
        }
        got.push_str(&d.finish());
        assert_eq!(got, "(Ø6 µm)\n");
        // "Abweichung (µm)" from a Windows editor: µ is the byte B5 alone, the fifth byte.
        let p = Decoder::default().decode(b"X1\n(\xb5m \x80)\n").unwrap();
        assert_eq!(p.text, "X1\n(µm €)\n");
        assert_eq!(p.legacy_from, Some(4));
        for (head, what) in [
            (&b"\x89PNG\r\n\x1a\n"[..], "a PNG image"),
            (b"%PDF-1.7", "a PDF document"),
            (b"PK\x03\x04", "a ZIP archive"),
            (b"G1 X\x00", "a binary file"),
            (b"\xff\xfeG\x00", "UTF-16 text"),
        ] {
            let e = Decoder::default().decode(head).map(|_| ()).unwrap_err();
            assert!(
                e.message.starts_with(&format!("the file is {what}")),
                "{}",
                e.message
            );
        }
    }
}
