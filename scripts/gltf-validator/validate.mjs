// Validates glTF / GLB files with the Khronos glTF-Validator.
// Usage: node validate.mjs FILE...
// Prints one line per file ("ok FILE" or its issues); exits 1 when any
// file has an error or a warning.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    // Buffers next to a .gltf file.
    externalResourceFunction: (uri) =>
      readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const { numErrors, numWarnings } = report.issues;
  if (numErrors > 0 || numWarnings > 0) {
    failed = true;
    const messages = report.issues.messages
      .filter((m) => m.severity <= 1)
      .map((m) => `${m.code} at ${m.pointer ?? '?'}: ${m.message}`);
    console.log(`FAIL ${file}: ${numErrors} error(s), ${numWarnings} warning(s)\n  ${messages.join('\n  ')}`);
  } else {
    console.log(`ok ${file}`);
  }
}
process.exit(failed ? 1 : 0);
