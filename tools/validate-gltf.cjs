#!/usr/bin/env node
// Validates glTF 2.0 files (.gltf or .glb) with the Khronos glTF validator.
//   node tools/validate-gltf.cjs FILE... [--json]
// Prints one line per file (errors, warnings) and each error; exits 1 if any file has an
// error, 2 on bad usage or an unreadable file.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const directory = path.dirname(file);
    return validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 100,
        externalResourceFunction: (uri) =>
            new Promise((resolve, reject) => {
                fs.readFile(path.resolve(directory, decodeURIComponent(uri)), (error, data) =>
                    error ? reject(error.toString()) : resolve(new Uint8Array(data)));
            }),
    });
}

async function main() {
    const args = process.argv.slice(2);
    const json = args.includes('--json');
    const files = args.filter((a) => a !== '--json');
    if (files.length === 0) {
        console.error('usage: validate-gltf.cjs FILE... [--json]');
        return 2;
    }
    let failed = false;
    for (const file of files) {
        let report;
        try {
            report = await validate(file);
        } catch (error) {
            console.error(`${file}: cannot validate: ${error}`);
            return 2;
        }
        const issues = report.issues;
        if (json) {
            console.log(JSON.stringify(report));
        }
        console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
                    `${issues.numInfos} infos`);
        for (const message of issues.messages) {
            if (message.severity === 0) {
                console.log(`  error ${message.code} at ${message.pointer}: ${message.message}`);
            }
        }
        failed = failed || issues.numErrors > 0;
    }
    return failed ? 1 : 0;
}

main().then((code) => process.exit(code));
