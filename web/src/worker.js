// The Web Worker that owns the Glint module (glint-mt.js with threads, glint-st.js without):
// the page's scene files live in the module's virtual file system, and renders advance a few
// tiles per call to Session.step, between which this worker returns to its event loop, so that
// the page gets the image tile by tile and its Cancel is heard. The page never waits on it.
//
// Messages from the page: init {variant, threads}; files {files: [{path, data}]};
// check {id, path, text}; render {id, path, text, reload, options, camera, time}; cancel {id};
// save {id}. Replies: ready, denoiser, checked, loaded, tiles, done, cancelled, failed, saved.
//
// A render's time is {animation, seconds} (a model's animation by index, posed at that many
// seconds; seconds "start": at its first key), or null: as loaded. A new time poses the loaded
// model again from the files parsed before (Session.load's reuse), unless files changed since.

let M = null;
let session = null;
let kernels = null;  // the traversal kernels scenes are prepared for (init)
let current = null;  // the render in progress: {id, cancelled}
let loadedPath = null, loadedText = null, loadedKey = null;
let loadedTime = null;  // the time the loaded model was posed at: {animation, seconds}, or null
let loadedVariant = '';  // the material variant the loaded model shows ('': the file's own)
let filesChanged = false;  // files written since the last load: model files are read again

const yieldToEvents = (() => {
    const channel = new MessageChannel();
    const waiting = [];
    channel.port1.onmessage = () => waiting.shift()();
    return () => new Promise((resolve) => {
        waiting.push(resolve);
        channel.port2.postMessage(0);
    });
})();

function mkdirs(path) {
    const parts = path.split('/').filter(Boolean);
    let dir = '';
    for (const part of parts.slice(0, -1)) {
        dir += '/' + part;
        if (!M.FS.analyzePath(dir).exists) M.FS.mkdir(dir);
    }
}

function writeFile(path, data) {
    mkdirs(path);
    M.FS.writeFile(path, typeof data === 'string' ? data : new Uint8Array(data));
}

async function init({ variant, threads, kernels: kernelsAsked, base }) {
    const started = performance.now();
    importScripts(base + `glint-${variant}.js`);
    M = await self.GlintModule({
        glintThreads: threads,
        locateFile: (file) => base + file,
        // Where the pthread Workers load the module from (loaded here by importScripts, it
        // cannot tell).
        mainScriptUrlOrBlob: base + `glint-${variant}.js`,
        print: () => {},
        printErr: (text) => console.warn('glint:', text),
    });
    session = new M.Session(variant === 'mt' ? threads : 1);
    kernels = kernelsAsked === 'portable' ? 'portable' : M.kernels();
    postMessage({
        type: 'ready',
        variant,
        threads: session.threads(),
        kernels,
        commands: M.commandNames(),
        integrators: M.integratorNames(),
        ms: performance.now() - started,
    });
    // The network denoiser's weights (Open Image Denoise's, beside the page when the build had
    // them: denoise-weights/README.md), fetched once the module is ready so that nothing waits
    // for them: a render that ends before they are here is denoised by the filter.
    try {
        const response = await fetch(base + 'denoise/rt_hdr_alb_nrm.tza');
        if (response.ok) {
            const error = M.registerWeights('rt_hdr_alb_nrm',
                                            new Uint8Array(await response.arrayBuffer()));
            if (error) console.warn('glint:', error);
        }
    } catch (e) {
        console.warn('glint: the denoiser\'s weights did not come:', e);
    }
    postMessage({ type: 'denoiser', name: M.denoiser() });
}

function check({ id, path, text }) {
    writeFile(path, text);
    const result = session.load(path, { prepare: false });
    postMessage({ type: 'checked', id, path, result });
}

/// Copies the rectangle [x0, x1) x [y0, y1) of the RGBA image out of the module's memory.
function crop(image, width, x0, y0, x1, y1) {
    const w = x1 - x0, h = y1 - y0;
    const out = new Uint8ClampedArray(w * h * 4);
    for (let y = 0; y < h; ++y) {
        const from = ((y0 + y) * width + x0) * 4;
        out.set(image.subarray(from, from + w * 4), y * w * 4);
    }
    return out;
}

const timeKey = (t) => (t ? `${t.animation ?? ''}@${t.seconds}` : 'still');

async function render({ id, path, text, reload, options, camera, preview, time }) {
    const job = { id, cancelled: false };
    current = job;
    // What the loaded scene depends on besides its text: a model's look and framing (the full
    // image's size, also for a preview).
    const key = JSON.stringify([options.integrator, options.frameWidth, options.frameHeight]);
    // Another material variant: the file read anew (a parsed model keeps the variant it had).
    const same = !filesChanged && path === loadedPath && text === loadedText &&
                 (options.variant || '') === loadedVariant;
    const when = time || (same ? loadedTime : null);
    const reposing = same && timeKey(when) !== timeKey(loadedTime);  // the same model, a new time
    if (reload || !same || (key !== loadedKey && !preview) || reposing) {
        if (text !== undefined && text !== null) writeFile(path, text);
        const result = session.load(path, { prepare: true, integrator: options.integrator,
                                            width: options.frameWidth, height: options.frameHeight,
                                            kernels, animation: when ? when.animation : undefined,
                                            time: when ? when.seconds : undefined,
                                            variant: options.variant || undefined, reuse: same });
        postMessage({ type: 'loaded', id, path, result, reposed: reposing,
                      camera: result.ok ? session.camera(true) : null });
        filesChanged = false;
        if (!result.ok) {
            loadedPath = null;
            postMessage({ type: 'failed', id, error: result.error });
            return;
        }
        loadedPath = path;
        loadedText = text;
        loadedKey = key;
        loadedVariant = options.variant || '';
        loadedTime = result.animation === null
            ? null : { animation: result.animation, seconds: result.time };
    }
    if (camera) session.setCamera(camera);
    const begun = session.begin(options);
    if (begun.error) {
        postMessage({ type: 'failed', id, error: begun.error });
        return;
    }
    const { width, height } = begun;
    // The first call short, so that the first tiles show at once; then about 40 ms per call
    // (each call's tiles are posted together; Cancel is heard between calls).
    for (let calls = 0; ; ++calls) {
        const r = session.step(calls === 0 ? 10 : 40);
        if (r.error) {
            postMessage({ type: 'failed', id, error: r.error });
            return;
        }
        if (r.x1 > r.x0 && r.y1 > r.y0) {
            const pixels = crop(session.image(), width, r.x0, r.y0, r.x1, r.y1);
            postMessage({ type: 'tiles', id, width, height, rect: [r.x0, r.y0, r.x1, r.y1], pixels,
                          progress: r }, [pixels.buffer]);
        }
        if (r.done) {
            postMessage({ type: 'done', id, progress: r });
            return;
        }
        await yieldToEvents();  // hear Cancel, or a newer render
        if (job.cancelled || current !== job) {
            postMessage({ type: 'cancelled', id, progress: r });
            return;
        }
    }
}

function save({ id }) {
    const error = session.save('/glint-download.png');
    const data = error ? null : M.FS.readFile('/glint-download.png');
    postMessage({ type: 'saved', id, error, data }, data ? [data.buffer] : []);
}

self.onmessage = async (event) => {
    const message = event.data;
    try {
        switch (message.type) {
            case 'init': return await init(message);
            case 'files':
                for (const f of message.files) writeFile(f.path, f.data);
                filesChanged = true;
                return postMessage({ type: 'files-written', id: message.id });
            case 'check': return check(message);
            case 'render': return await render(message);
            case 'cancel':
                if (current && current.id === message.id) current.cancelled = true;
                return;
            case 'save': return save(message);
        }
    } catch (e) {
        postMessage({ type: 'failed', id: message.id,
                      error: { text: 'error: ' + (e && e.message ? e.message : String(e)),
                               line: 0, column: 0 } });
    }
};
