// Validates .glb files with the Khronos glTF validator; exits 1 if any has an error or a warning,
// printing what the validator reported. Usage: node validate.js FILE...
"use strict";
const fs = require("fs");
const validator = require("gltf-validator");

async function main(files) {
  let failed = false;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)));
    const { numErrors, numWarnings } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings (validator ${report.validatorVersion})`);
    for (const m of report.issues.messages) {
      console.log(`  severity ${m.severity} ${m.code} at ${m.pointer || "-"}: ${m.message}`);
    }
    if (numErrors > 0 || numWarnings > 0) failed = true;
  }
  return failed ? 1 : 0;
}

if (process.argv.length < 3) {
  console.error("usage: node validate.js FILE...");
  process.exit(2);
}
main(process.argv.slice(2)).then(
  (code) => process.exit(code),
  (error) => {
    console.error(String(error));
    process.exit(1);
  });
