#!/usr/bin/env python3
"""Benchmark: our decomposition beside CoACD, V-HACD 4 (vhacdx) and CGAL 6.2's voxel ACD.

Every method runs in its own child process on the same OBJ input; its hulls are scored by one
neutral tool (acd_metrics, C++): hull count, hull error (largest distance from the surface of the
union of hulls to the input surface, fraction of the bounding-box diagonal; split into outside the
solid and inside it for closed inputs), volume IoU with the
input solid (Monte Carlo, with its standard error). Wall time is the decomposition call alone; peak
memory is the child's whole-process peak resident set (its VmHWM). For ours also the paper's
concavity of the parts (the filter's max part concavity, fraction of the diagonal).

    bench/bench.sh                 whole corpus and the scaling table (about an hour on 2 cores)
    bench/bench.sh --quick         the bunny only, no scaling
    bench/bench.sh --quick --parts-before old/libfilter_acd.so   and that build's parts beside this one's
    bench/bench.sh --meshes cow spot --no-scaling
Writes out/bench/bench.md and out/bench/bench.png.
"""
import argparse
import datetime
import json
import math
import os
import pathlib
import platform
import subprocess
import sys
import textwrap
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED = REPO.parent / "shared" / "data" / "meshes"

# (method, setting label, parameters). Ours in bisector mode is the fast one; best mode for quality.
SETTINGS = [
    ("ours", "tau 5% best", {"tau": 5.0, "cut_plane_selection": "best"}),
    ("ours", "tau 3% bisector", {"tau": 3.0, "cut_plane_selection": "bisector"}),
    ("ours", "tau 2% bisector", {"tau": 2.0, "cut_plane_selection": "bisector"}),
    ("coacd", "threshold 0.05 (default)", {"threshold": 0.05}),
    ("coacd", "threshold 0.1", {"threshold": 0.1}),
    ("vhacd4", "resolution 100k", {"resolution": 100000}),
    ("vhacd4", "resolution 400k (default)", {"resolution": 400000}),
    ("cgal", "16 volumes (default)", {"max_hulls": 16}),
    ("cgal", "45 volumes", {"max_hulls": 45}),
]


def build_dir():
    return pathlib.Path(os.environ["ACD_BUILD_DIR"])


def corpus(names):
    """pymeshlab's bunny, cow, bone and airplane and the shared meshes, closed and manifold ones
    only (all methods get the same solid; ours refuses open input), each shape once."""
    import pymeshlab
    samples = pathlib.Path(pymeshlab.__file__).parent / "tests" / "sample_meshes"
    meshes = [samples / n for n in ("bunny.obj", "cow.obj", "bone.ply", "airplane.obj")]
    if SHARED.is_dir():
        meshes += sorted(p for p in SHARED.iterdir() if p.suffix in (".obj", ".ply", ".off", ".stl"))
    out, seen = [], set()
    for p in meshes:
        name = ("pymeshlab-" if p.parent == samples else "") + p.stem
        if p.stem in seen or (names and not any(n in name for n in names)):
            continue
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(p))
        t = ms.get_topological_measures()
        if t["boundary_edges"] or t["non_two_manifold_edges"]:
            print(f"[bench] skipping {name}: not a closed manifold solid", flush=True)
            continue
        seen.add(p.stem)
        out.append((name, p))
    return out


def to_obj(src, dst):
    """The mesh as plain triangles, what every method gets."""
    import pymeshlab
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(src))
    ms.save_current_mesh(str(dst), save_vertex_normal=False, save_vertex_color=False,
                         save_wedge_texcoord=False, save_face_color=False)


def face_count(obj):
    with open(obj) as f:
        return sum(1 for line in f if line.startswith("f "))


def read_obj(path):
    import numpy as np
    V, F = [], []
    for line in open(path):
        if line.startswith("v "):
            V.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            idx = [int(t.split("/")[0]) - 1 for t in line.split()[1:]]
            F += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return np.array(V, float), np.array(F, np.int64)


def write_hulls(path, hulls):
    from pymeshlab_acd.export import write_obj_objects
    write_obj_objects(path, hulls, "hull")


# ---- one method run, inside a child process ----------------------------------------------------
def run_child(method, params, inp, hulls_out):
    params = json.loads(params)
    info = {}
    if method == "ours":
        import pymeshlab
        import pymeshlab_acd  # noqa: F401  (the installed package; binds the filters)
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(inp)
        t0 = time.perf_counter()
        res = ms.generate_approximate_convex_decomposition(output_hulls=True, **params)
        secs = time.perf_counter() - t0
        hulls = []
        for i in range(ms.mesh_number() * 2 + 2):
            if ms.mesh_id_exists(i) and ms.mesh(i).label().startswith("acd_hull_"):
                m = ms.mesh(i)
                hulls.append((m.vertex_matrix(), m.face_matrix()))
        info["concavity"] = res["max_concavity"]
        info["bbox_diag"] = ms.mesh(0).bounding_box().diagonal()
        info.update({k: res.get(k) for k in ("preprocessing_time", "preprocessing_done", "holes_filled", "holes_on_planes", "wrap_capped", "wrap_skin",
                                         "wrap_alpha_used", "solid_to_input", "input_to_solid", "size")})
        info.update(parts_fingerprint(ms))
    else:
        V, F = read_obj(inp)
        t0 = time.perf_counter()
        if method == "coacd":
            import coacd
            coacd.set_log_level("error")
            parts = coacd.run_coacd(coacd.Mesh(V, F), **params)
            hulls = [(p[0], p[1]) for p in parts]
        elif method == "vhacd4":
            import numpy as np
            import vhacdx
            hulls = vhacdx.compute_vhacd(V, F.astype(np.uint32), **params)
        else:
            raise SystemExit("unknown method " + method)
        secs = time.perf_counter() - t0
    write_hulls(hulls_out, hulls)
    info.update(time=secs, hulls=len(hulls), peak_mb=peak_rss_mb())
    print("RESULT " + json.dumps(info))


def parts_fingerprint(ms, ids=None):
    """Count, total volume and a hash of the exact vertices and faces of the layers `ids` (default: the
    part layers, acd_* but not acd_hull_*)."""
    import hashlib
    import numpy as np
    if ids is None:
        ids = [i for i in range(ms.mesh_number() * 2 + 2) if ms.mesh_id_exists(i) and
               ms.mesh(i).label().startswith("acd_") and not ms.mesh(i).label().startswith("acd_hull_")]
    h, vol = hashlib.sha256(), 0.0
    for i in ids:
        V, F = ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()
        h.update(V.tobytes() + F.tobytes())
        vol += float(np.einsum("ij,ij->i", V[F[:, 0]], np.cross(V[F[:, 1]], V[F[:, 2]])).sum() / 6)
    return dict(parts=len(ids), parts_volume=vol, parts_sha=h.hexdigest()[:16])


def peak_rss_mb():
    """This process's own peak resident set (VmHWM starts afresh at exec, unlike ru_maxrss, which
    keeps the forking parent's size)."""
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024.0
    return None


def run_method(method, params, inp, hulls_out, timeout, plugin=None):
    if method == "cgal":
        cmd = [str(build_dir() / "core" / "cgal_acd_peer"), str(inp), str(hulls_out), str(params["max_hulls"])]
    else:
        cmd = [sys.executable, __file__, "--child", method, json.dumps(params), str(inp), str(hulls_out)]
    try:
        env = dict(os.environ, ACD_PLUGIN=str(plugin)) if plugin else None
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return {"error": "timeout after %d s" % timeout}
    out = r.stdout
    if method == "cgal":
        words = out.split()
        if len(words) >= 6 and words[0] == "hulls":
            return {"hulls": int(words[1]), "time": float(words[3]), "peak_mb": float(words[5]) / 1024.0}
        return {"error": (out + r.stderr).strip()[-300:]}
    for line in out.splitlines():
        if line.startswith("RESULT "):
            return json.loads(line[7:])
    msg = r.stderr.strip().splitlines()
    return {"error": (msg[-1] if msg else "exit status %d" % r.returncode)[:300]}


def metrics(inp, hulls, samples):
    r = subprocess.run([str(build_dir() / "core" / "acd_metrics"), str(inp), str(hulls), str(samples)],
                       capture_output=True, text=True, timeout=1800)
    try:
        return json.loads(r.stdout)
    except ValueError:
        return {"error": (r.stdout + r.stderr).strip()[-300:]}


def fmt(x, spec):
    return "n/a" if x is None else format(x, spec)


def inputs(args, outdir):
    """(name, OBJ copy) of each corpus mesh, converted once into outdir/inputs."""
    folder = outdir / "inputs"
    folder.mkdir(parents=True, exist_ok=True)
    for name, src in corpus(args.meshes):
        inp = folder / (name + ".obj")
        if not inp.exists():
            to_obj(src, inp)
        yield name, inp


def parts_side_by_side(args, outdir):
    """Ours at the defaults with another plugin build and with this one: the same parts?"""
    print("| mesh | parts (other / this) | parts' volume (other / this) | identical |\n|---|---|---|---|", flush=True)
    for name, inp in inputs(args, outdir):
        runs = [run_method("ours", {}, inp, outdir / "parts_check.obj", args.timeout, plugin)
                for plugin in (args.parts_before, None)]
        a, b = runs
        same = "error" not in a and all(a.get(k) == b.get(k) for k in ("parts", "parts_volume", "parts_sha"))
        print(f"| {name} | {a.get('parts', a.get('error'))} / {b.get('parts', b.get('error'))} | "
              f"{a.get('parts_volume')} / {b.get('parts_volume')} | {'yes' if same else 'NO'} |", flush=True)
    print(flush=True)


def bench_corpus(args, outdir):
    rows = []
    for name, inp in inputs(args, outdir):
        faces = face_count(inp)
        for method, label, params in SETTINGS:
            hulls = outdir / "hulls" / f"{name}__{method}__{label.split()[0]}{label.split()[1]}.obj"
            hulls.parent.mkdir(exist_ok=True)
            r = run_method(method, params, inp, hulls, args.timeout)
            if "error" not in r:
                r.update(metrics(inp, hulls, args.samples))
            row = dict(mesh=name, faces=faces, method=method, setting=label, **r)
            rows.append(row)
            print(row_line(row), flush=True)
    return rows


def row_line(r):
    if "error" in r:
        return f"| {r['mesh']} | {r['faces']} | {r['method']} | {r['setting']} | error: {r['error'][:80]} | | | | | | |"
    conc = r.get("concavity")
    conc = fmt(100 * conc / r["bbox_diag"], ".2f") if conc is not None else ""
    iou = "n/a" if r.get("iou") is None else f"{r['iou']:.3f} ± {r['iou_stderr']:.3f}"
    side = ("n/a" if r.get("hull_error_outside") is None else
            f"{100 * r['hull_error_outside']:.2f} / {100 * r['hull_error_inside']:.2f}")
    return (f"| {r['mesh']} | {r['faces']} | {r['method']} | {r['setting']} | {r['hulls']} | "
            f"{100 * r['hull_error']:.2f} | {side} | {iou} | {r['time']:.2f} | {r['peak_mb']:.0f} | {conc} |")


HEADER = ("| mesh | faces | method | setting | hulls | hull error (% diag) | outside / inside (% diag) | "
          "volume IoU | time (s) | peak memory (MB) | part concavity (% diag) |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|")


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    meshes = list(dict.fromkeys(r["mesh"] for r in rows))
    cols = min(4, len(meshes))
    nrows = math.ceil(len(meshes) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.4 * nrows), squeeze=False)
    markers = {"ours": "o", "coacd": "s", "vhacd4": "^", "cgal": "D"}
    colors = plt.cm.tab10.colors
    keys = [(m, l) for m, l, _ in SETTINGS]
    for ax, mesh in zip(axes.flat, meshes):
        for r in rows:
            if r["mesh"] != mesh or "error" in r:
                continue
            k = keys.index((r["method"], r["setting"]))
            ax.scatter(r["hulls"], 100 * r["hull_error"], marker=markers[r["method"]], color=colors[k % 10],
                       s=45, label=f"{r['method']} {r['setting']}")
        ax.set_title(mesh, fontsize=9)
        ax.set_xlabel("hulls")
        ax.set_ylabel("hull error (% diag)")
        ax.set_xscale("log")
    for ax in list(axes.flat)[len(meshes):]:
        ax.axis("off")
    handles, labels = [], []
    for ax in axes.flat:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8)
    fig.tight_layout(rect=(0, 0.06 + 0.02 * nrows / 2, 1, 1))
    fig.savefig(path, dpi=110)


def scaling(args, outdir):
    """Our filter at growing face counts of one shape (igea, or the bunny without the shared data)."""
    import pymeshlab
    src = SHARED / "igea.ply"
    if not src.exists():
        src = pathlib.Path(pymeshlab.__file__).parent / "tests" / "sample_meshes" / "bunny.obj"
    sdir = outdir / "scaling"
    sdir.mkdir(parents=True, exist_ok=True)
    # Meshes are made in a child: a child forked from a big parent would report the parent's memory.
    make = textwrap.dedent("""
        import sys, pymeshlab
        src, n0, t, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(src)
        if t < n0:
            ms.meshing_decimation_quadric_edge_collapse(targetfacenum=t, preservetopology=True)
        elif t > n0:   # midpoint subdivision: 4x the faces, same shape
            ms.meshing_surface_subdivision_midpoint(iterations=1, threshold=pymeshlab.PercentageValue(0))
        ms.save_current_mesh(out, save_vertex_normal=False, save_vertex_color=False,
                             save_wedge_texcoord=False, save_face_color=False)
        print(ms.current_mesh().face_number() if t == 0 else "")
    """)
    n0 = int(subprocess.run([sys.executable, "-c", make, str(src), "0", "0", str(sdir / "original.obj")],
                            check=True, capture_output=True, text=True).stdout)
    targets = [10000, 50000, 100000, n0, 4 * n0]
    paths = []
    for t in targets:
        p = sdir / f"{src.stem}_{t}.obj"
        if not p.exists():
            subprocess.run([sys.executable, "-c", make, str(src), str(n0), str(t), str(p)], check=True)
        paths.append(p)
    rows = []
    for p in paths:
        faces = face_count(p)
        r = run_method("ours", {"tau": 3.0, "cut_plane_selection": "bisector"}, p, sdir / "hulls.obj", args.timeout)
        r["faces"] = faces
        rows.append(r)
        print(f"| {faces} | {r.get('hulls', 'n/a')} | {fmt(r.get('time'), '.2f')} | {fmt(r.get('peak_mb'), '.0f')} |"
              + (f" {r['error']}" if "error" in r else ""), flush=True)
    ok = [r for r in rows if "error" not in r and r["time"] > 0]
    exp = None
    if len(ok) >= 2:
        xs = [math.log(r["faces"]) for r in ok]
        ys = [math.log(r["time"]) for r in ok]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        exp = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return src.stem, rows, exp


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--child", nargs=4, metavar=("METHOD", "PARAMS", "INPUT", "HULLS"), help=argparse.SUPPRESS)
    ap.add_argument("--quick", action="store_true", help="bunny only, no scaling table")
    ap.add_argument("--meshes", nargs="*", help="substrings of mesh names to keep")
    ap.add_argument("--no-scaling", action="store_true")
    ap.add_argument("--scaling-only", action="store_true")
    ap.add_argument("--samples", type=int, default=200000, help="Monte Carlo samples per metric")
    ap.add_argument("--timeout", type=int, default=900, help="seconds per method run")
    ap.add_argument("--out", default=str(REPO / "out" / "bench"))
    ap.add_argument("--parts-before", metavar="PLUGIN",
                    help="also decompose with this other build of the plugin (libfilter_acd.so) at the defaults "
                         "and print both builds' parts side by side (count, volume, exact hash)")
    args = ap.parse_args()
    if args.child:
        return run_child(*args.child)
    if args.quick:
        args.meshes, args.no_scaling = ["pymeshlab-bunny"], True
    outdir = pathlib.Path(args.out)
    outdir.mkdir(parents=True, exist_ok=True)
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    machine = f"{platform.system()} {platform.release()}, {os.cpu_count()} cores ({cpu}), " \
              f"{os.sysconf('SC_PAGE_SIZE') * os.sysconf('SC_PHYS_PAGES') / 2**30:.0f} GiB"
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    if args.scaling_only:
        print("| faces | parts | time (s) | peak memory (MB) |\n|---|---|---|---|", flush=True)
        shape, srows, exp = scaling(args, outdir)
        print("Fitted exponent (time ~ faces^k): k = " + fmt(exp, ".2f"))
        return
    if args.parts_before:
        parts_side_by_side(args, outdir)
    print(HEADER, flush=True)
    rows = bench_corpus(args, outdir)
    plot(rows, outdir / "bench.png")
    md = [f"Benchmark of {started} on {machine}.", "", "Command: `bench/bench.sh " + " ".join(sys.argv[1:]) + "`",
          "", HEADER] + [row_line(r) for r in rows]
    if not args.no_scaling:
        print("\n| faces | parts | time (s) | peak memory (MB) |\n|---|---|---|---|", flush=True)
        shape, srows, exp = scaling(args, outdir)
        md += ["", f"Scaling of our filter (tau 3%, bisector) on {shape} decimated / as is / midpoint-subdivided:", "",
               "| faces | parts | time (s) | peak memory (MB) |", "|---|---|---|---|"]
        md += [f"| {r['faces']} | {r.get('hulls', 'n/a')} | {fmt(r.get('time'), '.2f')} | {fmt(r.get('peak_mb'), '.0f')} |"
               + (f" {r['error']} |" if "error" in r else "") for r in srows]
        md += ["", "Fitted exponent (time ~ faces^k): k = " + fmt(exp, ".2f")]
    (outdir / "bench.md").write_text("\n".join(md) + "\n")
    json.dump(rows, open(outdir / "bench.json", "w"), indent=1)
    print("\n".join(md[-12:]) if not args.no_scaling else "")
    print(f"[bench] {outdir / 'bench.md'} and {outdir / 'bench.png'}")


if __name__ == "__main__":
    sys.exit(main())
