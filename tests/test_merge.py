"""merge_parts: after the cuts, neighbouring parts are merged while their union stays within tau.

Every merged decomposition is re-measured here, sharing no code with the core: parts closed and
2-manifold, volumes summing to the input's, no overlap (interior samples of one part inside no other),
each part's hull within tau (tests/support/hull_reach.py); the tree file's record of the merges is checked
against the leaves' own meshes.
"""
import json

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from support.meshes import add_mesh, box, extrude, is_closed_manifold, random_rotation, same_parts, torus, volume
from support.partition import check_partition

cad_solids = pytest.importorskip("support.cad_solids")
pytest.importorskip("manifold3d")


def solid(name):
    return torus(R=2.0, r=0.5, nu=24, nv=12) if name == "torus" else cad_solids.make(name)


def run(name, tau, merge, tree_file=None, **kw):
    V, F = solid(name)
    ms = pymeshlab.MeshSet()
    pymeshlab_acd.load()
    add_mesh(ms, V, F, name)
    if merge is not None:   # None: the filter's default
        kw["merge_parts"] = merge
    res, ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=tau, tree_file=str(tree_file or ""), **kw)
    return ms, res, ids


@pytest.mark.parametrize("name,tau", [("keyway", 2.0), ("through_slot", 2.0), ("torus", 5.0), ("spur_gear", 2.0)])
def test_merged_parts_are_an_exact_partition_within_tau(name, tau):
    ms, res, ids = run(name, tau, merge=True)
    _, cut, _ = run(name, tau, merge=False)
    assert res["tau_convex"]
    assert res["parts"] <= cut["parts"]
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10)
    print(f"{name} tau {tau}%: {cut['parts']} cut leaves, {res['parts']} parts merged")


def test_merging_makes_fewer_parts_by_default():
    """A ring cut arc by arc at 5%: neighbouring arcs that are convex enough together are merged, with
    the filter's default settings."""
    _, merged, _ = run("torus", 5.0, merge=None)
    _, cut, _ = run("torus", 5.0, merge=False)
    assert merged["merges"] > 0
    assert merged["parts"] < cut["parts"]


def test_stepped_shaft_in_at_most_four_parts():
    """Three coaxial cylinders: at tau 2% with the default settings, one piece per cylinder or close."""
    ms, res, ids = run("stepped_shaft", 2.0, merge=None)
    assert res["parts"] <= 4
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10)


def test_belt_pulley_in_its_three_pieces():
    """Flanges chamfered onto a faceted hub: each flange comes off whole across the rim it meets the hub
    at, where the rim's facets, one plane each, would cut it in wedges."""
    ms, res, ids = run("belt_pulley", 2.0, merge=None)
    assert res["parts"] <= 4
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10)


def test_low_boss_comes_off_its_plate_whole():
    """A boss whose sides rise 15 degrees from its plate: the plate's top face takes it off in one piece
    (the plate and the boss), where the bisector slices across both; merged by concavity they stay two.
    Merged by the hull's distance (the default) they are one part: the boss is low enough for the hull
    over both to stay within tau of them."""
    ms, res, ids = run("bossed_plate", 2.0, merge=None, merge_measure="concavity")
    parts = check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10, merge_measure="concavity")
    assert sorted(volume(V, F) for V, F, _ in parts) == pytest.approx([350.0, 9600.0], rel=1e-4)
    ms, res, ids = run("bossed_plate", 2.0, merge=None)
    parts = check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10)
    assert [volume(V, F) for V, F, _ in parts] == pytest.approx([9950.0], rel=1e-4)

    # In any pose: the flat is found by the faces' own planes, not by the axes.
    V, F = solid("bossed_plate")
    for seed in range(3):
        ms = pymeshlab.MeshSet()
        add_mesh(ms, V @ random_rotation(seed).T, F, "bossed_plate")
        _, ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=2.0, merge_measure="concavity")
        vols = sorted(volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids)
        assert vols == pytest.approx([350.0, 9600.0], rel=1e-4), seed


def test_the_tree_records_which_leaves_each_part_unites(tmp_path):
    tree = tmp_path / "tree.json"
    ms, res, ids = run("torus", 5.0, merge=True, tree_file=tree)
    nodes = json.loads(tree.read_text())["nodes"]
    leaves = [i for i, n in enumerate(nodes) if n["leaf"]]
    merged = [n for n in nodes if "merged" in n]
    assert merged
    seen = [l for n in merged for l in n["merged"]]
    assert len(seen) == len(set(seen)) and set(seen) <= set(leaves)   # each leaf in one part at most
    assert res["parts"] == len(leaves) - len(seen) + len(merged) == len(ids)
    for i, n in enumerate(nodes):
        if "merged" not in n:
            continue
        V = np.reshape(n["mesh"]["v"], (-1, 3))
        F = np.reshape(n["mesh"]["f"], (-1, 3))
        assert is_closed_manifold(F)
        parts = [np.reshape(nodes[l]["mesh"]["v"], (-1, 3)) for l in n["merged"]]
        faces = [np.reshape(nodes[l]["mesh"]["f"], (-1, 3)) for l in n["merged"]]
        assert volume(V, F) == pytest.approx(sum(volume(v, f) for v, f in zip(parts, faces)), rel=1e-9)
        assert all(nodes[l]["part"] == i for l in n["merged"])


def test_level_of_detail_gives_the_merged_parts_at_the_trees_tau(tmp_path):
    tree = tmp_path / "tree.json"
    _, res, _ = run("torus", 5.0, merge=True, tree_file=tree)
    ms = pymeshlab.MeshSet()
    lod, ids = pymeshlab_acd.level_of_detail(ms, tree, tau=5.0)
    assert lod["parts"] == res["parts"] == len(ids) and lod["open_parts"] == 0
    V, F = solid("torus")
    assert sum(volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids) == pytest.approx(
        volume(V, F), rel=1e-6)


def test_merge_off_gives_the_cut_trees_leaves(tmp_path):
    tree = tmp_path / "tree.json"
    _, res, ids = run("torus", 5.0, merge=False, tree_file=tree)
    nodes = json.loads(tree.read_text())["nodes"]
    assert not any("merged" in n for n in nodes)
    assert res["parts"] == sum(n["leaf"] for n in nodes)


def test_command_line_merges_unless_told_not_to(tmp_path):
    import subprocess
    import sys
    V, F = solid("torus")
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F)
    ms.save_current_mesh(str(tmp_path / "ring.obj"))
    parts = {}
    for flag in ("--merge-parts", "--no-merge-parts"):
        out = tmp_path / flag
        p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "decompose", str(tmp_path / "ring.obj"), "--tau", "5",
                            flag, "--out", str(out), "--no-progress"], capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, p.stderr
        parts[flag] = json.loads((out / "summary.json").read_text())["parts"]
    assert parts["--merge-parts"] < parts["--no-merge-parts"]


@pytest.mark.parametrize("name", ["keyway", "through_slot"])
def test_the_same_parts_merge_in_any_pose(name):
    """Rotated, the solid comes out in the same parts: the same count and the same sorted part volumes
    (measured here), whatever rounding the rotation brings to the cuts and the glued seams."""
    V, F = solid(name)

    def parts(W):
        ms = pymeshlab.MeshSet()
        pymeshlab_acd.load()
        add_mesh(ms, W, F, name)
        res, ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=2.0, cut_plane_selection="bisector")
        return res["merges"], np.sort([volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids])

    merges0, vols0 = parts(V)
    assert merges0 > 0
    for seed in range(3):
        merges, vols = parts(V @ random_rotation(seed).T)
        assert same_parts(vols, vols0), (seed, merges, merges0, len(vols), len(vols0))


def test_a_slot_narrower_than_tau_merges_by_the_hull_not_by_the_notches():
    """A block with a slot 0.2 wide and 1.6 deep, at tau 5% (0.19): by the hull's distance (the default)
    the block is one part, not cut, whose hull spans the slot within tau of it (re-measured here); merged
    by concavity, the slot's floor, 1.6 below that hull, keeps the block in more parts."""
    V, F = extrude([(0, 0), (3, 0), (3, 2), (1.6, 2), (1.6, 0.4), (1.4, 0.4), (1.4, 2), (0, 2)], 0, 1)
    res = {}
    for measure in ("hull_distance", "concavity"):
        ms = pymeshlab.MeshSet()
        pymeshlab_acd.load()
        add_mesh(ms, V, F, "slotted")
        res[measure], ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=5.0, merge_measure=measure)
        assert res[measure]["tau_convex"]
        check_partition(ms, 0, ids, tau_abs=res[measure]["tau_model_units"], overlap_samples=10, merge_measure=measure)
    assert res["hull_distance"]["parts"] == 1 < res["concavity"]["parts"]
    assert res["hull_distance"]["merges"] == 0   # the cuts stopped at the block: nothing to merge back
    assert res["hull_distance"]["hull_certified_parts"] == 1 and res["concavity"]["hull_certified_parts"] == 0
    assert res["hull_distance"]["max_concavity"] > res["hull_distance"]["tau_model_units"]   # the slot's floor


@pytest.mark.parametrize("gap,parts", [(0.1, 1), (0.8, 2)])
def test_separate_solids_of_an_assembly_share_a_hull_where_it_stays_within_tau(gap, parts):
    """Two blocks side by side (an assembly's pieces, one mesh of two closed shells), a gap between them:
    near, they are one part of both shells, its hull within tau of them; far, the middle of the gap
    lies beyond tau from both and they stay two, in any pose. By the paper's concavity alone they stay
    two."""
    Va, Fa = box((0, 0, 0), (1, 1, 1))
    Vb, Fb = box((1 + gap, 0.05, 0), (1.8 + gap, 0.95, 0.95))
    V, F = np.vstack([Va, Vb]), np.vstack([Fa, np.asarray(Fb) + len(Va)])
    ms = pymeshlab.MeshSet()
    pymeshlab_acd.load()
    add_mesh(ms, V, F, "assembly")
    res, ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=5.0)
    assert res["parts"] == parts and len(ids) == parts
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"])
    if parts == 1:
        Vp, Fp = ms.mesh(ids[0]).vertex_matrix(), ms.mesh(ids[0]).face_matrix()
        assert len(Fp) == len(F)
        assert volume(Vp, Fp) == pytest.approx(1.0 + 0.8 * 0.9 * 0.95, rel=1e-9)
    ms2 = pymeshlab.MeshSet()
    add_mesh(ms2, V, F, "assembly")
    res2, _ = pymeshlab_acd.decompose(ms2, with_tree=False, tau=5.0, merge_measure="concavity")
    assert res2["parts"] == 2
    # Turned, the same parts (count and volumes, measured here).
    vols0 = np.sort([volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids])
    for seed in range(2):
        mr = pymeshlab.MeshSet()
        add_mesh(mr, V @ random_rotation(seed).T, F, "assembly")
        _, rids = pymeshlab_acd.decompose(mr, with_tree=False, tau=5.0)
        vols = np.sort([volume(mr.mesh(i).vertex_matrix(), mr.mesh(i).face_matrix()) for i in rids])
        assert same_parts(vols, vols0), seed
