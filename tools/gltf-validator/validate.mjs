// Validates glTF/GLB files with the Khronos glTF-Validator; exits 1 when any file has an error.
// Usage: node validate.mjs FILE...
import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
let validator;
try {
    validator = createRequire(path.join(here, "package.json"))("gltf-validator");
} catch {
    console.error(`gltf-validator is not installed in ${here}: run scripts/setup.sh (npm ci)`);
    process.exit(1);
}

const files = process.argv.slice(2);
if (files.length === 0) {
    console.error("usage: node validate.mjs FILE...");
    process.exit(2);
}
let failed = 0;
for (const file of files) {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 100,
    });
    const { numErrors, numWarnings, messages } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings`);
    for (const m of messages) {
        if (m.severity <= 1) console.log(`  [${m.severity === 0 ? "error" : "warning"}] ${m.code} ${m.pointer ?? ""}: ${m.message}`);
    }
    if (numErrors > 0) failed++;
}
process.exit(failed > 0 ? 1 : 0);
