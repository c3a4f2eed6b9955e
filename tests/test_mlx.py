"""The example .mlx filter scripts (scripts/mlx) run through pymeshlab's script replay."""
import pathlib

import numpy as np
import pymeshlab
import pytest

from support.meshes import BUNNY, SHARED, is_closed_manifold, present, volume

MLX = pathlib.Path(__file__).resolve().parents[1] / "scripts" / "mlx"
MESHES = [BUNNY] + [SHARED / n for n in ("spot.obj", "fandisk.obj")]


@pytest.mark.parametrize("mesh", MESHES, ids=lambda p: pathlib.Path(p).stem)
def test_decompose_script_then_export_parts(ms, mesh, tmp_path):
    ms.load_new_mesh(present(mesh))
    v0 = volume(ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())
    ms.load_filter_script(str(MLX / "decompose.mlx"))
    ms.apply_filter_script()
    parts = [i for i in range(1, ms.mesh_number()) if ms.mesh(i).label().startswith("acd_")
             and not ms.mesh(i).label().startswith("acd_hull_")]
    hulls = [i for i in range(1, ms.mesh_number()) if ms.mesh(i).label().startswith("acd_hull_")]
    assert 2 <= len(parts) <= 64 and len(hulls) == len(parts)
    assert all(ms.mesh(i).vertex_number() <= 64 for i in hulls)
    total = 0.0
    for i in parts:   # export, as a script user would, and read back
        ms.set_current_mesh(i)
        out = tmp_path / f"{ms.mesh(i).label()}.obj"
        ms.save_current_mesh(str(out))
        back = pymeshlab.MeshSet()
        back.load_new_mesh(str(out))
        F = back.current_mesh().face_matrix()
        assert is_closed_manifold(F)
        total += volume(back.current_mesh().vertex_matrix(), F)
    assert total == pytest.approx(v0, rel=1e-5)   # OBJ text keeps ~7 digits


def test_wrap_and_decompose_script_on_an_open_mesh(ms):
    ms.load_new_mesh(BUNNY)
    V, F = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V, face_matrix=F[:-40]), "open bunny")
    ms.load_filter_script(str(MLX / "wrap_and_decompose.mlx"))
    ms.apply_filter_script()
    parts = [i for i in range(2, ms.mesh_number()) if ms.mesh(i).label().startswith("acd_")]
    assert len(parts) >= 2
    assert all(is_closed_manifold(ms.mesh(i).face_matrix()) for i in parts)
    total = sum(volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in parts)
    assert volume(V, F) <= total <= 1.1 * volume(V, F)
