"""2D benchmark: our polygon decomposition beside CGAL's Partition_2 on the same polygons, in one run.

For each polygon (the paper authors' .poly test set in ../shared/data/polygons when present, plus
generated stars, combs and a noisy outline), `polygon_peer` (plugin/core/bench) runs ours at tau = 2, 1,
0.5 (the polygon's units, as the paper's Figure 8) with the bisector and the best cut line, and CGAL's
approx_convex_partition_2 (Hertel-Mehlhorn), greene_approx_convex_partition_2 and, up to 120
vertices, optimal_convex_partition_2 (O(n^4)); CGAL's pieces are exactly convex and need simple
polygons (no holes). Prints a markdown table; writes it to out/bench/polygons.md.
"""
import json
import math
import os
import pathlib
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED = REPO.parent / "shared" / "data" / "polygons"
TAUS = "2,1,0.5,1e-9"   # the last: exactly convex pieces, as CGAL's


def write_poly(path, loop):
    with open(path, "w") as f:
        f.write(f"1\n{len(loop)} out\n")
        for x, y in loop:
            f.write(f"{x:.9g} {y:.9g}\n")
        f.write(" ".join(str(i + 1) for i in range(len(loop))) + "\n")


def generated(folder):
    sys.path.insert(0, str(REPO / "tests"))
    from support.polygons import comb, noisy_blob, star
    out = []
    for name, loop in [("star 5", star()), ("star 24", star(24, 20, 12)), ("comb 12", comb(12) * 3),
                       ("noisy outline 452", noisy_blob())]:
        p = os.path.join(folder, name.replace(" ", "_") + ".poly")
        write_poly(p, [tuple(v) for v in loop])
        out.append((name + " (generated)", p))
    return out


def main():
    build = os.environ["ACD_BUILD_DIR"]
    peer = os.path.join(build, "core", "polygon_peer")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        cases = generated(tmp)
        if SHARED.exists():
            names = ["simple1", "simple3", "simple4", "simple5", "simple6", "simple7", "simple8", "mammoth",
                     "dsb", "dragon", "BarbedThing", "batlogo", "star__star4_noise", "nazca__nazca_monkey",
                     "hole1", "hole2", "hole3", "hole5", "fisheye", "neuron__neuron"]
            cases += [(n, str(SHARED / f"{n}.poly")) for n in names if (SHARED / f"{n}.poly").exists()]
        else:
            print(f"({SHARED} not present: generated polygons only)")
        for name, path in cases:
            r = subprocess.run([peer, path, TAUS, "120"], capture_output=True, text=True, timeout=1800)
            if r.returncode != 0:
                print(f"{name}: {r.stderr.strip()}")
                continue
            res = [json.loads(l) for l in r.stdout.splitlines()]
            rows.append((name, res))
    head = ("| polygon | vertices | holes | notches | ours bisector tau 2 / 1 / 0.5 | ours best tau 2 / 1 / 0.5 "
            "| ours time (ms, tau 0.5: bisector / best) | ours exactly convex (tau 1e-9: bisector / best) "
            "| CGAL approx (Hertel-Mehlhorn) | CGAL Greene | CGAL optimal |")
    lines = [head, "|" + " --- |" * 11]
    for name, res in rows:
        inp = res[0]
        get = lambda m: [x for x in res if x["method"] == m]
        bis, best = get("ours_bisector"), get("ours_best")
        cg = lambda m: (f"{get(m)[0]['parts']}{'' if get(m)[0]['valid'] else ' (invalid)'} "
                        f"({1000 * get(m)[0]['seconds']:.2f} ms)" if get(m) else
                        ("holes: n/a" if inp["holes"] else "-"))
        lines.append(f"| {name} | {inp['vertices'] + 0} | {inp['holes']} | {inp['notches']} | "
                     f"{' / '.join(str(x['parts']) for x in bis[:3])} | {' / '.join(str(x['parts']) for x in best[:3])} | "
                     f"{1000 * bis[2]['seconds']:.2f} / {1000 * best[2]['seconds']:.2f} | "
                     f"{bis[3]['parts']} / {best[3]['parts']} | "
                     f"{cg('cgal_approx')} | {cg('cgal_greene')} | {cg('cgal_optimal')} |")
    table = "\n".join(lines)
    print(table)
    out = REPO / "out" / "bench"
    out.mkdir(parents=True, exist_ok=True)
    (out / "polygons.md").write_text(table + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
