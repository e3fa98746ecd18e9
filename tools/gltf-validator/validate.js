// Runs the Khronos glTF-Validator (npm package gltf-validator, installed here by
// scripts/setup) over glTF files, the way pbrkit's tests and CI check what pbrkit writes.
// Usage: node tools/gltf-validator/validate.js FILE.glb|FILE.gltf ...
// Prints each file's issue counts and every error and warning (with its JSON pointer);
// exits 1 when any file has an error or a warning, 2 when a file cannot be read.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    // External buffers and images of a .gltf are read relative to it, so they are checked
    // too (a missing or short buffer is an error).
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ` +
              `${i.numHints} hints (glTF-Validator ${report.validatorVersion})`);
  for (const m of i.messages) {
    // Severity: 0 error, 1 warning, 2 information, 3 hint.
    const level = ['error', 'warning', 'info', 'hint'][m.severity];
    if (m.severity <= 1) console.log(`  ${level} ${m.code} at ${m.pointer || '/'}: ${m.message}`);
  }
  return i.numErrors + i.numWarnings === 0;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: node validate.js FILE.glb|FILE.gltf ...');
    process.exit(2);
  }
  let ok = true;
  for (const file of files) {
    try {
      ok = (await validate(file)) && ok;
    } catch (e) {
      console.error(`${file}: cannot validate: ${e}`);
      process.exit(2);
    }
  }
  process.exit(ok ? 0 : 1);
})();
