// The web build against the native CLI (docs/performance.md, "The web build"). Not a test:
// figures, printed as a Markdown table. After make web and a native build:
//
//   node bench/web_bench.mjs --site build-web/site --glint build/glint [--runs 3]
//        [--screenshot docs/images/web.png]
//
// 1. scene7 in headless Chromium, threaded build on 2 threads, against `glint -t 2`;
// 2. the same with the portable kernels (?kernels=portable) against `glint -t 2 --kernels
//    portable`;
// 3. scene7 single-threaded (the page served without isolation) against `glint -t 1`;
// 4. the demo's first pixels on the canvas after opening the page (from navigation start);
// 5. the size of the modules and the page's code, raw and gzipped.
// Render times are medians of --runs; the module's is the time in render() summed over its
// tile batches, as --stats times the CLI's render (parse and BVH build excluded on both sides).
// A native render follows each web render, so that the ratio compares like with like.
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import zlib from 'node:zlib';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const { chromium } = createRequire(path.join(root, 'web/package.json'))('playwright-core');
const args = { runs: '3' };
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].slice(2)] = process.argv[i + 1];
if (!args.site || !args.glint) {
    console.error('usage: web_bench.mjs --site build-web/site --glint build/glint [--runs N]');
    process.exit(2);
}
const runs = Number(args.runs);
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const scene7 = path.join(root, 'tests/data/cse167x/scene7.test');

/// One native render of scene7: its render time (--stats).
function nativeRender(extra) {
    const out = execFileSync(args.glint, [scene7, '-o', '/tmp/glint-bench.png', '-q', '--stats',
                                          ...extra]).toString();
    return Number(/render ([\d.]+) s/.exec(out)[1]);
}

async function serve(isolated) {
    const server = spawn(process.execPath, [path.join(root, 'web/tools/serve.mjs'), args.site,
                                            '--port', '0', '--quiet',
                                            ...(isolated ? [] : ['--no-isolation'])]);
    const address = await new Promise((resolve) =>
        server.stdout.once('data', (d) => resolve(String(d).trim().split('\n')[0])));
    return { server, address };
}

async function waitDone(page, count) {
    await page.waitForFunction((n) => window.glintPage.rendersDone >= n &&
                                      window.glintPage.state === 'done', count,
                               { timeout: 300000, polling: 50 });
    return page.evaluate(() => window.glintPage);
}

const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true,
                                        args: ['--no-sandbox', '--disable-dev-shm-usage'] });
const rows = [];
// Threaded with the module's default kernels (SIMD128), threaded with the portable ones (what
// SIMD128 bought), single-threaded with each: each against the native CLI with the kernels named, one
// native render after each web render, so that both see the same load on a shared machine.
const configs = [
    { isolated: true, kernels: 'auto', native: ['-t', '2'] },
    { isolated: true, kernels: 'portable', native: ['-t', '2', '--kernels', 'portable'] },
    { isolated: false, kernels: 'auto', native: ['-t', '1'] },
    { isolated: false, kernels: 'portable', native: ['-t', '1', '--kernels', 'portable'] },
];
for (const { isolated, kernels, native: nativeArgs } of configs) {
    const { server, address } = await serve(isolated);
    const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
    await page.goto(`${address}?threads=2&example=scene7&kernels=${kernels}`);
    // The first render runs on the browser's baseline WebAssembly code (Liftoff) while the
    // optimised code (TurboFan) is compiled: reported alone; the median is of the runs after.
    const times = [], walls = [], natives = [];
    let first = 0;
    for (let i = 1; i <= runs + 1; ++i) {
        if (i > 1) await page.click('#render');
        const g = await waitDone(page, i);
        if (i === 1) first = g.last.seconds;
        else {
            times.push(g.last.seconds);
            walls.push(g.last.wallMs / 1000);
            natives.push(nativeRender(nativeArgs));
        }
    }
    const g = await page.evaluate(() => window.glintPage);
    const native = median(natives);
    const web = median(times);
    rows.push([`scene7, ${isolated ? `threaded build, ${g.threads} threads` : 'single-threaded build'}, ${g.kernels} kernels`,
               `${web.toFixed(3)} s (first run ${first.toFixed(2)} s; with parse and build ${median(walls).toFixed(2)} s)`,
               `${native.toFixed(3)} s (\`${nativeArgs.join(' ')}\`)`,
               `${(web / native).toFixed(2)}x`]);
    await page.close();
    server.kill();
}

// The demo's first pixels, from a fresh page each time.
{
    const { server, address } = await serve(true);
    const firsts = [];
    for (let i = 0; i < runs; ++i) {
        const page = await browser.newPage();
        await page.goto(address);
        await page.waitForFunction(() => window.glintPage.firstPixelMs !== null, null,
                                   { timeout: 60000, polling: 10 });
        firsts.push(await page.evaluate(() => window.glintPage.firstPixelMs));
        if (i === 0 && args.screenshot) {
            await waitDone(page, 1);
            await page.screenshot({ path: args.screenshot });
        }
        await page.close();
    }
    rows.push(['the demo\'s first pixels after opening the page', `${Math.round(median(firsts))} ms`, '', '']);
    server.kill();
}
await browser.close();

console.log('| what | web | native | web / native |');
console.log('|---|---|---|---|');
for (const r of rows) console.log(`| ${r.join(' | ')} |`);

console.log('\n| file | bytes | gzipped |');
console.log('|---|---|---|');
let total = 0, totalGz = 0;
for (const f of ['glint-mt.wasm', 'glint-mt.js', 'glint-mt.worker.js', 'glint-st.wasm', 'glint-st.js',
                 'main.js', 'worker.js']) {
    const data = fs.readFileSync(path.join(args.site, f));
    const gz = zlib.gzipSync(data, { level: 9 }).length;
    console.log(`| ${f} | ${data.length} | ${gz} |`);
    if (!f.startsWith('glint-st')) {
        total += data.length;
        totalGz += gz;
    }
}
console.log(`| what the threaded page loads | ${total} | ${totalGz} |`);
