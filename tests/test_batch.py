"""Batch decomposition: `python -m pymeshlab_acd batch` on a folder of meshes, locally with 2
workers and on a local 2-worker Ray instance; resumable; failures recorded without stopping the batch.
Each output is re-measured here: the parts' volumes add up to the input's."""
import csv
import json
import pathlib
import subprocess
import sys

import numpy as np
import pymeshlab
import pytest

from support.meshes import L_SHAPE, PLUS, add_mesh, box, extrude, is_closed_manifold, torus, volume
from pymeshlab_acd.options import DEFAULTS


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    """Three closed solids (one in a subfolder, one PLY), a box with a face given twice (refused as
    given, so auto-wrapped), a file that is not a mesh."""
    d = tmp_path_factory.mktemp("in")
    (d / "sub").mkdir()
    ms = pymeshlab.MeshSet()
    shapes = {"l_prism.obj": extrude(L_SHAPE, 0, 1), "plus.ply": extrude(PLUS, 0, 0.5),
              "sub/torus.obj": torus(nu=32, nv=12)}
    V, F = box()
    shapes["twice_box.obj"] = (V, np.vstack([F, F[:1]]))
    for name, (V, F) in shapes.items():
        add_mesh(ms, V, F, name)
        ms.save_current_mesh(str(d / name), save_vertex_color=False, save_face_color=False)
    (d / "notes.obj").write_text("this is not a mesh\n")
    return d, shapes


def batch(in_dir, out_dir, *extra, timeout=900, cache=None):
    """The batch CLI at tau 4, with a decomposition cache of its own beside out_dir unless `cache` is given
    (so that each test decomposes, and nothing is read from the user's cache)."""
    cache = cache or out_dir.with_name(out_dir.name + "-cache")
    p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "batch", str(in_dir), str(out_dir), "--tau", "4",
                        "--no-progress", "--cache-dir", str(cache), *extra], capture_output=True, text=True,
                       timeout=timeout)
    print(p.stdout[-3000:], p.stderr[-3000:])
    assert p.returncode == 0, p.stderr
    with open(out_dir / "summary.csv") as f:
        rows = {r["file"]: r for r in csv.DictReader(f)}
    assert json.loads((out_dir / "summary.json").read_text())   # the same records, as JSON
    return rows


def check_outputs(in_dir, out_dir, rows, shapes):
    for name, (V, F) in shapes.items():
        r = rows[name]
        assert r["status"] in ("ok", "done before"), r
        out = out_dir / r["output"]
        parts = sorted((out / "parts").glob("*.ply"))
        assert len(parts) == int(r["parts"]) >= 1
        assert len(list((out / "collision").glob("*.obj"))) == len(parts)
        assert len(list((out / "collision").glob("*.stl"))) == len(parts)
        stem = pathlib.Path(name).stem
        for f in (f"{stem}.urdf", f"{stem}.xml", f"{stem}.mlp"):
            assert (out / f).is_file(), f
        total = 0.0
        for p in parts:
            ms = pymeshlab.MeshSet()
            ms.load_new_mesh(str(p))
            m = ms.current_mesh()
            assert is_closed_manifold(m.face_matrix())
            total += volume(m.vertex_matrix(), m.face_matrix())
        if name != "twice_box.obj":      # the others were decomposed as given: the parts fill them exactly
            assert total == pytest.approx(volume(V, F), rel=1e-6), name
            assert r["preprocessing"] == "none"
        else:                           # wrapped first: close to the box, slightly larger
            assert r["preprocessing"] == f"alpha_wrap {DEFAULTS['wrap_alpha']:g}%" and "duplicate" in r["error"]
            assert 8 < total < 1.2 * 8          # the 2 x 2 x 2 box, and the wrap's small offset


def test_batch_with_two_workers_resumes_and_records_failures(meshes, tmp_path):
    in_dir, shapes = meshes
    out = tmp_path / "out"
    rows = batch(in_dir, out, "--workers", "2")
    assert set(rows) == set(shapes) | {"notes.obj"}
    assert rows["notes.obj"]["status"] == "failed" and "notes.obj" in rows["notes.obj"]["error"]
    assert not (out / "notes").exists() and not list(out.rglob("*.partial"))
    check_outputs(in_dir, out, rows, shapes)
    assert (out / "sub" / "torus" / "torus.urdf").is_file()     # the input's folders are kept

    # Again: nothing finished is redone (files untouched); the failure is retried and recorded again.
    stamp = {p: p.stat().st_mtime_ns for p in out.rglob("*") if p.is_file() and p.parent != out}
    rows2 = batch(in_dir, out, "--workers", "2")
    assert {n: r["status"] for n, r in rows2.items()} == dict({n: "done before" for n in shapes}, **{"notes.obj": "failed"})
    assert all(p.stat().st_mtime_ns == t for p, t in stamp.items())

    # A folder lost (and a half-written one left by a killed run): only that mesh is redone.
    import shutil
    shutil.rmtree(out / "plus")
    (out / "plus.partial").mkdir()
    rows3 = batch(in_dir, out, "--workers", "2")
    assert rows3["plus.ply"]["status"] == "ok"
    assert all(rows3[n]["status"] == "done before" for n in shapes if n != "plus.ply")
    assert not (out / "plus.partial").exists()

    # Other options make other outputs: everything is redone.
    rows4 = batch(in_dir, out, "--workers", "2", "--max-hull-vertices", "16")
    assert all(rows4[n]["status"] == "ok" for n in shapes)


def test_batch_and_robots_share_one_cache(meshes, tmp_path):
    """A second batch over the same meshes, into another folder, decomposes nothing and writes the same
    bytes; a robot whose link names one of those meshes finds it decomposed too (the same cache key for
    the same bytes and options), and a batch after the robot reuses what the robot stored."""
    import filecmp
    import shutil
    from pymeshlab_acd import decompose_robot
    in_dir, shapes = meshes
    cache = tmp_path / "cache"
    first = batch(in_dir, tmp_path / "a", "--workers", "2", cache=cache)
    assert all(first[n]["cached"] == "False" for n in shapes)
    again = batch(in_dir, tmp_path / "b", "--workers", "2", cache=cache)
    assert all(again[n]["cached"] == "True" and again[n]["status"] == "ok" for n in shapes)
    assert again["notes.obj"]["status"] == "failed"
    files = sorted(p.relative_to(tmp_path / "a") for p in (tmp_path / "a").rglob("*")
                   if p.is_file() and p.name not in ("summary.json", "summary.csv"))
    assert len(files) > 20
    assert all(filecmp.cmp(tmp_path / "a" / f, tmp_path / "b" / f, shallow=False) for f in files)
    check_outputs(in_dir, tmp_path / "b", again, shapes)
    # Without the cache the layers go from the filter to the export in memory: the same bytes, nothing stored.
    stored = sorted(cache.iterdir())
    fresh = batch(in_dir, tmp_path / "n", "--workers", "2", "--no-cache", cache=cache)
    assert all(fresh[n]["cached"] == "False" and fresh[n]["status"] == "ok" for n in shapes)
    assert sorted(cache.iterdir()) == stored
    assert all(filecmp.cmp(tmp_path / "a" / f, tmp_path / "n" / f, shallow=False) for f in files)

    # A robot of one link whose collision is l_prism.obj, at the batch's options.
    robot_dir = tmp_path / "robot"
    robot_dir.mkdir()
    shutil.copyfile(in_dir / "l_prism.obj", robot_dir / "arm.obj")
    shutil.copyfile(in_dir / "sub" / "torus.obj", robot_dir / "wheel.obj")
    (robot_dir / "r.urdf").write_text(
        '<robot name="r"><link name="base"><collision><geometry><mesh filename="arm.obj"/></geometry></collision>'
        '</link><link name="w"><collision><geometry><mesh filename="wheel.obj"/></geometry></collision></link>'
        '<joint name="j" type="fixed"><parent link="base"/><child link="w"/></joint></robot>')
    s = decompose_robot(robot_dir / "r.urdf", tmp_path / "robot_out", cache_dir=cache, tau=4)
    assert s["failed"] == 0 and s["meshes"] == 2 and s["decomposed"] == 0
    assert s["hulls"] == int(first["l_prism.obj"]["parts"]) + int(first["sub/torus.obj"]["parts"])

    # Other bytes: the robot decomposes them and stores them; a batch over them then finds them.
    V, F = box()
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V * [1, 2, 3], F)
    ms.save_current_mesh(str(robot_dir / "arm.obj"), save_vertex_color=False, save_face_color=False)
    s = decompose_robot(robot_dir / "r.urdf", tmp_path / "robot_out2", cache_dir=cache, tau=4)
    assert s["decomposed"] == 1
    (robot_dir / "r.urdf").unlink()
    rows = batch(robot_dir, tmp_path / "c", "--workers", "1", cache=cache)
    assert rows["arm.obj"]["cached"] == "True" and rows["wheel.obj"]["cached"] == "True"
    assert rows["arm.obj"]["parts"] == "1"


def test_batch_output_inside_its_input_is_not_read_back(tmp_path):
    V, F = extrude(L_SHAPE, 0, 1)
    ms = pymeshlab.MeshSet()
    add_mesh(ms, V, F)
    ms.save_current_mesh(str(tmp_path / "l.obj"), save_vertex_color=False, save_face_color=False)
    for _ in range(2):   # the second run would find the first run's OBJ/STL hulls if it looked
        rows = batch(tmp_path, tmp_path / "out", "--workers", "1")
        assert list(rows) == ["l.obj"]


def test_batch_saves_trees_for_coarser_levels(meshes, tmp_path):
    import pymeshlab_acd
    in_dir, shapes = meshes
    rows = batch(in_dir, tmp_path / "out", "--workers", "2", "--save-tree")
    tree = tmp_path / "out" / rows["sub/torus.obj"]["output"] / "tree.json"
    assert not list((tmp_path / "out").rglob(".tree-*"))
    # The cache's copy and the tree written straight to the output (no cache) hold the same bytes.
    fresh = batch(in_dir, tmp_path / "fresh", "--workers", "2", "--save-tree", "--no-cache")
    assert (tmp_path / "fresh" / fresh["sub/torus.obj"]["output"] / "tree.json").read_bytes() == tree.read_bytes()
    ms = pymeshlab.MeshSet()
    res, ids = pymeshlab_acd.level_of_detail(ms, tree, tau=20)
    assert 1 <= len(ids) < int(rows["sub/torus.obj"]["parts"])
    V, F = shapes["sub/torus.obj"]
    assert sum(volume(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in ids) == pytest.approx(
        volume(V, F), rel=1e-6)


def test_batch_timeout_is_recorded(meshes, tmp_path):
    in_dir, _ = meshes
    rows = batch(in_dir, tmp_path / "out", "--workers", "2", "--timeout", "0.05")
    assert all(r["status"] == "failed" for r in rows.values())
    assert all("timed out" in r["error"] for n, r in rows.items() if n != "notes.obj")


def test_batch_on_a_local_ray_instance_of_two_workers(meshes, tmp_path):
    pytest.importorskip("ray")
    in_dir, shapes = meshes
    local = batch(in_dir, tmp_path / "local", "--workers", "2")
    rows = batch(in_dir, tmp_path / "ray", "--ray", "local", "--workers", "2", timeout=1200)
    assert rows["notes.obj"]["status"] == "failed"
    check_outputs(in_dir, tmp_path / "ray", rows, shapes)
    # Same decomposition as without Ray, and the work was shared by two Ray workers.
    assert {n: rows[n]["parts"] for n in shapes} == {n: local[n]["parts"] for n in shapes}
    workers = {r["worker"] for r in rows.values() if r["status"] == "ok"}
    assert all(w.startswith("ray:") for w in workers)
    assert len(workers) == 2, workers


def test_batch_refuses_bad_arguments(tmp_path):
    p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "batch", str(tmp_path), str(tmp_path / "o")],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 1 and "no mesh files" in p.stderr
    (tmp_path / "a.obj").write_text("")
    p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "batch", str(tmp_path), str(tmp_path / "o"),
                        "--tau", "0"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 1 and "tau must be positive" in p.stderr
