"""Whole robots in PyBullet and MuJoCo (used by tests/test_robot_descriptions.py and
bench/bench_robot_descriptions.py): load a rewritten description, lift it just above a floor, let it fall
(PyBullet: joints held by its default motors; MuJoCo: limp, damped joints), and report where it comes to rest. Self-collision stays off in both, as
PyBullet's loadURDF has it by default: the question is the hulls against the floor."""
import xml.etree.ElementTree as ET

import numpy as np


def pybullet_load(urdf, search=None):
    """Load the URDF in PyBullet (DIRECT) and count its collision shapes; raises if it does not load.
    `search`: where package:// URIs' packages live (PyBullet's additional search path)."""
    import pybullet as p
    cid = p.connect(p.DIRECT)
    try:
        if search:
            p.setAdditionalSearchPath(str(search), physicsClientId=cid)
        body = p.loadURDF(str(urdf), physicsClientId=cid)
        return sum(len(p.getCollisionShapeData(body, k, physicsClientId=cid))
                   for k in range(-1, p.getNumJoints(body, physicsClientId=cid)))
    finally:
        p.disconnect(cid)


def _pb_box(p, body, cid):
    boxes = [p.getAABB(body, k, physicsClientId=cid) for k in range(-1, p.getNumJoints(body, physicsClientId=cid))]
    lo = np.min([b[0] for b in boxes], 0)
    hi = np.max([b[1] for b in boxes], 0)
    return lo, hi


def pybullet_drop(urdf, search=None, seconds=4.0, gap=0.02):
    """Drop the robot (free base, as loadURDF leaves it) onto a plane. Returns the lowest point of its
    links' bounding boxes at rest (margins included), the deepest contact, its size, the fastest link
    speed at the end and whether the base is free (a base of zero mass is fixed in PyBullet). None when
    PyBullet cannot report the body's state."""
    import pybullet as p
    cid = p.connect(p.DIRECT)
    try:
        if search:
            p.setAdditionalSearchPath(str(search), physicsClientId=cid)
        p.setGravity(0, 0, -9.81, physicsClientId=cid)
        p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE, physicsClientId=cid), physicsClientId=cid)
        body = p.loadURDF(str(urdf), basePosition=[0, 0, 10], physicsClientId=cid)
        try:
            p.getBasePositionAndOrientation(body, physicsClientId=cid)
        except p.error:   # PyBullet reports no state for a body of over 127 links (tiago_dual's 129)
            return None
        lo, hi = _pb_box(p, body, cid)
        size = float(np.linalg.norm(hi - lo))
        pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
        p.resetBasePositionAndOrientation(body, [pos[0], pos[1], pos[2] - lo[2] + gap * size], orn, physicsClientId=cid)
        n = p.getNumJoints(body, physicsClientId=cid)   # joints held by PyBullet's default velocity motors
        for _ in range(int(seconds * 240)):
            p.stepSimulation(physicsClientId=cid)
        lo, _ = _pb_box(p, body, cid)
        # Link boxes carry Bullet's collision margin: how deep the hulls are in the floor is read from the
        # contacts (negative distances); the boxes tell a fall through the floor.
        contacts = p.getContactPoints(bodyA=body, physicsClientId=cid)
        depth = max([0.0] + [-c[8] for c in contacts])
        speeds = [np.linalg.norm(p.getBaseVelocity(body, physicsClientId=cid)[0])]
        speeds += [np.linalg.norm(p.getLinkState(body, k, computeLinkVelocity=1, physicsClientId=cid)[6])
                   for k in range(n)]
        free = p.getDynamicsInfo(body, -1, physicsClientId=cid)[0] > 0
        return dict(lowest=float(lo[2]), depth=float(depth), contacts=len(contacts), size=size,
                    speed=float(np.nanmax(speeds)), free=free, finite=bool(np.all(np.isfinite(lo))))
    finally:
        p.disconnect(cid)


def settled(r):
    """On the floor: not through it (the lowest point, or PyBullet's deepest contact, within 3% of the size
    below it) and not thrown about (no point faster than the size per second after the fall: a limp
    robot may still roll a little on round links, an explosion is far faster)."""
    if r is None:
        return False
    deep = r["depth"] if "depth" in r else -r["lowest"]
    return r["finite"] and deep <= 0.03 * r["size"] and r["lowest"] > -0.2 * r["size"] and r["speed"] < r["size"]


def mujoco_compile(xml):
    import mujoco
    m = mujoco.MjModel.from_xml_path(str(xml))
    return dict(geoms=m.ngeom, meshes=m.nmesh, bodies=m.nbody)


def _lowest_mujoco(m, d, geoms):
    import mujoco
    low = np.inf
    for g in geoms:
        if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH:
            k = m.geom_dataid[g]
            V = m.mesh_vert[m.mesh_vertadr[k]:m.mesh_vertadr[k] + m.mesh_vertnum[k]]
            low = min(low, float((V @ d.geom_xmat[g].reshape(3, 3).T + d.geom_xpos[g])[:, 2].min()))
        else:   # its bounding box in the geom frame, turned into the world (exact for boxes and spheres)
            R = d.geom_xmat[g].reshape(3, 3)
            c, h = m.geom_aabb[g][:3], m.geom_aabb[g][3:]
            low = min(low, float(d.geom_xpos[g][2] + R[2] @ c - np.abs(R[2]) @ h))
    return low


def mujoco_drop(xml, scene, seconds=4.0, gap=0.02):
    """The MJCF with a free joint on its root body and a floor added (robot geoms collide with the floor
    only), dropped: the lowest collision point at rest, the size, the largest joint speed at the end.
    None when the robot has no body of its own under the world (nothing to free)."""
    import mujoco
    spec = mujoco.MjSpec.from_file(str(xml))
    root = spec.worldbody.first_body()
    if root is None:
        return None
    if len(root.joints) == 0:
        root.add_freejoint()
    elif not any(j.type == mujoco.mjtJoint.mjJNT_FREE for j in root.joints):
        return None   # the root moves on a joint of its own: not a floating base
    for j in spec.joints:
        if j.type != mujoco.mjtJoint.mjJNT_FREE:
            j.damping = np.maximum(np.asarray(j.damping, float), 0.05)
    for g in spec.geoms:
        if g.contype or g.conaffinity:
            g.contype, g.conaffinity = 1, 0
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.memory = 1 << 29   # thousands of hulls on the floor at once need more than the default arena
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[50, 50, 0.1], contype=0,
                            conaffinity=1)
    m = spec.compile()
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    colliding = [g for g in range(m.ngeom) if m.geom_contype[g] and m.geom(g).name != "floor"]
    low = _lowest_mujoco(m, d, colliding)
    pts = np.array([d.geom_xpos[g] for g in colliding])
    size = float(np.linalg.norm(np.ptp(pts, 0))) + 2 * float(max(m.geom_rbound[g] for g in colliding))
    d.qpos[2] += gap * size - low
    mujoco.mj_forward(m, d)
    for _ in range(int(seconds / m.opt.timestep)):
        mujoco.mj_step(m, d)
    scene.write_text(spec.to_xml())
    return dict(lowest=_lowest_mujoco(m, d, colliding), size=size, speed=float(np.abs(d.qvel[:3]).max()),
                finite=bool(np.all(np.isfinite(d.qpos))), contacts=int(d.ncon))


def collision_files(urdf):
    """The hull files a rewritten URDF names, per link: {link: [relative path, ...]}."""
    out = {}
    for link in ET.parse(urdf).getroot().findall("link"):
        for m in link.findall("collision/geometry/mesh"):
            if m.get("filename", "").startswith("collision/"):
                out.setdefault(link.get("name"), []).append(m.get("filename"))
    return out
