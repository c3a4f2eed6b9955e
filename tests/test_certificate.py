"""The certificate on CAD-shaped solids: every part's convex hull lies within tau of the part.

Low-poly machine parts (bores, slots, keyways, flanges, steps) are where a concavity measured only at
vertices can miss how far a hull stands off its part. Each solid is made exactly with manifold3d and
decomposed with every cut_plane_selection at three taus; each part's hull distance is measured again
with scipy and libigl (tests/support/hull_reach.py), sharing no code with the core, with a slack of 1% of tau.
"""
import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from support.meshes import add_mesh, hull_within, is_closed_manifold, volume
from support.hull_reach import hull_reach

cad_solids = pytest.importorskip("support.cad_solids")
pytest.importorskip("manifold3d")
pytest.importorskip("scipy")

SELECTIONS = ["best", "bisector", "min_section", "bisector_or_face"]


def decompose_solid(name, tau, selection):
    V, F = cad_solids.make(name)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F, name)
    res, ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=tau, cut_plane_selection=selection)
    return V, F, res, [(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix(), ms.mesh(i).label()) for i in ids]


@pytest.mark.parametrize("selection", SELECTIONS)
@pytest.mark.parametrize("tau", [1.0, 2.0, 5.0])
@pytest.mark.parametrize("name", sorted(cad_solids.SOLIDS))
def test_every_hull_within_tau(name, tau, selection):
    V, F, res, parts = decompose_solid(name, tau, selection)
    tau_abs = res["tau_model_units"]
    assert res["tau_convex"] and res["uncut_parts"] == 0
    total, worst = 0.0, 0.0
    for Vp, Fp, label in parts:
        assert is_closed_manifold(Fp), label
        total += volume(Vp, Fp)
        worst = max(worst, hull_within(Vp, Fp, tau_abs, f"{name} {label}"))
    assert total == pytest.approx(volume(V, F), rel=1e-6)
    # The filter's own report is a distance some hull point attains, so within tau as well.
    assert res["max_hull_distance"] <= 1.01 * tau_abs
    print(f"{name} tau {tau}% {selection}: {len(parts)} parts, worst hull {worst / tau_abs:.2f} tau")


def test_keyway_reproducer():
    """The keyway closed at both ends at tau 2% (0.738 units) with the default cut selection: no part
    is reported convex while its hull stands a keyway's width off it."""
    V, F, res, parts = decompose_solid("keyway", 2.0, "best")
    assert res["tau_model_units"] == pytest.approx(0.7376, abs=1e-3)
    for Vp, Fp, label in parts:
        hull_within(Vp, Fp, res["tau_model_units"], label)


@pytest.mark.parametrize("name", ["plate", "flange", "through_slot"])
def test_through_holes_are_cut(name):
    """A through-hole is a handle whose walls touch the hull only at its rims: one part would cover
    the hole with its hull. The holes must be cut, and the concavity filter must see them."""
    V, F = cad_solids.make(name)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F, name)
    measured = ms.compute_scalar_by_notch_concavity()
    lower, upper = hull_reach(V, F, slack=1e-3 * np.ptp(V, 0).max())
    assert measured["max_concavity"] >= 0.98 * lower
    _, _, res, parts = decompose_solid(name, 2.0, "best")
    assert len(parts) > 1
