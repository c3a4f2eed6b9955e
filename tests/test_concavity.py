"""compute_scalar_by_notch_concavity through pymeshlab."""
import math
import os

import numpy as np
import pymeshlab
import pytest

from support.meshes import BUNNY, L_SHAPE, U_SHAPE, add_mesh, extrude


def test_convex_meshes_have_no_notch(ms):
    ms.create_cube()
    r = ms.compute_scalar_by_notch_concavity()
    assert r["notches"] == 0 and r["max_concavity"] == 0 and not r["has_notch"]
    ms.create_sphere(subdiv=4)
    r = ms.compute_scalar_by_notch_concavity()
    assert r["notches"] == 0 and r["max_concavity"] == 0


@pytest.mark.parametrize("shape,height,expected,corners", [
    (L_SHAPE, 0.5, 1 / math.sqrt(2), [(1, 1)]),     # reflex corner (1,1) to the bridge x + y = 3
    (U_SHAPE, 1.0, 1.0, [(1, 1), (2, 1)]),          # notches (1,1), (2,1) to the bridge y = 2 (a tie)
])
def test_box_concavity_is_the_analytic_distance(ms, shape, height, expected, corners):
    V, F = extrude(shape, 0, height)
    add_mesh(ms, V, F)
    r = ms.compute_scalar_by_notch_concavity()
    assert r["max_concavity"] == pytest.approx(expected, rel=1e-6)
    # the reported notch lies on a reflex corner's vertical edge
    x, y, z = r["max_concavity_position"]
    assert any((x, y) == pytest.approx(c) for c in corners) and 0 <= z <= height
    # per-vertex quality holds the measure, and colours are set
    q = ms.current_mesh().vertex_scalar_array()
    assert q.max() == pytest.approx(expected, rel=1e-6)


def test_concavity_scales_with_the_mesh(ms):
    V, F = extrude(L_SHAPE, 0, 0.5)
    add_mesh(ms, V * 1000.0 + 5e4, F)
    r = ms.compute_scalar_by_notch_concavity()
    assert r["max_concavity"] == pytest.approx(1000 / math.sqrt(2), rel=1e-6)


def test_bunny_concavity_is_finite_positive_and_below_diagonal(ms):
    ms.load_new_mesh(BUNNY)
    r = ms.compute_scalar_by_notch_concavity()
    diag = ms.current_mesh().bounding_box().diagonal()
    assert r["notches"] > 1000 and r["bridges"] > 0 and r["pockets"] > 0
    assert 0 < r["max_concavity"] < diag and math.isfinite(r["max_concavity"])
    # independent bound: the measure is a distance from a vertex to a hull facet, so it cannot
    # exceed the largest distance of any vertex to any of the hull's facet planes
    ms.generate_convex_hull()
    hull = ms.current_mesh()
    HV, HF = hull.vertex_matrix(), hull.face_matrix()
    n = np.cross(HV[HF[:, 1]] - HV[HF[:, 0]], HV[HF[:, 2]] - HV[HF[:, 0]])
    n /= np.linalg.norm(n, axis=1)[:, None]
    off = np.einsum("ij,ij->i", n, HV[HF[:, 0]])
    ms.set_current_mesh(0)
    P = ms.current_mesh().vertex_matrix()
    depth = (off[None, :] - P @ n.T).max(axis=1)   # distance to the farthest facet plane
    assert r["max_concavity"] <= depth.max() + 1e-9
    pos = np.array(r["max_concavity_position"])
    assert np.min(np.linalg.norm(P - pos, axis=1)) < 1e-9   # the notch is a mesh vertex


def test_open_mesh_is_refused_with_a_reason(ms):
    V, F = extrude(L_SHAPE, 0, 1)
    add_mesh(ms, V, F[:-1])
    with pytest.raises(pymeshlab.PyMeshLabException, match="boundary edges"):
        ms.compute_scalar_by_notch_concavity()


def test_point_cloud_is_refused(ms):
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.random.default_rng(0).random((100, 3))))
    with pytest.raises(pymeshlab.PyMeshLabException):
        ms.compute_scalar_by_notch_concavity()


def test_filter_script_replays_with_the_same_result(ms, tmp_path):
    V, F = extrude(U_SHAPE, 0, 1)
    add_mesh(ms, V, F)
    ms.compute_scalar_by_notch_concavity()
    q1 = ms.current_mesh().vertex_scalar_array().copy()
    script = tmp_path / "concavity.mlx"
    ms.save_filter_script(str(script))
    assert "Notch Concavity" in script.read_text()
    ms2 = pymeshlab.MeshSet()
    add_mesh(ms2, V, F)
    ms2.load_filter_script(str(script))
    ms2.apply_filter_script()
    assert np.array_equal(ms2.current_mesh().vertex_scalar_array(), q1)
