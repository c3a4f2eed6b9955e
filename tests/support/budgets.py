"""Engine budgets re-measured with Qhull and trimesh (nothing read back from the core): a hull's vertex,
polygon and triangle counts, whether it contains a point set, and how far it reaches beyond the exact
hull of those points."""
import numpy as np
import trimesh
from scipy.spatial import ConvexHull

# The engines' documented limits: (vertices, polygons, triangles), 0 for none.
LIMITS = {"physx": (255, 255, 0), "physx_gpu": (64, 64, 0), "unity": (0, 0, 255), "none": (0, 0, 0)}


def counts(V, F):
    """Distinct vertices, polygons (coplanar neighbouring triangles merged, by trimesh) and triangles."""
    m = trimesh.Trimesh(np.asarray(V, float), np.asarray(F), process=True)
    in_facets = sum(len(f) for f in m.facets)
    return len(m.vertices), len(m.facets) + len(m.faces) - in_facets, len(m.faces)


def within(V, F, engine):
    v, p, t = counts(V, F)
    lv, lp, lt = LIMITS[engine]
    return (lv == 0 or v <= lv) and (lp == 0 or p <= lp) and (lt == 0 or t <= lt)


def outside(points, hull_V):
    """Largest distance of the points beyond the facet planes of the hull of hull_V (<= 0: contained)."""
    h = ConvexHull(np.asarray(hull_V, float))
    return float((np.asarray(points, float) @ h.equations[:, :3].T + h.equations[:, 3]).max())


def reach(hull_V, points):
    """How far the hull of hull_V reaches beyond the exact hull of `points`: its farthest vertex's
    distance to the surface of Qhull's hull, by libigl's exact point-triangle distances (the farthest
    point of a convex polytope from a convex set is one of its vertices)."""
    from .hull_reach import point_surface_distance
    h = ConvexHull(np.asarray(points, float))
    V = np.asarray(hull_V, float)
    out = V @ h.equations[:, :3].T + h.equations[:, 3]
    V = V[out.max(1) > 0]
    if len(V) == 0:
        return 0.0
    return float(point_surface_distance(V, h.points, h.simplices)[0].max())
