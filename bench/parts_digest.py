#!/usr/bin/env python3
"""Fingerprint of what the filters return on a fixed set of cases, for changes that must not change
results (refactors): per case the part count, the parts' total volume and a hash of every output
layer's exact vertex and face arrays. Run it once per plugin build and compare:

    ACD_PLUGIN=old/libfilter_acd.so python3 bench/parts_digest.py > old.json
    ACD_PLUGIN=new/libfilter_acd.so python3 bench/parts_digest.py --compare old.json

Cases: CAD solids (manifold3d) with every cut_plane_selection, the bundled bunny, a 2D polygon with
holes, the skeleton and the hull union."""
import argparse
import json
import pathlib
import sys

import pymeshlab

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
from support import cad_solids  # noqa: E402
sys.path.insert(0, str(REPO / "bench"))
import bench  # noqa: E402
import pymeshlab_acd  # noqa: E402
from pymeshlab_acd import polygon_io  # noqa: E402

DATA = REPO.parent / "shared" / "data"


def layers_digest(ms, first):
    """Part count, volume sum and exact hash of the layers added after id `first`."""
    f = bench.parts_fingerprint(ms, [i for i in pymeshlab_acd.mesh_ids(ms) if i > first])
    return dict(layers=f["parts"], volume=round(f["parts_volume"], 9), sha=f["parts_sha"])


def solid(ms, name):
    v, f = cad_solids.make(name)
    ms.add_mesh(pymeshlab.Mesh(v, f), name)


# Robot meshes (example-robot-data, when bench/bench.sh --robots has cached it): a film-dropping gripper
# link, a closed link as given, an open one (welded or wrapped).
ROBOT_MESHES = ["z1_description/meshes/collision/z1_GripperMover.STL",
                "ur_description/meshes/ur10/collision/forearm.stl",
                "laikago_description/meshes/hip.obj",
                "double_pendulum_description/meshes/link2.stl"]


def hollow_box(ms):
    """An L-shaped block with a closed cavity inside."""
    import manifold3d as mf
    block = mf.Manifold.cube([6, 4, 3]) + mf.Manifold.cube([2, 4, 6])
    v, f = cad_solids._arrays(block - mf.Manifold.cube([2, 2, 1]).translate([3, 1, 1]))
    ms.add_mesh(pymeshlab.Mesh(v, f), "hollow_box")


def polygon(ms, path):
    v, e = polygon_io.loops_to_mesh(polygon_io.read_loops(str(path)))
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, edge_matrix=e), "polygon")


def cases():
    for name in ("keyway", "flange", "pocket", "stepped_shaft", "t_slot_rail", "spur_gear"):
        for sel in ("best", "bisector", "min_section"):
            yield f"{name} {sel}", lambda ms, n=name: solid(ms, n), "decompose", dict(cut_plane_selection=sel)
    for hh in ("principal_plane", "best_plane", "keep_cavities"):
        yield f"hollow box {hh}", hollow_box, "decompose", dict(hole_handling=hh)
    yield "hollow box by_concavity", hollow_box, "decompose", dict(hole_order="by_concavity")
    bunny = pathlib.Path(pymeshlab.__file__).parent / "tests" / "sample_meshes" / "bunny.obj"
    yield "bunny default", lambda ms: ms.load_new_mesh(str(bunny)), "decompose", {}
    yield "bunny max_parts 5", lambda ms: ms.load_new_mesh(str(bunny)), "decompose", dict(max_parts=5)
    yield "keyway skeleton", lambda ms: solid(ms, "keyway"), "skeleton", {}
    yield "flange hull union", lambda ms: solid(ms, "flange"), "union", {}
    robots = None
    try:
        from support import robots as corpus
        robots = corpus.cache() / "robots" / "meshes"
    except Exception:
        pass
    for rel in ROBOT_MESHES:
        if robots is not None and (robots / rel).exists():
            yield rel.split("/")[-1], lambda ms, f=robots / rel: ms.load_new_mesh(str(f)), "decompose", \
                dict(preprocessing="auto")
    for poly in ("fisheye", "dsb", "batlogo"):
        yield f"{poly} 2D", lambda ms, p=poly: polygon(ms, DATA / "polygons" / f"{p}.poly"), "polygon", {}


def run_case(setup, kind, params):
    ms = pymeshlab.MeshSet()
    pymeshlab_acd.load()
    setup(ms)
    first = max(pymeshlab_acd.mesh_ids(ms))
    if kind == "decompose":
        res = ms.generate_approximate_convex_decomposition(**params)
    elif kind == "skeleton":
        res = ms.generate_skeleton_from_convex_decomposition(**params)
    elif kind == "union":
        res = ms.generate_convex_hull_union(**params)
    else:
        res = ms.generate_polygon_approximate_convex_decomposition(**params)
    out = layers_digest(ms, first)
    out["result"] = {k: (round(v, 9) if isinstance(v, float) else v) for k, v in sorted(res.items())
                     if isinstance(v, (int, float, bool, str)) and "time" not in k}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--compare", help="a digest from another build: print both side by side")
    args = ap.parse_args()
    rows = {}
    for label, setup, kind, params in cases():
        rows[label] = run_case(setup, kind, params)
        print(f"{label}: {rows[label]['layers']} layers, volume {rows[label]['volume']}, {rows[label]['sha']}",
              file=sys.stderr, flush=True)
    if not args.compare:
        print(json.dumps(rows, indent=1))
        return
    old = json.loads(pathlib.Path(args.compare).read_text())
    print("| case | layers (other / this) | volume (other / this) | identical |\n|---|---|---|---|")
    same, added = 0, set()
    for label, r in rows.items():
        o = old.get(label, {})
        # Result keys only one build reports (a key added since) are listed, not counted as a change.
        shared = set(o.get("result", {})) & set(r["result"])
        added |= set(r["result"]) ^ set(o.get("result", {}))
        eq = (o.get("sha"), o.get("layers")) == (r["sha"], r["layers"]) and all(
            o["result"][k] == r["result"][k] for k in shared)
        same += eq
        print(f"| {label} | {o.get('layers')} / {r['layers']} | {o.get('volume')} / {r['volume']} | "
              f"{'yes' if eq else 'NO'} |")
    print(f"\n{same} of {len(rows)} cases identical (layers' exact vertices and faces, and the filter's result)")
    if added:
        print("result keys in one build only: " + ", ".join(sorted(added)))
    sys.exit(0 if same == len(rows) else 1)


if __name__ == "__main__":
    main()
