"""The search on a decimated copy: a mesh over the proxy threshold (100,000 faces) is searched on a copy,
and every part is still cut from the mesh itself and certified on it.

Re-measured here, sharing no code with the core: the parts are closed and 2-manifold, their volumes sum
to the input's, no part overlaps another, each part's hull is within tau (tests/support/hull_reach.py).
"""
import numpy as np
import pymeshlab

import pymeshlab_acd
from support.meshes import add_mesh, torus
from support.partition import check_partition


def run(V, F, **kw):
    ms = pymeshlab.MeshSet()
    pymeshlab_acd.load()
    add_mesh(ms, V, F, "torus")
    res, ids = pymeshlab_acd.decompose(ms, with_tree=False, **kw)
    return ms, res, ids


def layers(ms, ids):
    return [(ms.mesh(i).vertex_matrix().tobytes(), ms.mesh(i).face_matrix().tobytes()) for i in ids]


def test_a_large_mesh_is_cut_and_certified_on_itself_and_the_same_on_any_thread_count():
    V, F = torus(R=2.0, r=0.5, nu=400, nv=160)
    assert len(F) > 100000
    ms, res, ids = run(V, F, tau=5.0, threads=1)
    assert 0 < res["proxy_faces"] <= 21000
    assert 0 < res["proxy_distance"] < 0.25 * res["tau_model_units"]
    assert res["tau_convex"]
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=200)
    # Below the threshold the mesh itself is searched.
    Vc, Fc = torus(R=2.0, r=0.5, nu=100, nv=40)
    _, coarse, _ = run(Vc, Fc, tau=5.0)
    assert coarse["proxy_faces"] == 0
    ms2, _, ids2 = run(V, F, tau=5.0, threads=2)
    assert layers(ms2, ids2) == layers(ms, ids)
