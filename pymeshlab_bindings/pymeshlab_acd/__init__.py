"""Approximate convex decomposition filters for pymeshlab.

``import pymeshlab_acd`` loads the meshlab-acd plugin into pymeshlab (once per process) and binds its
filters as ``pymeshlab.MeshSet`` methods::

    import pymeshlab, pymeshlab_acd
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh("bunny.obj")
    ms.compute_scalar_by_notch_concavity()
    ms.generate_approximate_convex_decomposition(tau=2.5)
    ms.generate_polygon_approximate_convex_decomposition(tau=1.0)   # on a planar polygon layer

or, from arrays, without a MeshSet::

    hulls = pymeshlab_acd.convex_decomposition(vertices, faces, tau=2.5)   # [(V, F), ...]

``tau`` is a float (percent of the size, or model units with ``tau_unit="model_units"``), or, as in
pymeshlab's own filters, ``pymeshlab.PercentageValue`` (percent of the bounding-box diagonal) or
``pymeshlab.PureValue`` (model units).
"""
import functools
import json
import os
import pathlib

import pymeshlab

__all__ = ["FILTERS", "plugin_path", "load", "decompose", "decompose_polygon", "level_of_detail", "mesh_ids",
           "convex_decomposition", "decompose_robot"]

# Python names of the plugin's filters (keep in sync with FilterACD::pythonFilterName).
FILTERS = (
    "compute_scalar_by_notch_concavity",
    "generate_approximate_convex_decomposition",
    "generate_polygon_approximate_convex_decomposition",
    "generate_convex_decomposition_level_of_detail",
    "generate_skeleton_from_convex_decomposition",
    "generate_convex_hull_union",
)

_PLUGIN = "libfilter_acd.so"
_loaded = None


def plugin_path():
    """Where the plugin is: $ACD_PLUGIN, the copy installed with this package, or a build in the cache."""
    candidates = []
    if os.environ.get("ACD_PLUGIN"):
        candidates.append(pathlib.Path(os.environ["ACD_PLUGIN"]))
    candidates.append(pathlib.Path(__file__).resolve().parent / "lib" / _PLUGIN)
    cache = os.environ.get("ACD_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "meshlab-acd")
    # Builds of several checkouts may share the cache: the newest first.
    candidates += sorted(pathlib.Path(cache).glob("build-double-*/filter_acd/" + _PLUGIN),
                         key=lambda p: p.stat().st_mtime, reverse=True)
    for c in candidates:
        if c.is_file():
            return c
    raise FileNotFoundError(
        "meshlab-acd plugin not found (looked in: %s). Build it with scripts/build_plugin.sh or "
        "pip install --no-build-isolation ./pymeshlab_bindings" % ", ".join(map(str, candidates)))


def load():
    """Load the plugin into pymeshlab and bind its filters; safe to call any number of times."""
    global _loaded
    if _loaded is None:
        path = plugin_path()
        if not all(name in pymeshlab.filter_list() for name in FILTERS):
            pymeshlab.load_plugin(str(path))   # a second load of the same plugin raises
        for name in FILTERS:
            method = _reset_log_on_error(pymeshlab.bind_function(name))
            method.__doc__ = _docstring(name)
            setattr(pymeshlab.MeshSet, name, method)
        _loaded = path
    return _loaded


def _docstring(name):
    """The filter's parameters with their types and defaults, as pymeshlab lists them (it prints them
    from C++ on the standard output's file descriptor, which is read back here)."""
    import ctypes
    import sys
    import tempfile
    text = ""
    try:
        sys.stdout.flush()
        with tempfile.TemporaryFile(mode="w+") as tmp:
            saved = os.dup(1)
            try:
                os.dup2(tmp.fileno(), 1)
                pymeshlab.print_filter_parameter_list(name)
                ctypes.CDLL(None).fflush(None)
            finally:
                os.dup2(saved, 1)
                os.close(saved)
            tmp.seek(0)
            text = tmp.read()
    except Exception:   # no file descriptors to redirect (an embedded interpreter): the short form
        pass
    params = [line.strip() for line in text.splitlines() if line.startswith("\t")]
    return (f"MeshLab filter {name} (meshlab-acd).\n\nParameters (name : type = default):\n"
            + "".join(f"    {p}\n" for p in params)
            + "\ntau also takes pymeshlab.PercentageValue (percent of the bounding-box diagonal) or "
              "pymeshlab.PureValue (model units).\nWhat each parameter does: docs/parameters.md in meshlab-acd.\n")


_anchor = None


def _reset_log_on_error(method):
    """pymeshlab 2025.07 keeps a static pointer to the log of the MeshSet whose filter last ran and
    clears it only when a filter succeeds. After a failed filter, once that MeshSet is freed, the
    next mesh load that reports progress (e.g. any .obj) writes through the dangling pointer and
    crashes the process. A successful, trivial filter on a private MeshSet clears the pointer."""
    @functools.wraps(method)
    def call(self, *args, **kwargs):
        global _anchor
        _tau_value(self, kwargs)
        try:
            return method(self, *args, **kwargs)
        except pymeshlab.PyMeshLabException:
            if _anchor is None:
                _anchor = pymeshlab.MeshSet()
            _anchor.create_cube()
            _anchor.clear()
            raise
    return call


def mesh_ids(ms):
    """Ids of the layers of a MeshSet, in creation order."""
    ids, i = [], 0
    while len(ids) < ms.mesh_number() and i < 1_000_000:
        if ms.mesh_id_exists(i):
            ids.append(i)
        i += 1
    return ids


def decompose(ms, with_tree=True, **params):
    """Decompose the current mesh. Returns (result dict, part layer ids); with `with_tree` (or a
    `tree_file` to keep), the tree, read back from the JSON file the filter writes, is under "tree".

    Parameters are the filter's (tau, tau_unit, cut_plane_selection, max_parts, merge_parts, merge_measure, cut_search, output_hulls,
    max_hull_vertices, engine, hole_handling, hole_order, preprocessing, wrap_alpha, wrap_offset,
    on_self_intersection, time_limit, tree_file).
    """
    import tempfile
    before = set(mesh_ids(ms))
    with tempfile.TemporaryDirectory() as tmp:
        tree_file = params.pop("tree_file", None) or (os.path.join(tmp, "tree.json") if with_tree else "")
        res = ms.generate_approximate_convex_decomposition(tree_file=str(tree_file), **params)
        if tree_file:
            with open(tree_file) as f:
                res["tree"] = json.load(f)
    new = [i for i in mesh_ids(ms) if i not in before]
    return res, new


def decompose_polygon(ms, **params):
    """Decompose the current layer as a planar polygon with holes. Returns (result dict with the trees
    under "tree", piece layer ids). Parameters are the filter's (tau, tau_unit, cut_line_selection,
    hole_handling, hole_order, max_parts)."""
    import tempfile
    before = set(mesh_ids(ms))
    with tempfile.TemporaryDirectory() as tmp:
        tree_file = os.path.join(tmp, "tree.json")
        res = ms.generate_polygon_approximate_convex_decomposition(tree_file=tree_file, **params)
        with open(tree_file) as f:
            res["tree"] = json.load(f)
    new = [i for i in mesh_ids(ms) if i not in before]
    return res, new


def level_of_detail(ms, tree_file, tau=None, depth=None, tau_unit="percent_of_size", output_hulls=False):
    """Parts of a coarser level from a tree saved by decompose(..., tree_file=...), nothing recomputed:
    where every part is within `tau` (>= the tree's own), or at tree `depth`. Returns (result, layer ids)."""
    if (tau is None) == (depth is None):
        raise ValueError("give exactly one of tau and depth")
    before = set(mesh_ids(ms))
    res = ms.generate_convex_decomposition_level_of_detail(
        tree_file=str(tree_file), level_by="depth" if depth is not None else "tau",
        tau=float(tau or 1.0), tau_unit=tau_unit, depth=int(depth or 0), output_hulls=output_hulls)
    return res, [i for i in mesh_ids(ms) if i not in before]


load()


def _tau_value(ms, params):
    """tau given as pymeshlab.PercentageValue (percent of the current mesh's bounding-box diagonal, as
    pymeshlab means it) or pymeshlab.PureValue (model units) becomes a length in model units."""
    tau = params.get("tau")
    if tau is None or isinstance(tau, (int, float)):
        return
    if isinstance(tau, (pymeshlab.PercentageValue, pymeshlab.PureValue)):
        if params.get("tau_unit", "model_units") != "model_units":
            raise ValueError(f"tau={type(tau).__name__}(...) already says its unit: drop tau_unit="
                             f"{params['tau_unit']!r}, or pass tau as a float")
        value = tau.value()
        if isinstance(tau, pymeshlab.PercentageValue):
            box = ms.current_mesh().bounding_box()
            value = value / 100.0 * box.diagonal()
        params["tau"], params["tau_unit"] = float(value), "model_units"
        return
    raise TypeError(f"tau must be a float (percent of the size; model units with tau_unit='model_units'), "
                    f"pymeshlab.PercentageValue or pymeshlab.PureValue, not {type(tau).__name__}")


def convex_decomposition(vertices, faces=None, tau=None, return_parts=False, **filter_params):
    """Approximate convex decomposition of a triangle mesh given as arrays, without a MeshSet or files.

    `vertices` (n x 3) and `faces` (m x 3), or a `trimesh.Trimesh` (or anything with `vertices` and
    `faces`) as the first argument. `tau` and `filter_params` are generate_approximate_convex_decomposition's
    (e.g. cut_plane_selection, max_parts, preprocessing, engine, max_hull_vertices); what is not given takes
    pymeshlab_acd.options.DEFAULTS, as the command line does (preprocessing "auto": an open or dirty mesh
    is welded or alpha wrapped). Returns the convex hulls as a list of (V, F) numpy arrays, one per part; with
    `return_parts=True`, (hulls, parts, result) where parts are the closed pieces of the solid the hulls
    stand for and result is the filter's result dictionary. With `engine` (e.g. "physx_gpu") every hull meets
    that engine's limits and still contains its part; result["collision"]["hulls"] then gives each hull's
    counts and how far it reaches beyond the exact hull.
    """
    import numpy as np
    load()
    if faces is None and hasattr(vertices, "vertices") and hasattr(vertices, "faces"):
        vertices, faces = vertices.vertices, vertices.faces
    if faces is None:
        raise TypeError("convex_decomposition needs faces: pass (vertices, faces) or a trimesh.Trimesh")
    V = np.ascontiguousarray(vertices, dtype=np.float64)
    F = np.ascontiguousarray(faces, dtype=np.int32)
    if V.ndim != 2 or V.shape[1] != 3 or F.ndim != 2 or F.shape[1] != 3:
        raise ValueError(f"vertices must be n x 3 and faces m x 3 (got {V.shape} and {F.shape})")
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=V, face_matrix=F), "input")
    from .options import DEFAULTS
    params = dict(DEFAULTS, **filter_params)
    params.update(tau=DEFAULTS["tau"] if tau is None else tau, output_hulls=True)
    reduced = params.get("engine", "none") != "none" or params.get("max_hull_vertices", 0) > 0
    res, ids = decompose(ms, with_tree=reduced, **params)
    if reduced:   # each hull's counts and reach beyond its exact hull
        res["collision"] = res.pop("tree")["collision"]
    hulls, parts = [], []
    for i in ids:
        m = ms.mesh(i)
        (hulls if m.label().startswith("acd_hull_") else parts).append(
            (np.array(m.vertex_matrix()), np.array(m.face_matrix())))
    return (hulls, parts, res) if return_parts else hulls


def decompose_robot(description, out_dir, **kwargs):
    """A URDF or MJCF robot with every link's collision meshes replaced by convex hulls; see
    pymeshlab_acd.robot.decompose_robot."""
    from .robot import decompose_robot as run
    return run(description, out_dir, **kwargs)
