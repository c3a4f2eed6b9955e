"""Batch decomposition: every mesh under a folder, each in its own process, on local workers or a Ray
cluster; physics-ready export per mesh; resumable; one summary (CSV + JSON) for the whole batch.

Each mesh runs in a child process (``python -m pymeshlab_acd.batch --one``) so a mesh that crashes,
hangs or exhausts memory costs only its own record, never the batch. Outputs are written to
``<name>.partial`` and renamed when complete, so a finished folder is never half-written: a rerun skips
folders whose summary.json says "ok" for the same options and retries the rest.
"""
import csv
import hashlib
import json
import os
import pathlib
import shutil
import socket
import subprocess
import sys
import tempfile
import time

from . import options

MESH_EXTENSIONS = {".obj", ".ply", ".stl", ".off", ".3ds", ".dae", ".wrl", ".gltf", ".glb", ".vmi"}

DEFAULTS = dict(options.DEFAULTS, timeout=1800.0, formats=["obj", "stl"], scale=1.0, density=1000.0, save_tree=False,
                cache=True, cache_dir=None)

# The options that change a mesh's outputs (a rerun with other values redoes the mesh).
# threads is not one of them (the parts are the same for any count), nor is the cache.
_OUTPUT_KEYS = ("tau", "tau_unit", "cut_plane_selection", "max_parts", "merge_parts", "merge_measure", "cut_search", "max_hull_vertices",
                "engine",
                "preprocessing",
                "wrap_alpha", "wrap_offset", "time_limit", "hole_handling", "hole_order", "on_self_intersection",
                "formats", "scale", "density", "save_tree")


SUMMARY_FIELDS = ("file", "status", "parts", "max_concavity", "max_concavity_pct", "hull_volume_ratio",
                  "preprocessing", "faces", "time", "cached", "worker", "error", "output")


def options_key(opts):
    return hashlib.sha1(json.dumps({k: opts[k] for k in _OUTPUT_KEYS}, sort_keys=True).encode()).hexdigest()[:12]


def find_meshes(in_dir, *skip):
    """Mesh files under in_dir (recursively, not those under the `skip` folders: a batch's own outputs and
    its cache are not its inputs), sorted, with their output folder names (relative)."""
    root = pathlib.Path(in_dir)
    skip = [pathlib.Path(d).resolve() for d in skip if d]
    files = sorted(p for p in root.rglob("*") if p.is_file() and p.suffix.lower() in MESH_EXTENSIONS
                   and not any(p.resolve().is_relative_to(d) for d in skip))
    stems = {}
    for p in files:
        stems.setdefault(p.relative_to(root).with_suffix(""), []).append(p)
    jobs = []
    for p in files:
        rel = p.relative_to(root).with_suffix("")
        # a.obj and a.ply side by side: keep both, named by extension
        name = rel if len(stems[rel]) == 1 else rel.with_name(rel.name + "_" + p.suffix[1:].lower())
        jobs.append((p, name.as_posix()))
    return jobs


# ---- one mesh, in a child process ------------------------------------------------------------
def decompose_file(src, out_dir, opts):
    """Decompose one mesh file and export it to out_dir; returns the summary record (raises on failure).
    The decomposition comes from the shared cache (hull_cache) when the same bytes were decomposed under
    the same options before, by a batch or a robot; it is stored there otherwise. With the cache off, nothing
    is stored: the parts and hulls go from the filter to the export in memory."""
    import numpy as np
    import pymeshlab
    from . import load
    from .export import merged_layers, export_decomposition, mass_properties
    from .hull_cache import cache_folder, entry_layers, fresh_layers, hull_mesh

    load()
    t0 = time.perf_counter()
    # The filter prepares the mesh by the core's one policy (preprocessing auto: as given, welded, holes filled or
    # wrapped, and a solid that crosses itself wrapped when its parts as given fall short of tau).
    filter_opts = {k: opts[k] for k in options.DEFAULTS if k != "threads"}
    cache_dir = cache_folder(opts["cache"], opts["cache_dir"])
    if cache_dir is None:   # nothing kept: the layers stay in memory, the tree goes only where it is asked for
        tree_file = pathlib.Path(out_dir) / "tree.json" if opts["save_tree"] else None
        if tree_file:
            tree_file.parent.mkdir(parents=True, exist_ok=True)
        res, layers = fresh_layers(src, filter_opts, opts["threads"], tree_file)
        cached = False
    else:
        entry, res, cached, _ = hull_mesh(src, filter_opts, cache_dir, opts["threads"])
        layers = entry_layers(entry, res)
        if opts["save_tree"]:   # for coarser levels later
            shutil.copyfile(entry / "tree.json", pathlib.Path(out_dir) / "tree.json")
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(src))
    if ms.mesh_number() > 1:   # as the decomposition saw it
        ms.generate_by_merging_visible_meshes()
    source = ms.current_mesh_id()
    ids = []
    for label, mesh in layers[0] + layers[1]:
        ms.add_mesh(mesh, mesh_name=label)
        ids.append(ms.current_mesh_id())
    parts, hulls = ids[:len(layers[0])], ids[len(layers[0]):]
    vol = mass_properties(*merged_layers(ms, parts))[0]      # the solid decomposed (the wrap, if wrapped)
    hull_vol = sum(mass_properties(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix())[0] for i in hulls)
    wrap = f"alpha_wrap {res['wrap_alpha_used']:.3g}%" + (
        ", openings capped" if res.get("wrap_capped") else ", a skin" if res.get("wrap_skin") else "")
    pre = ("none", f"welded {res['welded_vertices']} vertices", wrap,
           f"{res.get('holes_filled', 0)} holes filled")[res["preprocessing_done"]]
    note = ("wrapped: as given, it intersects itself and its parts fell short of tau or a cut opened a part"
            if res["self_crossing_wrapped"] else _not_as_given(res))
    written = export_decomposition(ms, source, parts, hulls, out_dir, name=pathlib.Path(src).stem,
                                   formats=tuple(opts["formats"]), scale=opts["scale"], density=opts["density"])
    m = ms.mesh(source)
    diag = float(np.linalg.norm(m.bounding_box().max() - m.bounding_box().min()))
    rec = dict(status="ok", parts=res["parts"], max_concavity=res["max_concavity"],
               tau_model_units=res["tau_model_units"], max_hull_distance=res["max_hull_distance"],
               tau_convex=res["tau_convex"],
               max_concavity_pct=100.0 * res["max_concavity"] / diag if diag > 0 else 0.0,
               hull_volume_ratio=hull_vol / vol, preprocessing=pre, faces=ms.mesh(source).face_number(),
               time=time.perf_counter() - t0, error=note, files=written, options_key=options_key(opts),
               worker=f"{socket.gethostname()}:{os.getpid()}", max_parts_reached=res["max_parts_reached"],
               time_limit_reached=res.get("time_limit_reached", False), engine=opts["engine"],
               hulls_reduced=res["hulls_reduced"], hull_reach=res["hull_reach"],
               collision_hull_distance=res["collision_hull_distance"], cached=cached)
    (pathlib.Path(out_dir) / "summary.json").write_text(json.dumps(rec, indent=1, default=float))
    return rec


# Why a mesh was not decomposed as given, by the core's error code (acd::Error::Code, in its order).
NOT_AS_GIVEN = ("", "a point cloud ({} vertices)", "{} faces repeat a vertex", "{} zero-area faces",
                "{} duplicate faces", "open ({} boundary edges)", "{} non-manifold edges",
                "{} misoriented edges", "a cut opened a part", "its boundary touches itself", "it intersects itself")


def _not_as_given(res):
    code = res.get("not_as_given_code", 0)
    if not code or res["preprocessing_done"] == 0:
        return ""
    how = "holes filled" if res["preprocessing_done"] == 3 else "wrapped"
    return how + ": as given, " + NOT_AS_GIVEN[code].format(res["not_as_given_count"]) if code < len(NOT_AS_GIVEN) else ""


def _reason(e):
    """One line of why: MeshLab's details without pymeshlab's 'Failed to apply filter' preamble."""
    text = str(e).strip()
    if "Details:" in text:
        text = text.split("Details:", 1)[1]
    return " ".join(text.split()) or type(e).__name__


def run_child(src, out_dir, opts):
    """Run decompose_file in a child process; returns its record, or a failure record."""
    out_dir = pathlib.Path(out_dir)
    tmp = out_dir.with_name(out_dir.name + ".partial")
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "pymeshlab_acd.batch", "--one", str(src), str(tmp), json.dumps(opts)]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=opts["timeout"] or None)
        err = None
        if p.returncode != 0:
            lines = [l for l in p.stderr.strip().splitlines() if l.strip()]
            err = (lines[-1] if lines and p.returncode > 0
                   else f"the process died (exit {p.returncode}); last output: {lines[-1] if lines else '-'}")
    except subprocess.TimeoutExpired:
        err = f"timed out after {opts['timeout']:.0f} s"
    if err is None and (tmp / "summary.json").is_file():
        shutil.rmtree(out_dir, ignore_errors=True)
        tmp.rename(out_dir)
        return json.loads((out_dir / "summary.json").read_text())
    shutil.rmtree(tmp, ignore_errors=True)
    return dict(status="failed", error=(err or "no output").removeprefix("error: "),
                time=time.perf_counter() - t0)


def finished(out_dir, opts):
    """The record of an earlier run of the same options, if it completed."""
    f = pathlib.Path(out_dir) / "summary.json"
    try:
        rec = json.loads(f.read_text())
    except (OSError, ValueError):
        return None
    return rec if rec.get("status") == "ok" and rec.get("options_key") == options_key(opts) else None


# ---- Ray: the same child process, on whichever node runs the task -------------------------------
def _ray_task(name, data, basename, opts):
    """Runs on a Ray worker: the mesh travels as bytes and the outputs come back as bytes, so the
    nodes need no shared file system, only pymeshlab_acd installed."""
    with tempfile.TemporaryDirectory() as tmp:
        src = pathlib.Path(tmp) / basename      # the name gives the model files theirs
        src.write_bytes(data)
        rec = run_child(src, pathlib.Path(tmp) / "out", opts)
        files = {}
        if rec["status"] == "ok":
            base = pathlib.Path(tmp) / "out"
            files = {p.relative_to(base).as_posix(): p.read_bytes() for p in base.rglob("*") if p.is_file()}
        rec["worker"] = f"ray:{socket.gethostname()}:{os.getpid()}"   # the Ray worker, not its child
        return name, rec, files


def _run_ray(todo, out_root, opts, address, workers, runtime_env, on_done):
    import ray
    init = dict(include_dashboard=False, log_to_driver=False, ignore_reinit_error=True)
    if runtime_env:
        init["runtime_env"] = runtime_env
    started_here = not ray.is_initialized()
    if address == "local":
        ray.init(num_cpus=workers, **init)
    else:
        ray.init(address=address, **init)
    try:
        task = ray.remote(num_cpus=1, max_retries=0)(_ray_task)
        # A window of tasks in flight, so thousands of meshes are not all in the object store at once.
        window = 2 * max(1, int(ray.cluster_resources().get("CPU", workers)))
        queue, names, pending = list(todo), {}, []
        while queue or pending:
            while queue and len(pending) < window:
                src, name = queue.pop(0)
                ref = task.remote(name, src.read_bytes(), src.name, opts)
                names[ref] = name
                pending.append(ref)
            done, pending = ray.wait(pending, num_returns=1)
            for ref in done:
                try:
                    name, rec, files = ray.get(ref)
                except Exception as e:   # the Ray worker itself died: record it, go on
                    name, rec, files = names[ref], dict(status="failed", error=f"Ray task failed: {e}".splitlines()[0]), {}
                if rec["status"] == "ok":
                    out = out_root / name
                    tmp = out.with_name(out.name + ".partial")
                    shutil.rmtree(tmp, ignore_errors=True)
                    for rel, data in files.items():
                        (tmp / rel).parent.mkdir(parents=True, exist_ok=True)
                        (tmp / rel).write_bytes(data)
                    shutil.rmtree(out, ignore_errors=True)
                    tmp.rename(out)
                on_done(name, rec)
    finally:
        if started_here:
            ray.shutdown()


# ---- the batch ----------------------------------------------------------------------------------
def run_batch(in_dir, out_dir, workers=1, ray_address=None, ray_runtime_env=None, progress=True, **options):
    """Decompose every mesh under in_dir into out_dir/<name>/; returns the list of summary records
    (also written to out_dir/summary.csv and summary.json)."""
    from concurrent.futures import ThreadPoolExecutor, as_completed
    from .hull_cache import cache_folder
    opts = dict(DEFAULTS)
    unknown = set(options) - set(opts)
    if unknown:
        raise ValueError("unknown batch options: " + ", ".join(sorted(unknown)))
    opts.update(options)
    if not opts["threads"]:   # each mesh decomposed at once gets its share of the cores, not all of them
        opts["threads"] = max(1, (os.cpu_count() or 1) // max(1, workers))
    if not opts["tau"] > 0:
        raise ValueError(f"tau must be positive (got {opts['tau']})")
    out_root = pathlib.Path(out_dir)
    out_root.mkdir(parents=True, exist_ok=True)
    jobs = find_meshes(in_dir, out_root, cache_folder(opts["cache"], opts["cache_dir"]))
    if not jobs:
        raise ValueError(f"no mesh files under {in_dir} (looked for {', '.join(sorted(MESH_EXTENSIONS))})")
    records = {}
    todo = []
    for src, name in jobs:
        rec = finished(out_root / name, opts)
        if rec is not None:
            records[name] = dict(rec, status="done before")
        else:
            todo.append((src, name))
    source_of = {name: src for src, name in jobs}

    bar = _progress(len(jobs), initial=len(records), enabled=progress)

    def on_done(name, rec):
        records[name] = rec
        bar.update(1)
        bar.set_postfix_str(f"{name}: {rec['status']}")
        _write_summary(out_root, records, source_of, in_dir)

    try:
        if ray_address:
            _run_ray(todo, out_root, opts, ray_address, workers, ray_runtime_env, on_done)
        else:
            with ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
                futs = {pool.submit(run_child, src, out_root / name, opts): name for src, name in todo}
                for f in as_completed(futs):
                    on_done(futs[f], f.result())
    finally:
        bar.close()
        _write_summary(out_root, records, source_of, in_dir)
    return [dict(records[n], file=str(source_of[n])) for _, n in jobs if n in records]


def _write_summary(out_root, records, source_of, in_dir):
    rows = []
    for name in sorted(records):
        r = records[name]
        row = {k: r.get(k, "") for k in SUMMARY_FIELDS}
        row["file"] = str(pathlib.Path(source_of[name]).relative_to(in_dir))
        row["output"] = name if r["status"] in ("ok", "done before") else ""
        rows.append(row)
    tmp = out_root / "summary.json.tmp"
    tmp.write_text(json.dumps(rows, indent=1, default=float))
    tmp.replace(out_root / "summary.json")
    with open(out_root / "summary.csv.tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=SUMMARY_FIELDS)
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    (out_root / "summary.csv.tmp").replace(out_root / "summary.csv")


def _progress(total, initial, enabled):
    try:
        from tqdm import tqdm
        return tqdm(total=total, initial=initial, unit="mesh", disable=not enabled, dynamic_ncols=True)
    except ImportError:   # a plain counter on stderr
        class Bar:
            n = initial

            def update(self, k):
                self.n += k

            def set_postfix_str(self, s):
                if enabled:
                    print(f"[{self.n}/{total}] {s}", file=sys.stderr)

            def close(self):
                pass
        return Bar()


def _main_one(argv):
    src, out, opts = argv[0], argv[1], json.loads(argv[2])
    try:
        decompose_file(src, out, opts)
    except Exception as e:   # one clear line for the batch's record
        print(f"error: {_reason(e)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--one":
        sys.exit(_main_one(sys.argv[2:]))
    sys.exit("usage: python -m pymeshlab_acd batch IN_DIR OUT_DIR (this module's own entry is internal)")
