#!/usr/bin/env python3
"""Load every model a batch exported (python -m pymeshlab_acd batch IN OUT) in MuJoCo (MJCF) and
PyBullet (URDF), drop it onto a plane from 10% of its size, and print where it comes to rest.

    python bench/sim_check.py OUT_DIR [--seconds 12]
"""
import argparse
import json
import pathlib
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
from support.simulators import drop_mujoco, drop_pybullet, hull_vertices  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--seconds", type=float, default=12.0, help="simulated time, at least (longer for large models)")
    a = ap.parse_args()
    folders = sorted(f.parent for f in pathlib.Path(a.out_dir).rglob("summary.json")
                     if f.parent != pathlib.Path(a.out_dir) and json.loads(f.read_text()).get("status") == "ok")
    print(f"{'model':<22} {'size':>8} {'sim s':>6} {'hulls':>5}  {'MuJoCo: lowest % size':>21} {'speed':>8}  "
          f"{'PyBullet: lowest % size':>23} {'speed':>8}  {'time s':>6}")
    bad = 0
    for d in folders:
        urdf = next(d.glob("*.urdf"))
        mjcf = urdf.with_suffix(".xml")
        files, hulls = hull_vertices(d, urdf)
        t = time.perf_counter()
        size = float(np.linalg.norm(np.ptp(np.concatenate(hulls), 0)))
        # Model units are metres here, so a large model falls and settles slowly: simulate longer.
        secs = max(a.seconds, 10 * (size / 9.81) ** 0.5)
        mj = drop_mujoco(mjcf, d / "scene.xml", urdf.stem, hulls, height=0.1 * size, seconds=secs)
        pb = drop_pybullet(urdf, hulls, height=0.1 * size, seconds=secs)
        ok = all(abs(r["lowest"]) < 0.01 * size and r["speed"] < 0.01 * size for r in (mj, pb))
        bad += not ok
        print(f"{d.name:<22} {size:>8.3g} {secs:>6.0f} {len(files):>5}  {100 * mj['lowest'] / size:>21.3f} {mj['speed']:>8.2g}  "
              f"{100 * pb['lowest'] / size:>23.3f} {pb['speed']:>8.2g}  {time.perf_counter() - t:>6.1f}"
              + ("" if ok else "  NOT AT REST ON THE PLANE"))
    print(f"{len(folders)} models, {len(folders) - bad} at rest on the plane in both simulators")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
