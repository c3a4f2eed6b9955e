"""Test shapes and independent geometry checks (numpy only; nothing read back from the core)."""
import os
import pathlib

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd

BUNNY = os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes", "bunny.obj")
SHARED = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "data" / "meshes"


def present(path):
    """`path` as a string, or the calling test skipped where it is absent (the shared data sits beside the
    repository, as CI places it)."""
    if not pathlib.Path(path).exists():
        pytest.skip(f"{path} not present (shared data sits beside the repo)")
    return str(path)


# ---- shapes ---------------------------------------------------------------------------------
def ear_clip(poly):
    """Triangles of a simple CCW polygon (small polygons)."""
    idx, tris = list(range(len(poly))), []

    def cross(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    while len(idx) > 3:
        for i in range(len(idx)):
            a, b, c = idx[i - 1], idx[i], idx[(i + 1) % len(idx)]
            if cross(poly[a], poly[b], poly[c]) <= 0:
                continue
            if any(cross(poly[a], poly[b], poly[j]) >= 0 and cross(poly[b], poly[c], poly[j]) >= 0
                   and cross(poly[c], poly[a], poly[j]) >= 0 for j in idx if j not in (a, b, c)):
                continue
            tris.append((a, b, c))
            idx.pop(i)
            break
    tris.append(tuple(idx))
    return tris


def extrude(poly, z0, z1):
    """Closed prism over a CCW polygon: (vertices, faces)."""
    n = len(poly)
    V = [(x, y, z0) for x, y in poly] + [(x, y, z1) for x, y in poly]
    F = []
    for a, b, c in ear_clip(poly):
        F += [(a, c, b), (a + n, b + n, c + n)]
    for i in range(n):
        j = (i + 1) % n
        F += [(i, j, j + n), (i, j + n, i + n)]
    return np.array(V, float), np.array(F, np.int32)


L_SHAPE = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
U_SHAPE = [(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)]
PLUS = [(1, 0), (2, 0), (2, 1), (3, 1), (3, 2), (2, 2), (2, 3), (1, 3), (1, 2), (0, 2), (0, 1), (1, 1)]


def torus(R=2.0, r=0.5, nu=48, nv=16):
    u, v = np.meshgrid(np.arange(nu) * 2 * np.pi / nu, np.arange(nv) * 2 * np.pi / nv, indexing="ij")
    V = np.stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], -1)
    V = V.reshape(-1, 3)
    F = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            F += [(a, b, c), (a, c, d)]
    return V, np.array(F, np.int32)


def icosphere(centre=(0, 0, 0), radius=1.0, level=2):
    """Outward unit icosphere, subdivided `level` times, scaled and moved."""
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
         (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        mid, nf = {}, []

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = V[a] + V[b]
                V.append(p / np.linalg.norm(p))
                mid[k] = len(V) - 1
            return mid[k]
        for a, b, c in F:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = nf
    return np.array(V) * radius + np.asarray(centre, float), np.array(F, np.int32)


def box(lo=(-1, -1, -1), hi=(1, 1, 1)):
    """Outward axis-aligned box: (vertices, faces)."""
    V, F = extrude([(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])], lo[2], hi[2])
    return V, F


def with_cavities(outer, cavities):
    """A solid: the outer shell as given, each cavity shell turned inward."""
    V, F = [np.asarray(outer[0], float)], [np.asarray(outer[1])]
    n = len(V[0])
    for Vc, Fc in cavities:
        V.append(np.asarray(Vc, float))
        F.append(np.asarray(Fc)[:, ::-1] + n)
        n += len(Vc)
    return np.concatenate(V), np.concatenate(F).astype(np.int32)


def add_mesh(ms, V, F, name="input"):
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(V, float), face_matrix=np.asarray(F, np.int32)), name)


# ---- independent checks ---------------------------------------------------------------------
def component_labels(n, pairs):
    """Connected-component label of each of n items joined by the (a, b) pairs (union-find)."""
    parent = list(range(n))

    def root(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for a, b in pairs:
        parent[root(a)] = root(b)
    return np.array([root(x) for x in range(n)])


def volume(V, F):
    V = np.asarray(V, float)
    V = V - V.mean(0)   # far from the origin the triple products would cancel catastrophically
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def is_closed_manifold(F):
    """Every directed edge appears once and its reverse once: closed, edge-manifold, oriented."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    directed = {tuple(x) for x in e.tolist()}
    if len(directed) != len(e):
        return False
    return all((b, a) in directed for a, b in directed)


def inside(V, F, pts):
    """Ray-parity point-in-solid for each point (numpy, Moller-Trumbore)."""
    V = np.asarray(V, float)
    d = np.array([0.5773502691896258, 0.5773502691896257, 0.5773502691896259]) + np.array([1e-3, -2e-3, 3e-3])
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    e1, e2 = b - a, c - a
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-300
    out = []
    for p in np.atleast_2d(pts):
        s = p - a
        u = np.einsum("ij,ij->i", s, h) / np.where(ok, det, 1)
        q = np.cross(s, e1)
        v = (q @ d) / np.where(ok, det, 1)
        t = np.einsum("ij,ij->i", e2, q) / np.where(ok, det, 1)
        hit = ok & (u >= 0) & (u <= 1) & (v >= 0) & (u + v <= 1) & (t > 0)
        out.append(int(hit.sum()) % 2 == 1)
    return np.array(out)


def interior_samples(V, F, n, rng):
    """Points strictly inside the solid: rejection sampling in its bounding box."""
    V = np.asarray(V, float)
    lo, hi = V.min(0), V.max(0)
    pts = rng.uniform(lo, hi, size=(n * 6, 3))
    ins = inside(V, F, pts)
    return pts[ins][:n]


def hull_within(V, F, tau_abs, label="part"):
    """Assert the part's convex hull lies within tau of the part, measured independently
    (tests/support/hull_reach.py: scipy's Qhull and libigl's exact point-triangle distances), with a slack of 1% of tau.
    Returns the attained distance."""
    from .hull_reach import hull_reach
    lower, upper = hull_reach(V, F, slack=0.01 * tau_abs, limit=tau_abs)
    assert upper <= 1.01 * tau_abs * (1 + 1e-9), \
        f"{label}: its hull lies {lower:.4g} from it (tau {tau_abs:.4g}, {lower / tau_abs:.2f} tau)"
    return lower


def random_rotation(seed):
    """A proper rotation drawn from the seed (QR of a Gaussian matrix, signs fixed, determinant +1)."""
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def same_parts(a, b, scale=1.0):
    """Two sorted lists of part volumes agree (b scaled by `scale`), to 1e-4 relative."""
    return len(a) == len(b) and np.allclose(a, b * scale, rtol=1e-4, atol=1e-4 * b.sum() * scale)
