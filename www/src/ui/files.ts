// Reading a file the user chose, the same way on every panel: a file that is not text refused by
// its first bytes with a sentence naming it; UTF-8, else Windows-1252, and a note saying which.
import { track } from '../engine/idle';
import { binaryKind, decodeText, HEAD_BYTES, refusal, WINDOWS_1252_NOTE } from './decode';

export { WINDOWS_1252_NOTE } from './decode';

/** A file refused because it is not text: `message` is the sentence to show. */
export class FileRefused extends Error {}

/** The sentence refusing `file` by its first bytes (an image, a PDF, an archive …), or null. */
export function checkFile(file: Blob, name: string, expected?: string): Promise<string | null> {
  return track(
    file.slice(0, HEAD_BYTES).arrayBuffer().then((b) => {
      const what = binaryKind(new Uint8Array(b));
      return what ? refusal(name, what, expected) : null;
    }),
  );
}

/** A chosen file's text (see decode.ts); throws FileRefused for a file that is not text. */
export function readTextFile(file: File, expected?: string): Promise<{ text: string; windows1252: boolean }> {
  return track(
    file.arrayBuffer().then((b) => {
      const bytes = new Uint8Array(b);
      const what = binaryKind(bytes.subarray(0, HEAD_BYTES));
      if (what) throw new FileRefused(refusal(file.name, what, expected));
      return decodeText(bytes);
    }),
  );
}

/** `readTextFile`, or null after `refused(message)` when the file is not text (an image, a PDF,
 *  an archive): each panel says so and greys what the file would have replaced. */
export async function readOrRefuse(file: File, refused: (message: string) => void, expected?: string): Promise<{ text: string; windows1252: boolean } | null> {
  try {
    return await readTextFile(file, expected);
  } catch (e) {
    if (!(e instanceof FileRefused)) throw e;
    refused(e.message);
    return null;
  }
}

/** " (read as Windows-1252: not valid UTF-8)" for a file read so, else "". */
export const encodingNote = (r: { windows1252: boolean }) => (r.windows1252 ? ` (${WINDOWS_1252_NOTE})` : '');
