// A file's bytes as text, for every file the page reads: UTF-8, else Windows-1252 (what Windows
// editors and older measuring software write: µ as the byte 0xB5); a file that is not text (an
// image, a PDF, an archive, UTF-16) is known by its first bytes. No DOM: the toolpath worker
// uses it too.

/** What the page says next to a file read as Windows-1252. */
export const WINDOWS_1252_NOTE = 'read as Windows-1252: not valid UTF-8';

/** Bytes looked at for a signature and for NUL bytes. */
export const HEAD_BYTES = 4096;

/** First bytes of files that are not text, and what the file is then. */
const SIGNATURES: [number[], string][] = [
  [[0x89, 0x50, 0x4e, 0x47], 'a PNG image'],
  [[0xff, 0xd8, 0xff], 'a JPEG image'],
  [[0x47, 0x49, 0x46, 0x38], 'a GIF image'],
  [[0x25, 0x50, 0x44, 0x46], 'a PDF document'],
  [[0x50, 0x4b, 0x03, 0x04], 'a ZIP archive (an Excel .xlsx or Word .docx file is one)'],
  [[0x50, 0x4b, 0x05, 0x06], 'a ZIP archive (empty)'],
  [[0x1f, 0x8b], 'a gzip archive'],
  [[0x37, 0x7a, 0xbc, 0xaf], 'a 7-Zip archive'],
  [[0x52, 0x61, 0x72, 0x21], 'a RAR archive'],
  [[0xd0, 0xcf, 0x11, 0xe0], 'an old Office document (Excel .xls or Word .doc)'],
  [[0x49, 0x49, 0x2a, 0x00], 'a TIFF image'],
  [[0x4d, 0x4d, 0x00, 0x2a], 'a TIFF image'],
  [[0xff, 0xfe], 'UTF-16 text (save it as UTF-8 or ANSI text)'],
  [[0xfe, 0xff], 'UTF-16 text (save it as UTF-8 or ANSI text)'],
];

/** What the first bytes of a file say it is when it is not text ("a PNG image"), else null. */
export function binaryKind(head: Uint8Array): string | null {
  for (const [sig, what] of SIGNATURES) {
    if (head.length >= sig.length && sig.every((b, i) => head[i] === b)) return what;
  }
  // RIFF….WEBP
  if (head.length >= 12 && String.fromCharCode(...head.subarray(0, 4)) === 'RIFF' && String.fromCharCode(...head.subarray(8, 12)) === 'WEBP') return 'a WebP image';
  return head.subarray(0, HEAD_BYTES).includes(0) ? 'a binary file' : null;
}

/** The sentence refusing file `name` of kind `what`. */
export function refusal(name: string, what: string, expected = 'a program or a table of numbers'): string {
  return `${name} is ${what}, not ${expected}.`;
}

/** The text of a whole file: UTF-8 (a leading BOM dropped), else Windows-1252. */
export function decodeText(bytes: Uint8Array): { text: string; windows1252: boolean } {
  try {
    return { text: new TextDecoder('utf-8', { fatal: true }).decode(bytes), windows1252: false };
  } catch {
    return { text: new TextDecoder('windows-1252').decode(bytes), windows1252: true };
  }
}

/** Whether bytes given piece by piece are all UTF-8 (for a file too large to hold as text). */
export function utf8Check() {
  const decoder = new TextDecoder('utf-8', { fatal: true });
  let valid = true;
  return {
    feed(piece: Uint8Array) {
      if (!valid) return;
      try {
        decoder.decode(piece, { stream: true });
      } catch {
        valid = false;
      }
    },
    /** True when every byte was UTF-8 (a sequence cut at the end is not). */
    finish(): boolean {
      if (!valid) return false;
      try {
        decoder.decode();
        return true;
      } catch {
        return false;
      }
    },
  };
}
