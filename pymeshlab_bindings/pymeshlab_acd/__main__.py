"""Command line: python -m pymeshlab_acd {concavity,decompose} [MESH] [options]

MESH defaults to pymeshlab's bundled bunny. Progress is printed while the filter runs.
"""
import argparse
import json
import os
import pathlib
import sys
import time

import pymeshlab

from . import decompose, load, mesh_ids

BUNNY = os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes", "bunny.obj")


def _meshset(path, verbose):
    load()
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    ms.set_verbosity(verbose)   # prints MeshLab's progress callback ("... [ 40% ]")
    return ms


def cmd_concavity(a):
    ms = _meshset(a.mesh, a.progress)
    r = ms.compute_scalar_by_notch_concavity()
    ms.set_verbosity(False)
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
    ms = _meshset(a.mesh, a.progress)
    src = ms.current_mesh_id()
    params = dict(tau=a.tau, tau_unit=a.tau_unit, cut_plane_selection=a.cut_plane_selection,
                  max_parts=a.max_parts, output_hulls=a.hulls, max_hull_vertices=a.max_hull_vertices,
                  time_limit=a.time_limit, preprocessing=a.preprocessing, wrap_alpha=a.wrap_alpha,
                  wrap_offset=a.wrap_offset, on_self_intersection=a.on_self_intersection,
                  hole_handling=a.hole_handling, hole_order=a.hole_order)
    t0 = time.perf_counter()
    res, ids = decompose(ms, **params)
    wall = time.perf_counter() - t0
    ms.set_verbosity(False)   # progress is over; keep the file saving quiet
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
    if a.out:
        out = pathlib.Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        for i in ids:
            m = ms.mesh(i)
            ms.set_current_mesh(i)
            ms.save_current_mesh(str(out / f"{m.label()}.obj"))
        (out / "tree.json").write_text(json.dumps(res["tree"], indent=1))
        summary = {k: v for k, v in res.items() if k != "tree"}
        (out / "summary.json").write_text(json.dumps(summary, indent=1, default=float))
        print(f"wrote            {len(ids)} layers as OBJ, tree.json, summary.json to {out}")
    return 0


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m pymeshlab_acd",
                                description="Approximate convex decomposition (Lien & Amato) through pymeshlab.")
    sub = p.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("concavity", help="measure notch concavity (compute_scalar_by_notch_concavity)")
    d = sub.add_parser("decompose", help="decompose (generate_approximate_convex_decomposition)")
    for s in (c, d):
        s.add_argument("mesh", nargs="?", default=BUNNY, help="closed mesh file (default: pymeshlab's bunny)")
        s.add_argument("--out", help="folder for output files")
        s.add_argument("--no-progress", dest="progress", action="store_false", help="do not print progress")
    d.add_argument("--tau", type=float, default=2.0, help="concavity tolerance (default 2 = 2%% of size)")
    d.add_argument("--tau-unit", default="percent_of_size", choices=["percent_of_size", "model_units"])
    d.add_argument("--cut-plane-selection", default="best", choices=["best", "bisector"])
    d.add_argument("--max-parts", type=int, default=0)
    d.add_argument("--hole-handling", default="best_plane", choices=["best_plane", "principal_plane", "keep_cavities"],
                   help="how cavities (closed inner shells) are resolved")
    d.add_argument("--hole-order", default="first", choices=["first", "by_concavity"],
                   help="cut cavities before notches (the paper) or in turn by concavity")
    d.add_argument("--hulls", action="store_true", help="also output each part's convex hull")
    d.add_argument("--max-hull-vertices", type=int, default=0)
    d.add_argument("--time-limit", type=float, default=0.0)
    d.add_argument("--preprocessing", default="none", choices=["none", "alpha_wrap"],
                   help="alpha_wrap: wrap dirty input (open, non-manifold, self-intersecting, points) first")
    d.add_argument("--wrap-alpha", type=float, default=1.0, help="alpha wrap: alpha, %% of size")
    d.add_argument("--wrap-offset", type=float, default=0.1, help="alpha wrap: offset, %% of size")
    d.add_argument("--on-self-intersection", default="warn", choices=["warn", "refuse"])
    a = p.parse_args(argv)
    try:
        return {"concavity": cmd_concavity, "decompose": cmd_decompose}[a.cmd](a)
    except pymeshlab.PyMeshLabException as e:
        print(f"error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
