"""Whole robots: a URDF or MJCF description in, the same description out with every link's collision
geometry replaced by convex hulls (one mesh element per hull, the hull files beside it), each within the
chosen engine's limits; optionally a USD stage for Isaac Sim and Omniverse.

    python -m pymeshlab_acd robot ROBOT.urdf --out DIR [--engine physx] [--format urdf,mjcf,usd]
    pymeshlab_acd.decompose_robot("ROBOT.urdf", "DIR", engine="physx")

Each distinct (mesh content, options) is decomposed once: a content-addressed cache (hash of the mesh's bytes
and of the options) serves a re-run, another robot sharing the mesh, or a batch.
"""
import copy
import json
import os
import pathlib
import shutil
import time
import xml.etree.ElementTree as ET

import numpy as np

from . import options
from .hull_cache import cache_folder, hull_mesh, read_objects


# ---- mesh paths ---------------------------------------------------------------------------------
def resolve(uri, base_dir, packages):
    """A mesh URI of a description as a file path: package://NAME/rest (NAME from `packages`, else the
    nearest folder named NAME above the description, else ROS_PACKAGE_PATH), file://, absolute or
    relative to the description. Returns the path (which may not exist)."""
    if uri.startswith("file://"):
        return pathlib.Path(uri[len("file://"):])
    if uri.startswith("package://"):
        name, _, rest = uri[len("package://"):].lstrip("/").partition("/")
        return _package_dir(name, base_dir, packages) / rest
    p = pathlib.Path(uri)
    return p if p.is_absolute() else pathlib.Path(base_dir) / p


def _package_dir(name, base_dir, packages):
    if name in packages:
        return pathlib.Path(packages[name])
    here = pathlib.Path(base_dir).resolve()
    for d in [here, *here.parents]:
        if d.name == name:
            return d
        if (d / name).is_dir():
            return d / name
    for root in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
        if root and (pathlib.Path(root) / name).is_dir():
            return pathlib.Path(root) / name
    raise FileNotFoundError(f"package '{name}' not found above {base_dir}: give --package {name}=DIR")


# ---- the robot --------------------------------------------------------------------------------
class Robot:
    """A description being rewritten: its XML, where its meshes are, and what each link got."""

    def __init__(self, path, packages):
        self.path = pathlib.Path(path)
        self.base = self.path.parent
        self.packages = dict(packages or {})
        self.kind = "mjcf" if self.path.suffix.lower() in (".xml", ".mjcf") else "urdf"
        self.name = self.path.stem
        self.rows = []        # one per decomposed collision: link, source, parts, hulls, ...
        self.hull_files = {}  # cache key -> relative hull file paths in the output


def decompose_robot(description, out_dir, packages=None, engine="none", formats=("urdf",), cache=True,
                    cache_dir=None, resolve_paths=False, progress=None, **filter_options):
    """Rewrite a URDF (read with yourdfpy) or MJCF (read with MuJoCo's MjSpec) with every link's collision
    meshes replaced by their convex decomposition's hulls, within `engine`'s limits.

    For each link the collision mesh is decomposed, or its visual mesh when it has no collision; primitives
    stay. `formats`: what to write ("urdf" for a URDF input, "mjcf", "usd"); the input's own kind is always
    written. `packages`: {name: folder} for package:// URIs. `cache_dir` (default ~/.cache/meshlab-acd/hulls)
    holds each decomposition by content; cache=False decomposes everything again. `resolve_paths`: the meshes
    kept (visuals, and collisions that were not decomposed) named by absolute file paths instead of their
    package:// URIs, for simulators without a ROS package resolver (PyBullet). `filter_options` are
    generate_approximate_convex_decomposition's, from pymeshlab_acd.options.DEFAULTS. `progress(text)` is
    called per mesh. Returns the summary (also written to OUT/summary.json).
    """
    t0 = time.perf_counter()
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    robot = Robot(description, packages)
    opts = dict(options.DEFAULTS, **filter_options, engine=engine)
    threads = opts.pop("threads")
    run = dict(opts=opts, threads=threads, cache_dir=cache_folder(cache, cache_dir), out=out,
               progress=progress or (lambda s: None), resolve_paths=resolve_paths)
    if robot.kind == "urdf":
        written = _rewrite_urdf(robot, run)
    else:
        written = _rewrite_mjcf(robot, run)
    format_errors = {}
    for f in formats:
        if f not in WRITERS and f not in ("urdf", "mjcf"):
            raise ValueError(f"unknown format {f!r}: urdf, mjcf or usd")
        if f != robot.kind and f in WRITERS:
            try:
                written.append(WRITERS[f](robot, run))
            except Exception as e:   # the rewritten description stands; say what the conversion refused
                format_errors[f] = f"{type(e).__name__}: {e}"
    summary = dict(robot=str(robot.path), kind=robot.kind, engine=engine, tau=opts["tau"], tau_unit=opts["tau_unit"],
                   links=robot.rows, hulls=sum(r.get("hulls", 0) for r in robot.rows),
                   meshes=len({r["key"] for r in robot.rows if "key" in r}),
                   decomposed=sum(1 for r in robot.rows if r.get("cached") is False),
                   failed=sum(1 for r in robot.rows if r.get("error")),
                   seconds=time.perf_counter() - t0, written=[str(p) for p in written],
                   format_errors=format_errors, mjcf_inertia_fixed=getattr(robot, "inertia_fixed", []))
    (out / "summary.json").write_text(json.dumps(summary, indent=1, default=float))
    return summary


def _hulls_for(robot, run, link, source):
    """Decompose one source mesh (once per content and options), place its hull files in the output,
    and record the link's row. Returns the hulls' relative paths, or None when the mesh failed."""
    row = dict(link=link, source=str(source))
    robot.rows.append(row)
    try:
        if not source.exists():
            raise FileNotFoundError(f"{source}: no such file")
        run["progress"](f"{robot.name}: {link} ({source.name})")
        folder, res, cached, key = hull_mesh(source, run["opts"], run["cache_dir"], run["threads"])
    except Exception as e:   # a mesh that cannot be decomposed keeps its link's collision as it was
        row["error"] = f"{type(e).__name__}: {e}"
        return None
    hulls = res["parts"]
    row.update(key=key, cached=cached, parts=res["parts"], hulls=hulls,
               tau_model_units=res["tau_model_units"], max_hull_distance=res["max_hull_distance"],
               hull_reach=res.get("hull_reach", 0.0), collision_hull_distance=res.get("collision_hull_distance"),
               certified=bool(res["tau_convex"]), seconds=0.0 if cached else res["seconds"])
    if key not in robot.hull_files:
        rel = pathlib.Path("collision") / f"{source.stem}_{key[:8]}"
        (run["out"] / rel).mkdir(parents=True, exist_ok=True)
        for f in [f"hull_{k}.obj" for k in range(hulls)] + ["parts.obj"]:
            shutil.copyfile(folder / f, run["out"] / rel / f)
        robot.hull_files[key] = [(rel / f"hull_{k}.obj").as_posix() for k in range(hulls)]
    if run["cache_dir"] is None:
        shutil.rmtree(folder, ignore_errors=True)
    return robot.hull_files[key]


# ---- URDF -------------------------------------------------------------------------------------
def _rewrite_urdf(robot, run):
    import yourdfpy
    model = yourdfpy.URDF.load(str(robot.path), build_scene_graph=False, load_meshes=False,
                               load_collision_meshes=False,
                               filename_handler=lambda fname: str(resolve(fname, robot.base, robot.packages)))
    tree = ET.parse(robot.path, parser=ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    root = tree.getroot()
    for link_el in root.findall("link"):
        name = link_el.get("name")
        if name not in model.link_map:
            continue
        colls = link_el.findall("collision")
        meshes = [c for c in colls if c.find("geometry/mesh") is not None]
        if not colls:   # no collision: its visual meshes stand in
            meshes = [v for v in link_el.findall("visual") if v.find("geometry/mesh") is not None]
        for el in meshes:
            mesh = el.find("geometry/mesh")
            rels = _hulls_for(robot, run, name, resolve(mesh.get("filename"), robot.base, robot.packages))
            if rels is None:
                continue
            at = list(link_el).index(el) if el.tag == "collision" else len(link_el)
            if el.tag == "collision":
                link_el.remove(el)
            base = el.get("name") or f"{name}_collision"
            for k, rel in enumerate(rels):
                c = ET.Element("collision", name=f"{base}_hull_{k}")
                origin = el.find("origin")
                if origin is not None:
                    c.append(copy.deepcopy(origin))
                m = ET.SubElement(ET.SubElement(c, "geometry"), "mesh", filename=rel)
                if mesh.get("scale"):
                    m.set("scale", mesh.get("scale"))
                link_el.insert(at + k, c)
    _rebase_paths(root, robot, run)
    ET.indent(tree)
    path = run["out"] / f"{robot.name}.urdf"
    tree.write(path, encoding="unicode", xml_declaration=True)
    robot.urdf = path
    return [path]


def _rebase_paths(root, robot, run):
    """Mesh paths relative to the input description, made relative to the output; with resolve_paths,
    package:// and file:// URIs as absolute paths too."""
    for m in root.iter("mesh"):
        f = m.get("filename")
        if not f or f.startswith("collision/"):
            continue
        if run["resolve_paths"]:
            try:
                m.set("filename", str(resolve(f, robot.base, robot.packages).resolve()))
            except FileNotFoundError:
                pass
        elif "://" not in f and not os.path.isabs(f):
            m.set("filename", os.path.relpath((robot.base / f).resolve(), run["out"].resolve()))


def _urdf_to_mjcf(robot, run):
    """The rewritten URDF compiled by MuJoCo (visuals left out: MuJoCo cannot read package:// URIs) and
    saved as MJCF beside it; each hull a mesh geom."""
    import mujoco
    root = ET.parse(robot.urdf).getroot()
    for link in root.findall("link"):
        for v in link.findall("visual"):
            link.remove(v)
        for c in link.findall("collision"):
            m = c.find("geometry/mesh")
            if m is not None and not m.get("filename", "").startswith("collision/"):
                link.remove(c)   # a mesh we could not decompose: MuJoCo would need its path
    robot.inertia_fixed = _valid_inertias(root)
    mj = root.find("mujoco")
    if mj is None:
        mj = ET.SubElement(root, "mujoco")
    # fusestatic off: the root link stays a body of its own (fixed to the world), which a user can free.
    # boundmass/boundinertia: massless frames on moving joints (virtual links) get MuJoCo's smallest mass.
    ET.SubElement(mj, "compiler", meshdir=".", strippath="false", balanceinertia="true", discardvisual="false",
                  fusestatic="false", boundmass="1e-6", boundinertia="1e-12")
    tmp = run["out"] / f".{robot.name}.mujoco.urdf"
    tmp.write_text(ET.tostring(root, encoding="unicode"))
    try:
        spec = mujoco.MjSpec.from_file(str(tmp))
        spec.compile()
        # The written file keeps the bounds, so that it compiles as this did.
        spec.compiler.boundmass, spec.compiler.boundinertia, spec.compiler.balanceinertia = 1e-6, 1e-12, True
        path = run["out"] / f"{robot.name}.xml"
        path.write_text(spec.to_xml())
    finally:
        tmp.unlink()
    return path


def _valid_inertias(root):
    """MuJoCo refuses an inertia tensor that no body has (a negative or zero principal moment with the
    others not zero, or one moment above the sum of the other two), which URDFs carry for sensor frames and
    rounded CAD exports. For the MJCF only, each such tensor keeps its principal axes with its moments
    raised just enough to be physical. Returns the links changed."""
    fixed = []
    for link in root.findall("link"):
        el = link.find("inertial/inertia")
        if el is None:
            continue
        g = lambda k: float(el.get(k, 0))   # noqa: E731
        I = np.array([[g("ixx"), g("ixy"), g("ixz")], [g("ixy"), g("iyy"), g("iyz")], [g("ixz"), g("iyz"), g("izz")]])
        e, R = np.linalg.eigh(I)
        if not np.any(I) or (e[0] > 0 and e[0] + e[1] >= e[2] * (1 + 1e-6)):   # MuJoCo's test has a tolerance
            continue
        floor = max(1e-9, 1e-3 * abs(e).max())
        e = np.maximum(e, floor)
        e[:2] = np.maximum(e[:2], e[2] / 2 * (1 + 1e-5))   # sorted: the two smaller reach half the largest
        J = R @ np.diag(e) @ R.T
        for k, (i, j) in zip(("ixx", "iyy", "izz", "ixy", "ixz", "iyz"), ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))):
            el.set(k, f"{J[i, j]:.9g}")
        fixed.append(link.get("name"))
    return fixed


# ---- MJCF -------------------------------------------------------------------------------------
def _rewrite_mjcf(robot, run):
    """Each colliding mesh geom: its mesh decomposed, one geom per hull added beside it (same frame,
    contact settings and class, no mass), and the geom itself kept for display only (it still gives
    the body its mass and inertia, as before)."""
    import mujoco
    spec = mujoco.MjSpec.from_file(str(robot.path))
    meshdir = pathlib.Path(spec.modelfiledir or robot.base) / (spec.meshdir or "")
    meshes = {m.name: m for m in spec.meshes}
    added, used = {}, {g.name for g in spec.geoms if g.name}
    for g in list(spec.geoms):
        if g.type != mujoco.mjtGeom.mjGEOM_MESH or (g.contype == 0 and g.conaffinity == 0):
            continue
        mesh = meshes[g.meshname]
        source = pathlib.Path(mesh.file) if os.path.isabs(mesh.file) else meshdir / mesh.file
        body = g.parent
        rels = _hulls_for(robot, run, body.name or g.name or g.meshname, source)
        if rels is None:
            continue
        names = added.setdefault(g.meshname, [])
        if not names:
            for k, rel in enumerate(rels):
                names.append(f"{g.meshname}_hull_{k}")
                spec.add_mesh(name=names[-1], file=str((run["out"] / rel).resolve()), scale=list(mesh.scale))
        for k, mname in enumerate(names):
            h = body.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=mname, pos=list(g.pos), quat=list(g.quat),
                              contype=g.contype, conaffinity=g.conaffinity, condim=g.condim, group=3,
                              friction=list(g.friction), priority=g.priority, margin=g.margin, gap=g.gap,
                              solref=list(g.solref), solimp=list(g.solimp), solmix=g.solmix, density=0)
            h.name = _unique(f"{g.name or body.name or g.meshname}_hull_{k}", used)
        g.contype, g.conaffinity = 0, 0
    spec.compile()
    text = spec.to_xml()
    # Hull paths relative to the output, the input's own meshes absolute (the output folder moves away).
    path = run["out"] / f"{robot.name}.xml"
    path.write_text(text.replace(str(run["out"].resolve()) + os.sep, ""))
    robot.mjcf = path
    return [path]


def _unique(name, used):
    out, k = name, 1
    while out in used:
        out, k = f"{name}_{k}", k + 1
    used.add(out)
    return out


# ---- USD ---------------------------------------------------------------------------------------
def _usd(robot, run):
    """A .usda stage: the robot as Xforms (a URDF's links at their joint frames in the zero configuration),
    each hull a Mesh prim with UsdPhysics' CollisionAPI and MeshCollisionAPI (approximation convexHull)."""
    from pxr import Gf, Usd, UsdGeom, UsdPhysics
    path = run["out"] / f"{robot.name}.usda"
    stage = Usd.Stage.CreateNew(str(path))
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    top = UsdGeom.Xform.Define(stage, "/" + _usd_name(robot.name))
    stage.SetDefaultPrim(top.GetPrim())
    for link, pose, hulls in _link_hulls(robot, run):
        x = UsdGeom.Xform.Define(stage, top.GetPath().AppendChild(_usd_name(link)))
        x.AddTransformOp().Set(Gf.Matrix4d(np.asarray(pose, float).T.tolist()))
        for k, (V, F) in enumerate(hulls):
            m = UsdGeom.Mesh.Define(stage, x.GetPath().AppendChild(f"hull_{k}"))
            m.CreatePointsAttr([Gf.Vec3f(*map(float, v)) for v in V])
            m.CreateFaceVertexCountsAttr([3] * len(F))
            m.CreateFaceVertexIndicesAttr([int(i) for i in np.asarray(F).ravel()])
            m.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
            UsdPhysics.CollisionAPI.Apply(m.GetPrim())
            UsdPhysics.MeshCollisionAPI.Apply(m.GetPrim()).CreateApproximationAttr(UsdPhysics.Tokens.convexHull)
    stage.GetRootLayer().Save()
    return path


def _usd_name(s):
    out = "".join(c if c.isalnum() or c == "_" else "_" for c in s)
    return out if out and not out[0].isdigit() else "_" + out


def _link_hulls(robot, run):
    """(link, 4x4 pose in the robot's frame, [hull (V, F) in the link's frame]) for each link with hulls."""
    by_link = {}
    if robot.kind == "urdf":
        import yourdfpy
        model = yourdfpy.URDF.load(str(robot.urdf), build_scene_graph=True, load_meshes=False,
                                   load_collision_meshes=False,
                                   filename_handler=lambda fname: str(resolve(fname, run["out"], robot.packages)))
        for name, link in model.link_map.items():
            for c in link.collisions:
                m = c.geometry.mesh
                if m is None or not m.filename.startswith("collision/"):
                    continue
                T = c.origin if c.origin is not None else np.eye(4)
                s = np.ones(3) * (m.scale if m.scale is not None else 1.0)
                for V, F in read_objects(run["out"] / m.filename):
                    by_link.setdefault(name, []).append(((V * s) @ T[:3, :3].T + T[:3, 3], F))
        for name in sorted(by_link):
            yield name, model.get_transform(name, model.base_link), by_link[name]
        return
    import mujoco
    m = mujoco.MjModel.from_xml_path(str(robot.mjcf))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    for g in range(m.ngeom):
        name = m.geom(g).name
        if "_hull_" not in name or m.geom_type[g] != mujoco.mjtGeom.mjGEOM_MESH:
            continue
        mid = m.geom_dataid[g]
        a, n = m.mesh_vertadr[mid], m.mesh_vertnum[mid]
        fa, fn = m.mesh_faceadr[mid], m.mesh_facenum[mid]
        V = m.mesh_vert[a:a + n]
        R = d.geom_xmat[g].reshape(3, 3)
        body = m.body(m.geom_bodyid[g]).name or f"body_{m.geom_bodyid[g]}"
        by_link.setdefault(body, []).append((V @ R.T + d.geom_xpos[g], m.mesh_face[fa:fa + fn]))
    for name in sorted(by_link):
        yield name, np.eye(4), by_link[name]


# What a robot can be written as besides its own kind: format -> writer(robot, run) -> the path written.
WRITERS = {
    "mjcf": _urdf_to_mjcf,
    "usd": _usd,
}
