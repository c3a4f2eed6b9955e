"""The robot corpus (example-robot-data 6.0.0 from PyPI, pinned and checksummed, cached outside the
repository), ours run on a mesh through the batch's child process, and the certificate of its exported
parts by the independent hull measure. Shared by the robot tests and bench/bench_robots.py."""
import hashlib
import os
import pathlib
import subprocess
import sys
import time
import zipfile

WHEEL = "example_robot_data-6.0.0-0-py3-none-any.whl"
WHEEL_SHA256 = "424092a8093411ac2cd4ccc0572382bfc6b5eb4833aa984ef5e671dd67cd0a6e"
PREFIX = "cmeel.prefix/share/example-robot-data/robots/"


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


def fetch_descriptions():
    """The whole package (URDFs, meshes of every kind) unpacked from the same wheel, as
    share/example-robot-data/ under the cache: package://example-robot-data/ resolves to it."""
    fetch_corpus()
    root = cache() / "robots" / "share"
    pkg = root / "example-robot-data"
    if (pkg / ".complete").exists():
        return pkg
    with zipfile.ZipFile(cache() / "robots" / WHEEL) as z:
        for info in z.infolist():
            if info.filename.startswith("cmeel.prefix/share/example-robot-data/") and not info.is_dir():
                dst = root / info.filename[len("cmeel.prefix/share/"):]
                dst.parent.mkdir(parents=True, exist_ok=True)
                dst.write_bytes(z.read(info))
    (pkg / ".complete").touch()
    return pkg


def descriptions(pkg):
    """Every URDF of the package whose links name meshes, sorted."""
    import xml.etree.ElementTree as ET
    out = []
    for p in sorted((pkg / "robots").rglob("*.urdf")):
        if any(True for _ in ET.parse(p).getroot().iter("mesh")):
            out.append(p)
    return out


def corpus(meshes):
    return sorted(p for p in meshes.rglob("*") if p.suffix.lower() in (".stl", ".obj", ".ply"))


def mesh_name(p, meshes, files):
    """A mesh's name in the tables: its path without the suffix, unless another file differs from it
    by the suffix alone (a robot shipping one model as .obj and .stl): then with it."""
    stem = p.with_suffix("")
    twins = sum(1 for q in files if q.with_suffix("") == stem)
    return p.relative_to(meshes).as_posix() if twins > 1 else stem.relative_to(meshes).as_posix()


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
def run_ours(src, out_dir, timeout, cache=False):
    """`cache`: read the decomposition from the shared cache when there (tests); benchmarks time a fresh one."""
    from pymeshlab_acd import batch
    opts = dict(batch.DEFAULTS, max_hull_vertices=0, formats=["obj"], timeout=timeout,   # the defaults' tau and cuts
                cache=cache)
    t0 = time.perf_counter()
    rec = batch.run_child(src, out_dir, opts)
    rec["wall"] = time.perf_counter() - t0
    return rec


def certificate(out_dir, tau_abs):
    """Worst part hull distance / tau (a distance attained) and the parts whose hull is not proven within
    tau + 1%, over the exported parts, measured independently."""
    import numpy as np
    import pymeshlab
    from .hull_reach import hull_reach
    worst, over = 0.0, 0
    for ply in sorted((pathlib.Path(out_dir) / "parts").glob("*.ply")):
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(ply))
        V, F = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
        lower, upper = hull_reach(V, F, slack=0.01 * tau_abs, limit=tau_abs)
        if lower <= 1.01 * tau_abs < upper:   # a point just past tau: settle "within tau + 1%" to 0.1% of tau
            lower2, upper = hull_reach(V, F, slack=0.001 * tau_abs, limit=1.009 * tau_abs)
            lower = max(lower, lower2)
        worst = max(worst, lower / tau_abs)   # attained; "over" counts the proven upper bounds
        over += upper > 1.01 * tau_abs
    return worst, over
