"""The same input and options give the same output bytes for any thread count: hulls.obj, parts.obj and
tree.json from the command line with --threads 1, 2 and the machine's count, on three meshes."""
import os
import subprocess
import sys

import numpy as np
import pytest

from support import cad_solids
from support.meshes import BUNNY, torus


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)


def outputs(mesh, out, threads, tau):
    r = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "decompose", str(mesh), "--out", str(out), "--tree",
                        "--tau", str(tau), "--threads", str(threads), "--no-progress"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    return {name: (out / name).read_bytes() for name in ("hulls.obj", "parts.obj", "tree.json")}


@pytest.mark.parametrize("name", ["bunny", "flange", "torus"])
def test_the_same_bytes_for_any_thread_count(tmp_path, name):
    if name == "bunny":
        mesh, tau = BUNNY, 4.0
    else:
        V, F = cad_solids.make("flange") if name == "flange" else torus(2.0, 0.5, 48, 16)
        mesh, tau = tmp_path / f"{name}.obj", 2.5
        write_obj(mesh, np.asarray(V), np.asarray(F))
    counts = sorted({1, 2, os.cpu_count() or 1})
    runs = {t: outputs(mesh, tmp_path / f"t{t}", t, tau) for t in counts}
    assert runs[1]["hulls.obj"].count(b"\no ") + runs[1]["hulls.obj"].startswith(b"o ") > 1   # several hulls
    for t in counts[1:]:
        for f in runs[1]:
            assert runs[t][f] == runs[1][f], f"{name}: {f} differs between 1 and {t} threads"
