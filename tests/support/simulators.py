"""Drop tests in MuJoCo and PyBullet for exported models (used by tests/test_export.py and
bench/sim_check.py): add a floor, lift the object so its lowest collision vertex is `height` above it
(optionally drop a ball onto it), simulate, and report where things come to rest."""
import xml.etree.ElementTree as ET

import numpy as np
import pymeshlab


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



def _lowest(hulls, R, t, com):
    return min(float(((h - com) @ R.T + t)[:, 2].min()) for h in hulls)


def drop_mujoco(model_file, scene_file, body, hulls, height, ball=None, seconds=6.0):
    """Add a floor (and optionally a ball), lift the body so its lowest point is `height` above the
    floor, simulate, and report where things rest."""
    import mujoco
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
    import pybullet as p
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
