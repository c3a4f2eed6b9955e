#!/usr/bin/env python3
"""Time against face count: ours at the defaults beside CoACD 0.05 and V-HACD's default, in one run.

Two series of the same shape at growing face counts:
  scan  pymeshlab's bunny made watertight by screened Poisson (depth 8), decimated to ~23k faces, then
        Loop-subdivided once, twice and three times (~92k, ~368k, ~1.5M faces);
  CAD   one closed robot link (example-robot-data), every face split at its edges' midpoints 0 to 3
        times: the same geometry, four times the faces per step.
Each method runs in its own child process (bench.py's run_method): wall time of the call alone, peak
memory of the child, hulls, and the two-sided hull error by the neutral acd_metrics tool.

    bench/bench.sh --scale                      both series, every method
    bench/bench.sh --scale --methods ours       ours only
    bench/bench.sh --scale --series CAD         the CAD series only (the plot keeps the scan's last run)
Writes bench/results/scale_scan.md, bench/results/scale_CAD.md and docs/scale.png.
"""
import argparse
import hashlib
import json
import os
import pathlib
import platform
import subprocess
import sys
import textwrap

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
import bench  # noqa: E402  (run_method, metrics, face_count)

CACHE = pathlib.Path(os.environ.get("XDG_CACHE_HOME", pathlib.Path.home() / ".cache")) / "meshlab-acd" / "scale"
METHODS = [("ours", "defaults", {}), ("coacd", "threshold 0.05", {"threshold": 0.05}),
           ("vhacd4", "default (400k voxels)", {"resolution": 400000})]

# Meshes are made in a child process: pymeshlab's filters hold the GIL and much memory. A series is its
# first mesh (the watertight bunny scan, or the CAD link as given) and three subdivisions of it: Loop for
# the scan, midpoints for CAD (the same flat faces). Screened Poisson runs on one thread: on several its
# surface differs from run to run, and so would the series.
MAKE_SERIES = textwrap.dedent("""
    import pathlib, sys, pymeshlab
    series, src, out = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    ms = pymeshlab.MeshSet()
    if series == "scan":
        ms.load_new_mesh(str(pathlib.Path(pymeshlab.__file__).parent / "tests" / "sample_meshes" / "bunny.obj"))
        ms.generate_surface_reconstruction_screened_poisson(depth=8, threads=1)
        ms.meshing_decimation_quadric_edge_collapse(targetfacenum=23000, preservetopology=True)
        ms.meshing_remove_unreferenced_vertices()
        subdivide = ms.meshing_surface_subdivision_loop
    else:
        ms.load_new_mesh(src)
        ms.meshing_remove_duplicate_vertices()
        subdivide = ms.meshing_surface_subdivision_midpoint
    for k in range(4):
        if k:
            subdivide(iterations=1, threshold=pymeshlab.PercentageValue(0))
        ms.save_current_mesh(str(out / f"{series}_{k}.obj"), save_vertex_normal=False, save_vertex_color=False,
                             save_wedge_texcoord=False, save_face_color=False)
""")


def cad_link():
    """The robot corpus's first closed, 2-manifold link (by path) with 3,000 to 12,000 faces that does not
    cross itself (a crossing link is alpha wrapped, which would time the wrap, not the search)."""
    import pymeshlab
    sys.path.insert(0, str(REPO / "tests"))
    from support import robots
    for path in robots.corpus(robots.fetch_corpus()):
        ms = pymeshlab.MeshSet()
        try:
            ms.load_new_mesh(str(path))
            ms.meshing_remove_duplicate_vertices()
        except pymeshlab.PyMeshLabException:
            continue
        m = ms.current_mesh()
        t = ms.get_topological_measures()
        if 3000 <= m.face_number() <= 12000 and not t["boundary_edges"] and not t["non_two_manifold_edges"] \
                and t["connected_components_number"] == 1:
            ms.compute_selection_by_self_intersections_per_face()
            if ms.current_mesh().selected_face_number() == 0:
                return path
    raise SystemExit("no closed robot link of 3k to 12k faces in the corpus")


def make(name, src=""):
    """The series `name` in the cache, made again when its source or the recipe has changed."""
    key = f"{src} {hashlib.sha256(MAKE_SERIES.encode()).hexdigest()[:16]}"
    made = CACHE / f"{name}_made.txt"
    if not made.exists() or made.read_text().strip() != key or not (CACHE / f"{name}_3.obj").exists():
        subprocess.run([sys.executable, "-c", MAKE_SERIES, name, src, str(CACHE)], check=True)
        made.write_text(key + "\n")
    return [CACHE / f"{name}_{k}.obj" for k in range(4)]


def series(which):
    CACHE.mkdir(parents=True, exist_ok=True)
    out = []
    if "scan" in which:
        out += [("scan", p, None) for p in make("scan")]
    if "CAD" in which:
        link = cad_link()
        out += [("CAD", p, link) for p in make("cad", str(link))]
    return out


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, name in zip(axes, ("scan", "CAD")):
        for method, label, _ in METHODS:
            pts = [(r["faces"], r["time"]) for r in rows if r["series"] == name and r["method"] == method and "time" in r]
            if pts:
                ax.loglog(*zip(*pts), marker="o", label=f"{method} ({label})")
        ax.set_title(f"{name} series")
        ax.set_xlabel("faces")
        ax.set_ylabel("time (s)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--methods", nargs="*", default=[m[0] for m in METHODS])
    ap.add_argument("--series", nargs="*", default=["scan", "CAD"], choices=["scan", "CAD"],
                    help="each series is written to bench/results/scale_<series>.md")
    ap.add_argument("--timeout", type=int, default=900, help="seconds per method run")
    ap.add_argument("--samples", type=int, default=200000, help="samples per hull error")
    ap.add_argument("--results", default=str(REPO / "bench" / "results"))
    ap.add_argument("--plot", default=str(REPO / "docs" / "scale.png"))
    args = ap.parse_args()
    for name in args.series:
        run_series(args, name)
    rows = []
    for name in ("scan", "CAD"):   # the plot shows both series, from their latest runs
        f = pathlib.Path(args.results) / f"scale_{name}.json"
        if f.exists():
            rows += json.load(open(f))
    plot(rows, args.plot)
    print(f"[bench] {args.plot}")


def run_series(args, which):
    meshes = series([which])
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    head = ["| series | faces | method | setting | hulls | hull error (% diag) | time (s) | peak memory (MB) | notes |",
            "|---|---|---|---|---|---|---|---|---|"]
    print("\n".join(head), flush=True)
    rows, lines = [], []
    for name, inp, link in meshes:
        faces = bench.face_count(inp)
        for method, label, params in METHODS:
            if method not in args.methods:
                continue
            hulls = CACHE / f"hulls_{inp.stem}_{method}.obj"
            r = bench.run_method(method, params, inp, hulls, args.timeout)
            if "error" not in r:
                r.update(bench.metrics(inp, hulls, args.samples))
            r.update(series=name, faces=faces, method=method, setting=label)
            rows.append(r)
            if "error" in r and "time" not in r:
                line = f"| {name} | {faces} | {method} | {label} | | | | | {r['error'][:80]} |"
            else:
                err = r.get("hull_error")
                line = (f"| {name} | {faces} | {method} | {label} | {r['hulls']} | "
                        f"{'n/a' if err is None else format(100 * err, '.2f')} | {r['time']:.2f} | {r['peak_mb']:.0f} | |")
            lines.append(line)
            print(line, flush=True)
    what = (f"the {which} series: the CAD link is `{link.relative_to(link.parents[2])}`" if link else f"the {which} series")
    md = [f"Scaling benchmark, {what}; on {platform.system()} {platform.release()}, {os.cpu_count()} cores ({cpu}); "
          f"command `bench/bench.sh --scale {' '.join(sys.argv[1:])}`.", ""] + head + lines
    out = pathlib.Path(args.results) / f"scale_{which}.md"
    out.write_text("\n".join(md) + "\n")
    json.dump(rows, open(out.with_suffix(".json"), "w"), indent=1)
    print(f"[bench] {out}")


if __name__ == "__main__":
    sys.exit(main())
