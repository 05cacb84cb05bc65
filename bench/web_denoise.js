// The web build's denoisers (docs/performance.md, "The network denoiser"). Not a test: figures.
// In Node, the module of `make web` (glint-mt.js on THREADS threads, or glint-st.js) renders
// the glass scene (scenes/glass.test) path traced at WIDTHxHEIGHT with 1 sample per pixel and the denoiser on, once
// with the filter (nlm) and once with the network (OIDN's balanced weights, registered as the
// page registers them), RUNS times each; prints the median of each denoiser's time (the
// module's own denoiseSeconds: the last pass's denoising, all of its bands).
//
//   node --no-experimental-fetch bench/web_denoise.js build-web/mt/glint-mt.js \
//       denoise-weights/oidn/rt_hdr_alb_nrm.tza [WIDTH HEIGHT THREADS RUNS]
'use strict';
const fs = require('fs');
const path = require('path');

const [modulePath, weights, w = '640', h = '480', t = '2', r = '3'] = process.argv.slice(2);
if (!weights) {
    console.error('usage: web_denoise.js MODULE.js WEIGHTS.tza [WIDTH HEIGHT THREADS RUNS]');
    process.exit(2);
}
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

(async () => {
    const threads = Number(t);
    const M = await require(path.resolve(modulePath))({ glintThreads: threads });
    const error = M.registerWeights('rt_hdr_alb_nrm', new Uint8Array(fs.readFileSync(weights)));
    if (error) throw new Error(error);
    const scene = path.join(__dirname, '..', 'scenes', 'glass.test');
    M.FS.writeFile('/glass.test', fs.readFileSync(scene));
    const session = new M.Session(threads);
    const loaded = session.load('/glass.test', { prepare: true, integrator: 'path' });
    if (!loaded.ok) throw new Error(JSON.stringify(loaded));
    for (const denoiser of ['nlm', 'oidn']) {
        const times = [];
        let name = '';
        for (let run = 0; run < Number(r); ++run) {
            const begun = session.begin({ width: Number(w), height: Number(h), spp: 1,
                                          denoise: true, denoiser });
            if (begun.error) throw new Error(JSON.stringify(begun.error));
            let s;
            do s = session.step(1000); while (!s.done && !s.error);
            if (s.error) throw new Error(JSON.stringify(s.error));
            times.push(s.denoiseSeconds);
            name = s.denoiser;
        }
        console.log(`${w}x${h}, ${threads} threads (${M.kernels ? M.kernels() : ''}): ` +
                    `${name} ${median(times).toFixed(3)} s (median of ${r})`);
    }
    process.exit(0);
})().catch((e) => { console.error(e); process.exit(1); });
