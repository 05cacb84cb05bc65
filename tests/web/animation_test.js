// The module's Session poses an animated glTF at a time, as `glint FILE --time-at T` does, and
// poses it again from the file parsed once (docs/web.md, docs/animation.md). Run by CTest as
// web.animation_st:
//
//   node --no-experimental-fetch tests/web/animation_test.js MODULE.js GLINT GLTF_DIR
//
// MODULE.js is glint-st.js or glint-mt.js (make web), GLINT the native binary, GLTF_DIR
// tests/data/gltf (animated.gltf: animation 0 'Turn', 0 to 4.125 s; a box turning as it rises and
// falls, a small box stepping between three places).
'use strict';
const { execFileSync } = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const [modulePath, glint, gltfDir] = process.argv.slice(2);
if (!gltfDir) {
    console.error('usage: animation_test.js MODULE.js GLINT GLTF_DIR');
    process.exit(2);
}
let failures = 0;
function check(ok, what) {
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
    if (!ok) failures++;
}

(async () => {
    const M = await require(path.resolve(modulePath))({ glintThreads: 1 });
    const session = new M.Session(1);
    const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'glint-anim-'));
    const file = '/anim/animated.gltf';
    const put = () => {
        if (!M.FS.analyzePath('/anim').exists) M.FS.mkdir('/anim');
        M.FS.writeFile(file, fs.readFileSync(path.join(gltfDir, 'animated.gltf')));
    };
    const look = { integrator: 'whitted', width: 96, height: 72, prepare: true };
    const size = ['--integrator', 'whitted', '--size', '96x72', '--spp', '1'];

    /// Renders the loaded scene in one pass (the command line's render) at its own size and
    /// depth (`options` may change them) and returns its RGBA bytes, copied out of the module's
    /// memory.
    function renderImage(options = {}) {
        const begun = session.begin({ spp: 1, integrator: 'whitted', ...options });
        if (begun.error) throw new Error(begun.error.text);
        for (;;) {
            const r = session.step(1000);
            if (r.error) throw new Error(r.error.text);
            if (r.done) return Buffer.from(session.image());
        }
    }
    /// Pixels of `a` and `b` (RGBA bytes) that differ at all.
    function differing(a, b) {
        let n = 0;
        for (let i = 0; i < a.length; i += 4)
            if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) ++n;
        return n;
    }

    // 1. Loaded at its animation's start: the animations are listed, and it is posed there.
    put();
    let r = session.load(file, { ...look, time: 'start' });
    check(r.ok, `animated.gltf loads at the start${r.ok ? '' : ': ' + r.error.text}`);
    const list = r.animations || [];
    check(list.length === 1 && list[0].name === 'Turn' && list[0].start === 0 &&
          list[0].end === 4.125 && list[0].channels === 3,
          `its animations are listed: ${JSON.stringify(list)}`);
    check(r.animation === 0 && r.time === 0, `posed by animation ${r.animation} at ${r.time} s`);
    const home = session.camera(true);

    // 2. Two times, two images; the CLI's pixels at each.
    const times = [1.0, 2.5];
    const images = [];
    for (const t of times) {
        r = session.load(file, { ...look, animation: 0, time: t, reuse: true });
        check(r.ok && r.time === t, `posed again at ${t} s (${r.ok ? r.time : r.error.text})`);
        images.push(renderImage());
        const png = `/anim-${t}.png`, native = path.join(tmp, `native-${t}.png`);
        check(session.save(png) === '', `saved the image at ${t} s`);
        execFileSync(glint, [path.join(gltfDir, 'animated.gltf'), '--time-at', String(t), ...size,
                             '-o', native, '-q']);
        check(Buffer.from(M.FS.readFile(png)).equals(fs.readFileSync(native)),
              `at ${t} s the PNG is glint --time-at ${t}'s byte for byte`);
    }
    const changed = differing(images[0], images[1]);
    check(changed > 96 * 72 / 50, `the images at 1 s and 2.5 s differ (${changed} pixels)`);

    // 3. The same time again gives the same image, posed from the document parsed before: the
    //    file is gone from the virtual files, and reuse still poses it.
    M.FS.unlink(file);
    r = session.load(file, { ...look, animation: 0, time: times[0], reuse: true });
    check(r.ok, `posed again without the file, from the parsed document${r.ok ? '' : ': ' + r.error.text}`);
    // A preview first (small, shallow, as the page's while the slider moves): the full image
    // after it is at the scene's size and depth again.
    const preview = r.ok ? renderImage({ width: 24, height: 18, maxDepth: 0 }) : Buffer.alloc(0);
    check(preview.length === 24 * 18 * 4, `a preview at 24x18 (${preview.length / 4} pixels)`);
    const again = r.ok ? renderImage() : Buffer.alloc(0);
    check(again.equals(images[0]), `1 s twice, after a preview: the same image at 96x72 (${again.length === images[0].length ? differing(again, images[0]) + ' pixels differ' : again.length / 4 + ' pixels'})`);
    r = session.load(file, { ...look, animation: 0, time: times[0] });
    check(!r.ok, `without reuse the file is read again (and is missing): ${r.ok ? 'loaded' : r.error.text}`);

    // 4. A camera the page moved stays where it was put when the model is posed anew; the
    //    model's own framing does not move with time (framed by the whole animation).
    put();
    r = session.load(file, { ...look, time: 'start' });
    const moved = { eye: [3, 2, 4], center: [0.5, 0.5, 0], up: [0, 1, 0] };
    session.setCamera(moved);
    r = session.load(file, { ...look, animation: 0, time: 3, reuse: true });
    const seen = session.camera(false), framed = session.camera(true);
    check(r.ok && JSON.stringify([seen.eye, seen.center, seen.up]) ===
          JSON.stringify([moved.eye, moved.center, moved.up]), `the moved camera stays: ${JSON.stringify(seen)}`);
    check(JSON.stringify(framed) === JSON.stringify(home), 'the framing is the same at 3 s as at the start');

    // 5. Animations by name; errors as the command line's.
    r = session.load(file, { ...look, animation: 'Turn', time: 'start', reuse: true });
    check(r.ok && r.animation === 0 && r.time === 0, `animation 'Turn' by name (${r.animation})`);
    r = session.load(file, { ...look, animation: 'Jump', time: 1, reuse: true });
    check(!r.ok && /no animation is named 'Jump'/.test(r.error.text), `an unknown name: ${r.ok ? 'loaded' : r.error.text}`);
    r = session.load(file, { ...look, time: NaN, reuse: true });
    check(!r.ok && /time/.test(r.error.text), `a time that is not a number: ${r.ok ? 'loaded' : r.error.text}`);
    r = session.load(file, { ...look, reuse: true });
    check(r.ok && r.animation === null && r.time === null && r.animations.length === 1,
          'without a time nothing plays (as glint FILE), and the animations are listed');

    if (failures) console.log(`${failures} check(s) failed; files in ${tmp}`);
    else fs.rmSync(tmp, { recursive: true });
    process.exit(failures ? 1 : 0);
})().catch((e) => {
    console.error(e);
    process.exit(1);
});
