#!/usr/bin/env python3
"""Open meshes against closed ones: ours at the defaults (preprocessing auto), the two-sided hull error by
the neutral acd_metrics tool, per set.

Two sets, each with its closed meshes and open ones:
  shared    the shared meshes (../shared/data/meshes): the closed ones, the open ones as they come (the
            bunny scan with holes in its base, open figures, a teapot of open pieces, ...), and three closed
            ones with 1, 3 and 10 holes of growing size punched in (tests/support/open_meshes.py);
  modelled  CAD solids made with manifold3d (tests/support/cad_solids.py, refined), closed, punched with
            1, 3 and 10 holes, as a triangle soup and with a patch turned.
The target: every open mesh's error at most 1.5x the median error of the closed meshes of its set, none
above 2x. A punched mesh is scored against the closed solid it was made from (its error to the input is
at least its largest hole's radius, whatever closes the hole); open meshes as they come, against
themselves. And the time of preprocessing against the decomposition that follows on a 1M-face open scan
(the bunny scan, its holes kept, Loop-subdivided twice: 1.1M faces).

    bench/bench.sh --open                 both sets and the 1M-face scan
    bench/bench.sh --open --methods ours coacd    CoACD 0.05 beside ours
Writes bench/results/open.md and open.json.
"""
import argparse
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(REPO / "tests"))
import bench  # noqa: E402
from support import cad_solids  # noqa: E402
from support.open_meshes import flipped_patch, punched, refined, soup  # noqa: E402

CACHE = pathlib.Path(os.environ.get("XDG_CACHE_HOME", pathlib.Path.home() / ".cache")) / "meshlab-acd" / "open"
SHARED = REPO.parent / "shared" / "data" / "meshes"
METHODS = {"ours": ("defaults", {}), "coacd": ("threshold 0.05", {"threshold": 0.05})}
PUNCHED_SHARED = ("spot.obj", "fandisk.obj", "homer.obj")
CAD = ("bracket", "flange", "spur_gear", "belt_pulley", "bossed_plate", "t_slot_rail")


def write_obj(path, V, F):
    from pymeshlab_acd.export import write_obj_objects
    write_obj_objects(path, [(V, F)], "mesh")


def load(path):
    import pymeshlab
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    return ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()


def is_open(V, F):
    import numpy as np
    e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return bool((counts != 2).any())


def shared_set(folder):
    """(name, kind, obj path, the closed solid it was made from or None) of the shared set."""
    for p in sorted(SHARED.iterdir()):
        if p.suffix not in (".obj", ".ply"):
            continue
        V, F = load(p)
        src = folder / (p.stem + ".obj")
        write_obj(src, V, F)
        yield p.stem, "open" if is_open(V, F) else "closed", src, None
        if p.name in PUNCHED_SHARED:
            for holes in (1, 3, 10):
                out = folder / f"{p.stem}_{holes}holes.obj"
                write_obj(out, *punched(V, F, holes))
                yield f"{p.stem} {holes} holes", "punched", out, src


def modelled_set(folder):
    for name in CAD:
        V, F = refined(*cad_solids.make(name))
        src = folder / (name + ".obj")
        write_obj(src, V, F)
        yield name, "closed", src, None
        variants = [(f" {h} holes", punched(V, F, h)) for h in (1, 3, 10)]
        variants += [(" soup, 3 holes", soup(*punched(V, F, 3))),
                     (" turned patch, 3 holes", flipped_patch(*punched(V, F, 3)))]
        for suffix, (V2, F2) in variants:
            out = folder / (name + suffix.replace(" ", "_").replace(",", "") + ".obj")
            write_obj(out, V2, F2)
            yield name + suffix, "punched", out, src


def scan_1m():
    """The bunny scan (holes kept) Loop-subdivided twice, made once into the cache."""
    out = CACHE / "bunny_scan_1m.obj"
    if not out.exists():
        CACHE.mkdir(parents=True, exist_ok=True)
        subprocess.run([sys.executable, "-c", (
            "import pymeshlab, sys\n"
            "ms = pymeshlab.MeshSet(); ms.load_new_mesh(sys.argv[1])\n"
            "for _ in range(2): ms.meshing_surface_subdivision_loop(iterations=1, "
            "threshold=pymeshlab.PercentageValue(0))\n"
            "ms.save_current_mesh(sys.argv[2])\n"), str(SHARED / "stanford-bunny.obj"), str(out)], check=True)
    return out


def run(name, kind, inp, methods, args, folder, closed=None):
    rows = []
    for method in methods:
        label, params = METHODS[method]
        hulls = folder / "hulls" / f"{inp.stem}__{method}.obj"
        hulls.parent.mkdir(exist_ok=True)
        r = bench.run_method(method, params, inp, hulls, args.timeout)
        if "error" not in r:
            r.update(bench.metrics(inp, hulls, args.samples))
            if closed is not None:   # what the punched mesh stands for
                r["closed_error"] = bench.metrics(closed, hulls, args.samples).get("hull_error")
        row = dict(mesh=name, kind=kind, faces=bench.face_count(inp), method=method, **r)
        print(json.dumps({k: row.get(k) for k in ("mesh", "kind", "faces", "method", "hulls", "hull_error", "time",
                                                   "preprocessing_time", "wrap_capped", "wrap_skin", "error")}),
              flush=True)
        rows.append(row)
    return rows


def pct(x):
    return "n/a" if x is None else f"{100 * x:.2f}"


def prep(r):
    if r.get("preprocessing_done") == 2:
        how = "capped" if r.get("wrap_capped") else "skin" if r.get("wrap_skin") else "wrapped"
        return f"wrap {r['wrap_alpha_used']:.3g}%, {how}"
    if r.get("preprocessing_done") == 3:
        return f"{r.get('holes_filled')} holes filled ({r.get('holes_on_planes') or 0} on planes)"
    return ("as given", "welded")[r.get("preprocessing_done", 0)]


def table(set_name, rows):
    ours = [r for r in rows if r["method"] == "ours" and "error" not in r]
    closed = [r["hull_error"] for r in ours if r["kind"] == "closed"]
    median = statistics.median(closed) if closed else None
    lines = [f"### {set_name}: median hull error of the closed meshes {pct(median)}% of the diagonal", "",
             "| mesh | kind | faces | method | hulls | hull error (% diag) | x closed median | to the closed solid "
             "(% diag, x median) | preprocessing | solid to input / input to solid (% size) | preprocessing (s) | "
             "total (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "error" in r:
            lines.append(f"| {r['mesh']} | {r['kind']} | {r['faces']} | {r['method']} | error: {r['error'][:60]} "
                         "| | | | | | | |")
            continue
        ratio = f"{r['hull_error'] / median:.2f}" if median else ""
        closed = (f"{pct(r['closed_error'])}, {r['closed_error'] / median:.2f}"
                  if median and r.get("closed_error") is not None else "")
        ours_only = r["method"] == "ours"
        dist = (f"{pct(r['solid_to_input'] / r['size'])} / {pct(r['input_to_solid'] / r['size'])}"
                if ours_only else "")
        lines.append(f"| {r['mesh']} | {r['kind']} | {r['faces']} | {r['method']} | {r['hulls']} | "
                     f"{pct(r['hull_error'])} | {ratio} | {closed} | {prep(r) if ours_only else ''} | {dist} | "
                     f"{r['preprocessing_time']:.2f} | {r['time']:.2f} |" if ours_only else
                     f"| {r['mesh']} | {r['kind']} | {r['faces']} | {r['method']} | {r['hulls']} | "
                     f"{pct(r['hull_error'])} | {ratio} | {closed} | | | | {r['time']:.2f} |")
    for kind, key, what in (("open", "hull_error", "to the input"), ("punched", "closed_error", "to the closed solid")):
        ratios = [r[key] / median for r in ours if r["kind"] == kind and r.get(key) is not None] if median else []
        if ratios:
            lines += ["", f"{kind.capitalize()} meshes (ours): {len(ratios)}; error {what} over the closed median: "
                          f"median {statistics.median(ratios):.2f}x, largest {max(ratios):.2f}x; at most 1.5x: "
                          f"{sum(x <= 1.5 for x in ratios)}, at most 2x: {sum(x <= 2 for x in ratios)}."]
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--methods", nargs="+", default=["ours"], choices=sorted(METHODS))
    ap.add_argument("--sets", nargs="+", default=["shared", "modelled", "scan_1m"])
    ap.add_argument("--samples", type=int, default=100000)
    ap.add_argument("--timeout", type=int, default=900)
    ap.add_argument("--out", default=str(REPO / "bench" / "results"))
    args = ap.parse_args()
    folder = REPO / "out" / "bench_open"
    folder.mkdir(parents=True, exist_ok=True)
    out = pathlib.Path(args.out)
    results, lines = {}, [f"Open meshes, {platform.node()}, {os.cpu_count()} cores; command: "
                          f"`{' '.join(['bench/bench.sh', '--open'] + sys.argv[1:])}`", ""]
    for set_name, make in (("shared", shared_set), ("modelled", modelled_set)):
        if set_name in args.sets:
            rows = [row for name, kind, inp, closed in make(folder)
                    for row in run(name, kind, inp, args.methods, args, folder, closed)]
            results[set_name] = rows
            lines += table(set_name, rows) + [""]
    if "scan_1m" in args.sets:
        r = run("bunny scan, Loop x2", "open", scan_1m(), ["ours"], args, folder)[0]
        results["scan_1m"] = r
        if "error" not in r:
            lines += ["### A 1.1M-face open scan", "",
                      f"{r['faces']} faces: preprocessing {r['preprocessing_time']:.2f} s ({prep(r)}), decomposition "
                      f"{r['time'] - r['preprocessing_time']:.2f} s, {r['hulls']} hulls, hull error "
                      f"{pct(r['hull_error'])}%, peak memory {r['peak_mb']:.0f} MB.", ""]
    (out / "open.md").write_text("\n".join(lines) + "\n")
    (out / "open.json").write_text(json.dumps(results, indent=1, default=str) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
