// The text of each page of a PDF, as Ghostscript's text device reads it (Debian's `gs`, the
// `ghostscript` package; the page's own code plays no part). Used by the report tests to check
// what is printed on which page.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

/** The text of each page of the PDF at `path`, in page order. */
export function pdfPages(path) {
  const dir = mkdtempSync(join(tmpdir(), 'pdftext-'));
  try {
    execFileSync(process.env.GS ?? 'gs', ['-q', '-dNOPAUSE', '-dBATCH', '-dSAFER', '-sDEVICE=txtwrite', `-sOutputFile=${join(dir, 'p-%04d.txt')}`, path]);
    return readdirSync(dir).sort().map((f) => readFileSync(join(dir, f), 'utf8'));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** Renders the pages of a PDF to PNG files `<prefix>-01.png` … (for looking at them). */
export function pdfImages(path, prefix, dpi = 60) {
  execFileSync(process.env.GS ?? 'gs', ['-q', '-dNOPAUSE', '-dBATCH', '-dSAFER', '-sDEVICE=png16m', `-r${dpi}`, `-sOutputFile=${prefix}-%02d.png`, path]);
}
