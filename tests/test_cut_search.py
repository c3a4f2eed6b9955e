"""cut_search: the thorough search grows the cut tree under two pick rules and keeps the one with fewer parts.

A thin shell of revolution (a cup) is where the worse-part rule fails: each cut through the wall's deepest
notch leaves both parts about as concave, so the wall falls in many slivers. The parts-needed rule keeps a
plane that leaves one part within tau. The partition is re-measured with code that shares nothing with
the core (hull distances by scipy and libigl, volumes, closedness).
"""
import pymeshlab
import pytest

import pymeshlab_acd
from support.meshes import add_mesh
from support.partition import check_partition

cad_solids = pytest.importorskip("support.cad_solids")
pytest.importorskip("manifold3d")


def decompose(name, **params):
    ms = pymeshlab.MeshSet()
    add_mesh(ms, *cad_solids.make(name), name)
    res, ids = pymeshlab_acd.decompose(ms, with_tree=False, **params)
    return ms, res, ids


def test_thorough_search_gives_the_cup_fewer_parts_all_within_tau():
    # Merged by concavity, as the cut trees' leaves are certified: the parts-needed tree is kept, with at
    # most two thirds of the greedy search's parts.
    _, fast, fast_ids = decompose("cup", cut_search="fast", merge_measure="concavity")
    ms, res, ids = decompose("cup", cut_search="thorough", merge_measure="concavity")
    assert res["tau_convex"] and fast["tau_convex"]
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10, merge_measure="concavity")
    assert res["cuts_by_parts_needed"]
    assert len(ids) <= 2 * len(fast_ids) / 3, (len(ids), len(fast_ids))
    # Merged by the hulls' distance (the default), the greedy tree's slivers merge too; still no more parts.
    _, _, fast_ids = decompose("cup", cut_search="fast")
    ms, res, ids = decompose("cup", cut_search="thorough")
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=10)
    assert len(ids) <= len(fast_ids), (len(ids), len(fast_ids))


@pytest.mark.parametrize("name", ["belt_pulley", "t_slot_rail"])
def test_thorough_search_never_gives_more_parts(name):
    """On CAD steps the worse-part rule cuts along the faces into exact pieces; the other rule would
    leave more parts, so the first tree is the one kept."""
    _, fast, fast_ids = decompose(name, cut_search="fast")
    ms, res, ids = decompose(name, cut_search="thorough")
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"])
    assert len(ids) <= len(fast_ids)
    assert not res["cuts_by_parts_needed"]


def test_thorough_search_is_the_same_on_any_thread_count():
    outs = []
    for threads in (1, 2):
        ms, res, ids = decompose("cup", cut_search="thorough", threads=threads)
        outs.append([ms.mesh(i).vertex_matrix().tobytes() + ms.mesh(i).face_matrix().tobytes() for i in ids])
    assert outs[0] == outs[1]
