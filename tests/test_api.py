"""The array API (pymeshlab_acd.convex_decomposition) and tau given as pymeshlab's value types."""
import numpy as np
import pymeshlab
import pytest
from scipy.spatial import ConvexHull

import pymeshlab_acd
from support.meshes import L_SHAPE, U_SHAPE, add_mesh, extrude, is_closed_manifold, volume


def test_arrays_in_hulls_out():
    """Each hull returned is convex and closed, holds its part; the parts fill the U exactly."""
    V, F = extrude(U_SHAPE, 0, 1)
    hulls, parts, res = pymeshlab_acd.convex_decomposition(V, F, tau=0.1, tau_unit="model_units",
                                                           return_parts=True)
    assert len(hulls) == len(parts) == res["parts"] == 3
    assert abs(sum(volume(*p) for p in parts) - volume(V, F)) < 1e-9
    for (Vh, Fh), (Vp, Fp) in zip(hulls, parts):
        assert isinstance(Vh, np.ndarray) and Vh.shape[1] == 3 and Fh.shape[1] == 3
        assert is_closed_manifold(Fh) and is_closed_manifold(Fp)
        qhull = ConvexHull(Vh).volume   # a convex mesh's volume is its hull's
        assert abs(volume(Vh, Fh) - qhull) < 1e-9 * max(1.0, qhull)
        assert abs(ConvexHull(Vp).volume - qhull) < 1e-9 * max(1.0, qhull)   # the hull of its part
    assert pymeshlab_acd.convex_decomposition(V, F, tau=0.1, tau_unit="model_units") \
        .__len__() == 3   # hulls only by default


def test_trimesh_like_input():
    class Mesh:   # what trimesh.Trimesh offers
        def __init__(self, V, F):
            self.vertices, self.faces = V, F
    V, F = extrude(L_SHAPE, 0, 1)
    hulls = pymeshlab_acd.convex_decomposition(Mesh(V, F), tau=0.1, tau_unit="model_units")
    assert len(hulls) == 2
    # parts may keep concavity up to tau, so their hulls hold a little more than the L's volume 3
    assert 3.0 - 1e-9 <= sum(ConvexHull(h[0]).volume for h in hulls) <= 3.0 * 1.001


def test_tau_as_percentage_and_pure_value():
    """PercentageValue is percent of the bounding-box diagonal, PureValue model units (pymeshlab's
    meaning); both give the same parts as the equal length in model units."""
    V, F = extrude(U_SHAPE, 0, 1)
    diag = float(np.linalg.norm(V.max(0) - V.min(0)))
    for tau, length in ((pymeshlab.PercentageValue(5), 0.05 * diag), (pymeshlab.PureValue(0.2), 0.2)):
        ms = pymeshlab.MeshSet()
        add_mesh(ms, V, F)
        res = ms.generate_approximate_convex_decomposition(tau=tau)
        assert abs(res["tau_model_units"] - length) < 1e-6 * length   # pymeshlab's box diagonal vs numpy's: ~1e-8 apart
        ref = pymeshlab_acd.convex_decomposition(V, F, tau=length, tau_unit="model_units")
        assert res["parts"] == len(ref)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F)
    with pytest.raises(TypeError, match="PercentageValue"):
        ms.generate_approximate_convex_decomposition(tau="3%")
    with pytest.raises(ValueError, match="drop tau_unit"):
        ms.generate_approximate_convex_decomposition(tau=pymeshlab.PercentageValue(3), tau_unit="percent_of_size")


def test_bad_arrays_are_refused_with_a_message():
    with pytest.raises(ValueError, match="n x 3"):
        pymeshlab_acd.convex_decomposition(np.zeros((4, 2)), np.zeros((1, 3), int))
    with pytest.raises(TypeError, match="needs faces"):
        pymeshlab_acd.convex_decomposition(np.zeros((4, 3)))
    V, F = extrude(L_SHAPE, 0, 1)
    with pytest.raises(pymeshlab.PyMeshLabException, match="open"):
        pymeshlab_acd.convex_decomposition(V, F[:-1], preprocessing="none")
    hulls = pymeshlab_acd.convex_decomposition(V, F[:-1], tau=5.0)
    assert len(hulls) >= 2


def _cli(*args):
    import subprocess
    import sys
    return subprocess.run([sys.executable, "-m", "pymeshlab_acd", *args], capture_output=True, text=True, timeout=120)


def test_cli_checks_arguments_before_any_work(tmp_path):
    """One-line refusals naming the fix, before any decomposition; --version; no silent default mesh."""
    r = _cli("--version")
    assert r.returncode == 0 and r.stdout.strip().split()[-1][0].isdigit()
    r = _cli("decompose")
    assert r.returncode == 2 and "--demo" in r.stderr
    r = _cli("decompose", str(tmp_path / "missing.obj"))
    assert r.returncode == 2 and "no such file" in r.stderr
    (tmp_path / "afile").write_text("x")
    r = _cli("decompose", "--demo", "--out", str(tmp_path / "afile"))
    assert r.returncode == 2 and "is a file" in r.stderr
    r = _cli("decompose", "--demo", "--export")
    assert r.returncode == 2 and "give --out" in r.stderr


def _filter_defaults(ms):
    """The MeshLab filter's own parameter defaults (the GUI dialog's, a bare pymeshlab call's), with each
    choice's menu index turned into its label."""
    from pymeshlab_acd.options import DEFAULTS, choices
    got = ms.filter_parameter_values("generate_approximate_convex_decomposition")
    return {k: (choices(k)[v] if isinstance(DEFAULTS.get(k), str) else v) for k, v in got.items()}


def _cli_defaults():
    from pymeshlab_acd.__main__ import main
    import argparse
    seen = {}
    real = argparse.ArgumentParser.parse_args

    def capture(self, args=None, namespace=None):
        seen.update(vars(real(self, args, namespace)))
        raise SystemExit(0)
    argparse.ArgumentParser.parse_args = capture
    try:
        with pytest.raises(SystemExit):
            main(["decompose", "x.obj"])
    finally:
        argparse.ArgumentParser.parse_args = real
    return seen


def test_the_filter_the_command_line_and_the_api_share_their_defaults(ms, monkeypatch):
    """Option by option, preprocessing included: the filter's defaults, the command line's and what
    convex_decomposition passes to the filter when given nothing but the mesh."""
    import inspect
    from pymeshlab_acd.options import DEFAULTS
    add_mesh(ms, *extrude(L_SHAPE, 0, 1))
    filt, cli = _filter_defaults(ms), _cli_defaults()
    passed = {}
    real = pymeshlab_acd.decompose
    monkeypatch.setattr(pymeshlab_acd, "decompose", lambda m, **kw: (passed.update(kw), real(m, **kw))[1])
    pymeshlab_acd.convex_decomposition(*extrude(L_SHAPE, 0, 1))
    assert inspect.signature(pymeshlab_acd.convex_decomposition).parameters["tau"].default is None
    for name, default in DEFAULTS.items():
        assert filt[name] == pytest.approx(default) if isinstance(default, float) else filt[name] == default, name
        assert cli[name] == default, name
        assert passed[name] == default, name
    assert DEFAULTS["preprocessing"] == "auto"


def test_convex_decomposition_decomposes_an_open_mesh_as_the_cli_does(tmp_path):
    """An open box (one face missing): the API's default preprocessing fills its hole, as the CLI's does."""
    import trimesh
    box = trimesh.creation.box((2, 1, 1))
    V, F = np.asarray(box.vertices), np.asarray(box.faces)[1:]
    hulls, parts, res = pymeshlab_acd.convex_decomposition(V, F, return_parts=True)
    assert not res["alpha_wrapped"] and res["preprocessing_done"] == 3 and res["holes_filled"] == 1
    assert len(hulls) >= 1 and res["tau_convex"]
    # the hulls cover the input: every input vertex lies inside or on some hull (scipy, not the core)
    from scipy.spatial import Delaunay
    inside = np.zeros(len(V), bool)
    for hv, _ in hulls:
        inside |= Delaunay(hv).find_simplex(V, tol=1e-9) >= 0
    assert inside.all()


def test_every_subcommand_starts_from_the_same_defaults():
    """One table (pymeshlab_acd.options.DEFAULTS) behind decompose, batch and structure, shown in --help."""
    from pymeshlab_acd.__main__ import main
    from pymeshlab_acd.options import DEFAULTS
    import argparse
    seen = {}
    real = argparse.ArgumentParser.parse_args

    def capture(self, args=None, namespace=None):
        ns = real(self, args, namespace)
        seen[ns.cmd] = vars(ns)
        raise SystemExit(0)
    argparse.ArgumentParser.parse_args = capture
    try:
        for argv in (["decompose", "x.obj"], ["batch", "in", "out"], ["structure", "x.obj", "--out", "o"]):
            with pytest.raises(SystemExit):
                main(argv)
    finally:
        argparse.ArgumentParser.parse_args = real
    for cmd in ("decompose", "batch"):
        for k, v in DEFAULTS.items():
            assert seen[cmd][k] == v, (cmd, k)
    assert seen["structure"]["tau"] == DEFAULTS["tau"] and seen["structure"]["preprocessing"] == "auto"
    assert seen["decompose"]["preprocessing"] == "auto"
    r = _cli("decompose", "--help")
    assert f"(default: {DEFAULTS['tau']})" in r.stdout and "(default: auto)" in r.stdout


def test_cli_writes_one_hulls_file_and_draws_one_progress_line(tmp_path):
    """Default output: hulls.obj with one object per hull and parts.obj with the parts, their volumes
    re-measured here; progress is one redrawn line, without pymeshlab's parameter dump."""
    V, F = extrude(U_SHAPE, 0, 1)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F)
    ms.save_current_mesh(str(tmp_path / "u.obj"))
    r = _cli("decompose", str(tmp_path / "u.obj"), "--tau", "0.1", "--tau-unit", "model_units",
             "--out", str(tmp_path / "o"))
    assert r.returncode == 0, r.stderr
    assert "Applying filter" not in r.stderr and "'tau'" not in r.stderr
    assert "[" + "#" * 24 + "] 100%" in r.stderr and "LOG:" not in r.stderr
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == ["hulls.obj", "parts.obj", "summary.json"]

    def objects(path):
        out, V = [], []
        for line in path.read_text().splitlines():
            if line.startswith("o "):
                out.append([])
            elif line.startswith("v "):
                V.append([float(x) for x in line.split()[1:]])
            elif line.startswith("f "):
                out[-1].append([int(x) - 1 for x in line.split()[1:]])
        V = np.array(V)
        return [(V[np.unique(f)], np.searchsorted(np.unique(f), np.array(f))) for f in out]
    hulls, parts = objects(tmp_path / "o" / "hulls.obj"), objects(tmp_path / "o" / "parts.obj")
    assert len(hulls) == len(parts) == 3
    assert abs(sum(volume(*p) for p in parts) - volume(V, F)) < 1e-6
    for Vh, Fh in hulls:
        assert is_closed_manifold(Fh)
        assert abs(volume(Vh, Fh) - ConvexHull(Vh).volume) < 1e-6


def test_bound_filters_document_their_parameters():
    doc = pymeshlab.MeshSet.generate_approximate_convex_decomposition.__doc__
    assert "tau : float = 2" in doc and "preprocessing : str = 'auto'" in doc and "PercentageValue" in doc
    for name in pymeshlab_acd.FILTERS:
        assert "Parameters" in getattr(pymeshlab.MeshSet, name).__doc__


def test_an_open_mesh_is_refused_with_this_tools_remedy_first():
    V, F = extrude(L_SHAPE, 0, 1)
    with pytest.raises(pymeshlab.PyMeshLabException) as e:
        pymeshlab_acd.convex_decomposition(V, F[:-1], preprocessing="none")
    msg = str(e.value)
    assert msg.index("preprocessing to 'auto'") < msg.index("Close Holes")


def test_convex_decomposition_returns_the_filters_hull_layers():
    V, F = extrude(U_SHAPE, 0, 1)
    hulls = pymeshlab_acd.convex_decomposition(V, F, tau=0.1, tau_unit="model_units")
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F)
    res, ids = pymeshlab_acd.decompose(ms, with_tree=False, tau=0.1, tau_unit="model_units", output_hulls=True)
    layers = [ms.mesh(i) for i in ids if ms.mesh(i).label().startswith("acd_hull_")]
    assert len(layers) == len(hulls) == res["parts"]
    for (Vh, Fh), m in zip(hulls, layers):
        assert np.array_equal(Vh, m.vertex_matrix()) and np.array_equal(Fh, m.face_matrix())


HULL_LAYERS_DIGEST = """
import hashlib, sys, pymeshlab, pymeshlab_acd
sys.path.insert(0, sys.argv[1])
from support import cad_solids
ms = pymeshlab.MeshSet()
pymeshlab_acd.load()
ms.add_mesh(pymeshlab.Mesh(*cad_solids.make("flange")))
ms.generate_convex_hull_union()
h = hashlib.sha256()
for i in pymeshlab_acd.mesh_ids(ms)[1:]:
    h.update(ms.mesh(i).vertex_matrix().tobytes() + ms.mesh(i).face_matrix().tobytes())
print(h.hexdigest())
"""


def test_hull_layers_are_the_same_in_every_session():
    """The same input gives byte-identical hull layers in separate processes (the hull's vertex and
    triangle order may not depend on memory layout)."""
    import os
    import subprocess
    import sys
    here = os.path.dirname(os.path.abspath(__file__))
    runs = [subprocess.run([sys.executable, "-c", HULL_LAYERS_DIGEST, here], capture_output=True, text=True,
                           timeout=300) for _ in range(3)]
    digests = {r.stdout.strip().splitlines()[-1] for r in runs if r.returncode == 0}
    assert all(r.returncode == 0 for r in runs), runs[0].stderr[-500:]
    assert len(digests) == 1
