"""Generated bad and random inputs for the robustness fuzz test (tests/test_fuzz.py).

A case is (base mesh, mutation, parameters), all derived from its index, so a failing case can be
replayed alone:  cd tests && python -m support.fuzz_cases run CASE_INDEX

Run as `python -m support.fuzz_cases child CACHE FIRST LAST` (from tests/), it processes cases FIRST..LAST-1 and prints one
line per case ("<i> ok <parts>" or "<i> error <message>" or "<i> violation <what>"), flushed, so the
parent can tell which case a crash or hang happened in.
"""
import pathlib
import sys

import numpy as np


SHARED = pathlib.Path(__file__).resolve().parents[1].parent / "shared" / "data" / "meshes"
BUNDLED = ["bunny", "cow", "airplane"]                      # ship with pymeshlab: always there
SHARED_BASES = ["spot", "fandisk", "homer", "rocker-arm"]   # ../shared/data/meshes, when present
BASES = (["cube", "sphere", "torus", "l_shape", "u_shape", "plus", "two_cubes", "cube_with_cavity",
          "random_hull"] + BUNDLED + [n for n in SHARED_BASES if (SHARED / f"{n}.obj").exists()])
MUTATIONS = ["none", "drop_faces", "flip_faces", "flip_all", "split_vertices", "jitter_small",
             "jitter_large", "nan", "inf", "scale_tiny", "scale_huge", "far_away", "duplicate_face",
             "repeated_index", "zero_area", "point_cloud", "empty", "unreferenced", "soup", "overlapping_copy"]
SEEDS = 6
TAUS = [10.0, 4.0, 10.0, 0.0, 10.0, -1.0, 1e9, 25.0, 10.0, float("nan"), 15.0, 6.0]
CASES = len(BASES) * len(MUTATIONS) * SEEDS

KINDS = [   # message fragment -> kind, first match wins
    ("Internal error", "internal"), ("pymeshlab:", "refused by pymeshlab"), ("tau", "invalid tau"),
    ("empty", "empty"), ("point cloud", "point cloud"), ("does not have Any Faces", "point cloud"),
    ("NaN", "NaN/Inf"), ("open", "open"), ("non-manifold", "non-manifold"), ("oriented", "orientation"),
    ("repeat a vertex", "repeated index"), ("duplicate other faces", "duplicate faces"),
    ("zero area", "zero area"), ("size", "coordinate scale"), ("no volume", "no volume"),
    ("coplanar", "no volume"), ("intersect", "self-intersection"),
]
# The refusal meant for each mutation of a solid, as given (no preprocessing). A mutation missing here,
# or None among its kinds, may also be decomposed; nothing else is accepted.
REFUSALS = {
    "drop_faces": {"open"}, "split_vertices": {"open"}, "soup": {"open"},
    "flip_faces": {"orientation"}, "duplicate_face": {"duplicate faces"}, "repeated_index": {"repeated index"},
    "zero_area": {"zero area", None}, "nan": {"NaN/Inf"}, "inf": {"NaN/Inf"},
    "point_cloud": {"point cloud"}, "empty": {"refused by pymeshlab", "empty"},
}
# Mutations that make a mesh cross itself: refused as self-intersecting (when asked to, or when a cut
# through the crossing cannot close a part). Any case may be refused so with on_self_intersection =
# refuse: the decimated scanned bases cross themselves already.
CAN_SELF_INTERSECT = {"jitter_large", "overlapping_copy", "soup"}


def kind_of(message):
    return next((k for frag, k in KINDS if frag in message), "other: " + message[:60])


def allowed(i, with_tau=True):
    """The outcomes case i may have: refusal kinds, and None for a decomposition."""
    _, how, _, params = case(i)
    if params.get("preprocessing") == "alpha_wrap":   # the wrap makes every non-empty input a solid
        ok = {"refused by pymeshlab", "empty"} if how == "empty" else {None}
    elif params.get("preprocessing") == "auto":   # a mesh refused as given is wrapped; a valid one is not
        ok = {"refused by pymeshlab", "empty"} if how == "empty" else {None}
        if how in CAN_SELF_INTERSECT or params.get("on_self_intersection") == "refuse":
            ok |= {"self-intersection"}
    else:
        ok = set(REFUSALS.get(how, {None}))
        if how in CAN_SELF_INTERSECT or params.get("on_self_intersection") == "refuse":
            ok |= {"self-intersection"}
    tau = params["tau"]
    if with_tau and (not tau > 0 or tau != tau):
        ok = (ok - {None}) | {"invalid tau"}   # a bad tau must be refused, by its own message or the mesh's
    return ok


def cube(c=(0, 0, 0), s=1.0):
    from .meshes import extrude
    V, F = extrude([(0, 0), (1, 0), (1, 1), (0, 1)], 0, 1)
    return V * s + np.asarray(c, float), F


def base_mesh(name, cache):
    """Small closed meshes (bundled and shared ones decimated to ~800 faces, cached as .npz)."""
    import pymeshlab
    from .meshes import BUNNY, L_SHAPE, PLUS, U_SHAPE, extrude, torus
    if name == "cube":
        return cube()
    if name == "sphere":
        ms = pymeshlab.MeshSet()
        ms.create_sphere(subdiv=2)
        return ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    if name == "torus":
        return torus(nu=24, nv=8)
    if name in ("l_shape", "u_shape", "plus"):
        return extrude({"l_shape": L_SHAPE, "u_shape": U_SHAPE, "plus": PLUS}[name], 0, 1)
    if name == "two_cubes":
        (V1, F1), (V2, F2) = cube(), cube((2, 0, 0))
        return np.vstack([V1, V2]), np.vstack([F1, F2 + len(V1)])
    if name == "cube_with_cavity":
        (V1, F1), (V2, F2) = cube((-1, -1, -1), 3), cube()
        return np.vstack([V1, V2]), np.vstack([F1, F2[:, ::-1] + len(V1)])   # inner shell inward
    if name == "random_hull":
        ms = pymeshlab.MeshSet()
        pts = np.random.default_rng(1).normal(size=(60, 3))
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts))
        ms.generate_convex_hull()
        return ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    path = pathlib.Path(cache) / f"{name}.npz"
    if not path.exists():
        src = str(pathlib.Path(BUNNY).with_name(f"{name}.obj")) if name in BUNDLED else str(SHARED / f"{name}.obj")
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(src)
        ms.meshing_decimation_quadric_edge_collapse(targetfacenum=800, preservetopology=True)
        np.savez(path, V=ms.current_mesh().vertex_matrix(), F=ms.current_mesh().face_matrix())
    d = np.load(path)
    return d["V"], d["F"]


def mutate(V, F, how, rng):
    V, F = np.array(V, float), np.array(F, np.int32)
    diag = float(np.linalg.norm(V.max(0) - V.min(0))) if len(V) else 1.0
    k = int(rng.integers(1, 6))
    pick = lambda n, m: rng.choice(n, size=min(m, n), replace=False)   # noqa: E731
    if how == "drop_faces":
        F = np.delete(F, pick(len(F), k), axis=0)
    elif how == "flip_faces":
        i = pick(len(F), k)
        F[i] = F[i][:, ::-1]
    elif how == "flip_all":
        F = F[:, ::-1].copy()
    elif how == "split_vertices":
        for f in pick(len(F), k):
            V = np.vstack([V, V[F[f, 0]]])
            F[f, 0] = len(V) - 1
    elif how == "jitter_small":
        V += rng.normal(scale=1e-4 * diag, size=V.shape)
    elif how == "jitter_large":
        V += rng.normal(scale=0.05 * diag, size=V.shape)
    elif how == "nan":
        V[rng.integers(len(V))] = np.nan
    elif how == "inf":
        V[rng.integers(len(V)), rng.integers(3)] = np.inf
    elif how == "scale_tiny":
        V *= 1e-9
    elif how == "scale_huge":
        V *= 1e9
    elif how == "far_away":
        V += np.array([1e7, -3e7, 2e7])
    elif how == "duplicate_face":
        F = np.vstack([F, F[pick(len(F), k)]])
    elif how == "repeated_index":
        F[rng.integers(len(F)), 1] = F[rng.integers(len(F)), 0]
        f = rng.integers(len(F))
        F[f, 1] = F[f, 0]
    elif how == "zero_area":
        f = rng.integers(len(F))
        V[F[f, 2]] = (V[F[f, 0]] + V[F[f, 1]]) / 2
    elif how == "point_cloud":
        F = np.zeros((0, 3), np.int32)
    elif how == "empty":
        V, F = np.zeros((0, 3)), np.zeros((0, 3), np.int32)
    elif how == "unreferenced":
        V = np.vstack([V, rng.normal(size=(k, 3))])
    elif how == "soup":
        n = int(rng.integers(1, 40))
        V = rng.normal(size=(3 * n, 3))
        F = np.arange(3 * n, dtype=np.int32).reshape(n, 3)
    elif how == "overlapping_copy":
        F = np.vstack([F, F + len(V)])
        V = np.vstack([V, V + 0.3 * diag / np.sqrt(3)])
    return V, F


def case(i):
    """(base, mutation, seed, parameters) of case i."""
    b, rest = divmod(i, len(MUTATIONS) * SEEDS)
    m, s = divmod(rest, SEEDS)
    params = {"tau": TAUS[(i * 7) % len(TAUS)], "cut_plane_selection": ("bisector", "best")[i % 2],
              "max_parts": 24, "time_limit": 20.0}
    if i % 7 == 3:
        params["on_self_intersection"] = "refuse"
    if i % 5 == 4:   # the preprocessing that makes dirty input decomposable
        params.update(preprocessing="alpha_wrap", wrap_alpha=5.0, wrap_offset=0.5)
    elif i % 5 == 2:   # as given when valid, else wrapped
        params.update(preprocessing="auto", wrap_alpha=5.0, wrap_offset=0.5)
    else:   # as given
        params["preprocessing"] = "none"
    return BASES[b], MUTATIONS[m], s, params


def run_case(i, cache):
    """One case through every filter; returns (kind, detail)."""
    import pymeshlab
    import pymeshlab_acd
    from .meshes import add_mesh, is_closed_manifold, volume
    base, how, seed, params = case(i)
    V, F = mutate(*base_mesh(base, cache), how, np.random.default_rng(1000 * i + seed))
    ms = pymeshlab.MeshSet()
    try:
        add_mesh(ms, V, F)
    except Exception as e:   # pymeshlab refuses the arrays before any filter runs
        return "error", f"pymeshlab: {e}"
    V0, F0 = ms.current_mesh().vertex_matrix().copy(), ms.current_mesh().face_matrix().copy()
    try:   # the concavity filter takes the mesh as given, with no tau
        ms.compute_scalar_by_notch_concavity()
    except pymeshlab.PyMeshLabException as e:
        as_given = allowed(i, with_tau=False) if params["preprocessing"] == "none" else set(REFUSALS.get(how, {None}))
        if kind_of(str(e)) not in as_given:
            return "violation", f"notch concavity refused {how} as {kind_of(str(e))!r}: {' '.join(str(e).split())}"
    ms.set_current_mesh(0)
    try:
        res, ids = pymeshlab_acd.decompose(ms, **params)
    except pymeshlab.PyMeshLabException as e:
        msg = str(e).strip()
        if not msg:
            return "violation", "an error without a message"
        if kind_of(msg) not in allowed(i):
            return "violation", f"{how} refused as {kind_of(msg)!r}, meant: {sorted(map(str, allowed(i)))}: {msg}"
        return "error", msg
    if None not in allowed(i):
        return "violation", f"{how} was decomposed, meant to be refused as {sorted(map(str, allowed(i)))}"
    m0 = ms.mesh(0)
    if not (np.array_equal(m0.vertex_matrix(), V0, equal_nan=True) and np.array_equal(m0.face_matrix(), F0)):
        return "violation", "the input layer was modified"
    # the partition checks, measured here
    total = 0.0
    for j in ids:
        Vp, Fp = ms.mesh(j).vertex_matrix(), ms.mesh(j).face_matrix()
        if not is_closed_manifold(Fp):
            return "violation", f"part {ms.mesh(j).label()} is not closed"
        vol = volume(Vp, Fp)
        if not vol > 0:
            return "violation", f"part {ms.mesh(j).label()} has volume {vol}"
        total += vol
    if res["alpha_wrapped"]:
        return "ok", f"{res['parts']} parts of the wrap"   # the wrap's volume is not the input's
    if res.get("holes_filled"):
        # the input's faces with patches across its holes: the parts' boundary holds every vertex a face of
        # the input uses (within the weld, 1e-5 of the size); an open input encloses no volume to compare
        return on_parts_boundary(ms, ids, V0, F0, res)
    v0 = abs(volume(V0, F0))
    if not abs(total - v0) <= 1e-6 * v0:
        return "violation", f"part volumes sum to {total}, the input's is {v0}"
    return "ok", f"{res['parts']} parts"


def on_parts_boundary(ms, ids, V0, F0, res):
    from .hull_reach import point_surface_distance
    P = np.concatenate([ms.mesh(j).vertex_matrix() for j in ids])
    offset = np.cumsum([0] + [ms.mesh(j).vertex_number() for j in ids])[:-1]
    T = np.concatenate([ms.mesh(j).face_matrix() + o for j, o in zip(ids, offset)])
    used = np.unique(F0[((F0 >= 0) & (F0 < len(V0))).all(axis=1)])
    Q = V0[used]
    Q = Q[np.isfinite(Q).all(axis=1)]
    d, _ = point_surface_distance(Q, P, T)
    diag = float(np.linalg.norm(np.ptp(Q, axis=0)))
    if d.max() > 2e-5 * diag:
        return "violation", f"holes filled, but an input vertex lies {d.max() / diag:.3g} of the size off the parts"
    return "ok", f"{res['parts']} parts, {res['holes_filled']} holes filled"


def child(cache, first, last):
    import pymeshlab_acd
    pymeshlab_acd.load()
    for i in range(first, last):
        print(f"{i} start", flush=True)
        try:
            kind, detail = run_case(i, cache)
        except Exception as e:   # a bug in this harness, not in the filters: reported, not a crash
            kind, detail = "harness", f"{type(e).__name__}: {e}"
        print(f"{i} {kind} {' '.join(detail.split())}", flush=True)


if __name__ == "__main__":
    if sys.argv[1] == "child":
        child(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))
    elif sys.argv[1] == "run":
        import tempfile
        import pymeshlab_acd
        pymeshlab_acd.load()
        print(case(int(sys.argv[2])), run_case(int(sys.argv[2]), tempfile.mkdtemp()))
