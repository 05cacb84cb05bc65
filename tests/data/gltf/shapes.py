"""Shapes for the scripts that write glTF test and benchmark assets (make_gltf.py here,
bench/cycles/lights/make_lights.py): positions, normals and triangle indices. Standard library
only, deterministic."""
import math

def uv_sphere(radius, rings, segs):
    """A smooth UV sphere about the origin: positions, normals and triangle indices."""
    P, N, I = [], [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s_ in range(segs + 1):
            ph = 2 * math.pi * s_ / segs
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            N.append(n)
            P.append(tuple(radius * c for c in n))
    for r in range(rings):
        for s_ in range(segs):
            k = r * (segs + 1) + s_
            I += [k, k + segs + 1, k + 1, k + 1, k + segs + 1, k + segs + 2]
    return P, N, I


def cuboid(half, centre=(0, 0, 0)):
    """A box of half-sizes `half` about `centre`, flat-shaded, faces outwards: positions,
    normals and triangle indices."""
    P, N, I = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            base = len(P)
            u, v = (axis + 1) % 3, (axis + 2) % 3
            for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = sign * half[axis], cu * half[u], cv * half[v]
                P.append(tuple(p[i] + centre[i] for i in range(3)))
                n = [0, 0, 0]
                n[axis] = sign
                N.append(tuple(n))
            I += [base + i for i in ([0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2])]
    return P, N, I

