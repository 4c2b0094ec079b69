// Runs the Khronos glTF validator on glTF files or on every .glb/.gltf of the folders given.
// Usage: node validate.mjs [--max-warnings N] PATH...   Exit 1 when a file has an error or more
// warnings than allowed. The validator does not decode Draco payloads (it reports them as info).
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');

const args = process.argv.slice(2);
let maxWarnings = Infinity;
const paths = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--max-warnings') maxWarnings = Number(args[++i]);
  else paths.push(args[i]);
}
if (paths.length === 0) {
  console.error('usage: node validate.mjs [--max-warnings N] PATH...');
  process.exit(2);
}

const files = [];
for (const p of paths) {
  if (statSync(p).isDirectory()) {
    for (const f of readdirSync(p).sort()) if (/\.(glb|gltf)$/.test(f)) files.push(join(p, f));
  } else files.push(p);
}
if (files.length === 0) {
  console.error('validate: no glTF files in ' + paths.join(' '));
  process.exit(1);
}

let failed = false;
for (const file of files) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    uri: file,
    externalResourceFunction: (uri) => Promise.resolve(new Uint8Array(readFileSync(resolve(dirname(file), decodeURIComponent(uri))))),
  });
  const { numErrors, numWarnings, numInfos } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos`);
  for (const m of report.issues.messages) {
    if (m.severity <= 1) console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} at ${m.pointer}: ${m.message}`);
  }
  if (numErrors > 0 || numWarnings > maxWarnings) failed = true;
}
process.exit(failed ? 1 : 0);
