"""How far a part's convex hull reaches beyond the part: the largest distance from a point of the hull's
surface to the part's surface, measured here with scipy's hull (Qhull) and libigl's exact point-triangle distances (an
AABB tree); nothing is shared with the core.

The distance to a surface is 1-Lipschitz, so a hull triangle whose centre lies at distance d and whose
corners lie within R of that centre holds no point farther than d + R. Triangles are split in four
until that bound settles the question: the result is a lower bound (a point attains it) and an upper
bound no more than `slack` above it, or above `limit` when the hull is shown to be within it."""
import numpy as np
from scipy.spatial import ConvexHull, QhullError


def point_surface_distance(P, V, F):
    """Exact distance from each point of P to the triangle surface (V, F), and the nearest face:
    libigl's AABB tree over the triangles (point_mesh_squared_distance)."""
    import igl
    P = np.ascontiguousarray(np.atleast_2d(np.asarray(P, float)))
    sq, face, _ = igl.point_mesh_squared_distance(P, np.ascontiguousarray(V, float),
                                                  np.ascontiguousarray(F, np.int64))
    return np.sqrt(np.maximum(sq, 0)), np.asarray(face, np.int64)


def _point_triangle(p, a, b, c):
    ab, ac, ap = b - a, c - a, p - a
    with np.errstate(divide="ignore", invalid="ignore"):
        return _point_triangle_unchecked(p, a, b, c, ab, ac, ap)


def _point_triangle_unchecked(p, a, b, c, ab, ac, ap):
    n = np.cross(ab, ac)
    nn = (n * n).sum(1)
    ok = nn > 1e-300
    nh = n / np.sqrt(np.where(ok, nn, 1))[:, None]
    h = (ap * nh).sum(1)
    q = p - h[:, None] * nh
    # barycentric coordinates of the projection
    d00, d01, d11 = (ab * ab).sum(1), (ab * ac).sum(1), (ac * ac).sum(1)
    aq = q - a
    d20, d21 = (aq * ab).sum(1), (aq * ac).sum(1)
    den = np.where(ok, d00 * d11 - d01 * d01, 1)
    v = (d11 * d20 - d01 * d21) / den
    w = (d00 * d21 - d01 * d20) / den
    inside = ok & (v >= 0) & (w >= 0) & (v + w <= 1)

    def seg(x, y):
        xy = y - x
        t = np.clip(((p - x) * xy).sum(1) / np.maximum((xy * xy).sum(1), 1e-300), 0, 1)
        return np.sqrt(((p - x - t[:, None] * xy) ** 2).sum(1))
    edges = np.minimum(np.minimum(seg(a, b), seg(b, c)), seg(c, a))
    return np.where(inside, np.abs(h), edges)


def _covered(hull, V, F):
    """Per hull simplex: does the surface tile its whole facet (the coplanar simplices around it)?
    Surface faces lying in a facet's plane, facing its way, are inside it; if their areas add up to
    the facet's, the hull is on the surface there and nothing of that facet can stand off it."""
    eq = hull.equations                      # (s, 4): outward unit normal, offset
    size = np.ptp(hull.points, 0).max()
    eps = 1e-9 * size
    # facets: simplices joined across edges when their planes agree
    label = np.arange(len(eq))

    def root(i):
        while label[i] != i:
            label[i] = label[label[i]]
            i = label[i]
        return i
    for i, nbrs in enumerate(hull.neighbors):
        for j in nbrs:
            if np.abs(eq[i] - eq[j]).max() <= 1e-9 * max(1.0, size):
                label[root(i)] = root(j)
    groups = np.array([root(i) for i in range(len(eq))])
    P = hull.points[hull.simplices]
    s_area = 0.5 * np.linalg.norm(np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), axis=1)
    roots, gid = np.unique(groups, return_inverse=True)
    e = eq[roots]   # one plane per facet
    # The facets each vertex lies on (within eps), found a block of vertices at a time: a face can lie
    # in a facet only if its first corner does, so each face is tested against those facets alone, not
    # against each of a dense scan's thousands.
    used = np.unique(F)
    normals = np.ascontiguousarray(e[:, :3].T)
    pv, pg = [], []
    for k in range(0, len(used), 256):
        ids = used[k:k + 256]
        D = V[ids] @ normals
        D += e[:, 3]
        boundary = D.max(1) >= -eps   # most vertices of a scan lie inside: one pass rules them out
        vi, gi = np.nonzero(np.abs(D[boundary]) <= eps)
        pv.append(ids[boundary][vi])
        pg.append(gi)
    pv, pg = np.concatenate(pv), np.concatenate(pg)   # sorted by vertex, as `used` is
    start = np.searchsorted(pv, np.arange(len(V)))
    count = np.searchsorted(pv, np.arange(len(V)), side="right") - start
    # Each face paired with every facet its first corner lies on: face i's run of pairs starts at
    # start[F[i, 0]] and is per[i] long.
    per = count[F[:, 0]]
    face = np.repeat(np.arange(len(F)), per)
    g = pg[np.repeat(start[F[:, 0]], per) + np.arange(per.sum()) - np.repeat(np.cumsum(per) - per, per)]
    a, b, c = V[F[face, 0]], V[F[face, 1]], V[F[face, 2]]
    n = np.cross(b - a, c - a)
    on = ((np.abs((b * e[g, :3]).sum(1) + e[g, 3]) <= eps) & (np.abs((c * e[g, :3]).sum(1) + e[g, 3]) <= eps)
          & ((n * e[g, :3]).sum(1) > 0))
    tiled = np.bincount(g[on], 0.5 * np.linalg.norm(n[on], axis=1), len(roots))   # area of faces in each facet
    covered = (tiled >= np.bincount(gid, s_area, len(roots)) * (1 - 1e-7))[gid]
    return covered


def hull_reach(V, F, slack, limit=None, max_triangles=2_000_000):
    """(lower, upper) bounds of the largest distance from the convex hull of V to the surface (V, F).
    upper - lower <= slack, except with `limit`: the search stops once upper <= limit + slack, or as
    soon as a point lies beyond limit + slack (upper is then infinite).

    A triangle's bound is the smaller of d(centre) + R and the largest distance from its corners to
    the face nearest its centre (the distance to one triangle is convex, so it peaks at a corner)."""
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64)
    pts = V[np.unique(F)]
    try:
        hull = ConvexHull(pts)
    except QhullError:   # a nearly flat part Qhull cannot settle exactly: joggle (about 1e-11 of its size)
        hull = ConvexHull(pts, qhull_options="QJ")
    tris = pts[hull.simplices[~_covered(hull, V, F)]]   # (m, 3, 3): only where the hull leaves the surface
    A, B, C = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    lower, upper = 0.0, 0.0
    while len(tris):
        c = tris.mean(1)
        R = np.sqrt(((tris - c[:, None, :]) ** 2).sum(-1)).max(1)
        d, face = point_surface_distance(c, V, F)
        lower = max(lower, float(d.max()))
        if limit is not None and lower > limit + slack:
            return lower, np.inf   # a point beyond the limit: nothing more to prove
        corner = np.max([_point_triangle(tris[:, k], A[face], B[face], C[face]) for k in range(3)], axis=0)
        ub = np.minimum(d + R, corner)
        bar = (limit if limit is not None else lower) + slack   # with a limit, lower is within limit + slack here
        keep = ub > bar
        upper = max(upper, float(ub[~keep].max()) if (~keep).any() else 0.0)
        tris = tris[keep]
        if len(tris) * 4 > max_triangles:
            upper = max(upper, float(ub[keep].max()))
            break
        a, b, cc = tris[:, 0], tris[:, 1], tris[:, 2]
        ab, bc, ca = (a + b) / 2, (b + cc) / 2, (cc + a) / 2
        tris = np.concatenate([np.stack(t, 1) for t in ((a, ab, ca), (ab, b, bc), (ca, bc, cc), (ab, bc, ca))])
    return lower, max(upper, lower)
