"""Skeleton and hull-union simplification from the decomposition. Checked here:
skeleton points inside the mesh (ray parity in numpy), connectivity (union-find), the union's volume
IoU re-estimated in numpy, face counts."""
import re
import subprocess
import sys

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from support.meshes import (BUNNY, SHARED, add_mesh, component_labels, extrude, inside, is_closed_manifold, present,
                      torus, volume)


def layer(ms, label):
    return next(ms.mesh(i) for i in pymeshlab_acd.mesh_ids(ms) if ms.mesh(i).label() == label)


def samples_along(m, n, seed=0):
    V, E = m.vertex_matrix(), m.edge_matrix()
    rng = np.random.default_rng(seed)
    L = np.linalg.norm(V[E[:, 0]] - V[E[:, 1]], axis=1)
    pick = rng.choice(len(E), n, p=L / L.sum())
    s = rng.random(n)[:, None]
    return V[E[pick, 0]] * (1 - s) + V[E[pick, 1]] * s


def components(m):
    return len(np.unique(component_labels(m.vertex_number(), m.edge_matrix().tolist())))


@pytest.mark.parametrize("name", ["bunny", "horse"])
def test_skeleton_inside_and_connected(ms, name):
    path = BUNNY if name == "bunny" else present(SHARED / "horse.ply")
    ms.load_new_mesh(str(path))
    V0, F0 = ms.mesh(0).vertex_matrix(), ms.mesh(0).face_matrix()
    res = ms.generate_skeleton_from_convex_decomposition()   # default cut: min_section
    sk = layer(ms, "acd_skeleton")
    assert sk.edge_number() == res["edges"] > 0 and sk.face_number() == 0
    assert components(sk) == 1 == res["components"]
    pts = samples_along(sk, 2000)
    ratio = inside(V0, F0, pts).mean()
    print(f"{name}: skeleton of {res['parts']} parts ({res['refinements']} refinements): "
          f"{sk.vertex_number()} vertices, {ratio:.4f} of 2000 points inside")
    assert ratio >= 0.99


def half_ring():
    """A C: half an annulus (radii 1.5 and 2.5) extruded by 1; its hull's axis runs across the gap."""
    th = np.linspace(0, np.pi, 25)
    return extrude(np.r_[np.c_[2.5 * np.cos(th), 2.5 * np.sin(th)], np.c_[1.5 * np.cos(th[::-1]), 1.5 * np.sin(th[::-1])]], 0, 1)


@pytest.mark.parametrize("shape,tau,loops", [("ring", 0.3, 1), ("ring", 0.5, 1), ("C", 1.6, 0)])
def test_skeleton_refines_bent_parts_and_closes_the_ring(ms, shape, tau, loops):
    # ring at 0.3: cut into arcs, joined around; ring at 0.5 and the C at 1.6: one tau-convex part
    # whose hull axis crosses the hole, so the skeleton splits it across the axis at the bend
    V, F = torus(R=2.0, r=0.5) if shape == "ring" else half_ring()
    add_mesh(ms, V, F)
    res = ms.generate_skeleton_from_convex_decomposition(tau=tau, tau_unit="model_units")
    sk = layer(ms, "acd_skeleton")
    if res["parts"] == 1:
        assert res["refinements"] > 0
    # pieces: the tree's nodes kept whole (at most its leaves) plus the extra splits
    assert res["pieces"] <= res["parts"] + res["refinements"]
    assert res["components"] == 1 == components(sk)
    # genus 1: a cut meets the ring in two cross-sections, each a joint, so the skeleton has a loop
    assert sk.edge_number() - sk.vertex_number() + 1 == loops
    ratio = inside(V, F, samples_along(sk, 2000)).mean()
    print(f"{shape} at tau {tau}: {res['parts']} parts, {res['refinements']} refinements, {ratio:.4f} inside")
    assert ratio >= 0.99


def skeleton_distances(mesh_path, seeds, **kw):
    """Mean distance (fraction of the bbox diagonal) between the skeleton of a mesh and that of a copy
    with Gaussian noise of 0.5% of the diagonal on its vertices (alpha-wrapped: its faces cross), per seed."""
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(mesh_path))
    V0, F0 = ms.mesh(0).vertex_matrix(), ms.mesh(0).face_matrix()
    diag = np.linalg.norm(V0.max(0) - V0.min(0))
    ms.generate_skeleton_from_convex_decomposition(**kw)
    A = samples_along(layer(ms, "acd_skeleton"), 2000)
    d = lambda X, Y: np.min(np.linalg.norm(X[:, None, :] - Y[None, ::4, :], axis=2), axis=1).mean()
    out = []
    for seed in seeds:
        noisy = pymeshlab.MeshSet()
        add_mesh(noisy, V0 + np.random.default_rng(seed).normal(scale=0.005 * diag, size=V0.shape), F0)
        noisy.generate_skeleton_from_convex_decomposition(preprocessing="alpha_wrap", **kw)
        B = samples_along(layer(noisy, "acd_skeleton"), 2000)
        out.append(0.5 * (d(A, B) + d(B, A)) / diag)
    return out


@pytest.mark.parametrize("name", ["bunny", "horse"])
def test_skeleton_under_noise(name):
    path = BUNNY if name == "bunny" else present(SHARED / "horse.ply")
    means = skeleton_distances(path, range(1, 9))
    print(f"{name} skeleton, noise 0.5% of the diagonal, seeds 1-8: mean distance "
          + ", ".join(f"{m:.4f}" for m in means) + f" of the diagonal (average {np.mean(means):.4f})")
    # The target is 2%. Measured: all 16 draws below it, the worst at 0.019997 (docs/parameters.md); a draw
    # can swap the order of two near-equal notches, so one draw is allowed a little more.
    assert np.mean(means) < 0.02 and max(means) < 0.025


@pytest.mark.parametrize("merge", ["together", "boolean_union"])
def test_hull_union_simplifies_faithfully(ms, merge):
    ms.load_new_mesh(BUNNY)
    V0, F0 = ms.mesh(0).vertex_matrix(), ms.mesh(0).face_matrix()
    maxv = 64 if merge == "together" else 0   # bounded hulls (as physics engines need), or exact ones
    res = ms.generate_convex_hull_union(tau=3.0, cut_plane_selection="bisector", max_hull_vertices=maxv, merge=merge,
                                        iou_samples=100000)
    hulls = [ms.mesh(i) for i in pymeshlab_acd.mesh_ids(ms) if ms.mesh(i).label().startswith("acd_hull_")
             and ms.mesh(i).label() != "acd_hull_union"]
    union = layer(ms, "acd_hull_union")
    assert len(hulls) == res["hulls"] >= 2
    assert all((maxv == 0 or h.vertex_number() <= maxv) and is_closed_manifold(h.face_matrix()) for h in hulls)
    assert union.face_number() == res["union_faces"] < F0.shape[0]
    if merge == "boolean_union":
        assert is_closed_manifold(union.face_matrix())
    else:
        assert union.face_number() == sum(h.face_number() for h in hulls)
    # IoU re-estimated here: points in the bounding box, inside the mesh vs inside some hull
    rng = np.random.default_rng(5)
    lo, hi = V0.min(0), V0.max(0)
    P = rng.uniform(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), size=(4000, 3))
    in_mesh = inside(V0, F0, P)
    in_hull = np.zeros(len(P), bool)
    for h in hulls:
        Vh, Fh = h.vertex_matrix(), h.face_matrix()
        n = np.cross(Vh[Fh[:, 1]] - Vh[Fh[:, 0]], Vh[Fh[:, 2]] - Vh[Fh[:, 0]])
        off = np.einsum("ij,ij->i", n, Vh[Fh[:, 0]])
        in_hull |= np.all(P @ n.T <= off + 1e-12, axis=1)
    iou = (in_mesh & in_hull).sum() / (in_mesh | in_hull).sum()
    print(f"hull union ({merge}): {res['hulls']} hulls, {res['union_faces']} faces from {res['input_faces']} "
          f"({res['face_reduction']:.1f}x fewer), IoU {res['volume_iou']:.3f} (filter) / {iou:.3f} (test)")
    assert abs(iou - res["volume_iou"]) < 0.02 and res["volume_iou"] > 0.9
    if maxv == 0:
        # the parts tile the mesh, so their exact hulls hold it: IoU >= mesh volume / sum of hull volumes
        bound = volume(V0, F0) / sum(volume(h.vertex_matrix(), h.face_matrix()) for h in hulls)
        assert res["volume_iou"] >= bound - 4 * res["volume_iou_stderr"]


def test_cli_structure_reports_level_skeleton_and_union(tmp_path):
    # the demo's command on a ring: a coarser level from the saved tree, the skeleton, the hull union
    V, F = torus(R=2.0, r=0.5)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F)
    ms.save_current_mesh(str(tmp_path / "ring.obj"))
    p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "structure", str(tmp_path / "ring.obj"), "--tau", "3",
                        "--coarser", "12", "--out", str(tmp_path / "out"), "--no-progress"],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    print(p.stdout)
    fine = int(re.search(r"decomposition +tau 3.0%: (\d+) parts", p.stdout).group(1))
    coarse = int(re.search(r"coarser level +tau 12.0%: (\d+) parts", p.stdout).group(1))
    # fewer parts at 12%, but never one: the ring's notches (0.5) are within 12% of its size (5), its
    # hull over the hole (1.5) is not
    assert 3 <= coarse < fine
    sk = pymeshlab.MeshSet()
    sk.load_new_mesh(str(tmp_path / "out" / "skeleton.obj"))
    assert sk.current_mesh().edge_number() > 0
    assert inside(V, F, samples_along(sk.current_mesh(), 500)).mean() >= 0.99
    un = pymeshlab.MeshSet()
    un.load_new_mesh(str(tmp_path / "out" / "hull_union.obj"))
    assert 0 < un.current_mesh().face_number() < 64 * 2 * fine
