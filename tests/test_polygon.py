"""generate_polygon_approximate_convex_decomposition through pymeshlab (with holes).

Checks are independent of the core: each piece's outline is read back from its layer's edges, its
concavity is measured again here (a numpy version of the paper's Algorithm 5.1: hull, bridges,
distance of reflex vertices to their pocket's bridge line), areas are summed from the pieces'
triangles, and overlap is tested by point-in-polygon on sample points.
"""
import math

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from pymeshlab_acd import polygon_io
from support.meshes import SHARED, present
from support.polygons import comb, noisy_blob, star

POLYGONS = SHARED.parent / "polygons"


# ---- shapes ---------------------------------------------------------------------------------
def regular(n, r=1.0, c=(0, 0), phase=0.0):
    t = phase + 2 * np.pi * np.arange(n) / n
    return np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)])





def square(s=10.0, c=(0, 0)):
    return np.array([(c[0] - s, c[1] - s), (c[0] + s, c[1] - s), (c[0] + s, c[1] + s), (c[0] - s, c[1] + s)], float)


# ---- independent checks ---------------------------------------------------------------------
def signed_area(l):
    x, y = l[:, 0], l[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def concavity(loop):
    """Algorithm 5.1 on a counter-clockwise loop: max distance of a reflex vertex to its bridge line."""
    P = np.asarray(loop, float)
    if signed_area(P) < 0:
        P = P[::-1]
    n = len(P)
    order = sorted(range(n), key=lambda i: (P[i, 0], P[i, 1]))

    def cr(o, a, b):
        return (P[a, 0] - P[o, 0]) * (P[b, 1] - P[o, 1]) - (P[a, 1] - P[o, 1]) * (P[b, 0] - P[o, 0])
    hull = []
    for seq in (order, order[::-1]):
        part = []
        for i in seq:
            while len(part) >= 2 and cr(part[-2], part[-1], i) <= 0:
                part.pop()
            part.append(i)
        hull += part[:-1]
    d = np.zeros(n)
    for a, b in zip(hull, hull[1:] + hull[:1]):
        if (b - a) % n <= 1:
            continue
        e = (P[b] - P[a]) / np.linalg.norm(P[b] - P[a])
        v = a
        while (v := (v + 1) % n) != b:
            d[v] = max(0.0, e[0] * (P[v, 1] - P[a, 1]) - e[1] * (P[v, 0] - P[a, 0]))
    size = 2 * np.max(np.linalg.norm(P - P.mean(0), axis=1))
    best = 0.0
    for v in range(n):
        chord = P[(v + 1) % n] - P[v - 1]
        if np.linalg.norm(chord) == 0:
            continue
        c = chord / np.linalg.norm(chord)
        if c[0] * (P[v, 1] - P[v - 1, 1]) - c[1] * (P[v, 0] - P[v - 1, 0]) > 1e-9 * size:   # reflex
            best = max(best, d[v])
    return best


def loops_of(m):
    """Closed loops of a layer's edges, in the plane of its first three non-collinear points."""
    V, E = m.vertex_matrix(), m.edge_matrix()
    c = V.mean(0)
    _, _, vt = np.linalg.svd(V - c, full_matrices=False)
    P = (V - c) @ vt[:2].T
    nxt = {}
    for a, b in E.tolist():
        nxt.setdefault(a, []).append(b)
        nxt.setdefault(b, []).append(a)
    seen, loops = set(), []
    for s in nxt:
        if s in seen:
            continue
        loop, prev, v = [], None, s
        while v not in seen:
            seen.add(v)
            loop.append(v)
            a, b = nxt[v]
            prev, v = v, (a if a != prev else b)
        loops.append(P[loop])
    return loops, P


def in_polygon(loops, pts):
    inside = np.zeros(len(pts), bool)
    for l in loops:
        x0, y0 = l[:, 0], l[:, 1]
        x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
        for k, (px, py) in enumerate(pts):
            cond = (y0 > py) != (y1 > py)
            xs = (x1 - x0) * (py - y0) / np.where(cond, y1 - y0, 1) + x0
            inside[k] ^= bool(np.sum(cond & (px < xs)) % 2)
    return inside


def add_loops(ms, loops, name="polygon", transform=None):
    V, E = polygon_io.loops_to_mesh(loops)
    if transform is not None:
        V = V @ transform[:3, :3].T + transform[:3, 3]
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V, edge_matrix=E), name)


def polygon_area(loops):
    areas = sorted((abs(signed_area(np.asarray(l, float))) for l in loops), reverse=True)
    return areas[0] - sum(areas[1:])   # one outer boundary and its holes


def check_pieces(ms, ids, total_area, tau=None, overlap=20, seed=0):
    rng = np.random.default_rng(seed)
    pieces, area = [], 0.0
    for i in ids:
        m = ms.mesh(i)
        loops, P = loops_of(m)
        F = m.face_matrix()
        a, b, c = P[F[:, 0]], P[F[:, 1]], P[F[:, 2]]
        tri = 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
        assert tri.min() > 0
        area += tri.sum()
        assert abs(tri.sum() - polygon_area(loops)) <= 1e-9 * tri.sum()   # faces fill the outline
        if tau is not None:
            assert len(loops) == 1, f"{m.label()} still has a hole"
            assert concavity(loops[0]) <= tau * (1 + 1e-9), f"{m.label()} exceeds tau"
        pieces.append((m, loops, P, F, tri))
    assert abs(area - total_area) <= 1e-9 * total_area
    # points well inside one piece's triangles are inside no other piece (all share one plane frame
    # only up to sign, so compare in 3D through each piece's own frame: map samples back)
    for k, (m, loops, P, F, tri) in enumerate(pieces):
        if not overlap:
            break
        pick = rng.choice(len(F), size=min(overlap, len(F)), p=tri / tri.sum())
        w = rng.dirichlet([4, 4, 4], size=len(pick))
        X3 = np.einsum("ij,ijk->ik", w, m.vertex_matrix()[F[pick]])
        for j, (m2, loops2, P2, F2, _) in enumerate(pieces):
            if j == k:
                continue
            V2 = m2.vertex_matrix()
            c2 = V2.mean(0)
            _, _, vt = np.linalg.svd(V2 - c2, full_matrices=False)
            assert not in_polygon(loops2, (X3 - c2) @ vt[:2].T).any(), f"{m.label()} overlaps {m2.label()}"
    return pieces


def run(ms, **params):
    return pymeshlab_acd.decompose_polygon(ms, **params)


# ---- tests ----------------------------------------------------------------------------------
def test_convex_polygon_is_one_piece(ms):
    add_loops(ms, [regular(12, 5.0)])
    res, ids = run(ms, tau=0.01, tau_unit="model_units")
    assert res["parts"] == 1 == len(ids) and res["notches"] == 0


@pytest.mark.parametrize("selection", ["bisector", "best"])
def test_star_and_comb_known_counts(ms, selection):
    # A 5-point star (5 notches): a bisector cut resolves only its own notch: notches + 1 = 6 pieces.
    # `best` also cuts from notch to notch, resolving two at once: fewer, but never below the optimum
    # (4, CGAL's optimal_convex_partition_2 in the 2D benchmark).
    add_loops(ms, [star()])
    res, ids = run(ms, tau=0.05, tau_unit="model_units", cut_line_selection=selection)
    assert res["notches"] == 5
    assert res["parts"] == 6 if selection == "bisector" else 4 <= res["parts"] <= 5
    check_pieces(ms, ids, abs(signed_area(star())), tau=0.05)
    # A comb of k teeth has 2(k-1) right-angle notches. The bisector (45 degrees) resolves one per cut:
    # 2k - 1 pieces. `best` finds the cut along the tooth's foot from one gap's corner to the next
    # gap's corner, which resolves two: the optimum k + 1 (each tooth and the bar).
    for teeth in (2, 4, 6):
        m = pymeshlab.MeshSet()
        add_loops(m, [comb(teeth)])
        res, ids = run(m, tau=0.05, tau_unit="model_units", cut_line_selection=selection)
        assert res["notches"] == 2 * (teeth - 1)
        assert res["parts"] == (2 * teeth - 1 if selection == "bisector" else teeth + 1)
        check_pieces(m, ids, abs(signed_area(comb(teeth))), tau=0.05)


@pytest.mark.parametrize("handling", ["principal_plane", "best_plane", "keep_cavities"])
@pytest.mark.parametrize("holes", [1, 3])
def test_polygons_with_holes(ms, holes, handling):
    centres = [(0, 0)] if holes == 1 else [(-5, -4), (5, -4), (0, 5)]
    loops = [square(10.0)] + [regular(16, 2.5, c, phase=0.1) * np.array([1.0, 0.6]) + np.array(c) * np.array([0, 0.4])
                              for c in centres]
    add_loops(ms, loops)
    res, ids = run(ms, tau=0.2, tau_unit="model_units", hole_handling=handling)
    assert res["holes"] == holes
    if handling == "keep_cavities":
        pieces = check_pieces(ms, ids, polygon_area(loops))
        kept = sum(len(p[1]) - 1 for p in pieces)
        assert kept == holes == res["kept_holes"] and not res["tau_convex"]
        for m, pl, P, F, tri in pieces:   # the outer boundary alone is tau-convex
            outer = max(pl, key=lambda l: abs(signed_area(l)))
            assert concavity(outer) <= 0.2 * (1 + 1e-9)
    else:
        check_pieces(ms, ids, polygon_area(loops), tau=0.2)
        assert res["hole_cuts"] >= 1 and res["tau_convex"]


@pytest.mark.parametrize("order", ["first", "by_concavity"])
def test_hole_order(ms, order):
    loops = [comb(4) * 4, regular(12, 1.0, (14.0, 2.0))]
    add_loops(ms, loops)
    res, ids = run(ms, tau=0.1, tau_unit="model_units", hole_order=order)
    assert res["holes"] == 1 and res["hole_cuts"] == 1
    check_pieces(ms, ids, polygon_area(loops), tau=0.1)
    root = res["tree"]["polygons"][0]["nodes"][0]
    # holes first: the root's cut goes through the hole; by concavity: the deeper comb notches first
    assert root["hole_cut"] == (order == "first")


def test_best_plane_never_leaves_more_concavity_than_the_principal_axis(ms):
    loops = [square(10.0), regular(24, 3.0, (2, 1), 0.3) * np.array([1.0, 0.35]) + np.array([0, 0.65])]
    left = {}
    for handling in ("principal_plane", "best_plane"):
        m = pymeshlab.MeshSet()
        add_loops(m, loops)
        res, ids = run(m, tau=0.05, tau_unit="model_units", hole_handling=handling, max_parts=2)
        assert res["parts"] == 2 and res["hole_cuts"] == 1
        left[handling] = max(concavity(loops_of(m.mesh(i))[0][0]) for i in ids)
    assert left["best_plane"] <= left["principal_plane"] * (1 + 1e-9)


def test_noisy_outline_counts_like_figure_8(ms):
    blob = noisy_blob()
    counts = {}
    for tau in (2.0, 1.0, 0.5):
        m = pymeshlab.MeshSet()
        add_loops(m, [blob])
        res, ids = run(m, tau=tau, tau_unit="model_units", cut_line_selection="bisector")
        counts[tau] = res["parts"]
        check_pieces(m, ids, abs(signed_area(blob)), tau=tau, overlap=5)
        notches = res["notches"]
    print(f"noisy outline: {len(blob)} vertices, {notches} notches; pieces at tau 2, 1, 0.5: "
          f"{counts[2.0]}, {counts[1.0]}, {counts[0.5]}")
    assert 180 <= notches <= 240
    assert counts[2.0] <= counts[1.0] <= counts[0.5] < notches / 2


@pytest.mark.parametrize("name,expected", [("simple7", (18, 26, 36)), ("hole5", None), ("hole3", None)])
def test_the_papers_polygons(ms, name, expected):
    loops = polygon_io.read_loops(present(POLYGONS / f"{name}.poly"))
    counts = []
    for tau in (2.0, 1.0, 0.5):
        m = pymeshlab.MeshSet()
        add_loops(m, loops)
        res, ids = run(m, tau=tau, tau_unit="model_units", cut_line_selection="bisector",
                       hole_handling="principal_plane")
        check_pieces(m, ids, polygon_area(loops), tau=tau, overlap=5)
        counts.append(res["parts"])
    print(f"{name}: pieces at tau 2, 1, 0.5: {counts}")
    if expected:
        assert tuple(counts) == expected   # the paper's Figure 8 (top)
    assert counts == sorted(counts)


def test_planar_triangle_mesh_in_a_tilted_plane(ms):
    # an L-shaped slab with a square hole, given as triangles (its boundary loops are the polygon)
    outer = np.array([(0, 0), (6, 0), (6, 2), (2, 2), (2, 6), (0, 6)], float)
    hole = np.array([(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5)], float)
    m0 = pymeshlab.MeshSet()
    add_loops(m0, [outer, hole])
    res0, ids0 = run(m0, tau=100, tau_unit="model_units", hole_handling="keep_cavities")   # one piece: a triangulation
    tri = m0.mesh(ids0[0])
    R, _ = np.linalg.qr(np.random.default_rng(3).normal(size=(3, 3)))
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, (5.0, -2.0, 7.0)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=tri.vertex_matrix() @ R.T + T[:3, 3], face_matrix=tri.face_matrix()), "slab")
    res, ids = run(ms, tau=0.05, tau_unit="model_units")
    assert res["holes"] == 1 and res["parts"] >= 3
    n = np.array([res["plane_normal_x"], res["plane_normal_y"], res["plane_normal_z"]])
    assert abs(abs(n @ R[:, 2]) - 1) < 1e-9   # the fitted plane is the tilted one
    check_pieces(ms, ids, polygon_area([outer, hole]), tau=0.05)


def test_svg_and_plain_text_input(tmp_path):
    svg = tmp_path / "p.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 40 0 L 40 30 L 20 10 L 0 30 Z '
                   'm 5 3 h 4 v 3 h -4 z"/></svg>')
    txt = tmp_path / "p.txt"
    txt.write_text("0 0\n40 0\n40 -30\n20 -10\n0 -30\n\n5 -3\n9 -3\n9 -6\n5 -6\n")
    a, b = polygon_io.read_loops(svg), polygon_io.read_loops(txt)
    assert len(a) == len(b) == 2
    for x, y in zip(a, b):
        assert np.allclose(x, y)   # SVG's y axis points down
    from pymeshlab_acd.__main__ import main
    assert main(["polygon", str(svg), "--tau", "0.5", "--tau-unit", "model_units", "--no-progress",
                 "--out", str(tmp_path / "out")]) == 0
    assert (tmp_path / "out" / "pieces.svg").stat().st_size > 0


@pytest.mark.parametrize("loops,params,match", [
    ([np.array([(0, 0), (4, 0), (0, 4), (4, 4)], float)], {}, "cross"),             # a bow tie
    ([square(), square(2.0, (9.5, 0))], {}, "cross"),                                # hole touching the outline
    ([np.array([(0, 0), (1, 0), (2, 0)], float)], {}, "cross or touch"),             # flat: folds onto itself
    ([square()], {"tau": 0.0}, "tau"),
])
def test_bad_polygons_get_a_clear_error(ms, loops, params, match):
    add_loops(ms, loops)
    with pytest.raises(pymeshlab.PyMeshLabException, match=match):
        run(ms, **{"tau": 1.0, **params})


def test_open_or_non_planar_outlines_get_a_clear_error(ms):
    V, E = polygon_io.loops_to_mesh([square()])
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V, edge_matrix=E[:-1]), "open")
    with pytest.raises(pymeshlab.PyMeshLabException, match="closed loops"):
        run(ms, tau=1.0)
    V2 = V.copy()
    V2[0, 2] = 3.0
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V2, edge_matrix=E), "bent")
    with pytest.raises(pymeshlab.PyMeshLabException, match="not planar"):
        run(ms, tau=1.0)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V), "points")
    with pytest.raises(pymeshlab.PyMeshLabException, match="neither faces nor edges"):
        run(ms, tau=1.0)


@pytest.mark.parametrize("seed", range(6))
def test_random_star_shaped_polygons_partition(ms, seed):
    # random star-shaped outlines (3-200 vertices), some with a hole near the centre, every option
    rng = np.random.default_rng(seed)
    for case in range(6):
        n = int(rng.integers(3, 200))
        t = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = rng.uniform(3.0, 10.0, n)
        loops = [np.column_stack([r * np.cos(t), r * np.sin(t)])]
        if case % 2:
            loops.append(regular(int(rng.integers(3, 20)), 1.0, rng.uniform(-0.5, 0.5, 2)))
        m = pymeshlab.MeshSet()
        add_loops(m, loops)
        tau = float(rng.choice([0.05, 0.3, 1.0]))
        handling = str(rng.choice(["best_plane", "principal_plane", "keep_cavities"]))
        res, ids = run(m, tau=tau, tau_unit="model_units", cut_line_selection=str(rng.choice(["best", "bisector"])),
                       hole_handling=handling, hole_order=str(rng.choice(["first", "by_concavity"])))
        keep = handling == "keep_cavities" and len(loops) > 1
        check_pieces(m, ids, polygon_area(loops), tau=None if keep else tau, overlap=3, seed=case)
