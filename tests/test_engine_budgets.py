"""Hulls cut down to an engine's limits still contain their parts: counts, containment and reach re-measured
with Qhull and trimesh, on the bunny."""
import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from support.budgets import counts, outside, reach, within
from support.meshes import BUNNY


@pytest.mark.parametrize("engine", ["physx", "physx_gpu", "unity"])
def test_hulls_meet_the_engine_and_contain_their_parts(engine):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(BUNNY)
    V0 = ms.current_mesh().vertex_matrix()
    size = float(np.linalg.norm(V0.max(0) - V0.min(0)))
    hulls, parts, res = pymeshlab_acd.convex_decomposition(ms.current_mesh().vertex_matrix(),
                                                           ms.current_mesh().face_matrix(), tau=4.0,
                                                           engine=engine, return_parts=True)
    report = res["collision"]["hulls"]
    assert res["collision"]["engine"] == engine and len(hulls) == len(parts) == len(report) == res["parts"]
    assert res["hulls_reduced"] >= 1 and res["hulls_over_budget"] == 0
    far = 0.0
    for (Vh, Fh), (Vp, _), r in zip(hulls, parts, report):
        assert within(Vh, Fh, engine), (engine, counts(Vh, Fh))
        assert outside(Vp, Vh) <= 1e-9 * size            # every part vertex inside or on its hull
        measured = reach(Vh, Vp)
        assert measured == pytest.approx(r["reach"], abs=1e-6 * size)
        far = max(far, measured)
    assert far == pytest.approx(res["hull_reach"], abs=1e-6 * size) and far > 0
    # The bound the hulls hold is stated as the exact hulls' distance plus that reach.
    assert res["collision_hull_distance"] == pytest.approx(res["max_hull_distance"] + far, abs=1e-6 * size)
    assert far < 0.6 * res["tau_model_units"]


def test_a_vertex_cap_holds_without_an_engine():
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(BUNNY)
    hulls, parts, res = pymeshlab_acd.convex_decomposition(ms.current_mesh().vertex_matrix(),
                                                           ms.current_mesh().face_matrix(), tau=6.0,
                                                           max_hull_vertices=20, return_parts=True)
    for (Vh, Fh), (Vp, _) in zip(hulls, parts):
        assert counts(Vh, Fh)[0] <= 20
        assert outside(Vp, Vh) <= 1e-9
