// Validates .glb files with the Khronos glTF-Validator (npm gltf-validator).
// Usage: NODE_PATH=<build>/npm/node_modules node validate_gltf.mjs FILE.glb...
// Prints the issue counts and every message; exits 1 when any file has an error or a warning
// (infos and hints, e.g. "unsupported extension EXT_mesh_gpu_instancing", are allowed).
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

// An ESM import ignores NODE_PATH, so resolve through require() rooted in the modules dir.
function loadValidator() {
  const here = path.dirname(fileURLToPath(import.meta.url));
  const candidates = [
    ...(process.env.NODE_PATH || '').split(path.delimiter).filter(Boolean),
    path.resolve(here, '../../build/npm/node_modules'),
  ];
  for (const dir of candidates) {
    try {
      return createRequire(path.join(path.resolve(dir), 'x'))('gltf-validator');
    } catch (e) {
      if (e.code !== 'MODULE_NOT_FOUND') throw e;
    }
  }
  console.error(`gltf-validator not found in: ${candidates.join(', ')}`);
  process.exit(2);
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: validate_gltf.mjs FILE.glb...');
  process.exit(2);
}
const validator = loadValidator();
let failed = false;
for (const file of files) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, { maxIssues: 200 });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ` +
              `${i.numInfos} infos, ${i.numHints} hints (validator ${report.validatorVersion})`);
  const severity = ['error', 'warning', 'info', 'hint'];
  for (const m of i.messages)
    console.log(`  ${severity[m.severity] ?? m.severity} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  if (i.numErrors > 0 || i.numWarnings > 0) failed = true;
}
process.exit(failed ? 1 : 0);
