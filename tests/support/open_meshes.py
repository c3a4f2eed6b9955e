"""Open meshes made from closed ones, for the preprocessing tests: holes of growing size punched into a
solid, its triangle soup, a patch turned against its neighbours, and a sheet; and the independent measures
of hulls against the closed solid they came from (libigl's distances and winding number, scipy's Qhull)."""
import numpy as np


def diagonal(V):
    return float(np.linalg.norm(np.ptp(np.asarray(V, float), axis=0)))


def refined(V, F, edges=60):
    """Faces split until no edge is longer than 1/edges of the diagonal (CAD solids' long faces would
    otherwise fall out whole)."""
    import trimesh
    V2, F2 = trimesh.remesh.subdivide_to_size(np.asarray(V, float), np.asarray(F, np.int64),
                                              max_edge=diagonal(V) / edges)
    return np.asarray(V2, float), np.asarray(F2, np.int32)


def punched(V, F, holes):
    """The faces whose centroid lies within r_k of seed k removed, for `holes` seeds spread by farthest
    point sampling from the vertex of largest x; r_k grows from 2% to 8% of the diagonal."""
    V, F = np.asarray(V, float), np.asarray(F)
    seeds = [int(np.argmax(V[:, 0]))]
    d = np.linalg.norm(V - V[seeds[0]], axis=1)
    while len(seeds) < holes:
        seeds.append(int(np.argmax(d)))
        d = np.minimum(d, np.linalg.norm(V - V[seeds[-1]], axis=1))
    c = V[F].mean(1)
    keep = np.ones(len(F), bool)
    for k, s in enumerate(seeds):
        r = diagonal(V) * (0.02 + 0.06 * k / max(1, holes - 1))
        keep &= np.linalg.norm(c - V[s], axis=1) > r
    return V, F[keep]


def soup(V, F):
    """Every face with its own three corners, as an STL stores them."""
    V, F = np.asarray(V, float), np.asarray(F)
    return V[F.reshape(-1)].copy(), np.arange(3 * len(F), dtype=np.int32).reshape(-1, 3)


def flipped_patch(V, F, share=0.1):
    """The faces nearest the vertex of largest y, `share` of them, turned."""
    V, F = np.asarray(V, float), np.array(F)
    d = np.linalg.norm(V[F].mean(1) - V[int(np.argmax(V[:, 1]))], axis=1)
    turn = np.argsort(d, kind="stable")[: int(share * len(F))]
    F[turn] = F[turn][:, ::-1]
    return V, F


def sheet(n=30, size=1.0):
    """A wavy square sheet, open along its whole border."""
    x, y = np.meshgrid(np.linspace(0, size, n + 1), np.linspace(0, size, n + 1))
    V = np.stack([x.ravel(), y.ravel(), 0.05 * size * np.sin(6 * x.ravel() / size)], 1)
    a = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    F = np.concatenate([np.stack([a, a + 1, a + n + 2], 1), np.stack([a, a + n + 2, a + n + 1], 1)])
    return V, F.astype(np.int32)


def surface_samples(hulls, n, rng):
    """The hulls' vertices and n points spread over their faces by area."""
    tris = np.concatenate([V[F] for V, F in hulls])
    area = np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1)
    pick = rng.choice(len(tris), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    t = tris[pick]
    pts = t[:, 0] + u[:, None] * (t[:, 1] - t[:, 0]) + v[:, None] * (t[:, 2] - t[:, 0])
    return np.concatenate([np.concatenate([V for V, _ in hulls]), pts])


def reach_beyond(hulls, V, F, rng, n=20000):
    """How far the hulls reach outside the closed solid (V, F): the largest distance to its surface from
    the hulls' surface points outside it (libigl: winding number and point-triangle distances)."""
    import igl
    P = surface_samples(hulls, n, rng)
    V, F = np.ascontiguousarray(V, float), np.ascontiguousarray(F, np.int64)
    outside = np.abs(igl.winding_number(V, F, P)) < 0.5
    if not outside.any():
        return 0.0
    sq, _, _ = igl.point_mesh_squared_distance(P[outside], V, F)
    return float(np.sqrt(sq.max()))


def covered(hulls, V, F, rng, n=2000):
    """The share of points inside the closed solid (V, F) that some hull holds (scipy's Qhull)."""
    import igl
    from scipy.spatial import ConvexHull
    V, F = np.ascontiguousarray(V, float), np.ascontiguousarray(F, np.int64)
    lo, hi = V.min(0), V.max(0)
    P = rng.uniform(lo, hi, size=(8 * n, 3))
    P = P[np.abs(igl.winding_number(V, F, P)) > 0.5][:n]
    held = np.zeros(len(P), bool)
    for HV, _ in hulls:
        eq = ConvexHull(HV).equations
        held |= (P @ eq[:, :3].T + eq[:, 3] <= 1e-9 * diagonal(V)).all(1)
    return float(held.mean())
