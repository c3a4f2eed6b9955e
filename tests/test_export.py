"""Physics-ready export: URDF loaded by PyBullet, MJCF by MuJoCo, a drop onto a plane in each,
a MeshLab project with one layer per part, and mass properties checked against trimesh.

The trough test shows the simulators really collide with the parts: a ball dropped into a U-shaped
trough lands inside the channel with the decomposition, and on top of the rim with one convex hull
(the control, so the test can fail)."""
import json
import subprocess
import sys

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from pymeshlab_acd.export import export_decomposition, mass_properties
from support.meshes import BUNNY, U_SHAPE, add_mesh, extrude, is_closed_manifold, volume
from support.simulators import drop_mujoco, drop_pybullet, hull_vertices

mujoco = pytest.importorskip("mujoco")
pybullet = pytest.importorskip("pybullet")


# ---- mass properties, against trimesh ---------------------------------------------------------
def test_mass_properties_match_trimesh():
    trimesh = pytest.importorskip("trimesh")
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(BUNNY)
    V, F = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    V = V @ np.array([[0.8, 0.6, 0], [-0.6, 0.8, 0], [0, 0, 1]]) + [3, -2, 5]   # off the origin, turned
    vol, com, inertia = mass_properties(V, F)
    t = trimesh.Trimesh(V, F, process=False)
    assert vol == pytest.approx(t.volume, rel=1e-9)
    assert np.allclose(com, t.center_mass, atol=1e-9)
    assert np.allclose(inertia, t.moment_inertia, rtol=1e-7, atol=1e-12 * np.abs(t.moment_inertia).max())


def test_mass_properties_of_a_box_are_analytic():
    from support.meshes import box
    V, F = box((0, 0, 0), (1, 2, 3))
    vol, com, inertia = mass_properties(V, F)
    assert vol == pytest.approx(6)
    assert np.allclose(com, [0.5, 1, 1.5])
    assert np.allclose(inertia, np.diag([6 * (4 + 9) / 12, 6 * (1 + 9) / 12, 6 * (1 + 4) / 12]))


def test_mass_properties_refuse_an_inside_out_mesh():
    from support.meshes import box
    V, F = box()
    with pytest.raises(ValueError):
        mass_properties(V, F[:, ::-1])


# ---- the bunny through the command line ---------------------------------------------------------
@pytest.fixture(scope="module")
def bunny_export(tmp_path_factory):
    out = tmp_path_factory.mktemp("bunny")
    p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "decompose", BUNNY, "--tau", "5",
                        "--cut-plane-selection", "bisector", "--out", str(out), "--export",
                        "--max-hull-vertices", "48", "--no-progress"], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    return out / "export", json.loads((out / "summary.json").read_text())


def test_export_files(bunny_export):
    d, summary = bunny_export
    parts = summary["parts"]
    files, hulls = hull_vertices(d, d / "bunny.urdf")
    assert len(files) == parts
    assert all(len(h) <= 48 for h in hulls)
    assert len(list((d / "collision").glob("*.stl"))) == parts
    files_mj, _ = hull_vertices(d, d / "bunny.xml")
    assert sorted(files_mj) == sorted(files)


def test_mujoco_loads_and_drops_the_bunny(bunny_export):
    d, summary = bunny_export
    model = mujoco.MjModel.from_xml_path(str(d / "bunny.xml"))
    assert model.nmesh == summary["parts"] + 1          # the hulls and the visual mesh
    assert model.nbody == 2 and model.njnt == 1          # world and the bunny, on a free joint
    # The mass is the solid's: density x the bunny's volume (independently measured).
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(BUNNY)
    vol = volume(ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix())
    assert model.body_mass[1] == pytest.approx(1000 * vol, rel=1e-3)
    _, hulls = hull_vertices(d, d / "bunny.xml")
    z = drop_mujoco(d / "bunny.xml", d / "scene.xml", "bunny", hulls, height=0.3)
    print(f"MuJoCo: bunny rests with its lowest hull vertex at z = {z['lowest']:.5f} (size {z['size']:.3f})")
    assert z["moved"] > 0.1                              # it fell
    assert abs(z["lowest"]) < 0.01 * z["size"]           # onto the plane, neither through nor above it
    assert z["speed"] < 1e-2                             # and came to rest
    assert z["contacts_on_hulls"] > 0


def test_pybullet_loads_and_drops_the_bunny(bunny_export):
    d, summary = bunny_export
    _, hulls = hull_vertices(d, d / "bunny.urdf")
    z = drop_pybullet(d / "bunny.urdf", hulls, height=0.3)
    print(f"PyBullet: bunny rests with its lowest hull vertex at z = {z['lowest']:.5f} (size {z['size']:.3f})")
    assert z["shapes"] == summary["parts"]
    assert z["moved"] > 0.1
    assert abs(z["lowest"]) < 0.01 * z["size"]
    assert z["speed"] < 1e-2


def test_mujoco_loads_an_open_mesh_as_the_visual(tmp_path):
    """An open input (wrapped to decompose it) stays the visual mesh; MuJoCo cannot weigh an open
    mesh, and need not: the body's inertia is explicit."""
    from support.meshes import icosphere
    pymeshlab_acd.load()
    V, F = icosphere(level=4)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F[1:], "open_sphere")            # one face missing
    src = ms.current_mesh_id()
    res, ids = pymeshlab_acd.decompose(ms, tau=5, preprocessing="alpha_wrap", wrap_alpha=10, output_hulls=True)
    hulls = [i for i in ids if ms.mesh(i).label().startswith("acd_hull_")]
    export_decomposition(ms, src, [i for i in ids if i not in hulls], hulls, tmp_path, name="open_sphere")
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "open_sphere.xml"))
    assert model.nmesh == len(hulls) + 1
    assert model.body_mass[1] == pytest.approx(1000 * 4 / 3 * np.pi, rel=0.05)   # the wrapped unit ball
    _, hv = hull_vertices(tmp_path, tmp_path / "open_sphere.xml")
    z = drop_mujoco(tmp_path / "open_sphere.xml", tmp_path / "scene.xml", "open_sphere", hv, height=0.5)
    assert abs(z["lowest"]) < 0.01 * z["size"] and z["moved"] > 0.4


# ---- a ball into a trough: the parts, not one hull, collide --------------------------------------
@pytest.fixture(scope="module")
def trough(tmp_path_factory):
    """U profile (channel 1 wide, 1 deep, 3 wide outside) extruded 2 along y, opening upwards;
    exported twice: decomposed, and as the single convex hull of the whole (the control)."""
    pymeshlab_acd.load()
    V, F = extrude(U_SHAPE, 0.0, 2.0)
    V = V[:, [0, 2, 1]]               # profile's y becomes height; the swap mirrors, so turn the faces
    F = F[:, ::-1]
    assert is_closed_manifold(F) and volume(V, F) > 0
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F, "trough")
    src = ms.current_mesh_id()
    res, ids = pymeshlab_acd.decompose(ms, tau=2, output_hulls=True)
    hulls = [i for i in ids if ms.mesh(i).label().startswith("acd_hull_")]
    parts = [i for i in ids if i not in hulls]
    base = tmp_path_factory.mktemp("trough")
    export_decomposition(ms, src, parts, hulls, base / "parts", name="trough")
    ms.set_current_mesh(src)
    ms.generate_convex_hull()
    export_decomposition(ms, src, [src], [ms.current_mesh_id()], base / "hull", name="trough")
    return base, res["parts"]


def ball_rest_height(sim, folder):
    model = folder / ("trough.xml" if sim == "mujoco" else "trough.urdf")
    _, hulls = hull_vertices(folder, model)
    if sim == "mujoco":
        r = drop_mujoco(model, folder / "scene.xml", "trough", hulls, height=0.0, ball=(1.5, 1.0, 3.0, 0.3))
    else:
        r = drop_pybullet(model, hulls, height=0.0, ball=(1.5, 1.0, 3.0, 0.3))
    return r["ball_z"]


@pytest.mark.parametrize("sim", ["mujoco", "pybullet"])
def test_a_ball_falls_into_the_decomposed_trough(trough, sim):
    base, parts = trough
    assert parts >= 2
    inside = ball_rest_height(sim, base / "parts")
    control = ball_rest_height(sim, base / "hull")
    print(f"{sim}: ball rests at z = {inside:.3f} in the decomposed trough ({parts} parts), "
          f"{control:.3f} on its single hull (rim at z = 2, channel floor at z = 1)")
    assert inside == pytest.approx(1.3, abs=0.05)       # on the channel floor (radius 0.3)
    assert control == pytest.approx(2.3, abs=0.05)      # on the hull's top: the test can fail


# ---- MeshLab project ---------------------------------------------------------------------------
def test_meshlab_project_has_one_layer_per_part(bunny_export):
    d, summary = bunny_export
    ms = pymeshlab.MeshSet()
    ms.load_project(str(d / "bunny.mlp"))
    assert ms.mesh_number() == summary["parts"]
    total = 0.0
    for i in pymeshlab_acd.mesh_ids(ms):
        m = ms.mesh(i)
        assert m.label().startswith("acd_") and m.has_vertex_color()
        assert is_closed_manifold(m.face_matrix())
        total += volume(m.vertex_matrix(), m.face_matrix())
    ref = pymeshlab.MeshSet()
    ref.load_new_mesh(BUNNY)
    assert total == pytest.approx(volume(ref.current_mesh().vertex_matrix(), ref.current_mesh().face_matrix()),
                                  rel=1e-6)
