"""Whole robots through `python -m pymeshlab_acd robot` / pymeshlab_acd.decompose_robot: every mesh-bearing
URDF of example-robot-data rewritten, loaded in PyBullet and (as MJCF) in MuJoCo, free-base robots dropped
on a floor in both; an MJCF round trip; hulls within the engine's limits and holding their parts (Qhull and
trimesh); the USD stage; the cache; the same bytes for any thread count. Skipped without the robot data.

The corpus runs at coarse settings (tau 10%, alpha 5% for open meshes, 2 s of cutting per mesh: what is
tested here is the rewriting, loading and simulation, not the decomposition's detail), through the shared
cache; bench/bench_robot_descriptions.py runs it at the defaults."""
import filecmp
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from support.budgets import check_hull_folders
from support.robot_sim import collision_files, mujoco_compile, mujoco_drop, pybullet_drop, pybullet_load, settled

robots = pytest.importorskip("support.robots")
pytest.importorskip("yourdfpy")
pytest.importorskip("mujoco")
pytest.importorskip("pybullet")

COARSE = dict(tau=10.0)
CORPUS = dict(tau=10.0, wrap_alpha=5.0, time_limit=2.0)


@pytest.fixture(scope="module")
def package():
    try:
        return robots.fetch_descriptions()
    except Exception as e:   # no network and nothing cached
        pytest.skip(f"example-robot-data not available: {e}")


@pytest.fixture(scope="module")
def corpus(package, tmp_path_factory):
    """Every mesh-bearing URDF, rewritten once for the module (engine physx_gpu, the tightest budget),
    through the shared cache outside the repository (a rerun of the suite decomposes nothing)."""
    from pymeshlab_acd import decompose_robot
    out = tmp_path_factory.mktemp("robots")
    done = {}
    for urdf in robots.descriptions(package):
        name = urdf.relative_to(package / "robots").parts[0] + "__" + urdf.stem
        done[name] = (urdf, out / name, decompose_robot(urdf, out / name, engine="physx_gpu",
                                                         formats=("urdf", "mjcf"), resolve_paths=True, **CORPUS))
    return done


def test_every_urdf_is_rewritten_and_loads_in_pybullet_and_mujoco(corpus, package):
    assert len(corpus) >= 60
    failed_meshes, dropped, unreported = [], {"pybullet": 0, "mujoco": 0}, []
    for name, (urdf, out, s) in corpus.items():
        failed_meshes += [f"{name}: {r['link']}: {r['error']}" for r in s["links"] if r.get("error")]
        files = collision_files(out / f"{urdf.stem}.urdf")
        n = sum(len(v) for v in files.values())
        assert n == s["hulls"] and not s["format_errors"], (name, s["format_errors"])
        if n == 0:   # collisions all primitives (a1, laikago), or meshes on another machine (romeo_laas_small)
            assert all(r.get("error") for r in s["links"]), name
            assert any(True for _ in ET.parse(urdf).getroot().iter("collision")), name
        # Every hull file named is there, and each link kept its primitives.
        assert all((out / f).exists() for v in files.values() for f in v), name
        before = ET.parse(urdf).getroot()
        after = ET.parse(out / f"{urdf.stem}.urdf").getroot()
        for tag in ("joint", "link", "transmission"):
            assert len(before.findall(tag)) == len(after.findall(tag)), (name, tag)
        for prim in ("box", "cylinder", "sphere"):
            assert len(list(before.iter(prim))) <= len(list(after.iter(prim))), (name, prim)
        assert len(list(before.iter("visual"))) == len(list(after.iter("visual"))), name
        if any(r.get("error") for r in s["links"]):
            continue   # a mesh the description names but the package does not ship: nothing can load it
        if n == 0:
            continue   # nothing of ours to load or drop
        shapes = pybullet_load(out / f"{urdf.stem}.urdf")
        assert shapes >= n, name
        pb = pybullet_drop(out / f"{urdf.stem}.urdf")
        if pb is None:   # PyBullet's limit, not ours: the original description fails the same way
            assert pybullet_drop(urdf) is None, name
            unreported.append(name)
        elif pb["free"]:
            assert settled(pb), (name, pb)
            dropped["pybullet"] += 1
        assert mujoco_compile(out / f"{urdf.stem}.xml")["geoms"] >= n, name
        mj = mujoco_drop(out / f"{urdf.stem}.xml", out / ".scene.xml")
        if mj is not None:
            assert settled(mj), (name, mj)
            dropped["mujoco"] += 1
    print(f"\n{len(corpus)} robots; dropped and settled: {dropped}; PyBullet reports no state for {unreported}; "
          f"meshes the package lacks: {failed_meshes}")
    # Only meshes the descriptions name by absolute paths of another machine (romeo's NAOqi SDK) fail.
    assert all("no such file" in f for f in failed_meshes)
    assert dropped["pybullet"] >= 10 and dropped["mujoco"] >= 30


def test_every_hull_is_within_budget_and_holds_its_part(corpus):
    total = 0
    for name, (urdf, out, s) in corpus.items():
        if not (out / "collision").exists():
            continue
        n, within, holding, worst = check_hull_folders(out / "collision", "physx_gpu")
        assert within == n and holding == n, (name, n, within, holding, worst)
        total += n
    assert total > 500


def test_a_mjcf_model_round_trips(package, tmp_path):
    """An MJCF with mesh geoms (solo12's URDF compiled by MuJoCo, meshes by absolute path): every colliding
    mesh geom gets its hulls beside it, the geom stays for display and mass (body masses unchanged),
    and the result compiles and settles on a floor."""
    import mujoco
    from pymeshlab_acd import decompose_robot
    urdf = package / "robots" / "solo_description" / "robots" / "solo12.urdf"
    root = ET.parse(urdf).getroot()
    for m in root.iter("mesh"):
        m.set("filename", m.get("filename").replace("package://example-robot-data", str(package)))
    ET.SubElement(ET.SubElement(root, "mujoco"), "compiler", strippath="false", fusestatic="false",
                  discardvisual="true")
    (tmp_path / "solo12.urdf").write_text(ET.tostring(root, encoding="unicode"))
    spec = mujoco.MjSpec.from_file(str(tmp_path / "solo12.urdf"))
    spec.compile()
    (tmp_path / "solo12.xml").write_text(spec.to_xml())
    m0 = mujoco.MjModel.from_xml_path(str(tmp_path / "solo12.xml"))
    s = decompose_robot(tmp_path / "solo12.xml", tmp_path / "out", engine="physx", **COARSE)
    assert s["kind"] == "mjcf" and s["failed"] == 0 and s["hulls"] > len(s["links"])
    m1 = mujoco.MjModel.from_xml_path(str(tmp_path / "out" / "solo12.xml"))
    hull_geoms = [g for g in range(m1.ngeom) if "_hull_" in m1.geom(g).name]
    assert len(hull_geoms) == s["hulls"]
    assert all(m1.geom_contype[g] == 1 for g in hull_geoms)
    meshes0 = sum(1 for g in range(m0.ngeom) if m0.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH)
    assert sum(1 for g in range(m1.ngeom) if m1.geom_contype[g] == 0 and m1.geom_conaffinity[g] == 0) >= meshes0
    assert np.allclose(m0.body_mass, m1.body_mass) and np.allclose(m0.body_inertia, m1.body_inertia)
    assert settled(mujoco_drop(tmp_path / "out" / "solo12.xml", tmp_path / "scene.xml"))


def test_the_usd_stage_has_a_collision_hull_per_hull(package, tmp_path):
    pxr = pytest.importorskip("pxr")
    from pxr import Usd, UsdGeom, UsdPhysics
    from pymeshlab_acd import decompose_robot
    urdf = package / "robots" / "solo_description" / "robots" / "solo12.urdf"
    s = decompose_robot(urdf, tmp_path, engine="physx_gpu", formats=("urdf", "usd"), **COARSE)
    stage = Usd.Stage.Open(str(tmp_path / "solo12.usda"))
    assert stage and stage.GetDefaultPrim()
    meshes = [p for p in stage.Traverse() if p.IsA(UsdGeom.Mesh)]
    assert len(meshes) == s["hulls"]
    for p in meshes:
        assert p.HasAPI(UsdPhysics.CollisionAPI) and p.HasAPI(UsdPhysics.MeshCollisionAPI)
        assert UsdPhysics.MeshCollisionAPI(p).GetApproximationAttr().Get() == UsdPhysics.Tokens.convexHull
        assert 4 <= len(p.GetAttribute("points").Get()) <= 64
    # The feet sit where the URDF's zero configuration puts them: lowest hull point below the base's.
    xf = UsdGeom.XformCache()
    lows = {p.GetParent().GetName(): min((xf.GetLocalToWorldTransform(p).Transform(v))[2]
                                         for v in p.GetAttribute("points").Get()) for p in meshes}
    assert min(lows[k] for k in lows if "FOOT" in k) < lows["base_link"]
    del pxr


def test_a_second_run_decomposes_nothing(package, tmp_path, monkeypatch):
    """Everything from the cache: the filter is never called (it would raise), and the outputs are the
    same bytes. (The time this saves is measured in bench/bench_robot_descriptions.py.)"""
    from pymeshlab_acd import decompose_robot, hull_cache
    urdf = package / "robots" / "ur_description" / "urdf" / "ur5_robot.urdf"
    first = decompose_robot(urdf, tmp_path / "a", cache_dir=tmp_path / "cache", **COARSE)
    assert first["decomposed"] == first["meshes"] > 0

    def refuse(*a, **k):
        raise AssertionError("decomposed again")
    monkeypatch.setattr(hull_cache, "_decompose_mesh", refuse)
    again = decompose_robot(urdf, tmp_path / "b", cache_dir=tmp_path / "cache", **COARSE)
    assert again["decomposed"] == 0 and again["failed"] == 0 and all(r["cached"] for r in again["links"])
    assert _same_files(tmp_path / "a", tmp_path / "b")
    # Another option is another entry: decomposed again (here refused, so every mesh fails).
    other = decompose_robot(urdf, tmp_path / "c", cache_dir=tmp_path / "cache", engine="unity", **COARSE)
    assert other["failed"] == len(other["links"]) and all("decomposed again" in r["error"] for r in other["links"])


def _same_files(a, b):
    names = sorted(p.relative_to(a) for p in a.rglob("*") if p.is_file() and p.name != "summary.json")
    assert names == sorted(p.relative_to(b) for p in b.rglob("*") if p.is_file() and p.name != "summary.json")
    return all(filecmp.cmp(a / n, b / n, shallow=False) for n in names)


def test_the_same_bytes_for_any_thread_count(package, tmp_path):
    """solo12 rewritten without the cache on 1, 2 and every thread, in separate processes: the URDF, MJCF
    and every hull and part file compare equal."""
    urdf = package / "robots" / "solo_description" / "robots" / "solo12.urdf"
    outs = []
    for threads in (1, 2, 0):
        out = tmp_path / f"t{threads}"
        r = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "robot", str(urdf), "--out", str(out),
                            "--no-cache", "--no-progress", "--engine", "physx_gpu", "--tau", "5",
                            "--threads", str(threads)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        outs.append(out)
    assert _same_files(outs[0], outs[1]) and _same_files(outs[0], outs[2])


def test_a_reduced_hull_is_the_same_on_any_thread_count_and_within_budget(package, tmp_path):
    """g1's right knee link at the defaults under physx: one of its hulls is cut down from planes that nearly
    meet in points, and welding its corners splits polygons. 1 and 2 threads in separate processes give the
    same hull bytes; no hull is over the budget by the package's own count, none by trimesh's, and every
    hull holds its part."""
    from support.budgets import outside, read_obj_objects, within
    mesh = package / "robots" / "g1_description" / "meshes" / "right_knee_link.STL"
    outs = []
    for threads in (1, 2):
        out = tmp_path / f"t{threads}"
        r = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "decompose", str(mesh), "--out", str(out),
                            "--no-progress", "--engine", "physx", "--threads", str(threads)],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        outs.append(out)
    assert (outs[0] / "hulls.obj").read_bytes() == (outs[1] / "hulls.obj").read_bytes()
    assert json.loads((outs[0] / "summary.json").read_text())["hulls_over_budget"] == 0
    hulls, parts = read_obj_objects(outs[0] / "hulls.obj"), read_obj_objects(outs[0] / "parts.obj")
    size = float(np.ptp(np.vstack([V for V, _ in parts]), axis=0).max())
    assert len(hulls) == len(parts) > 1
    for (Vh, Fh), (Vp, _) in zip(hulls, parts):
        assert within(Vh, Fh, "physx")
        assert outside(Vp, Vh) <= 1e-9 * size


def test_the_command_line_names_what_is_wrong(tmp_path):
    r = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "robot", str(tmp_path / "none.urdf"), "--out",
                        str(tmp_path / "o")], capture_output=True, text=True)
    assert r.returncode == 2 and "no such file" in r.stderr
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"><collision><geometry>'
                                     '<mesh filename="package://nowhere/m.stl"/></geometry></collision></link></robot>')
    r = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "robot", str(tmp_path / "r.urdf"), "--out",
                        str(tmp_path / "o"), "--package", "bad"], capture_output=True, text=True)
    assert r.returncode == 1 and "NAME=FOLDER" in r.stderr
    r = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "robot", str(tmp_path / "r.urdf"), "--out",
                        str(tmp_path / "o"), "--no-progress"], capture_output=True, text=True)
    assert r.returncode == 1 and "--package nowhere=DIR" in r.stdout + r.stderr
