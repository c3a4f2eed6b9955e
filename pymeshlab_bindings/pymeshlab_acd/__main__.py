"""Command line: python -m pymeshlab_acd {concavity,decompose,structure} [MESH] [options]
              python -m pymeshlab_acd polygon POLYGON [options]
              python -m pymeshlab_acd batch IN_DIR OUT_DIR [--workers N] [--ray ADDRESS|local] [options]
              python -m pymeshlab_acd robot ROBOT.urdf|ROBOT.xml --out DIR [--engine E] [--format urdf,mjcf,usd]

MESH is a mesh file; --demo takes pymeshlab's bundled bunny instead. POLYGON is a .poly, .svg or plain
list-of-loops file (see pymeshlab_acd.polygon_io). Every subcommand starts from the same defaults
(pymeshlab_acd.options); a one-line progress bar is drawn on stderr while a filter runs.
"""
import argparse
import json
import os
import pathlib
import sys
import time

import numpy as np
import pymeshlab

from . import decompose, decompose_polygon, level_of_detail, load, mesh_ids
from . import polygon_io
from .batch import DEFAULTS as BATCH
from .export import export_decomposition, write_obj_objects
from .options import DEFAULTS, add_arguments
from .progress import ProgressBar

BUNNY = os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes", "bunny.obj")


def _meshset(path):
    load()
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    return ms


def cmd_concavity(a):
    ms = _meshset(a.mesh)
    with ProgressBar(ms, a.progress):
        r = ms.compute_scalar_by_notch_concavity()
    m = ms.current_mesh()
    print(f"mesh            {a.mesh}  ({m.vertex_number()} vertices, {m.face_number()} faces)")
    print(f"notches         {r['notches']}")
    print(f"bridges         {r['bridges']}")
    print(f"pockets         {r['pockets']}")
    print(f"max concavity   {r['max_concavity']:.6g} (model units)")
    print(f"at              {tuple(round(float(x), 6) for x in r['max_concavity_position'])}")
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        out = os.path.join(a.out, "concavity.ply")
        ms.save_current_mesh(out, save_vertex_quality=True, save_vertex_color=True)
        print(f"wrote           {out} (vertex quality = concavity)")
    return 0


def cmd_decompose(a):
    ms = _meshset(a.mesh)
    src = ms.current_mesh_id()
    params = dict(tau=a.tau, tau_unit=a.tau_unit, cut_plane_selection=a.cut_plane_selection,
                  max_parts=a.max_parts, merge_parts=a.merge_parts, merge_measure=a.merge_measure, cut_search=a.cut_search, output_hulls=bool(a.hulls or a.out), max_hull_vertices=a.max_hull_vertices, engine=a.engine,
                  time_limit=a.time_limit, preprocessing=a.preprocessing, wrap_alpha=a.wrap_alpha,
                  wrap_offset=a.wrap_offset, on_self_intersection=a.on_self_intersection,
                  hole_handling=a.hole_handling, hole_order=a.hole_order, threads=a.threads)
    t0 = time.perf_counter()
    with ProgressBar(ms, a.progress):
        res, ids = decompose(ms, with_tree=a.tree, **params)
    wall = time.perf_counter() - t0
    print(f"mesh             {a.mesh}  ({ms.mesh(src).face_number()} faces)")
    print(f"tau              {a.tau} {a.tau_unit} = {res['tau_model_units']:.6g} model units")
    print(f"parts            {res['parts']}")
    print(f"max concavity    {res['max_concavity']:.6g} (root {res['root_concavity']:.6g})")
    print(f"time             {res['time']:.2f} s (wall {wall:.2f} s)")
    if res["max_parts_reached"]:
        print("note             max_parts reached: some parts exceed tau")
    if res.get("cavities"):
        print(f"cavities         {res['cavities']} in the input; {res['hole_cuts']} cuts through cavities"
              + (f"; {res['kept_cavities']} kept inside parts (not tau-convex)" if res["kept_cavities"] else ""))
    if res.get("self_intersections"):
        print(f"note             the mesh intersects itself ({res['self_intersections']} face pairs cross)")
    if res.get("wrap_alpha_used"):
        how = (", openings capped along the surface" if res.get("wrap_capped")
               else ", a skin: the input encloses no solid" if res.get("wrap_skin") else "")
        print(f"preprocessing    alpha-wrapped at {res['wrap_alpha_used']:.3g}%{how} (the input is not a closed solid); "
              f"the solid reaches {res['solid_to_input']:.4g} from the input, the input {res['input_to_solid']:.4g} "
              f"from it")
    elif res.get("holes_filled"):
        print(f"preprocessing    {res['holes_filled']} holes filled ({res.get('holes_on_planes', 0)} on the planes their "
              f"rims run on, the rest faired; the input is not a closed solid); "
              f"the patches reach {res['solid_to_input']:.4g} from the input")
    elif res.get("welded_vertices"):
        print(f"preprocessing    {res['welded_vertices']} duplicate vertices welded")
    if a.engine != "none" or res.get("hulls_reduced"):
        print(f"hulls            {res['hulls_reduced']} of {res['parts']} cut down to {a.engine}'s limits, each "
              f"still containing its part; they reach at most {res['hull_reach']:.4g} beyond the exact hulls, so "
              f"every hull lies within {res['collision_hull_distance']:.4g} of its part"
              + (f"; {res['hulls_thin']} too thin for {a.engine}" if res.get("hulls_thin") else ""))
    if not res.get("tau_convex", True):
        print("note             not every part is certified within tau (see the log above)")
    if a.out:
        out = pathlib.Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        hulls = [i for i in ids if ms.mesh(i).label().startswith("acd_hull_")]
        parts = [i for i in ids if i not in hulls]
        arrays = lambda layers: [(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in layers]  # noqa: E731
        write_obj_objects(out / "hulls.obj", arrays(hulls), "hull")
        write_obj_objects(out / "parts.obj", arrays(parts), "part")
        summary = {k: v for k, v in res.items() if k != "tree"}
        (out / "summary.json").write_text(json.dumps(summary, indent=1, default=float))
        wrote = ["hulls.obj", "parts.obj", "summary.json"]
        if a.part_files:
            for i in ids:
                ms.set_current_mesh(i)
                ms.save_current_mesh(str(out / f"{ms.mesh(i).label()}.obj"))
            wrote.append(f"{len(ids)} layer OBJs")
        if a.tree:
            (out / "tree.json").write_text(json.dumps(res["tree"], indent=1))
            wrote.append("tree.json")
        print(f"wrote            {', '.join(wrote)} to {out}")
        if a.export:
            w = export_decomposition(ms, src, parts, hulls, out / "export", name=pathlib.Path(a.mesh).stem,
                                     scale=a.scale, density=a.density)
            print(f"exported         {len(hulls)} collision hulls (OBJ, STL), {w['urdf'][0]}, {w['mjcf'][0]}, "
                  f"{w['mlp'][0]} to {out / 'export'}")
    return 0


def cmd_structure(a):
    """What the tree gives (the paper's Section 7, Figure 18): a coarser level read back from the saved tree,
    the skeleton (its points checked against the mesh by MeshLab's own signed distance), the hull union."""
    ms = _meshset(a.mesh)
    src = ms.current_mesh_id()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    with ProgressBar(ms, a.progress):
        res, _ = decompose(ms, tau=a.tau, preprocessing=a.preprocessing, tree_file=str(out / "tree.json"))
    print(f"mesh             {a.mesh}  ({ms.mesh(src).face_number()} faces)")
    print(f"decomposition    tau {a.tau}%: {res['parts']} parts in {res['time']:.2f} s, tree saved to {out / 'tree.json'}")
    t0 = time.perf_counter()
    lod, _ = level_of_detail(ms, out / "tree.json", tau=a.coarser)
    print(f"coarser level    tau {a.coarser}%: {lod['parts']} parts from the saved tree in "
          f"{time.perf_counter() - t0:.2f} s (nothing recomputed)")

    ms.set_current_mesh(src)
    sk = ms.generate_skeleton_from_convex_decomposition(tau=a.tau, preprocessing=a.preprocessing)
    ms.set_current_mesh([i for i in mesh_ids(ms) if ms.mesh(i).label() == "acd_skeleton"][-1])
    V, E = ms.current_mesh().vertex_matrix(), ms.current_mesh().edge_matrix()
    ms.save_current_mesh(str(out / "skeleton.obj"))
    # 2000 points along the edges, by length; inside the mesh where MeshLab's signed distance is negative
    rng = np.random.default_rng(0)
    length = np.linalg.norm(V[E[:, 1]] - V[E[:, 0]], axis=1)
    pick = rng.choice(len(E), 2000, p=length / length.sum())
    t = rng.random((2000, 1))
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V[E[pick, 0]] * (1 - t) + V[E[pick, 1]] * t), "skeleton_samples")
    ms.compute_scalar_by_distance_from_another_mesh_per_vertex(
        measuremesh=ms.current_mesh_id(), refmesh=src, signeddist=True, maxdist=pymeshlab.PercentageValue(100))
    inside = float((ms.current_mesh().vertex_scalar_array() < 0).mean())
    print(f"skeleton         {sk['pieces']} pieces, {sk['vertices']} vertices, {sk['edges']} edges, "
          f"{sk['components']} component(s); {100 * inside:.1f}% of 2000 points along it inside the mesh; "
          f"{out / 'skeleton.obj'}")

    ms.set_current_mesh(src)
    hu = ms.generate_convex_hull_union(tau=a.tau, max_hull_vertices=a.union_hull_vertices,
                                       preprocessing=a.preprocessing)
    union = [i for i in mesh_ids(ms) if ms.mesh(i).label() == "acd_hull_union"][-1]
    ms.set_current_mesh(union)
    ms.save_current_mesh(str(out / "hull_union.obj"))
    print(f"hull union       {hu['hulls']} hulls of at most {a.union_hull_vertices} vertices: {hu['union_faces']} "
          f"faces from {hu['input_faces']} ({hu['face_reduction']:.1f}x fewer), volume IoU with the mesh "
          f"{hu['volume_iou']:.3f} +- {hu['volume_iou_stderr']:.3f}; {out / 'hull_union.obj'}")
    if sk["components"] != 1 or inside < 0.99:
        print("note             the skeleton is not one component lying inside the mesh")
        return 1
    return 0


def _short(text, n=90):
    return text if len(text) <= n else text[:n - 3] + "..."


def cmd_batch(a):
    from .batch import run_batch
    fmt = [f.strip() for f in a.formats.split(",") if f.strip()]
    records = run_batch(a.in_dir, a.out_dir, workers=a.workers, ray_address=a.ray,
                        ray_runtime_env=json.loads(a.ray_runtime_env) if a.ray_runtime_env else None,
                        progress=a.progress, tau=a.tau, tau_unit=a.tau_unit,
                        cut_plane_selection=a.cut_plane_selection, max_parts=a.max_parts,
                        merge_parts=a.merge_parts, merge_measure=a.merge_measure, cut_search=a.cut_search, max_hull_vertices=a.max_hull_vertices, engine=a.engine,
                        preprocessing=a.preprocessing,
                        wrap_alpha=a.wrap_alpha, wrap_offset=a.wrap_offset,
                        time_limit=a.time_limit, hole_handling=a.hole_handling, hole_order=a.hole_order,
                        on_self_intersection=a.on_self_intersection, threads=a.threads, timeout=a.timeout, formats=fmt, scale=a.scale, density=a.density,
                        save_tree=a.save_tree, cache=a.cache, cache_dir=a.cache_dir)
    w = max([len(pathlib.Path(r["file"]).name) for r in records] + [4])
    print(f"{'file':<{w}}  {'status':<11} {'parts':>5} {'concavity %':>11} {'hulls/vol':>9} {'time s':>7}  "
          f"{'preprocessing':<15} note")
    for r in records:
        ok = r["status"] in ("ok", "done before")
        print(f"{pathlib.Path(r['file']).name:<{w}}  {r['status']:<11} "
              + (f"{r['parts']:>5} {r['max_concavity_pct']:>11.3f} {r['hull_volume_ratio']:>9.3f} "
                 if ok else f"{'-':>5} {'-':>11} {'-':>9} ")
              + f"{r.get('time', 0):>7.1f}  {r.get('preprocessing') or '-':<15} {_short(r.get('error') or '')}")
    failed = sum(r["status"] == "failed" for r in records)
    print(f"{len(records)} meshes, {len(records) - failed} decomposed, {failed} failed; "
          f"summary: {pathlib.Path(a.out_dir) / 'summary.csv'} and summary.json")
    return 0


def cmd_robot(a):
    from .robot import decompose_robot
    packages = {}
    for spec in a.package or []:
        name, sep, folder = spec.partition("=")
        if not sep or not name or not folder:
            raise ValueError(f"--package {spec}: write it as NAME=FOLDER")
        packages[name] = folder
    bar = (lambda text: print(f"\r\033[K{_short(text, 100)}", end="", file=sys.stderr, flush=True)) if a.progress else None
    opts = {k: getattr(a, k) for k in ("tau", "tau_unit", "cut_plane_selection", "max_parts", "merge_parts", "merge_measure", "cut_search",
                                        "max_hull_vertices", "preprocessing", "wrap_alpha", "wrap_offset",
                                        "time_limit", "hole_handling", "hole_order", "on_self_intersection", "threads")}
    fmts = [f.strip() for f in a.format.split(",") if f.strip()]
    s = decompose_robot(a.description, a.out, packages=packages, engine=a.engine, formats=fmts,
                        cache=a.cache, cache_dir=a.cache_dir, resolve_paths=a.resolve_paths, progress=bar, **opts)
    if bar:
        print("\r\033[K", end="", file=sys.stderr)
    w = max([len(r["link"]) for r in s["links"]] + [4])
    print(f"{'link':<{w}}  {'parts':>5} {'hulls':>5} {'within (model units)':>20} {'time s':>7}  {'cached':<6} source")
    for r in s["links"]:
        if r.get("error"):
            print(f"{r['link']:<{w}}  {'-':>5} {'-':>5} {'-':>20} {'-':>7}  {'-':<6} {r['source']}: {r['error']}")
            continue
        bound = f"{r['collision_hull_distance']:.4g}" + ("" if r["certified"] else " (!)")
        print(f"{r['link']:<{w}}  {r['parts']:>5} {r['hulls']:>5} {bound:>20} {r['seconds']:>7.2f}  "
              f"{'yes' if r['cached'] else 'no':<6} {pathlib.Path(r['source']).name}")
    print(f"{s['robot']}: {len(s['links'])} collision meshes ({s['meshes']} distinct, {s['decomposed']} decomposed, "
          f"{s['failed']} failed), {s['hulls']} hulls, engine {s['engine']}, tau {s['tau']} {s['tau_unit']}, "
          f"{s['seconds']:.1f} s; wrote {', '.join(pathlib.Path(p).name for p in s['written'])} and "
          f"summary.json to {a.out}")
    for f, e in s["format_errors"].items():
        print(f"error: {f}: {e}", file=sys.stderr)
    if s["mjcf_inertia_fixed"]:
        print(f"note: in the MJCF, {len(s['mjcf_inertia_fixed'])} inertias MuJoCo refuses were made physical "
              f"(principal moments raised): {', '.join(s['mjcf_inertia_fixed'][:5])}")
    return 0 if not s["failed"] and not s["format_errors"] else 1


def cmd_polygon(a):
    load()
    loops = polygon_io.read_loops(a.polygon)
    V, E = polygon_io.loops_to_mesh(loops)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V, edge_matrix=E), pathlib.Path(a.polygon).stem)
    params = dict(tau=a.tau, tau_unit=a.tau_unit, cut_line_selection=a.cut_line_selection,
                  hole_handling=a.hole_handling, hole_order=a.hole_order, max_parts=a.max_parts)
    with ProgressBar(ms, a.progress):
        res, ids = decompose_polygon(ms, **params)
    print(f"polygon          {a.polygon}  ({len(V)} vertices in {len(loops)} loops)")
    print(f"polygons         {res['polygons']}, holes {res['holes']}, notches {res['notches']}")
    print(f"tau              {a.tau} {a.tau_unit} = {res['tau_model_units']:.6g} units")
    print(f"pieces           {res['parts']}")
    print(f"max concavity    {res['max_concavity']:.6g} (root {res['root_concavity']:.6g})")
    print(f"time             {res['time']:.3f} s")
    if res["kept_holes"]:
        print(f"note             {res['kept_holes']} holes kept inside pieces (not tau-convex)")
    if a.out:
        out = pathlib.Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        pieces = []
        for i in ids:
            m = ms.mesh(i)
            Vp, Fp = m.vertex_matrix(), m.face_matrix()
            pieces.append((Vp[:, :2] if np.allclose(Vp[:, 2], 0) else _in_plane(Vp), Fp))
            ms.set_current_mesh(i)
            ms.save_current_mesh(str(out / f"{m.label()}.ply"))
        polygon_io.write_svg(str(out / "pieces.svg"), loops, pieces)
        (out / "tree.json").write_text(json.dumps(res["tree"], indent=1))
        summary = {k: v for k, v in res.items() if k != "tree"}
        (out / "summary.json").write_text(json.dumps(summary, indent=1, default=float))
        print(f"wrote            {len(ids)} pieces as PLY (faces + outline edges), pieces.svg, tree.json, "
              f"summary.json to {out}")
    return 0


def _in_plane(V):
    """2D coordinates of planar points in their own principal frame (for the picture)."""
    c = V - V.mean(0)
    _, _, vt = np.linalg.svd(c, full_matrices=False)
    return c @ vt[:2].T


def main(argv=None):
    fmt = argparse.ArgumentDefaultsHelpFormatter
    p = argparse.ArgumentParser(prog="python -m pymeshlab_acd", formatter_class=fmt,
                                description="Approximate convex decomposition (Lien & Amato) through pymeshlab.")
    p.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = p.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("concavity", formatter_class=fmt, help="measure notch concavity (compute_scalar_by_notch_concavity)")
    d = sub.add_parser("decompose", formatter_class=fmt, help="decompose (generate_approximate_convex_decomposition)")
    g = sub.add_parser("polygon", formatter_class=fmt, help="decompose a 2D polygon with holes "
                                                            "(generate_polygon_approximate_convex_decomposition)")
    g.add_argument("polygon", help=".poly, .svg or plain text file of loops")
    g.add_argument("--out", help="folder for the pieces (PLY), pieces.svg, tree.json, summary.json")
    g.add_argument("--no-progress", dest="progress", action="store_false", help="no progress bar")
    add_arguments(g, "tau", "tau_unit", "max_parts")
    g.add_argument("--cut-line-selection", default="best", choices=["best", "bisector"])
    g.add_argument("--hole-handling", default="best_plane", choices=["best_plane", "principal_plane", "keep_cavities"],
                   help="holes: the best of several lines, the principal axis (the paper), or kept")
    g.add_argument("--hole-order", default="first", choices=["first", "by_concavity"])
    for s in (c, d):
        s.add_argument("mesh", nargs="?", help="mesh file (closed, or see --preprocessing)")
        s.add_argument("--demo", action="store_true", help="use pymeshlab's bundled bunny as MESH")
        s.add_argument("--no-progress", dest="progress", action="store_false", help="no progress bar")
    c.add_argument("--out", help="folder for concavity.ply (vertex quality = concavity)")
    d.add_argument("--out", help="folder for hulls.obj (one object per hull), parts.obj and summary.json")
    add_arguments(d, "tau", "tau_unit", "cut_plane_selection", "max_parts", "merge_parts", "merge_measure", "cut_search",
                  "max_hull_vertices", "engine", "preprocessing", "wrap_alpha", "wrap_offset", "time_limit", "hole_handling", "hole_order",
                  "on_self_intersection", "threads")
    d.add_argument("--hulls", action="store_true", help="also add each part's hull as a layer (always with --out)")
    d.add_argument("--part-files", action="store_true", help="also write every part and hull as its own OBJ")
    d.add_argument("--tree", action="store_true", help="also write the cut tree as tree.json")
    d.add_argument("--export", action="store_true",
                   help="also write collision hulls (OBJ, STL), a URDF, an MJCF and a MeshLab project to OUT/export")
    st = sub.add_parser("structure", formatter_class=fmt,
                        help="from the tree: a coarser level, the skeleton, the hull union")
    st.add_argument("mesh", nargs="?", help="mesh file (closed, or see --preprocessing)")
    st.add_argument("--demo", action="store_true", help="use pymeshlab's bundled bunny as MESH")
    st.add_argument("--out", required=True, help="folder for tree.json, skeleton.obj, hull_union.obj")
    st.add_argument("--no-progress", dest="progress", action="store_false", help="no progress bar")
    add_arguments(st, "tau", "preprocessing")
    st.add_argument("--coarser", type=float, default=3 * DEFAULTS["tau"],
                    help="coarser tau read back from the tree (%% of the size)")
    st.add_argument("--union-hull-vertices", type=int, default=64, help="per hull of the hull union")
    b = sub.add_parser("batch", formatter_class=fmt, help="decompose every mesh under a folder, with physics-ready export")
    b.add_argument("in_dir")
    b.add_argument("out_dir")
    b.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="meshes decomposed at once")
    b.add_argument("--ray", metavar="ADDRESS", help="run on a Ray cluster (ADDRESS, e.g. ray://head:10001 "
                   "or auto), or 'local' to start a local Ray instance of --workers CPUs")
    b.add_argument("--ray-runtime-env", metavar="JSON", help="Ray runtime_env for the workers, e.g. "
                   "'{\"pip\": [\"/shared/pymeshlab_acd-0.1.0-py3-none-any.whl\"]}'")
    add_arguments(b, "tau", "tau_unit", "cut_plane_selection", "max_parts", "merge_parts", "merge_measure", "cut_search",
                  "max_hull_vertices", "engine", "preprocessing", "wrap_alpha", "wrap_offset", "time_limit", "hole_handling", "hole_order",
                  "on_self_intersection", "threads")
    b.add_argument("--timeout", type=float, default=BATCH["timeout"],
                   help="per mesh process, killed after (s; 0: none)")
    b.add_argument("--formats", default=",".join(BATCH["formats"]), help="collision hull files: obj, stl or both")
    b.add_argument("--save-tree", action="store_true", help="also keep each mesh's tree.json (with geometry: "
                   "coarser levels later, without recomputing, by pymeshlab_acd.level_of_detail)")
    b.add_argument("--no-progress", dest="progress", action="store_false", help="no progress bar")
    r = sub.add_parser("robot", formatter_class=fmt, help="a URDF or MJCF robot with every link's collision "
                                                         "replaced by convex hulls (and USD for Isaac Sim)")
    r.add_argument("description", help="ROBOT.urdf or an MJCF ROBOT.xml")
    r.add_argument("--out", required=True, help="folder for the rewritten description, collision/ hulls, summary.json")
    r.add_argument("--package", action="append", metavar="NAME=FOLDER",
                   help="where package://NAME/ points (else the nearest folder NAME above the description, or "
                        "ROS_PACKAGE_PATH); repeatable")
    r.add_argument("--format", default="urdf,mjcf", help="what to write besides the input's own kind: urdf, mjcf, usd")
    r.add_argument("--resolve-paths", action="store_true", help="name kept meshes (visuals) by absolute paths "
                   "instead of package:// URIs, for simulators without a ROS package resolver (PyBullet)")
    r.add_argument("--no-progress", dest="progress", action="store_false", help="no progress line")
    add_arguments(r, "tau", "tau_unit", "cut_plane_selection", "max_parts", "merge_parts", "merge_measure", "cut_search",
                  "max_hull_vertices", "engine", "preprocessing", "wrap_alpha", "wrap_offset", "time_limit", "hole_handling", "hole_order",
                  "on_self_intersection", "threads")
    for s in (b, r):   # one cache for both: a robot's meshes and a batch's are decomposed once
        s.add_argument("--cache-dir", help="cache of decompositions by mesh content and options (default "
                                           "~/.cache/meshlab-acd/hulls)")
        s.add_argument("--no-cache", dest="cache", action="store_false", help="decompose every mesh again")
    for s in (d, b):
        s.add_argument("--scale", type=float, default=1.0, help="metres per model unit (URDF, MJCF)")
        s.add_argument("--density", type=float, default=1000.0, help="kg/m^3, for the mass and inertia")
    a = p.parse_args(argv)
    _check_paths(p, a)
    try:
        return {"concavity": cmd_concavity, "decompose": cmd_decompose, "polygon": cmd_polygon,
                "batch": cmd_batch, "structure": cmd_structure, "robot": cmd_robot}[a.cmd](a)
    except (pymeshlab.PyMeshLabException, ValueError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1


def _version():
    try:
        from importlib.metadata import version
        return version("pymeshlab_acd")
    except Exception:   # run from a source tree that is not installed
        return "unknown"


def _check_paths(p, a):
    """Arguments and output paths are checked before any work: a mistake costs no decomposition."""
    if hasattr(a, "demo"):
        if a.demo and a.mesh:
            p.error("give a mesh file or --demo, not both")
        if a.demo:
            a.mesh = BUNNY
        elif not a.mesh:
            p.error("give a mesh file (or --demo for pymeshlab's bunny)")
    for name in ("mesh", "polygon", "in_dir", "description"):
        path = getattr(a, name, None)
        if path and not os.path.exists(path):
            p.error(f"{path}: no such file or folder")
    for name in ("out", "out_dir"):
        path = getattr(a, name, None)
        if path and os.path.exists(path) and not os.path.isdir(path):
            p.error(f"--{name.replace('_', '-')} {path} is a file; it must be a folder (it is created if missing)")
    if getattr(a, "export", False) and not a.out:
        p.error("--export writes to OUT/export: give --out FOLDER")


if __name__ == "__main__":
    sys.exit(main())
