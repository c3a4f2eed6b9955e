#!/usr/bin/env python3
"""Robot corpus benchmark: every mesh of example-robot-data 6.0.0 (PyPI; 491 STL/OBJ meshes of robot
descriptions), decomposed at the filter's default settings, each part's hull checked against tau by
an independent measure (tests/hull_reach.py: scipy's Qhull and exact distances in numpy); and the peers
(CoACD 0.05 and 0.1, V-HACD 4, CGAL 16 and 45) beside ours on a fixed sample of 60 meshes that
represents every robot.

    scripts/bench.sh --robots             whole corpus (ours) and the 60-mesh sample (all methods)
    scripts/bench.sh --robots --quick     a fixed 20-mesh subset, ours and the peers
    scripts/bench.sh --robots --no-peers  ours only
Meshes closed as shipped are decomposed as given; open or non-manifold ones take the batch's `auto`
path (alpha wrap, with the hollow check). Writes out/robots/robots.md and robots.json.
"""
import argparse
import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time
import zipfile

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "scripts"))
sys.path.insert(0, str(REPO / "tests"))
import bench  # noqa: E402  (run_method, metrics, write_hulls, read_obj)

WHEEL = "example_robot_data-6.0.0-0-py3-none-any.whl"
WHEEL_SHA256 = "424092a8093411ac2cd4ccc0572382bfc6b5eb4833aa984ef5e671dd67cd0a6e"
PREFIX = "cmeel.prefix/share/example-robot-data/robots/"
DEFAULT = {"tau": 2.0, "cut_plane_selection": "best"}   # the filter's defaults
PEERS = [s for s in bench.SETTINGS if s[0] != "ours"]


def cache():
    return pathlib.Path(os.environ.get("ACD_CACHE") or pathlib.Path.home() / ".cache" / "meshlab-acd")


def fetch_corpus():
    """The wheel (pinned, checksum checked) into the cache, its meshes unpacked beside it."""
    root = cache() / "robots"
    meshes = root / "meshes"
    if (meshes / ".complete").exists():
        return meshes
    wheel = root / WHEEL
    if not wheel.exists() or hashlib.sha256(wheel.read_bytes()).hexdigest() != WHEEL_SHA256:
        root.mkdir(parents=True, exist_ok=True)
        subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-deps", "-d", str(root),
                        "example-robot-data==6.0.0"], check=True)
        if hashlib.sha256(wheel.read_bytes()).hexdigest() != WHEEL_SHA256:
            raise SystemExit(f"{wheel}: checksum mismatch (expected {WHEEL_SHA256})")
    with zipfile.ZipFile(wheel) as z:
        for info in z.infolist():
            name = info.filename
            if name.startswith(PREFIX) and name.lower().endswith((".stl", ".obj", ".ply")):
                dst = meshes / name[len(PREFIX):]
                dst.parent.mkdir(parents=True, exist_ok=True)
                dst.write_bytes(z.read(info))
    (meshes / ".complete").touch()
    return meshes


def corpus(meshes):
    return sorted(p for p in meshes.rglob("*") if p.suffix.lower() in (".stl", ".obj", ".ply"))


def robot_of(p, meshes):
    return p.relative_to(meshes).parts[0]


def sample(files, meshes, n):
    """A fixed sample of n meshes with every robot represented: robots in turn, each robot's meshes
    in name order, until n are taken."""
    by_robot = {}
    for p in files:
        by_robot.setdefault(robot_of(p, meshes), []).append(p)
    out, k = [], 0
    while len(out) < min(n, len(files)):
        for r in sorted(by_robot):
            if k < len(by_robot[r]) and len(out) < n:
                out.append(by_robot[r][k])
        k += 1
    return sorted(out)


# ---- ours, through the batch's child process (auto preprocessing), then the certificate ---------
def run_ours(src, out_dir, timeout):
    from pymeshlab_acd import batch
    opts = dict(batch.DEFAULTS, tau=DEFAULT["tau"], cut_plane_selection=DEFAULT["cut_plane_selection"],
                max_hull_vertices=0, formats=["obj"], timeout=timeout)
    t0 = time.perf_counter()
    rec = batch.run_child(src, out_dir, opts)
    rec["wall"] = time.perf_counter() - t0
    return rec


def certificate(out_dir, tau_abs):
    """Worst part's hull distance / tau over the exported parts, measured independently."""
    import numpy as np
    import pymeshlab
    from hull_reach import hull_reach
    worst, over = 0.0, 0
    for ply in sorted((pathlib.Path(out_dir) / "parts").glob("*.ply")):
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(ply))
        V, F = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
        lower, upper = hull_reach(V, F, slack=0.01 * tau_abs, limit=tau_abs)
        worst = max(worst, min(upper, lower if np.isinf(upper) else upper) / tau_abs)
        over += upper > 1.01 * tau_abs
    return worst, over


def hulls_obj(out_dir, dst):
    files = sorted((pathlib.Path(out_dir) / "collision").glob("acd_hull_*.obj"))
    bench.write_hulls(dst, [bench.read_obj(f) for f in files])
    return len(files)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="a fixed 20-mesh subset (ours and the peers)")
    ap.add_argument("--no-peers", action="store_true", help="ours only")
    ap.add_argument("--sample", type=int, default=60, help="meshes the peers run on (every robot represented)")
    ap.add_argument("--limit", type=int, default=0, help="at most this many meshes for ours (0: all)")
    ap.add_argument("--samples", type=int, default=100000, help="Monte Carlo samples per metric")
    ap.add_argument("--timeout", type=int, default=900, help="seconds per method run")
    ap.add_argument("--out", default=str(REPO / "out" / "robots"))
    args = ap.parse_args()
    meshes = fetch_corpus()
    files = corpus(meshes)
    peer_set = set(sample(files, meshes, 20 if args.quick else args.sample))
    if args.quick:
        files = sorted(peer_set)
    elif args.limit:
        files = files[:args.limit]
    out = pathlib.Path(args.out)
    (out / "inputs").mkdir(parents=True, exist_ok=True)
    print(f"[robots] {len(files)} meshes; peers on {0 if args.no_peers else len(peer_set)}", flush=True)
    print("| mesh | faces | method | setting | hulls | hull error (% diag) | volume IoU | time (s) | "
          "worst hull / tau | preprocessing |\n|---|---|---|---|---|---|---|---|---|---|", flush=True)
    rows = []
    for p in files:
        name = p.relative_to(meshes).with_suffix("").as_posix()
        inp = out / "inputs" / (name.replace("/", "__") + ".obj")
        if not inp.exists():
            bench.to_obj(p, inp)
        faces = bench.face_count(inp)
        with tempfile.TemporaryDirectory() as tmp:
            rec = run_ours(p, pathlib.Path(tmp) / "o", args.timeout)
            row = dict(mesh=name, faces=faces, method="ours", setting="tau 2% best (default)")
            if rec.get("status") != "ok":
                row["error"] = str(rec.get("error"))[:200]
            else:
                worst, over = certificate(pathlib.Path(tmp) / "o", rec["tau_model_units"])
                hobj = pathlib.Path(tmp) / "hulls.obj"
                row.update(hulls=hulls_obj(pathlib.Path(tmp) / "o", hobj), time=rec["time"], worst=worst,
                           over=over, preprocessing=rec["preprocessing"], tau_convex=rec.get("tau_convex"))
                row.update(bench.metrics(inp, hobj, args.samples))
        rows.append(row)
        print(line(row), flush=True)
        if p in peer_set and not args.no_peers:
            for method, label, params in PEERS:
                hobj = out / "hulls" / f"{name.replace('/', '__')}__{method}__{label.split()[0]}{label.split()[1]}.obj"
                hobj.parent.mkdir(exist_ok=True)
                r = bench.run_method(method, params, inp, hobj, args.timeout)
                if "error" not in r:
                    r.update(bench.metrics(inp, hobj, args.samples))
                rows.append(dict(mesh=name, faces=faces, method=method, setting=label, **r))
                print(line(rows[-1]), flush=True)
        json.dump(rows, open(out / "robots.json", "w"), indent=1)
    summary = summarize(rows, peer_set, meshes)
    print("\n".join(summary))
    (out / "robots.md").write_text("\n".join(summary) + "\n")


def line(r):
    if "error" in r:
        return f"| {r['mesh']} | {r['faces']} | {r['method']} | {r['setting']} | error: {r['error'][:80]} | | | | | |"
    iou = "n/a" if r.get("iou") is None else f"{r['iou']:.3f}"
    worst = f"{r['worst']:.2f}" if "worst" in r else ""
    return (f"| {r['mesh']} | {r['faces']} | {r['method']} | {r['setting']} | {r['hulls']} | "
            f"{100 * r.get('hull_error', float('nan')):.2f} | {iou} | {r['time']:.2f} | {worst} | "
            f"{r.get('preprocessing', '')} |")


def summarize(rows, peer_set, meshes):
    ours = [r for r in rows if r["method"] == "ours"]
    ok = [r for r in ours if "error" not in r]
    over = sum(r["over"] for r in ok)
    parts = sum(r["hulls"] for r in ok)
    out = [f"Ours at default settings on {len(ours)} meshes: {len(ok)} decomposed, {len(ours) - len(ok)} failed; "
           f"{parts} parts, {over} of them with a hull farther than tau (+1%) from the part by the independent "
           f"measure; worst part hull / tau {max((r['worst'] for r in ok), default=0):.3f}; "
           f"{sum(1 for r in ok if r['preprocessing'] != 'none')} wrapped; total time "
           f"{sum(r['time'] for r in ok):.0f} s.", ""]
    keyed = {}
    for r in rows:
        keyed.setdefault(r["mesh"], {})[(r["method"], r["setting"])] = r
    sample_meshes = [m for m, d in keyed.items() if len(d) > 1]
    if sample_meshes:
        out.append(f"Peers on the {len(sample_meshes)}-mesh sample (medians; time summed):")
        out.append("")
        out.append("| method | setting | median hulls | median hull error (% diag) | total time (s) | failures |")
        out.append("|---|---|---|---|---|---|")
        settings = [("ours", "tau 2% best (default)")] + [(m, l) for m, l, _ in PEERS]
        for key in settings:
            rs = [keyed[m].get(key) for m in sample_meshes]
            good = [r for r in rs if r and "error" not in r]
            med = lambda xs: sorted(xs)[len(xs) // 2] if xs else float("nan")
            out.append(f"| {key[0]} | {key[1]} | {med([r['hulls'] for r in good])} | "
                       f"{100 * med([r['hull_error'] for r in good]):.2f} | {sum(r['time'] for r in good):.0f} | "
                       f"{len(rs) - len(good)} |")
    return out


if __name__ == "__main__":
    sys.exit(main())
