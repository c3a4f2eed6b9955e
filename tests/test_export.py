"""Physics-ready export (issue 11): URDF loaded by PyBullet, MJCF by MuJoCo, a drop onto a plane in each,
a MeshLab project with one layer per part, and mass properties checked against trimesh.

The trough test shows the simulators really collide with the parts: a ball dropped into a U-shaped
trough lands inside the channel with the decomposition, and on top of the rim with one convex hull
(the control, so the test can fail)."""
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pymeshlab
import pytest

import pymeshlab_acd
from pymeshlab_acd.export import export_decomposition, mass_properties
from conftest import BUNNY, U_SHAPE, add_mesh, extrude, is_closed_manifold, volume

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
    from conftest import box
    V, F = box((0, 0, 0), (1, 2, 3))
    vol, com, inertia = mass_properties(V, F)
    assert vol == pytest.approx(6)
    assert np.allclose(com, [0.5, 1, 1.5])
    assert np.allclose(inertia, np.diag([6 * (4 + 9) / 12, 6 * (1 + 9) / 12, 6 * (1 + 4) / 12]))


def test_mass_properties_refuse_an_inside_out_mesh():
    from conftest import box
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


def hull_vertices(export_dir, link_xml):
    """World-independent collision vertices, read back from the OBJ files the model file names."""
    root = ET.parse(link_xml).getroot()
    files = [m.get("filename") or m.get("file") for m in root.iter("mesh")]
    files = [f for f in files if f.startswith("collision/")]
    out = []
    for f in files:
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(export_dir / f))
        out.append(ms.current_mesh().vertex_matrix())
    return files, out


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


# ---- simulators ----------------------------------------------------------------------------------
def _lowest(hulls, R, t, com):
    return min(float(((h - com) @ R.T + t)[:, 2].min()) for h in hulls)


def drop_mujoco(model_file, scene_file, body, hulls, height, ball=None, seconds=6.0):
    """Add a floor (and optionally a ball), lift the body so its lowest point is `height` above the
    floor, simulate, and report where things rest."""
    root = ET.parse(model_file).getroot()
    world = root.find("worldbody")
    ET.SubElement(world, "geom", name="floor", type="plane", size="20 20 0.1")
    b = world.find(f"body[@name='{body}']")
    lo = min(float(h[:, 2].min()) for h in hulls)
    b.set("pos", f"0 0 {height - lo}")
    if ball:
        bb = ET.SubElement(world, "body", name="ball", pos=" ".join(map(str, ball[:3])))
        ET.SubElement(bb, "freejoint")
        ET.SubElement(bb, "geom", type="sphere", size=str(ball[3]), density="500")
    scene_file.write_text(ET.tostring(root, encoding="unicode"))
    m = mujoco.MjModel.from_xml_path(str(scene_file))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    start = d.xpos[m.body(body).id].copy()
    for _ in range(int(seconds / m.opt.timestep)):
        mujoco.mj_step(m, d)
    bid = m.body(body).id
    R = d.xmat[bid].reshape(3, 3)
    # xpos is the body frame (the mesh's own coordinates), so the hull vertices map without the centre.
    lowest = _lowest(hulls, R, d.xpos[bid], np.zeros(3))
    geoms = {m.geom(g).name for g in range(m.ngeom)}
    on_hulls = sum(1 for c in d.contact[:d.ncon]
                   if {m.geom(c.geom1).name, m.geom(c.geom2).name} & {g for g in geoms if "_hull_" in g})
    size = float(np.linalg.norm(np.ptp(np.concatenate(hulls), 0)))
    out = dict(lowest=lowest, moved=float(start[2] - d.xpos[bid][2]) if height else 0.0,
               speed=float(np.abs(d.qvel[:6]).max()), size=size, contacts_on_hulls=on_hulls)
    if ball:
        out["ball_z"] = float(d.xpos[m.body("ball").id][2])
    return out


def drop_pybullet(urdf, hulls, height, ball=None, seconds=6.0):
    p = pybullet
    cid = p.connect(p.DIRECT)
    try:
        p.setGravity(0, 0, -9.81, physicsClientId=cid)
        p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE, physicsClientId=cid), physicsClientId=cid)
        lo = min(float(h[:, 2].min()) for h in hulls)
        body = p.loadURDF(str(urdf), basePosition=[0, 0, height - lo],   # the link frame, lifted
                          flags=p.URDF_USE_INERTIA_FROM_FILE, physicsClientId=cid)
        shapes = len(p.getCollisionShapeData(body, -1, physicsClientId=cid))
        start = p.getBasePositionAndOrientation(body, physicsClientId=cid)[0][2]
        if ball:
            s = p.createMultiBody(0.3, p.createCollisionShape(p.GEOM_SPHERE, radius=ball[3], physicsClientId=cid),
                                  basePosition=ball[:3], physicsClientId=cid)
        for _ in range(int(seconds * 240)):
            p.stepSimulation(physicsClientId=cid)
        pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
        # The base pose is the inertial frame's, which PyBullet turns to the principal axes: back to the link's.
        local = p.getDynamicsInfo(body, -1, physicsClientId=cid)[3:5]
        lpos, lorn = p.multiplyTransforms(pos, orn, *p.invertTransform(*local))
        R = np.array(p.getMatrixFromQuaternion(lorn)).reshape(3, 3)
        lin, ang = p.getBaseVelocity(body, physicsClientId=cid)
        out = dict(lowest=_lowest(hulls, R, np.array(lpos), np.zeros(3)), moved=start - pos[2], shapes=shapes,
                   speed=float(max(np.abs(lin).max(), np.abs(ang).max())),
                   size=float(np.linalg.norm(np.ptp(np.concatenate(hulls), 0))))
        if ball:
            out["ball_z"] = p.getBasePositionAndOrientation(s, physicsClientId=cid)[0][2]
        return out
    finally:
        p.disconnect(cid)
