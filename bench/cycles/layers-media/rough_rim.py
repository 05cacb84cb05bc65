"""Issue 23 (bench/cycles/layers-media/README.md), a check of media-sss's rough ball: the
panel light reflected by the ball's rough outer surface alone (maxdepth 1), computed without
either renderer. For each pixel of the 320x240 camera that sees the rough ball (centre
(-0.55, 0.45, 0), radius 0.45), the integral over the panel of f_r(wo, wi) L cos_i cos_L / r^2
by Monte Carlo over its area (4096 points), f_r the single-scattering GGX dielectric
(alpha 0.3, separable Smith G, exact Fresnel of index 1.4). Prints the mean luminance over the
ball's disc within 0.8 of its radius (in pixels: centre (95, 119), 52) and over its rim (0.85 to
0.98), to compare with renders of media-sss.test with interior none, no background and
maxdepth 1 (Cycles: 0 bounces). Needs NumPy: run with Blender's Python,
    blender -b --factory-startup --python bench/cycles/layers-media/rough_rim.py
"""
# Direct reflection of the panel by the rough glass ball (maxdepth 1), by Monte Carlo over the
# panel's area, with the GGX microfacet BRDF (separable Smith G, exact dielectric Fresnel).
import numpy as np, math, sys
W, H, fov = 320, 240, 36.0
eye = np.array([0, 0.9, 3.2]); look = np.array([0, 0.45, 0]); up = np.array([0, 1.0, 0])
f = look - eye; f /= np.linalg.norm(f); r = np.cross(f, up); r /= np.linalg.norm(r); u = np.cross(r, f)
C = np.array([-0.55, 0.45, 0]); R = 0.45
P0 = np.array([-0.8, 2.4, 0.2]); E1 = np.array([1.0, 0, 0]); E2 = np.array([0, 0, 1.0]); Lum = 0.2126*12+0.7152*11.5+0.0722*11
alpha, eta = 0.3, 1.4
t = math.tan(math.radians(fov / 2))
def fres(c, eta):
    s2 = (1 - c*c) / (eta*eta); ct = np.sqrt(np.maximum(1 - s2, 0))
    rs = (c - eta*ct) / (c + eta*ct); rp = (eta*c - ct) / (eta*c + ct)
    return np.where(s2 >= 1, 1.0, 0.5*(rs*rs + rp*rp))
def D(ch):
    a2 = alpha*alpha; d = ch*ch*(a2 - 1) + 1
    return a2 / (math.pi * d*d)
def G1(c):
    c2 = np.clip(c*c, 1e-12, 1); t2 = (1 - c2) / c2
    return 2 / (1 + np.sqrt(1 + alpha*alpha*t2))
rng = np.random.default_rng(1)
N = 4096
uv = rng.random((N, 2))
Lp = P0 + uv[:, :1]*E1 + uv[:, 1:]*E2; area = 1.0
ln = np.cross(E1, E2); ln /= np.linalg.norm(ln)
rim = []; inner = []
for py in range(H):
    for px in range(W):
        x = (2*(px + 0.5)/W - 1) * t * W / H; y = (1 - 2*(py + 0.5)/H) * t
        d = f + x*r + y*u; d /= np.linalg.norm(d)
        oc = eye - C; b = np.dot(oc, d); c = np.dot(oc, oc) - R*R; disc = b*b - c
        if disc < 0: continue
        th = -b - math.sqrt(disc); p = eye + th*d; n = (p - C) / R
        # the region test as regions.py: distance from the ball's projected centre in pixels
        wo = -d
        wi = Lp - p; dist = np.linalg.norm(wi, axis=1); wi /= dist[:, None]
        cosL = -(wi @ ln)
        ci = wi @ n; co = np.dot(wo, n)
        h = wi + wo; h /= np.linalg.norm(h, axis=1)[:, None]
        ch = h @ n; oh = h @ wo
        val = np.where((ci > 0) & (cosL > 0) & (co > 0),
                       D(ch) * G1(co) * G1(ci) * fres(np.abs(oh), eta) / (4*co*np.maximum(ci, 1e-9))
                       * ci * cosL / dist**2 * area, 0.0)
        rim.append((px, py, Lum * val.mean()))
vals = {(a, b): v for a, b, v in rim}
for part, r0, r1 in (("inner", 0, 0.8), ("rim", 0.85, 0.98)):
    s = [v for (a, b), v in vals.items() if r0 <= math.hypot(a + 0.5 - 95, b + 0.5 - 119)/52 < r1]
    n = sum(1 for a in range(W) for b in range(H) if r0 <= math.hypot(a + 0.5 - 95, b + 0.5 - 119)/52 < r1)
    print(f"rough_rim.py: {part}: mean luminance {sum(s) / n:.5f}")
