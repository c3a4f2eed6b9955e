"""Cavities (the paper's hole boundaries in 3D) and genus through pymeshlab.

Every check is independent of the core's report: closedness, shells, volumes and concavity are
measured again here (concavity through the separate notch-concavity filter on each part).
"""
import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from support.meshes import (L_SHAPE, SHARED, add_mesh, box, component_labels, extrude, icosphere, inside,
                      is_closed_manifold, present, torus, volume, with_cavities)
from support.partition import check_partition, remeasured_concavity, within_tau

HANDLING = ["principal_plane", "best_plane", "keep_cavities"]


def one_cavity():
    return with_cavities(box(), [icosphere((0.1, 0.05, 0), 0.5, 2)])


def ellipsoid(centre, axes, angle):
    """An icosphere stretched along `axes` and turned by `angle` about z, then about x."""
    V, F = icosphere((0, 0, 0), 1.0, 2)
    c, s = np.cos(angle), np.sin(angle)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    return (V * np.asarray(axes)) @ R.T + np.asarray(centre), F


def two_cavities():
    # a round cavity and a flat, tilted one (where the principal plane's choice matters)
    return with_cavities(box((-1.5, -1, -1), (1.5, 1, 1)),
                         [icosphere((-0.7, 0, 0), 0.4, 2), ellipsoid((0.7, 0.2, 0.1), (0.5, 0.3, 0.12), 0.6)])


def shells(F):
    """Face-connected components of a face list (faces sharing an edge are joined)."""
    first, pairs = {}, []
    for f, t in enumerate(F.tolist()):
        for k in range(3):
            e = tuple(sorted((t[k], t[(k + 1) % 3])))
            pairs.append((f, first.setdefault(e, f)))
    comp = component_labels(len(F), pairs)
    return [F[comp == c] for c in np.unique(comp)]


CASES = {"one_cavity": one_cavity, "two_cavities": two_cavities}


@pytest.mark.parametrize("order", ["first", "by_concavity"])
@pytest.mark.parametrize("handling", HANDLING)
@pytest.mark.parametrize("case", CASES)
def test_cavities_decompose_into_closed_parts(ms, case, handling, order):
    V, F = CASES[case]()
    n_cav = int(case.split("_")[0] == "two") + 1
    add_mesh(ms, V, F)
    res, ids = pymeshlab_acd.decompose(ms, tau=0.15, tau_unit="model_units", hole_handling=handling,
                                       hole_order=order)
    assert res["cavities"] == n_cav
    kept = handling == "keep_cavities"
    # closed parts, volumes summing to outer minus cavities, no overlap; tau-convex unless kept
    parts = check_partition(ms, 0, ids, tau_abs=None if kept else 0.15, overlap_samples=0 if kept else 20)
    inner = 0
    for Vp, Fp, label in parts:
        sh = shells(Fp)
        assert all(is_closed_manifold(s) for s in sh)
        vols = [volume(Vp, s) for s in sh]
        inner += sum(v < 0 for v in vols)
        assert sum(v > 0 for v in vols) == 1, f"{label} is not one solid"
    if kept:
        # the cavities are reported and still inside the parts, whole
        assert res["kept_cavities"] == n_cav == inner and res["hole_cuts"] == 0 and not res["tau_convex"]
    else:
        assert inner == 0 and res["hole_cuts"] >= 1 and res["kept_cavities"] == 0 and res["tau_convex"]


def test_kept_cavity_stays_whole_while_the_outside_is_cut(ms):
    # an L-shaped solid with a cavity in its long arm: the notch is cut, the cavity is not
    V, F = with_cavities(extrude([(x * 3, y * 3) for x, y in L_SHAPE], 0, 3), [icosphere((4.5, 1.5, 1.5), 0.6, 2)])
    add_mesh(ms, V, F)
    res, ids = pymeshlab_acd.decompose(ms, tau=0.1, tau_unit="model_units", hole_handling="keep_cavities")
    assert res["parts"] >= 2 and res["kept_cavities"] == 1
    parts = check_partition(ms, 0, ids)
    with_cavity = [p for p in parts if len(shells(p[1])) == 2]
    assert len(with_cavity) == 1
    # its outer surface is tau-convex (re-measured without the cavity's shell)
    Vp, Fp, _ = with_cavity[0]
    outer = max(shells(Fp), key=lambda s: volume(Vp, s))
    assert within_tau(Vp, outer, 0.1)
    assert inside(Vp, Fp, [(4.5, 1.5, 1.5 + 0.8)]).all() and not inside(Vp, Fp, [(4.5, 1.5, 1.5)]).any()


@pytest.mark.parametrize("case", CASES)
def test_best_plane_never_leaves_more_concavity_than_the_principal_plane(ms, case):
    # the first cut (max_parts = 2) is the hole cut: compare the concavity it leaves, re-measured
    left = {}
    for handling in ("principal_plane", "best_plane"):
        m = pymeshlab.MeshSet()
        V, F = CASES[case]()
        add_mesh(m, V, F)
        res, ids = pymeshlab_acd.decompose(m, tau=0.15, tau_unit="model_units", hole_handling=handling,
                                           max_parts=2)
        assert res["parts"] == 2 and res["hole_cuts"] == 1
        left[handling] = max(remeasured_concavity(m.mesh(i).vertex_matrix(), m.mesh(i).face_matrix()) for i in ids)
    assert left["best_plane"] <= left["principal_plane"] * (1 + 1e-9)
    print(f"{case}: max concavity after the hole cut: {left}")


def test_cavity_shells_given_outward_are_reoriented(ms):
    # the cavity's shell given with outward faces: nesting (point in solid) says it is a cavity
    (Vo, Fo), (Vc, Fc) = box(), icosphere((0.1, 0.05, 0), 0.5, 2)
    V, F = np.vstack([Vo, Vc]), np.vstack([Fo, Fc + len(Vo)])
    add_mesh(ms, V, F)
    res, ids = pymeshlab_acd.decompose(ms, tau=0.15, tau_unit="model_units")
    assert res["cavities"] == 1
    total = sum(volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids)
    assert total == pytest.approx(volume(Vo, Fo) - volume(Vc, Fc), rel=1e-6)


@pytest.mark.parametrize("handling", HANDLING)
def test_torus_genus_one_with_each_hole_handling(ms, handling):
    V, F = torus(R=2.0, r=0.5)
    add_mesh(ms, V, F)
    res, ids = pymeshlab_acd.decompose(ms, tau=0.2, tau_unit="model_units", hole_handling=handling)
    assert res["parts"] >= 3 and res["cavities"] == 0   # a ring is never 2 convex parts
    check_partition(ms, 0, ids, tau_abs=0.2, overlap_samples=10)


@pytest.mark.parametrize("handling", HANDLING)
def test_rocker_arm_genus_with_each_hole_handling(ms, handling):
    ms.load_new_mesh(present(SHARED / "rocker-arm.obj"))
    res, ids = pymeshlab_acd.decompose(ms, tau=4.0, cut_plane_selection="bisector", hole_handling=handling)
    assert res["parts"] >= 3
    check_partition(ms, 0, ids, tau_abs=res["tau_model_units"], overlap_samples=4)
