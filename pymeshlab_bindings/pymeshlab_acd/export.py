"""Physics-ready export of a decomposition: convex collision hulls as OBJ/STL, a URDF (one link, one
collision element per hull), an MJCF (one body with a free joint, one mesh geom per hull), and a MeshLab
project (.mlp) with one layer per part.

Mass properties come from the parts (closed shells that partition the solid, so the divergence theorem
applies), not from the overlapping hulls: simulators would otherwise count the overlaps twice.
"""
import pathlib
import re
import xml.etree.ElementTree as ET

import numpy as np
import pymeshlab


def mass_properties(V, F):
    """Volume, centre of mass and inertia tensor about the centre (unit density) of a closed,
    outward-oriented triangle mesh, by summing signed tetrahedra from the origin."""
    V = np.asarray(V, float)
    F = np.asarray(F, np.int64)
    o = V.mean(0)                       # a nearby origin keeps the sums well conditioned
    a, b, c = V[F[:, 0]] - o, V[F[:, 1]] - o, V[F[:, 2]] - o
    d = np.einsum("ij,ij->i", a, np.cross(b, c))            # 6 x signed tetra volume
    vol = d.sum() / 6.0
    if not vol > 0:
        raise ValueError("mesh encloses no positive volume (open or inward-facing?)")
    com = (d[:, None] * (a + b + c)).sum(0) / 24.0 / vol
    # Second moments: for a tetra (0,a,b,c), int x_i x_j = det/120 * (sum_k p_k,i p_k,j + s_i s_j), s = a+b+c.
    s = a + b + c
    M = (np.einsum("n,ni,nj->ij", d, a, a) + np.einsum("n,ni,nj->ij", d, b, b)
         + np.einsum("n,ni,nj->ij", d, c, c) + np.einsum("n,ni,nj->ij", d, s, s)) / 120.0
    M -= vol * np.outer(com, com)      # move the second moments to the centre of mass
    inertia = np.trace(M) * np.eye(3) - M
    return vol, com + o, inertia


def merged_layers(ms, ids):
    """The layers' triangles as one mesh (disjoint closed shells add up in mass_properties)."""
    Vs, Fs, n = [], [], 0
    for i in ids:
        m = ms.mesh(i)
        Vs.append(m.vertex_matrix())
        Fs.append(m.face_matrix() + n)
        n += len(Vs[-1])
    return np.concatenate(Vs), np.concatenate(Fs)


def write_obj_objects(path, meshes, prefix):
    """One OBJ holding every (V, F) mesh as its own object (`o <prefix>_<k>`), as CoACD and V-HACD write hulls."""
    # One %-format per block, not one per line: a scan's parts hold 10^5 to 10^6 lines.
    with open(path, "w") as f:
        base = 1
        for k, (V, F) in enumerate(meshes):
            f.write(f"o {prefix}_{k}\n")
            f.write("v %.17g %.17g %.17g\n" * len(V) % tuple(np.asarray(V, float).ravel().tolist()))
            f.write("f %d %d %d\n" * len(F) % tuple((np.asarray(F, np.int64) + base).ravel().tolist()))
            base += len(V)


def _save(ms, layer_id, path, **kw):
    ms.set_current_mesh(layer_id)
    ms.save_current_mesh(str(path), **kw)


def export_decomposition(ms, source_id, part_ids, hull_ids, out_dir, name="object", formats=("obj", "stl"),
                         scale=1.0, density=1000.0, descriptions=None, visual=True):
    """Write the decomposition held in `ms` to `out_dir`.

    source_id: the input layer; part_ids / hull_ids: the parts' and their hulls' layers (hull_ids may be
    empty: then the parts are the collision meshes, and simulators take their hulls). `formats`: mesh
    formats of the collision files (MESH_FORMATS); `descriptions`: what else to write (DESCRIPTIONS; all
    when None). `scale` maps model units to metres; `density` is in kg/m^3. Returns {kind: [relative paths]}.
    """
    out = pathlib.Path(out_dir)
    (out / "collision").mkdir(parents=True, exist_ok=True)
    written = {"collision": [], "parts": [], "visual": []} | {k: [] for k in DESCRIPTIONS}
    colliders = hull_ids or part_ids
    for i in colliders:
        for ext in formats:
            rel = f"collision/{ms.mesh(i).label()}.{ext}"
            _save(ms, i, out / rel, **MESH_FORMATS[ext])
            written["collision"].append(rel)
    mesh_ext = "obj" if "obj" in formats else formats[0]
    if visual:
        _save(ms, source_id, out / f"visual.{mesh_ext}", **MESH_FORMATS[mesh_ext])
        written["visual"].append(f"visual.{mesh_ext}")
    V, F = merged_layers(ms, part_ids)
    vol, com, inertia = mass_properties(V * scale, F)
    body = Body(name, [f"collision/{ms.mesh(i).label()}.{mesh_ext}" for i in colliders], written["visual"],
                density * vol, com, density * inertia, scale, ms, part_ids, out)
    for kind in DESCRIPTIONS if descriptions is None else descriptions:
        written[kind] = DESCRIPTIONS[kind](body)
    written["parts"] = getattr(body, "parts", [])   # the project's part files
    return written


class Body:
    """What a description writer gets: the object's name, its collision and visual files (relative to the
    export folder), mass properties, the scale to metres, and the parts' layers."""
    def __init__(self, name, coll, visual, mass, com, inertia, scale, ms, part_ids, out):
        self.name, self.coll, self.visual, self.mass, self.com, self.inertia = name, coll, visual, mass, com, inertia
        self.scale, self.ms, self.part_ids, self.out = scale, ms, part_ids, out

    def write(self, suffix, text):
        (self.out / f"{self.name}{suffix}").write_text(text)
        return [f"{self.name}{suffix}"]


def _fmt(*xs):
    return " ".join(f"{x:.9g}" for x in xs)


def _urdf(name, coll, visual, mass, com, I, scale):
    robot = ET.Element("robot", name=name)
    link = ET.SubElement(robot, "link", name=f"{name}_link")
    inertial = ET.SubElement(link, "inertial")
    ET.SubElement(inertial, "origin", xyz=_fmt(*com), rpy="0 0 0")
    ET.SubElement(inertial, "mass", value=_fmt(mass))
    ET.SubElement(inertial, "inertia", ixx=_fmt(I[0, 0]), ixy=_fmt(I[0, 1]), ixz=_fmt(I[0, 2]),
                  iyy=_fmt(I[1, 1]), iyz=_fmt(I[1, 2]), izz=_fmt(I[2, 2]))
    for f in visual:
        v = ET.SubElement(link, "visual")
        ET.SubElement(ET.SubElement(v, "geometry"), "mesh", filename=f, scale=_fmt(scale, scale, scale))
    for k, f in enumerate(coll):
        c = ET.SubElement(link, "collision", name=f"{name}_hull_{k}")
        ET.SubElement(ET.SubElement(c, "geometry"), "mesh", filename=f, scale=_fmt(scale, scale, scale))
    ET.indent(robot)
    return '<?xml version="1.0"?>\n' + ET.tostring(robot, encoding="unicode") + "\n"


def _mjcf(name, coll, visual, mass, com, I, scale):
    root = ET.Element("mujoco", model=name)
    # The body's explicit <inertial> wins over its geoms ("auto"), so the overlapping hulls' volumes do
    # not add up to a wrong mass; bodies a user adds without one still get theirs from their geoms.
    ET.SubElement(root, "compiler", meshdir=".", inertiafromgeom="auto")
    asset = ET.SubElement(root, "asset")
    for k, f in enumerate(coll):
        ET.SubElement(asset, "mesh", name=f"{name}_hull_{k}", file=f, scale=_fmt(scale, scale, scale))
    for f in visual:
        # Never weighed (the body's inertial is explicit), and may be open: MuJoCo must not need its volume.
        ET.SubElement(asset, "mesh", name=f"{name}_visual", file=f, scale=_fmt(scale, scale, scale), inertia="shell")
    world = ET.SubElement(root, "worldbody")
    body = ET.SubElement(world, "body", name=name)
    ET.SubElement(body, "freejoint", name=f"{name}_free")
    ET.SubElement(body, "inertial", pos=_fmt(*com), mass=_fmt(mass),
                  fullinertia=_fmt(I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2]))
    for k in range(len(coll)):
        ET.SubElement(body, "geom", name=f"{name}_hull_{k}", type="mesh", mesh=f"{name}_hull_{k}", group="3")
    if visual:
        # Drawn, never collides.
        ET.SubElement(body, "geom", name=f"{name}_visual", type="mesh", mesh=f"{name}_visual",
                      contype="0", conaffinity="0", group="1")
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


_ATTRIBUTE = r'[\w:]+="[^"]*"'


def _sorted_attributes(xml):
    """Every tag's attributes in name order. Qt writes them in its per-process hash order, so the same
    project would otherwise be different bytes from one run to the next."""
    def tag(m):
        return "<" + m[1] + "".join(" " + a for a in sorted(re.findall(_ATTRIBUTE, m[2]))) + m[3] + ">"
    return re.sub(r"<(\w+)((?:\s+" + _ATTRIBUTE + r")+)(\s*/?)>", tag, xml)


def _mlp(body):
    """A MeshLab project with one layer per part (coloured PLY), written by MeshLab's own project
    writer from a MeshSet that holds only the parts."""
    ms, part_ids, out, name = body.ms, body.part_ids, body.out, body.name
    (out / "parts").mkdir(parents=True, exist_ok=True)
    proj = pymeshlab.MeshSet()
    rels = []
    for i in part_ids:
        m = ms.mesh(i)
        proj.add_mesh(m, m.label())
        rel = f"parts/{m.label()}.ply"
        proj.save_current_mesh(str(out / rel), save_vertex_color=True)
        rels.append(rel)
    mlp = out / f"{name}.mlp"
    proj.save_project(str(mlp))   # MeshLab stores the layers' paths relative to it
    mlp.write_text(_sorted_attributes(mlp.read_text()))
    body.parts = rels
    return [f"{name}.mlp"]


# Collision mesh formats: name -> the options pymeshlab's writer takes.
MESH_FORMATS = {
    "obj": dict(save_vertex_color=False),
    "stl": {},
}

# What else an export writes: name -> writer(body) -> the relative paths written. A new format is a
# writer above and its row here.
DESCRIPTIONS = {
    "urdf": lambda b: b.write(".urdf", _urdf(b.name, b.coll, b.visual, b.mass, b.com, b.inertia, b.scale)),
    "mjcf": lambda b: b.write(".xml", _mjcf(b.name, b.coll, b.visual, b.mass, b.com, b.inertia, b.scale)),
    "mlp": _mlp,
}
