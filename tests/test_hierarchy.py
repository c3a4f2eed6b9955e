"""The decomposition tree as level of detail: saved once, coarser levels read back
without recomputing. Parts are re-measured here (closedness, volumes, concavity through the
notch-concavity filter), not read from the tree."""
import json

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from support.meshes import BUNNY, add_mesh, hull_within, is_closed_manifold, torus, volume
from support.partition import certified


@pytest.fixture(scope="module")
def bunny_tree(tmp_path_factory):
    tree = tmp_path_factory.mktemp("lod") / "bunny_tree.json"
    ms = pymeshlab.MeshSet()
    pymeshlab_acd.load()
    ms.load_new_mesh(BUNNY)
    res, ids = pymeshlab_acd.decompose(ms, tau=3.0, cut_plane_selection="bisector", tree_file=tree)
    v0 = volume(ms.mesh(0).vertex_matrix(), ms.mesh(0).face_matrix())
    return tree, res, v0


def test_tree_saves_hulls_planes_and_concavity(bunny_tree):
    tree, res, v0 = bunny_tree
    nodes = json.loads(tree.read_text())["nodes"]
    cut = [n for n in nodes if "merged" not in n]   # the cut tree; merged parts are listed after it
    leaves = [n for n in cut if n["leaf"]]
    assert len(cut) == 2 * len(leaves) - 1
    assert res["parts"] == len(leaves) - sum(len(n["merged"]) - 1 for n in nodes if "merged" in n)
    for n in nodes:
        assert "hull" in n and len(n["hull"]["f"]) >= 12 and "concavity" in n and "volume" in n
        assert ("plane" in n) == (not n["leaf"] and "merged" not in n)
        assert ("mesh" in n) == (n["leaf"] or "merged" in n)


def test_concavity_decreases_with_depth(bunny_tree):
    tree, res, v0 = bunny_tree
    nodes = json.loads(tree.read_text())["nodes"]
    for n in nodes:
        for c in n["children"]:
            if c >= 0:
                # a child never needs more than its parent (up to rounding of the measure)
                assert nodes[c]["concavity"] <= n["concavity"] * (1 + 1e-6) + 1e-12, (n["path"], nodes[c]["path"])


@pytest.mark.parametrize("coarse", [3.0, 6.0, 12.0])
def test_coarser_levels_without_recomputing(ms, bunny_tree, coarse):
    tree, res, v0 = bunny_tree
    lod, ids = pymeshlab_acd.level_of_detail(ms, tree, tau=coarse)
    assert lod["parts"] == len(ids) and lod["tree_parts"] == res["parts"] and lod["open_parts"] == 0
    if coarse == 3.0:
        assert lod["parts"] == res["parts"]   # the tree's own level: its leaves
    else:
        assert lod["parts"] < res["parts"]
    tau_abs = lod["tau_model_units"]
    total = 0.0
    for i in ids:
        V, F = ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()
        assert is_closed_manifold(F), ms.mesh(i).label()
        total += volume(V, F)
        # the rebuilt part is the saved node's solid: re-measured within tau' (a part merged by its
        # hull by its hull alone)
        certified(V, F, tau_abs * (1 + 1e-6), ms.mesh(i).label())
    assert total == pytest.approx(v0, rel=1e-6)
    print(f"bunny tree at 3%: {res['parts']} parts; level at {coarse}%: {lod['parts']} parts, "
          f"{lod['time']:.2f} s (decomposition took {res['time']:.2f} s)")


def test_levels_by_depth_and_hulls(ms, bunny_tree):
    tree, res, v0 = bunny_tree
    counts = []
    for d in range(0, 4):
        m = pymeshlab.MeshSet()
        lod, ids = pymeshlab_acd.level_of_detail(m, tree, depth=d, output_hulls=(d == 2))
        parts = [i for i in ids if not m.mesh(i).label().startswith("acd_hull_")]
        counts.append(len(parts))
        assert sum(volume(m.mesh(i).vertex_matrix(), m.mesh(i).face_matrix()) for i in parts) == pytest.approx(v0, rel=1e-6)
        if d == 2:
            assert len(ids) == 2 * len(parts)
    assert counts[0] == 1 and counts[1] == 2 and counts == sorted(counts)


def test_bad_tree_files_get_a_clear_error(ms, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(pymeshlab.PyMeshLabException, match="not valid JSON"):
        pymeshlab_acd.level_of_detail(ms, bad, tau=5.0)
    with pytest.raises(pymeshlab.PyMeshLabException, match="Cannot read"):
        pymeshlab_acd.level_of_detail(ms, tmp_path / "missing.json", tau=5.0)


def test_coarser_level_never_covers_a_hole(ms, tmp_path):
    """A low-poly ring's root has a small notch concavity while its hull covers the hole: a coarser
    level at a tau between the two must still split the ring, every part's hull within that tau by the
    independent measure."""
    from support.hull_reach import hull_reach
    V, F = torus(R=2.0, r=0.5, nu=8, nv=6)
    add_mesh(ms, V, F)
    tree = tmp_path / "ring.json"
    res, _ = pymeshlab_acd.decompose(ms, tau=0.1, tau_unit="model_units", tree_file=tree)
    root = json.loads(tree.read_text())["nodes"][0]
    reach, _ = hull_reach(V, F, slack=1e-3)   # the whole ring's hull over its hole
    coarse = 1.05 * root["concavity"]
    assert coarse < reach, (root["concavity"], reach)   # the notches alone would keep the ring whole
    ms.set_current_mesh(0)
    lod, ids = pymeshlab_acd.level_of_detail(ms, tree, tau=coarse, tau_unit="model_units")
    assert 1 < lod["parts"] <= res["parts"]
    total = 0.0
    for i in ids:
        Vp, Fp = ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()
        assert is_closed_manifold(Fp)
        total += volume(Vp, Fp)
        hull_within(Vp, Fp, coarse, ms.mesh(i).label())
    assert total == pytest.approx(volume(V, F), rel=1e-6)
    print(f"ring: root notch concavity {root['concavity']:.3f}, hull reach {reach:.3f}; "
          f"level at {coarse:.3f}: {lod['parts']} of {res['parts']} parts")
