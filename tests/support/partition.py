"""A decomposition checked as a partition, by code that shares nothing with the core: every part closed
and 2-manifold, volumes adding up to the input's, no two parts overlapping, each part's hull distance within tau,
and its concavity too unless it was merged by its hull."""
import numpy as np
import pymeshlab

from .meshes import add_mesh, hull_within, inside, interior_samples, is_closed_manifold, volume


def parts_of(ms, ids):
    return [(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix(), ms.mesh(i).label()) for i in ids]


def check_partition(ms, src_id, ids, tau_abs=None, overlap_samples=0, seed=0, hull_check=True,
                    merge_measure="hull_distance"):
    src = ms.mesh(src_id)
    v0 = volume(src.vertex_matrix(), src.face_matrix())
    parts = parts_of(ms, ids)
    total = 0.0
    for V, F, label in parts:
        assert label.startswith("acd_")
        assert is_closed_manifold(F), f"{label} is not closed and 2-manifold"
        vol = volume(V, F)
        assert vol > 0
        total += vol
        if tau_abs is not None:
            certified(V, F, tau_abs, label, hull_check, merge_measure)
    assert abs(total - v0) / v0 < 1e-6
    if overlap_samples:
        rng = np.random.default_rng(seed)
        for i, (V, F, label) in enumerate(parts):
            pts = interior_samples(V, F, overlap_samples, rng)
            for j, (V2, F2, label2) in enumerate(parts):
                if i != j and len(pts):
                    # points well inside part i (not on a shared cap) must not be inside part j
                    assert not inside(V2, F2, pts).any(), f"{label} overlaps {label2}"
    return parts


def remeasured(V, F):
    m = pymeshlab.MeshSet()
    add_mesh(m, V, F)
    return m.compute_scalar_by_notch_concavity()


def remeasured_concavity(V, F):
    return remeasured(V, F)["max_concavity"]


def certified(V, F, tau_abs, label, hull_check=True, merge_measure="hull_distance"):
    """A part within tau as the result promises it: under merge_measure hull_distance (the default) by
    its hull alone, as a part whose hull stays within tau is neither cut nor kept from merging, its
    notches may lie deeper; under concavity by its notches too."""
    by_hull = merge_measure == "hull_distance"
    if not by_hull:
        assert within_tau(V, F, tau_abs), f"{label} exceeds tau"
    if hull_check or by_hull:
        hull_within(V, F, tau_abs, label)


def within_tau(V, F, tau_abs):
    """The part measured alone is within tau: its notches' concavity at most tau, and where the measure
    charges the hull's reach as the concavity (a reach beyond the notches), that reach within the
    certificate's 1% of tau more, as hull_within allows it."""
    r = remeasured(V, F)
    c = r["max_concavity"]
    if c <= tau_abs * (1 + 1e-9):
        return True
    return c == r["hull_distance"] and c <= 1.01 * tau_abs * (1 + 1e-9)
