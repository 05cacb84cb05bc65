// Glint's web page: the scene editor, the canvas the worker fills tile by tile, the examples,
// the controls that mirror the command line's, dropped files, the camera under the mouse, and
// an animated model's time (docs/web.md). The renderer runs in a Web Worker (worker.js): this
// page never blocks.
import { EditorView, keymap, lineNumbers } from '@codemirror/view';
import { EditorState } from '@codemirror/state';
import { defaultKeymap, history, historyKeymap } from '@codemirror/commands';
import { lintGutter, setDiagnostics } from '@codemirror/lint';
import { courseLanguage, setCommandNames } from './course-language.js';
import { Orbit } from './orbit.js';

const $ = (id) => document.getElementById(id);
const isolated = self.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function';
const params = new URLSearchParams(location.search);
const variant = isolated ? 'mt' : 'st';
const threads = Math.max(1, Math.min(Number(params.get('threads')) ||
                                     navigator.hardwareConcurrency || 2, 16));
// Traversal kernels, as glint --kernels: the module's default (simd128) unless ?kernels=portable
// (the benchmark compares them).
const kernels = params.get('kernels') || 'auto';

// What the tests and the benchmarks read (tests/web/browser_test.mjs, bench/web_bench.mjs).
const page = (window.glintPage = {
    variant, threads: 1, kernels: null, opened: performance.now(), firstPixelMs: null, rendersDone: 0,
    previewsDone: 0, rendersCancelled: 0, last: null, state: 'starting', checks: 0,
    animations: [], animation: null, time: null, playing: false, materialVariants: [],
});

// ---- the worker -------------------------------------------------------------------------
const worker = new Worker('worker.js');
let nextId = 1;
const pending = new Map();  // id -> resolve, for requests answered once
function request(message, transfer = []) {
    const id = nextId++;
    return new Promise((resolve) => {
        pending.set(id, resolve);
        worker.postMessage({ ...message, id }, transfer);
    });
}

// ---- the editor -------------------------------------------------------------------------
let checked = null;  // the module's last verdict on the editor's text: {error, warnings}
let checkTimer = 0;
let scenePath = '/examples/demo.test';  // where the editor's text lives in the virtual files
let model = null;  // a dropped model rendered on its own (no scene text): its path

const editor = new EditorView({
    parent: $('editor'),
    state: EditorState.create({
        doc: '',
        extensions: [
            lineNumbers(), history(), keymap.of([...defaultKeymap, ...historyKeymap]),
            courseLanguage(), lintGutter(),
            EditorView.updateListener.of((u) => {
                if (u.docChanged && !settingText) scheduleCheck();
            }),
        ],
    }),
});
let settingText = false;
window.glintEditor = editor;  // for the tests: its state holds the text
function setText(text) {
    checked = null;
    settingText = true;
    editor.dispatch({ changes: { from: 0, to: editor.state.doc.length, insert: text } });
    editor.dispatch(setDiagnostics(editor.state, []));
    settingText = false;
}

function scheduleCheck() {
    if (model) showAnimations({});  // the scene's text from now on, not the model's time
    model = null;
    clearTimeout(checkTimer);
    checkTimer = setTimeout(check, 200);
}

/// Parses the editor's text with the module's parser, the command line's: its error, at its
/// line and column, in the editor and under it.
async function check() {
    const text = editor.state.doc.toString();
    const reply = await request({ type: 'check', path: scenePath, text });
    if (text !== editor.state.doc.toString()) return;  // typed on meanwhile: a newer check comes
    page.checks++;
    showDiagnostics(reply.result);
}

/// The last check's error and warnings in the editor's file, as CodeMirror diagnostics of `doc`
/// (the line and column the parser gave, to the end of that line).
function lintDiagnostics(doc) {
    if (!checked) return [];
    const name = scenePath.split('/').pop();
    const mine = (d) => d.file === scenePath || d.file.endsWith('/' + name) || d.file === name;
    const list = [];
    const toCm = (d, severity) => {
        if (!mine(d) || d.line < 1 || d.line > doc.lines) return;
        const line = doc.line(d.line);
        const from = Math.min(line.from + Math.max(0, d.column - 1), line.to);
        list.push({ from, to: Math.max(from, line.to), severity, message: d.message });
    };
    if (checked.error) toCm(checked.error, 'error');
    for (const w of checked.warnings) toCm(w, 'warning');
    return list;
}

function showDiagnostics(result) {
    checked = { error: result.error, warnings: result.warnings };
    editor.dispatch(setDiagnostics(editor.state, lintDiagnostics(editor.state.doc)));
    const lines = [];
    if (result.error) lines.push(result.error.text);
    for (const w of result.warnings) lines.push(w.text);
    $('errors').textContent = lines.join('\n');
    $('errors').className = result.error ? 'bad' : lines.length ? 'warn' : '';
}

// ---- the canvas -------------------------------------------------------------------------
const canvas = $('canvas');
const context = canvas.getContext('2d');
const scratch = document.createElement('canvas');  // a preview, before it is scaled up
const scratchContext = scratch.getContext('2d');
let job = null;  // the render in progress: {id, width, height, preview, started, time}

function drawTiles(message) {
    const [x0, y0, x1, y1] = message.rect;
    job.width = message.width;
    job.height = message.height;
    if (!job.preview && (canvas.width !== message.width || canvas.height !== message.height)) {
        canvas.width = message.width;
        canvas.height = message.height;
    }
    const image = new ImageData(message.pixels, x1 - x0, y1 - y0);
    if (message.width === canvas.width && message.height === canvas.height) {
        context.putImageData(image, x0, y0);
    } else {  // a low-resolution preview: drawn scaled to the canvas
        if (scratch.width !== message.width || scratch.height !== message.height) {
            scratch.width = message.width;
            scratch.height = message.height;
        }
        scratchContext.putImageData(image, x0, y0);
        context.imageSmoothingEnabled = false;
        const sx = canvas.width / message.width, sy = canvas.height / message.height;
        context.drawImage(scratch, x0, y0, x1 - x0, y1 - y0, x0 * sx, y0 * sy, (x1 - x0) * sx,
                          (y1 - y0) * sy);
    }
    // Since the navigation started (performance.now()'s origin): what the user waits.
    if (page.firstPixelMs === null) page.firstPixelMs = performance.now();
}

function showProgress(p, final) {
    const seconds = p.seconds || 0;
    $('progress').value = final ? 1 : p.fraction;
    const mrays = seconds > 0 ? p.rays / seconds / 1e6 : 0;
    $('stats').textContent = `${seconds.toFixed(2)} s, ${mrays.toFixed(1)} Mrays/s` +
                             (p.samples > 1 ? `, ${p.samples} spp` : '') +
                             (p.denoiseSeconds > 0
                                  ? `, denoised (${p.denoiser === 'oidn balanced' ? 'network, ' : ''}` +
                                    `${p.denoiseSeconds.toFixed(2)} s)` : '');
}

function setState(state, text) {
    page.state = state;
    document.body.dataset.state = state;
    $('render').disabled = false;
    $('cancel').disabled = state !== 'rendering';
    if (text !== undefined) $('status').textContent = text;
}

// ---- controls ---------------------------------------------------------------------------
let sceneInfo = null;  // what the module said of the loaded scene: width, height, spp, ...
const orbit = new Orbit(canvas, {
    onMove: (camera) => startRender({ camera, preview: true }),
    onEnd: (camera) => startRender({ camera, preview: false }),
});

/// The render's settings from the controls; size, samples and depth left empty are the
/// scene's (the module fills them in).
function options(preview) {
    const size = /^(\d+)\s*[x×]\s*(\d+)$/.exec($('size').value.trim());
    const spp = Number($('spp').value) || undefined;
    const depth = $('maxdepth').value === '' ? undefined : Number($('maxdepth').value);
    const integrator = $('integrator').value || undefined;
    const path = (integrator || (sceneInfo && sceneInfo.integrator)) === 'path';
    // The path tracer's noise is denoised after each pass and in the preview; the Whitted
    // integrator's images (the course's) stay exact.
    const o = { width: size ? Number(size[1]) : undefined,
                height: size ? Number(size[2]) : undefined,
                spp, maxDepth: depth, integrator, passes: path,
                denoise: path && $('denoise').checked,
                variant: $('variant').value || undefined };
    // A model is framed for the full image, also in a preview.
    o.frameWidth = o.width;
    o.frameHeight = o.height;
    if (preview) {  // fast: about 160 pixels across, one sample, short paths
        const width = o.width || canvas.width, height = o.height || canvas.height;
        const scale = Math.max(1, Math.round(Math.max(width, height) / 160));
        const sceneDepth = depth ?? (sceneInfo ? sceneInfo.maxDepth : 5);
        Object.assign(o, { width: Math.ceil(width / scale), height: Math.ceil(height / scale),
                           spp: 1, passes: false, maxDepth: Math.min(sceneDepth, path ? 3 : 2) });
    }
    return o;
}

async function startRender({ camera = null, preview = false, reload = false } = {}) {
    if (job) worker.postMessage({ type: 'cancel', id: job.id });
    preview = preview || (anim !== null && anim.playing);  // playing: previews only
    const o = options(preview);
    const id = nextId++;
    // The time: the animation's, or of a file loaded anew, its first animation's start.
    const time = anim ? { animation: anim.index, seconds: anim.time }
                      : reload ? { seconds: 'start' } : null;
    job = { id, preview, started: performance.now(), width: 0, height: 0,
            time: anim ? anim.time : null };
    setState('rendering', anim && anim.playing ? 'Playing: fast previews'
                          : preview ? 'Moving: a fast preview' : 'Rendering');
    $('progress').value = 0;
    const text = model ? null : editor.state.doc.toString();
    worker.postMessage({ type: 'render', id, path: model || scenePath, text, reload, preview,
                         options: o, camera: camera || orbit.camera, time });
}

// ---- time: a model's animations --------------------------------------------------------
// Frames per second, as the command line's --fps: the readout's frame numbers, and the step of
// playback when images come slower than that.
const fps = 24;
// The loaded model's animations: {list: [{name, start, end}], index, time (seconds), playing,
// last (performance.now() of the last step)}; null for a still scene.
let anim = null;
let playFrame = 0;

/// Shows the time controls for the model just loaded (hidden for a still one); a model posed
/// anew at another time keeps the page's own time and play state.
function showAnimations(result) {
    const list = result.animations || [];
    const same = anim && JSON.stringify(anim.list) === JSON.stringify(list);
    if (!list.length) {
        pause(false);
        anim = null;
    } else if (!same) {
        pause(false);
        const index = result.animation ?? 0;
        anim = { list, index, time: result.time ?? list[index].start, playing: false, last: 0 };
        const select = $('animation');
        select.replaceChildren(...list.map((a, i) => {
            const option = document.createElement('option');
            option.value = String(i);
            option.textContent = `${i}: ${a.name || 'unnamed'}`;
            return option;
        }));
        select.hidden = list.length < 2;
    }
    $('timeline').hidden = !anim;
    page.animations = list;
    showTime();
}

/// The material variants of the model just loaded (KHR_materials_variants): a choice beside the
/// integrator, hidden for a file without them; the choice stays while the same list does.
function showVariants(result) {
    const list = result.variants || [];
    const select = $('variant');
    const shown = [...select.options].slice(1).map((o) => o.value);
    if (JSON.stringify(shown) !== JSON.stringify(list)) {
        const own = document.createElement('option');
        own.value = '';
        own.textContent = "the file's own";
        select.replaceChildren(own, ...list.map((name) => {
            const option = document.createElement('option');
            option.value = name;
            option.textContent = name;
            return option;
        }));
    }
    $('variant-label').hidden = list.length === 0;
    page.materialVariants = list;
}

/// The slider, the readout and the Play button as the time and play state are.
function showTime() {
    page.animation = anim ? anim.index : null;
    page.time = anim ? anim.time : null;
    page.playing = anim !== null && anim.playing;
    if (!anim) return;
    const a = anim.list[anim.index];
    const slider = $('time');
    slider.min = String(a.start);
    slider.max = String(a.end);
    slider.value = String(anim.time);
    $('animation').value = String(anim.index);
    $('play').textContent = anim.playing ? 'Pause' : 'Play';
    $('play').disabled = !(a.end > a.start);
    $('clock').textContent = `${anim.time.toFixed(2)} s of ${a.start.toFixed(2)} to ` +
                             `${a.end.toFixed(2)} s, frame ${Math.floor(anim.time * fps + 1e-6)}` +
                             (anim.list.length === 1 && a.name ? ` ('${a.name}')` : '');
}

/// The next image while playing: time advances as real time does, but by at most one frame
/// (1/fps s) per image, so slow images play slowly rather than skip; it loops at the end.
function step() {
    playFrame = 0;
    if (!anim || !anim.playing) return;
    const now = performance.now();
    const a = anim.list[anim.index];
    let t = anim.time + Math.min((now - anim.last) / 1000, 1 / fps);
    if (t > a.end) t = a.start + ((t - a.start) % (a.end - a.start));
    anim.last = now;
    anim.time = t;
    showTime();
    startRender({ preview: true });
}

function play() {
    const a = anim.list[anim.index];
    if (anim.playing || !(a.end > a.start)) return;
    anim.playing = true;
    anim.last = performance.now();
    showTime();
    startRender({ preview: true });  // the time shown, then on from there
}

/// Stops playing; with `render`, the image refines at the time shown.
function pause(render = true) {
    cancelAnimationFrame(playFrame);
    playFrame = 0;
    if (!anim || !anim.playing) return;
    anim.playing = false;
    showTime();
    if (render) startRender();
}

/// Poses the model at `seconds` (the slider): a preview while it moves, then the full image.
function seek(seconds, preview) {
    if (!anim) return;
    anim.time = seconds;
    anim.last = performance.now();
    showTime();
    if (!anim.playing) startRender({ preview });
}

function onRenderMessage(m) {
    if (!job || m.id !== job.id) return;  // a render since replaced
    switch (m.type) {
        case 'loaded':
            if (!model) showDiagnostics(m.result);
            if (m.result.ok) {
                sceneInfo = m.result;
                orbit.setHome(m.camera, m.reposed);  // posed anew: the view stays the user's
                $('size').placeholder = `${m.result.width}x${m.result.height}`;
                $('spp').placeholder = m.result.spp || 1;
                $('maxdepth').placeholder = m.result.maxDepth;
                if (m.result.note && !m.reposed) $('status').textContent = m.result.note;
                showAnimations(m.result);
                showVariants(m.result);
                job.time = m.result.time ?? null;  // the time posed (a file's start: its own)
            }
            return;
        case 'tiles':
            drawTiles(m);
            showProgress(m.progress, false);
            return;
        case 'done':
            showProgress(m.progress, true);
            page.last = { ...m.progress, preview: job.preview, width: job.width, height: job.height,
                          wallMs: performance.now() - job.started, time: job.time };
            if (!job.preview) page.rendersDone++;
            else page.previewsDone++;
            job = null;
            if (anim && anim.playing) {  // the next image at the display's next frame
                setState('playing', 'Playing: fast previews');
                cancelAnimationFrame(playFrame);
                playFrame = requestAnimationFrame(step);
                return;
            }
            setState('done', 'Done');
            return;
        case 'cancelled':
            page.rendersCancelled++;
            job = null;
            pause(false);
            setState('cancelled', 'Cancelled');
            return;
        case 'failed':
            job = null;
            pause(false);
            $('errors').textContent = m.error.text;
            $('errors').className = 'bad';
            setState('error', 'Not rendered: see the error below the editor');
            return;
    }
}

worker.onmessage = (event) => {
    const m = event.data;
    if (m.type === 'ready') {
        page.threads = m.threads;
        page.kernels = m.kernels;
        page.readyMs = performance.now();  // the module started (since navigation start)
        setCommandNames(m.commands);
        for (const name of m.integrators) {
            const option = document.createElement('option');
            option.value = option.textContent = name;
            $('integrator').appendChild(option);
        }
        $('mode').textContent = variant === 'mt'
            ? `Threaded build, ${m.threads} render threads, ${m.kernels} kernels`
            : 'Not cross-origin isolated: running the single-threaded build (serve the page ' +
              'with the headers of docs/web.md for threads)';
        $('mode').className = variant === 'mt' ? '' : 'warn';
        ready();
        return;
    }
    if (m.type === 'denoiser') {  // the network's weights came (oidn), or not (nlm)
        page.denoiser = m.name;
        $('denoise').parentElement.title = m.name === 'oidn'
            ? 'The path tracer\'s image denoised: each pass by the fast filter, the last by ' +
              'Open Image Denoise\'s network (docs/clean-images.md)'
            : 'The path tracer\'s image denoised after each pass (docs/clean-images.md)';
        return;
    }
    if (pending.has(m.id) && (m.type === 'checked' || m.type === 'saved' ||
                              m.type === 'files-written')) {
        pending.get(m.id)(m);
        pending.delete(m.id);
        return;
    }
    onRenderMessage(m);
};

// ---- examples and dropped files ---------------------------------------------------------
let examples = [];
// Fetched while the module starts.
const examplesList = fetch('examples/examples.json').then((r) => r.json());

async function openExample(name) {
    const example = examples.find((e) => e.name === name);
    if (!example) return;
    if (job) worker.postMessage({ type: 'cancel', id: job.id });
    const files = await Promise.all(example.files.map(async (f) => ({
        path: '/examples/' + f,
        data: await (await fetch('examples/' + f)).arrayBuffer(),
    })));
    await request({ type: 'files', files }, files.map((f) => f.data));
    scenePath = '/examples/' + example.main;
    model = null;
    showAnimations({});
    const text = await (await fetch('examples/' + example.main)).text();
    setText(text);
    $('integrator').value = example.integrator || '';
    $('spp').value = example.spp || '';
    $('size').value = '';
    $('maxdepth').value = '';
    $('examples').value = name;
    orbit.reset();
    startRender({ reload: true });
}

const modelExtensions = ['.obj', '.gltf', '.glb', '.ply', '.stl'];
async function dropFiles(fileList) {
    const files = await Promise.all([...fileList].map(async (f) => ({
        path: '/drop/' + f.name, data: await f.arrayBuffer() })));
    if (!files.length) return;
    await request({ type: 'files', files }, files.map((f) => f.data));
    const names = files.map((f) => f.path);
    const scene = names.find((n) => n.endsWith('.test'));
    const modelFile = names.find((n) => modelExtensions.some((e) => n.toLowerCase().endsWith(e)));
    $('examples').value = '';
    showAnimations({});  // a new file: its own animations, from the start of the first
    if (scene) {
        scenePath = scene;
        model = null;
        setText(new TextDecoder().decode(files.find((f) => f.path === scene).data));
    } else if (modelFile) {
        model = modelFile;
        setText(`# ${modelFile.slice(6)}: rendered as \`glint ${modelFile.slice(6)}\` renders it.\n` +
                `# Or place it in a scene:\n# mesh ${modelFile.slice(6)}\n`);
        scenePath = '/drop/scene.test';
        model = modelFile;
        $('status').textContent = 'Dropped ' + names.map((n) => n.slice(6)).join(', ');
    } else {
        $('status').textContent = 'Dropped ' + names.map((n) => n.slice(6)).join(', ') +
                                  ': files for the scene to use (mesh, texture)';
        return;
    }
    orbit.reset();  // a new scene: its own camera, not the view orbited in the last one
    startRender({ reload: true });
}

// ---- start ------------------------------------------------------------------------------
async function ready() {
    setState('idle', 'Ready');
    examples = await examplesList;
    const select = $('examples');
    let group = null;
    for (const e of examples) {
        if (!group || group.label !== e.group) {
            group = document.createElement('optgroup');
            group.label = e.group;
            select.appendChild(group);
        }
        const option = document.createElement('option');
        option.value = e.name;
        option.textContent = e.title;
        group.appendChild(option);
    }
    select.onchange = () => openExample(select.value);
    await openExample(params.get('example') || 'demo');
}

$('render').onclick = () => startRender({ reload: true });
$('cancel').onclick = () => job && worker.postMessage({ type: 'cancel', id: job.id });
$('home').onclick = () => {
    orbit.reset();
    startRender();
};
$('download').onclick = async () => {
    const reply = await request({ type: 'save' });
    if (reply.error) {
        $('status').textContent = 'Cannot save: ' + reply.error;
        return;
    }
    const link = document.createElement('a');
    link.href = URL.createObjectURL(new Blob([reply.data], { type: 'image/png' }));
    link.download = (model || scenePath).split('/').pop().replace(/\.[^.]*$/, '') + '.png';
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
};
$('play').onclick = () => (anim && anim.playing ? pause() : play());
$('animation').onchange = () => {
    anim.index = Number($('animation').value);
    seek(anim.list[anim.index].start, false);
};
$('time').addEventListener('input', () => seek(Number($('time').value), true));
$('time').addEventListener('change', () => seek(Number($('time').value), false));
for (const id of ['size', 'spp', 'maxdepth', 'integrator', 'denoise', 'variant'])
    $(id).addEventListener('change', () => startRender({ reload: id === 'integrator' }));
document.addEventListener('keydown', (e) => {
    if ((e.ctrlKey || e.metaKey) && e.key === 'Enter') startRender({ reload: true });
});

const drop = document.body;
drop.addEventListener('dragover', (e) => {
    e.preventDefault();
    drop.classList.add('dragging');
});
drop.addEventListener('dragleave', () => drop.classList.remove('dragging'));
drop.addEventListener('drop', (e) => {
    e.preventDefault();
    drop.classList.remove('dragging');
    dropFiles(e.dataTransfer.files);
});
$('open').onchange = (e) => dropFiles(e.target.files);

setState('starting', 'Starting the renderer');
worker.postMessage({ type: 'init', variant, threads, kernels, base: new URL('.', location.href).href });
