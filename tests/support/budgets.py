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


def read_obj_objects(path):
    """(V, F) per `o` object of an OBJ file (the package's hull and part files), parsed here."""
    out, V, F, base = [], [], [], 1
    for line in open(path):
        if line.startswith("o "):
            if V:
                out.append((np.array(V, float), np.array(F, np.int64) - base))
                base += len(V)
            V, F = [], []
        elif line.startswith("v "):
            V.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            F.append([int(x.split("/")[0]) for x in line.split()[1:4]])
    if V:
        out.append((np.array(V, float), np.array(F, np.int64) - base))
    return out


def check_hull_folders(collision_dir, engine):
    """Every hull file hull_<k>.obj under collision_dir against its folder's parts.obj (part k): within the
    engine's limits, and holding every vertex of its part. Returns (hulls, within, containing, worst excess
    over the part's size)."""
    import pathlib
    hulls = within_n = holding = 0
    worst = 0.0
    for folder in sorted(p for p in pathlib.Path(collision_dir).iterdir() if p.is_dir()):
        parts = read_obj_objects(folder / "parts.obj")
        for k, (Vp, _) in enumerate(parts):
            (Vh, Fh), = read_obj_objects(folder / f"hull_{k}.obj")
            hulls += 1
            within_n += within(Vh, Fh, engine)
            size = float(np.linalg.norm(np.ptp(Vp, 0)))
            excess = outside(Vp, Vh) / size
            holding += excess <= 1e-9
            worst = max(worst, excess)
    return hulls, within_n, holding, worst
