// The WebAssembly module renders the course's graded scenes to PNG files byte for byte the
// native command line's (docs/web.md). Run by CTest as web.wasm_identical_{mt,st}:
//
//   node --no-experimental-fetch tests/web/wasm_identical.js MODULE.js GLINT DATA_DIR THREADS \
//       [SCENE...]
//
// MODULE.js is glint-mt.js or glint-st.js (make web), GLINT the native binary, DATA_DIR
// tests/data/cse167x. Each further SCENE (Glint's own example scenes: the path tracer, media)
// is rendered the same way at 48 x 36 pixels and 16 samples, its `size` and `spp` lines
// replaced: the path tracer's random numbers and media's tracking are identical too. Each scene is rendered by both, natively with the default kernels (AVX2
// where the CPU has them) and in WebAssembly with its default ones (SIMD128), which are
// bit-identical (both are to the portable ones).
'use strict';
const { execFileSync } = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const [modulePath, glint, dataDir, threadsArg, ...extra] = process.argv.slice(2);
if (!threadsArg) {
    console.error('usage: wasm_identical.js MODULE.js GLINT DATA_DIR THREADS');
    process.exit(2);
}
const threads = Number(threadsArg);
const scenes = ['scene4-ambient', 'scene4-diffuse', 'scene4-emission', 'scene4-specular',
                'scene5', 'scene6', 'scene7'];

(async () => {
    const GlintModule = require(path.resolve(modulePath));
    const M = await GlintModule({ glintThreads: threads });
    const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'glint-wasm-'));
    let failures = 0;
    const jobs = scenes.map((name) => ({ name, scene: path.join(dataDir, name + '.test') }));
    for (const file of extra) {
        const name = path.basename(file, '.test');
        const small = path.join(tmp, name + '.test');
        fs.writeFileSync(small, fs.readFileSync(file, 'utf8')
            .replace(/^size .*$/m, 'size 48 36').replace(/^spp .*$/m, 'spp 16'));
        jobs.push({ name, scene: small });
    }
    for (const { name, scene } of jobs) {
        const nativePng = path.join(tmp, name + '-native.png');
        execFileSync(glint, [scene, '-o', nativePng, '-q', '-t', String(threads)]);
        M.FS.writeFile('/' + name + '.test', fs.readFileSync(scene));
        const start = Date.now();
        const error = M.renderFile('/' + name + '.test', '/' + name + '.png', threads, '');
        const ms = Date.now() - start;
        if (error) {
            console.log(`${name}: FAIL: the module says: ${error}`);
            ++failures;
            continue;
        }
        const wasm = Buffer.from(M.FS.readFile('/' + name + '.png'));
        const native = fs.readFileSync(nativePng);
        const same = wasm.length === native.length && wasm.equals(native);
        let firstDiff = -1;
        if (!same) {
            firstDiff = 0;
            while (firstDiff < Math.min(wasm.length, native.length) &&
                   wasm[firstDiff] === native[firstDiff]) ++firstDiff;
            fs.writeFileSync(path.join(tmp, name + '-wasm.png'), wasm);
        }
        console.log(`${name}: ${same ? 'identical' : 'DIFFERENT'} (${wasm.length} bytes; native ` +
                    `${native.length}${same ? '' : `, first difference at byte ${firstDiff}`}); ` +
                    `wasm render ${ms} ms on ${threads} thread(s)`);
        if (!same) ++failures;
    }
    if (failures) console.log(`${failures} scene(s) differ; files kept in ${tmp}`);
    else fs.rmSync(tmp, { recursive: true });
    process.exit(failures ? 1 : 0);
})().catch((e) => {
    console.error(e);
    process.exit(1);
});
