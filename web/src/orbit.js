// Orbit, pan and zoom of the scene's camera with the mouse: drag to orbit about the point the
// camera looks at, drag with Shift (or the right button) to pan, the wheel to zoom. While the
// mouse moves, onMove(camera) asks for a fast preview; when it stops, onEnd(camera) for the
// full render. Cameras are {eye, center, up, fovy} in scene units, as the `camera` command.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]];
const length = (a) => Math.sqrt(dot(a, a));
const normalize = (a) => scale(a, 1 / (length(a) || 1));

/// `v` rotated by `angle` radians about the unit axis `k` (Rodrigues).
function rotate(v, k, angle) {
    const c = Math.cos(angle), s = Math.sin(angle);
    return add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1 - c)));
}

export class Orbit {
    constructor(element, { onMove, onEnd }) {
        this.element = element;
        this.onMove = onMove;
        this.onEnd = onEnd;
        this.home = null;
        this.camera = null;  // null until the page moves it: the scene's own
        this.drag = null;
        this.wheelTimer = 0;
        this.frame = 0;
        element.addEventListener('pointerdown', (e) => this.down(e));
        element.addEventListener('pointermove', (e) => this.move(e));
        element.addEventListener('pointerup', (e) => this.up(e));
        element.addEventListener('pointercancel', (e) => this.up(e));
        element.addEventListener('contextmenu', (e) => e.preventDefault());
        element.addEventListener('wheel', (e) => this.wheel(e), { passive: false });
    }

    /// The scene's camera as loaded; the view returns to it with reset(). A new home drops the
    /// view moved from the old one, unless `keepView` (the same model posed at another time).
    setHome(camera, keepView = false) {
        const changed = !this.home || JSON.stringify(this.home) !== JSON.stringify(camera);
        this.home = camera;
        if (changed && !keepView) this.camera = null;
    }

    reset() { this.camera = null; }

    current() { return this.camera || this.home; }

    down(e) {
        if (!this.home) return;
        this.element.setPointerCapture(e.pointerId);
        this.drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2,
                      start: this.current(), moved: false };
    }

    move(e) {
        if (!this.drag) return;
        const dx = e.clientX - this.drag.x, dy = e.clientY - this.drag.y;
        if (Math.abs(dx) + Math.abs(dy) < 2 && !this.drag.moved) return;
        this.drag.moved = true;
        const c = this.drag.start;
        const forward = sub(c.center, c.eye);
        const distance = length(forward);
        const up = normalize(c.up);
        const right = normalize(cross(forward, up));
        let eye, center;
        if (this.drag.pan) {
            const perPixel = 2 * distance * Math.tan((c.fovy * Math.PI) / 360) /
                             this.element.getBoundingClientRect().height;
            const trueUp = normalize(cross(right, forward));
            const shift = add(scale(right, -dx * perPixel), scale(trueUp, dy * perPixel));
            eye = add(c.eye, shift);
            center = add(c.center, shift);
        } else {
            // Yaw about the camera's up, then pitch about its right, short of the poles.
            let offset = rotate(sub(c.eye, c.center), up, -dx * 0.01);
            const r = normalize(cross(scale(offset, -1), up));
            const pitched = rotate(offset, r, -dy * 0.01);
            if (Math.abs(dot(normalize(pitched), up)) < 0.99) offset = pitched;
            eye = add(c.center, offset);
            center = c.center;
        }
        this.camera = { ...c, eye, center };
        this.request(this.onMove);
    }

    up(e) {
        if (!this.drag) return;
        const moved = this.drag.moved;
        this.drag = null;
        if (this.element.hasPointerCapture(e.pointerId))
            this.element.releasePointerCapture(e.pointerId);
        if (moved) this.request(this.onEnd, true);
    }

    wheel(e) {
        if (!this.home) return;
        e.preventDefault();
        const c = this.current();
        const factor = Math.exp(Math.max(-0.5, Math.min(0.5, e.deltaY * 0.0015)));
        this.camera = { ...c, eye: add(c.center, scale(sub(c.eye, c.center), factor)) };
        this.request(this.onMove);
        clearTimeout(this.wheelTimer);
        this.wheelTimer = setTimeout(() => this.request(this.onEnd, true), 250);
    }

    /// At most one request per animation frame while moving; the final one at once.
    request(callback, now = false) {
        if (now) {
            cancelAnimationFrame(this.frame);
            this.frame = 0;
            callback(this.camera);
            return;
        }
        if (this.frame) return;
        this.frame = requestAnimationFrame(() => {
            this.frame = 0;
            callback(this.camera);
        });
    }
}
