#!/usr/bin/env python3
"""Does the decomposition depend on the pose? Parts and hull error across random rotations.

For the bunny and three shared meshes: ours over 10 rotations, CoACD and V-HACD 4 over 3 (they are
slower), each rotated copy decomposed and scored by the same neutral tool as bench/bench.py (hull
error of the union of hulls, as % of the rotated input's bounding-box diagonal). Prints min / max of
the part count and hull error per method.

    bench/bench.sh --rotation        (installs what bench/bench.sh installs, then runs this)
Writes out/bench/rotation.md.
"""
import json
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import bench  # noqa: E402  (same runner and metrics)

METHODS = [("ours", {"tau": 3.0, "cut_plane_selection": "bisector"}, 10),
           ("coacd", {"threshold": 0.05}, 3),
           ("vhacd4", {"resolution": 100000}, 3)]
MESHES = ["pymeshlab-bunny", "spot", "fandisk", "homer"]


def rotation(seed):
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)


def main():
    out = bench.REPO / "out" / "bench" / "rotation"
    out.mkdir(parents=True, exist_ok=True)
    lines = ["| mesh | method | setting | rotations | parts (min / max) | hull error % diag (min / max) |",
             "|---|---|---|---|---|---|"]
    print("\n".join(lines), flush=True)
    for name, src in bench.corpus(MESHES):
        base = out / f"{name}.obj"
        bench.to_obj(src, base)
        V, F = bench.read_obj(base)
        for method, params, n in METHODS:
            parts, errors = [], []
            for seed in range(n):
                inp = out / f"{name}_r{seed}.obj"
                write_obj(inp, V @ rotation(seed).T if seed else V, F)   # seed 0: as given
                hulls = out / f"{name}_r{seed}_{method}.obj"
                r = bench.run_method(method, params, inp, hulls, 1800)
                if "error" in r:
                    print(f"[rotation] {name} {method} seed {seed}: {r['error']}", flush=True)
                    continue
                m = bench.metrics(inp, hulls, 100000)
                parts.append(r["hulls"])
                errors.append(100 * m["hull_error"])
            setting = ", ".join(f"{k} {v}" for k, v in params.items())
            line = (f"| {name} | {method} | {setting} | {len(parts)} | {min(parts)} / {max(parts)} | "
                    f"{min(errors):.2f} / {max(errors):.2f} |") if parts else f"| {name} | {method} | {setting} | 0 | | |"
            lines.append(line)
            print(line, flush=True)
    (out.parent / "rotation.md").write_text("\n".join(lines) + "\n")
    print(f"[bench] {out.parent / 'rotation.md'}")


if __name__ == "__main__":
    main()
