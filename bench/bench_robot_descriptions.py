"""Every mesh-bearing URDF of example-robot-data through `python -m pymeshlab_acd robot` (the API it calls),
then checked: the rewritten URDF loads in PyBullet and settles on a floor when dropped (free base), its MJCF
compiles in MuJoCo and settles likewise, every hull is within the engine's limits and holds its part
(tests/support/budgets.py), and a second run from the cache. Writes bench/results/robot_descriptions.json/.md.

    python bench/bench_robot_descriptions.py [--engine physx] [--only NAME ...] [--out DIR]
"""
import argparse
import json
import pathlib
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

from support.budgets import check_hull_folders   # noqa: E402
from support.robot_sim import mujoco_compile, mujoco_drop, pybullet_drop, pybullet_load, settled   # noqa: E402
from support.robots import cache, descriptions, fetch_descriptions   # noqa: E402


def check(urdf, out, name, engine, share):
    row = {}
    if not (out / "collision").exists():
        return row   # collisions all primitives: nothing of ours to load
    try:
        row["pybullet_shapes"] = pybullet_load(out / f"{name}.urdf", share)
        pb = pybullet_drop(out / f"{name}.urdf", share)
        if pb is None:
            row.update(pybullet_free=None, pybullet_settled=None, pybullet_note="no state reported (over 127 links)")
        else:
            row.update(pybullet_free=pb["free"], pybullet_settled=settled(pb), pybullet_depth=pb["depth"] / pb["size"])
    except Exception as e:
        row["pybullet_error"] = str(e)[:200]
    try:
        row["mujoco_geoms"] = mujoco_compile(out / f"{name}.xml")["geoms"]
        mj = mujoco_drop(out / f"{name}.xml", out / ".drop_scene.xml")
        row.update(mujoco_free=mj is not None, mujoco_settled=settled(mj) if mj else None,
                   mujoco_lowest=mj["lowest"] / mj["size"] if mj else None)
    except Exception as e:
        row["mujoco_error"] = str(e)[:200]
    if (out / "collision").exists():
        n, within, holding, worst = check_hull_folders(out / "collision", engine)
        row.update(hull_files=n, within_budget=within, containing=holding, worst_excess=worst)
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--engine", default="physx")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--out", default=str(cache() / "bench-robot-descriptions"))
    ap.add_argument("--results", default=str(HERE / "results" / "robot_descriptions"))
    ap.add_argument("--recheck", action="store_true", help="keep the times and counts of the last run, write "
                    "every robot again from its cache (nothing decomposed) and redo the checks")
    a = ap.parse_args()
    from pymeshlab_acd.robot import decompose_robot
    pkg = fetch_descriptions()
    share = pkg.parent
    out_root = pathlib.Path(a.out)
    hull_cache = out_root / "hull-cache"
    import shutil
    if a.recheck:
        return recheck(a, pkg, out_root, hull_cache, share)
    shutil.rmtree(out_root, ignore_errors=True)
    rows = []
    for urdf in descriptions(pkg):
        name = urdf.relative_to(pkg / "robots").parts[0] + "/" + urdf.stem
        if a.only and not any(o in name for o in a.only):
            continue
        out = out_root / name
        t0 = time.perf_counter()
        s = decompose_robot(urdf, out, engine=a.engine, formats=("urdf", "mjcf", "usd"), cache_dir=hull_cache,
                            resolve_paths=True)
        first = time.perf_counter() - t0
        t0 = time.perf_counter()
        again = decompose_robot(urdf, out_root / "again" / name, engine=a.engine, formats=("urdf",),
                                cache_dir=hull_cache, resolve_paths=True)
        second = time.perf_counter() - t0
        row = dict(robot=name, links=len(s["links"]), meshes=s["meshes"], decomposed=s["decomposed"],
                   hulls=s["hulls"], failed=s["failed"], seconds=first, cached_seconds=second,
                   cached_decomposed=again["decomposed"],
                   errors=[f"{r['link']}: {r['error']}" for r in s["links"] if r.get("error")][:3],
                   decompose_seconds=sum(r.get("seconds", 0) for r in s["links"]))
        row.update(check(urdf, out, urdf.stem, a.engine, share))
        rows.append(row)
        print(json.dumps(row), flush=True)
    res = pathlib.Path(a.results)
    res.parent.mkdir(parents=True, exist_ok=True)
    res.with_suffix(".json").write_text(json.dumps(dict(engine=a.engine, rows=rows), indent=1))
    res.with_suffix(".md").write_text(table(rows, a.engine))
    print(table(rows, a.engine))


def recheck(a, pkg, out_root, hull_cache, share):
    from pymeshlab_acd.robot import decompose_robot
    res = pathlib.Path(a.results)
    old = json.loads(res.with_suffix(".json").read_text())
    rows = []
    for row in old["rows"]:
        urdf = next(p for p in descriptions(pkg) if row["robot"] == p.relative_to(pkg / "robots").parts[0] + "/" + p.stem)
        out = out_root / row["robot"]
        s = decompose_robot(urdf, out, engine=old["engine"], formats=("urdf", "mjcf", "usd"), cache_dir=hull_cache,
                            resolve_paths=True)
        assert s["decomposed"] == 0 and s["hulls"] == row["hulls"], row["robot"]
        keep = {k: row[k] for k in ("robot", "links", "meshes", "decomposed", "hulls", "failed", "seconds",
                                    "cached_seconds", "cached_decomposed", "errors", "decompose_seconds")}
        keep.update(check(urdf, out, urdf.stem, old["engine"], share))
        rows.append(keep)
        print(json.dumps(keep), flush=True)
    res.with_suffix(".json").write_text(json.dumps(dict(engine=old["engine"], rows=rows), indent=1))
    res.with_suffix(".md").write_text(table(rows, old["engine"]))
    print(table(rows, old["engine"]))


def table(rows, engine):
    yes = lambda v: "-" if v is None else ("yes" if v else "no")   # noqa: E731
    lines = [f"Engine `{engine}`; every URDF of example-robot-data 6.0.0 that names meshes. Time: the first run "
             "(meshes another robot already decomposed come from the cache); again: the same robot once more.", "",
             "| robot | collision meshes | decomposed | hulls | failed | time s | again s | PyBullet loads / settles | "
             "MuJoCo compiles / settles | hulls in budget, holding their part |",
             "|---|---:|---:|---:|---:|---:|---:|---|---|---|"]
    for r in rows:
        if r["hulls"] == 0:
            pb = mj = "- (its meshes are not in the package)" if r["failed"] else "- (collisions all primitives)"
        else:
            pb = ("error" if "pybullet_error" in r else f"yes / {yes(r['pybullet_settled'])}"
                  + ("" if r.get("pybullet_free") or r.get("pybullet_note") else " (fixed base)")
                  + (f" ({r['pybullet_note']})" if r.get("pybullet_note") else ""))
            mj = "error" if "mujoco_error" in r else f"yes / {yes(r.get('mujoco_settled'))}"
        hb = f"{r.get('within_budget', 0)} / {r.get('containing', 0)} of {r.get('hull_files', 0)}"
        lines.append(f"| {r['robot']} | {r['links']} | {r['decomposed']} | {r['hulls']} | {r['failed']} | "
                     f"{r['seconds']:.1f} | {r['cached_seconds']:.2f} | {pb} | {mj} | {hb} |")
    tot = lambda k: sum(r[k] for r in rows)   # noqa: E731
    lines += ["", f"{len(rows)} robots, {tot('hulls')} hulls, {tot('decomposed')} meshes decomposed, "
                  f"{tot('failed')} failed; {tot('seconds'):.0f} s in all, again from the cache {tot('cached_seconds'):.0f} s."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
