"""Decompositions kept by content: each (mesh bytes, filter options, plugin build) is decomposed once, and a
re-run, another robot sharing the mesh, or a batch gets the stored result instead.

An entry is a folder named by the key: hull_<k>.obj (one object each, as PyBullet reads them), parts.obj
(part k in object k), tree.json (the filter's tree, with geometry) and result.json (the filter's numbers,
each hull's report, the layer names). Entries are written to a temporary folder and renamed, so a reader
sees a whole entry or none, and processes sharing the cache never see each other's half-written files.
"""
import functools
import hashlib
import json
import os
import pathlib
import shutil
import tempfile
import time

import numpy as np

from . import options
from .export import write_obj_objects

_KEY_VERSION = 2   # bump when what an entry holds changes


def default_cache():
    """~/.cache/meshlab-acd/hulls (ACD_CACHE or XDG_CACHE_HOME move it)."""
    root = os.environ.get("ACD_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "meshlab-acd")
    return pathlib.Path(root) / "hulls"


def cache_folder(cache=True, cache_dir=None):
    """The cache a run uses: `cache_dir`, else default_cache(); None when `cache` is off."""
    return (pathlib.Path(cache_dir) if cache_dir else default_cache()) if cache else None


@functools.lru_cache(maxsize=None)
def _plugin_digest():
    """The plugin binary's hash: another build may cut differently, so it is part of every key."""
    from . import plugin_path
    return hashlib.sha256(pathlib.Path(plugin_path()).read_bytes()).hexdigest()


def mesh_key(path, opts):
    """The cache key of a mesh file under options: its bytes, the options and the plugin build."""
    h = hashlib.sha256()
    h.update(pathlib.Path(path).read_bytes())
    h.update(_plugin_digest().encode())
    # 4 and 4.0 are one tau: numbers are typed as the defaults' are.
    typed = {k: float(v) if isinstance(options.DEFAULTS.get(k), float) else v for k, v in opts.items()}
    h.update(json.dumps(typed, sort_keys=True, default=str).encode())
    h.update(f"v{_KEY_VERSION}".encode())
    return h.hexdigest()[:24]


def hull_mesh(path, opts, cache_dir=None, threads=0):
    """The decomposition of the mesh file at `path` under `opts` (the filter's options, without threads), as
    an entry folder. Returns (folder, result, cached, key). The folder is `cache_dir`'s entry for the same
    bytes and options when there is one; otherwise the mesh is decomposed and the entry stored (without a
    cache_dir, in a temporary folder the caller removes). `threads` is not part of the key: the parts are
    the same for any count."""
    key = mesh_key(path, opts)
    entry = pathlib.Path(cache_dir) / key if cache_dir else None
    if entry and (entry / "result.json").exists():
        return entry, json.loads((entry / "result.json").read_text()), True, key
    parent = entry.parent if entry else pathlib.Path(tempfile.gettempdir())
    parent.mkdir(parents=True, exist_ok=True)
    tmp = pathlib.Path(tempfile.mkdtemp(dir=parent, prefix=".acd-"))
    try:
        result = _decompose_mesh(path, dict(opts, threads=threads), tmp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    if not entry:
        return tmp, result, False, key
    try:
        tmp.rename(entry)            # atomic: a reader sees a whole entry or none
    except OSError:                  # another process stored it first
        shutil.rmtree(tmp, ignore_errors=True)
    return entry, result, False, key


def _run_filter(path, opts, tree_file):
    """Decompose the mesh file with the hulls as layers (the tree written to `tree_file` when one is given).
    Returns (result, arrays): result with the layer names and part colours, arrays = (parts, hulls), each a
    list of (V, F) in the filter's layer order."""
    import pymeshlab
    from . import decompose, load
    load()
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    if ms.mesh_number() > 1:   # a file of several meshes (COLLADA scenes): one mesh
        ms.generate_by_merging_visible_meshes()
    t0 = time.perf_counter()
    res, ids = decompose(ms, with_tree=bool(tree_file), tree_file=str(tree_file or ""), output_hulls=True, **opts)
    tree = res.pop("tree", {})
    hulls = [i for i in ids if ms.mesh(i).label().startswith("acd_hull_")]
    parts = [i for i in ids if i not in hulls]
    res.update(seconds=time.perf_counter() - t0, collision=tree.get("collision", {}),
               hull_labels=[ms.mesh(i).label() for i in hulls], part_labels=[ms.mesh(i).label() for i in parts],
               part_colors=[ms.mesh(i).vertex_color_matrix()[0].tolist() for i in parts])   # one colour per part
    arrays = tuple([(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids] for ids in (parts, hulls))
    return res, arrays


def _decompose_mesh(path, opts, folder):
    """Decompose the mesh file into the entry files under `folder`; returns the result written there."""
    res, (parts, hulls) = _run_filter(path, opts, folder / "tree.json")
    for k, mesh in enumerate(hulls):
        write_obj_objects(folder / f"hull_{k}.obj", [mesh], "hull")
    write_obj_objects(folder / "parts.obj", parts, "part")
    (folder / "result.json").write_text(json.dumps(res, indent=1, default=float))
    return res


def fresh_layers(path, opts, threads=0, tree_file=None):
    """The decomposition of the mesh file under `opts`, computed now and kept in memory (no cache entry is
    written; the tree only to `tree_file`, when given). Returns (result, layers) as entry_layers gives them."""
    res, arrays = _run_filter(path, dict(opts, threads=threads), tree_file)
    return res, _layers(res, *arrays)


def read_objects(path):
    """(V, F) per object of an OBJ written by write_obj_objects (`o` lines, then each object's `v` lines
    and triangle `f` lines; `f a/b/c` corners read as a). Numbers are parsed a block at a time."""
    out, base = [], 1
    for block in ("\n" + pathlib.Path(path).read_text()).split("\no ")[1:]:
        lines = block.split("\n")[1:]
        v = " ".join(line[2:] for line in lines if line.startswith("v "))
        f = " ".join(line[2:] for line in lines if line.startswith("f "))
        if "/" in f:
            f = " ".join(t.split("/")[0] for t in f.split())
        V = np.array(v.split(), float).reshape(-1, 3)
        out.append((V, np.array(f.split(), np.int64).reshape(-1, 3) - base))
        base += len(V)
    return out


def entry_layers(folder, result):
    """An entry's parts and hulls as pymeshlab meshes with their layer names, [(label, Mesh)] each, in the
    filter's layer order and with the parts' colours."""
    parts = read_objects(folder / "parts.obj")
    hulls = [read_objects(folder / f"hull_{k}.obj")[0] for k in range(len(result["hull_labels"]))]
    return _layers(result, parts, hulls)


def _layers(result, parts, hulls):
    import pymeshlab
    return ([(n, pymeshlab.Mesh(V, F, v_color_matrix=np.tile(c, (len(V), 1))))
             for n, c, (V, F) in zip(result["part_labels"], result["part_colors"], parts)],
            [(n, pymeshlab.Mesh(V, F)) for n, (V, F) in zip(result["hull_labels"], hulls)])
