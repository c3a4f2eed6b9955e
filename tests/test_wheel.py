"""The wheel (scripts/build_wheel.sh) installs into a fresh virtual environment that holds only pymeshlab
and numpy from the registry, with the build cache out of reach (ACD_CACHE an empty folder, no build
tree on any path), and decomposes a mesh there; every library the installed plugin needs resolves to the
wheel, pymeshlab's wheel or the system libraries the manylinux policy allows."""
import os
import pathlib
import subprocess
import sys
import venv

import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]
# System libraries a manylinux wheel may rely on (PEP 600 policies), and those pymeshlab itself needs
# from the system (its libmpfr needs libgmp; its Qt needs X11 and OpenGL).
SYSTEM = ("linux-vdso", "ld-linux", "libc.so", "libm.so", "libdl.so", "librt.so", "libpthread.so",
          "libstdc++.so", "libgcc_s.so", "libGL", "libGLX", "libGLdispatch", "libX", "libxcb", "libz.so",
          "libgmp.so", "libbsd.so", "libmd.so", "libEGL", "libOpenGL", "libexpat", "libffi", "libglib",
          "libgobject", "libgthread", "libresolv", "libutil")


def _cache_dir():
    return pathlib.Path(os.environ.get("ACD_CACHE") or pathlib.Path.home() / ".cache" / "meshlab-acd")


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    p = subprocess.run(["bash", str(REPO / "scripts" / "build_wheel.sh"), str(out)], capture_output=True, text=True,
                       timeout=1800)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return pathlib.Path(p.stdout.strip().splitlines()[-1])


def test_wheel_name_and_contents(wheel):
    import zipfile
    assert wheel.name.startswith("pymeshlab_acd-") and "manylinux_2_" in wheel.name and wheel.name.endswith("_x86_64.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert "pymeshlab_acd/lib/libfilter_acd.so" in names
    assert any(n.startswith("pymeshlab_acd.libs/libgmp") for n in names)          # shipped: not in pymeshlab's wheel
    assert not any("libmeshlab-common" in n or "libQt5" in n for n in names)    # pymeshlab's own: not shipped


def test_wheel_installs_alone_and_decomposes(wheel, tmp_path):
    # The registry's pymeshlab and numpy, downloaded once into the cache (outside the fresh environment).
    house = _cache_dir() / "wheelhouse"
    house.mkdir(parents=True, exist_ok=True)
    p = subprocess.run([sys.executable, "-m", "pip", "download", "-q", "-d", str(house), "pymeshlab==2025.7.post1",
                        "numpy"], capture_output=True, text=True, timeout=1800)
    if p.returncode != 0 and not any(house.glob("pymeshlab-2025.7.post1-*.whl")):
        pytest.skip(f"no registry and no cached pymeshlab wheel: {p.stderr[-300:]}")
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(with_pip=True, clear=True).create(env_dir)
    py = env_dir / "bin" / "python"
    p = subprocess.run([str(py), "-m", "pip", "install", "-q", "--no-index", "--find-links", str(house),
                        "pymeshlab==2025.7.post1", "numpy", str(wheel)], capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stderr[-2000:]
    empty = tmp_path / "empty-cache"
    empty.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "ACD_PLUGIN", "ACD_BUILD_DIR", "LD_LIBRARY_PATH")}
    env.update(ACD_CACHE=str(empty), XDG_CACHE_HOME=str(empty), HOME=str(tmp_path))
    # An L: two boxes sharing a face, built as one closed surface by pymeshlab's own boolean union.
    script = (
        "import numpy as np, pymeshlab, pymeshlab_acd\n"
        "ms = pymeshlab.MeshSet()\n"
        "ms.create_cube(size=1.0); ms.compute_matrix_from_scaling_or_normalization(axisx=3, axisy=1, axisz=1, uniformflag=False)\n"
        "ms.create_cube(size=1.0); ms.compute_matrix_from_scaling_or_normalization(axisx=1, axisy=3, axisz=1, uniformflag=False)\n"
        "ms.compute_matrix_from_translation(axisx=-1, axisy=1)\n"
        "ms.generate_boolean_union(first_mesh=0, second_mesh=1)\n"
        "m = ms.current_mesh()\n"
        "hulls, parts, res = pymeshlab_acd.convex_decomposition(m.vertex_matrix(), m.face_matrix(), tau=1.0, "
        "return_parts=True)\n"
        "vol = lambda V, F: float(np.einsum('ij,ij->i', V[F[:, 0]], np.cross(V[F[:, 1]], V[F[:, 2]])).sum() / 6)\n"
        "print(pymeshlab_acd.plugin_path())\n"
        "print(len(hulls), sum(vol(*p) for p in parts), vol(m.vertex_matrix(), m.face_matrix()))\n"
    )
    p = subprocess.run([str(py), "-c", script], capture_output=True, text=True, timeout=600, env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr[-2000:]
    where, numbers = p.stdout.strip().splitlines()[-2:]
    assert str(env_dir) in where and str(REPO) not in where and str(_cache_dir()) not in where
    n, parts_volume, volume = numbers.split()
    assert int(n) == 2 and abs(float(parts_volume) - float(volume)) < 1e-9 * float(volume)

    plugin = pathlib.Path(where)
    site = plugin.parents[2]
    ldd = subprocess.run(["ldd", str(plugin)], capture_output=True, text=True, env=env).stdout
    for line in ldd.splitlines():
        name = os.path.basename(line.split()[0])
        path = line.split("=>")[1].split("(")[0].strip() if "=>" in line else name
        assert "not found" not in line, line
        inside = path.startswith(str(site / "pymeshlab_acd")) or path.startswith(str(site / "pymeshlab"))
        assert inside or any(name.startswith(s) for s in SYSTEM), line
