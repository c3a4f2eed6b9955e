#!/usr/bin/env python3
"""Robot corpus benchmark: every mesh of example-robot-data 6.0.0 (PyPI; 491 STL/OBJ meshes of robot
descriptions), decomposed at the filter's default settings, each part's hull checked against tau by
an independent measure (tests/support/hull_reach.py: scipy's Qhull and exact distances in numpy); and the peers
(CoACD 0.05 and 0.1, V-HACD 4, CGAL 16 and 45) beside ours on a fixed sample of 60 meshes that
represents every robot.

    bench/bench.sh --robots                  whole corpus (ours) and the 60-mesh sample (all methods)
    bench/bench.sh --robots --quick          a fixed 20-mesh subset: ours afresh, the peers' rows resumed
    bench/bench.sh --robots --methods ours   ours only (--methods peers: the peers only)
Meshes closed as shipped are decomposed as given; open or non-manifold ones take the batch's `auto`
path (alpha wrap, with the hollow check). Rows are kept per method group in out/robots/robots-ours.json
and robots-peers.json, so a run resumes where the last one stopped (--fresh starts over; a fresh
checkout starts from the rows published in bench/results/robots/) and the two groups can run side by side;
the summary (robots.md) is written from both. `--quick` always runs ours afresh (its own store,
robots-ours-quick.json) beside the peers' kept rows (pinned versions; `--fresh` reruns them too).
"""
import argparse
import contextlib
import fcntl
import hashlib
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time
import zipfile

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "bench"))
sys.path.insert(0, str(REPO / "tests"))
import bench  # noqa: E402  (run_method, metrics, read_obj)
from support.robots import (WHEEL, cache, certificate, corpus, fetch_corpus, mesh_name, robot_of,  # noqa: E402
                            run_ours, sample)

# CoACD at its default and at 0.1, V-HACD 4 and CGAL at their defaults.
PEERS = [s for s in bench.SETTINGS if s[0] != "ours" and s[1] != "resolution 100k" and s[1] != "45 volumes"]
OURS = ("ours", "tau 2.5% bisector_or_face (default)")


def hulls_obj(out_dir, dst):
    files = sorted((pathlib.Path(out_dir) / "collision").glob("acd_hull_*.obj"))
    bench.write_hulls(dst, [bench.read_obj(f) for f in files])
    return len(files)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="a fixed 20-mesh subset: ours afresh, beside the peers' kept rows")
    ap.add_argument("--methods", choices=["all", "ours", "peers"], default="all")
    ap.add_argument("--fresh", action="store_true", help="discard the rows of earlier runs")
    ap.add_argument("--report", action="store_true", help="run nothing: write the summary of the rows kept")
    ap.add_argument("--sample", type=int, default=60, help="meshes the peers run on (every robot represented)")
    ap.add_argument("--limit", type=int, default=0, help="at most this many meshes for ours (0: all)")
    ap.add_argument("--samples", type=int, default=100000, help="Monte Carlo samples per metric")
    ap.add_argument("--timeout", type=int, default=900, help="seconds per method run")
    ap.add_argument("--out", default=str(REPO / "out" / "robots"))
    ap.add_argument("--reverse", action="store_true",
                    help="meshes in reverse order: a second run on the same --out meets the first halfway")
    args = ap.parse_args()
    t_start = time.perf_counter()
    meshes = fetch_corpus()
    files = all_files = corpus(meshes)
    peer_set = set(sample(files, meshes, 20 if args.quick else args.sample))
    if args.quick:
        files = sorted(peer_set)
    elif args.limit:
        files = files[:args.limit]
    out = pathlib.Path(args.out)
    (out / "inputs").mkdir(parents=True, exist_ok=True)
    groups = [] if args.report else ["ours", "peers"] if args.methods == "all" else [args.methods]
    stores = {g: out / f"robots-{g}.json" for g in ("ours", "peers")}
    if args.quick:   # ours always runs afresh on the subset (the check of the code at hand), in its own store
        stores["ours"] = out / "robots-ours-quick.json"
        stores["ours"].unlink(missing_ok=True)
    for g in groups if args.fresh else []:   # the rows kept are read under a lock below: gone, not only ignored
        stores[g].unlink(missing_ok=True)
    for g, f in stores.items():   # a fresh checkout resumes from the rows published in bench/results/robots/
        published = REPO / "bench" / "results" / "robots" / f.name
        if not f.exists() and published.exists() and not args.fresh:
            f.write_text(published.read_text())
    done = {g: ([] if args.fresh and g in groups else json.loads(f.read_text()) if f.exists() else [])
            for g, f in stores.items()}
    have = {(r["mesh"], r["method"], r["setting"]) for rs in done.values() for r in rs}
    n_peers = len(peer_set) if "peers" in groups else 0
    print(f"[robots] {len(files) if 'ours' in groups else 0} meshes for ours; peers on {n_peers}", flush=True)
    print("| mesh | faces | method | setting | hulls | hull error (% diag) | volume IoU | time (s) | "
          "worst hull / tau | preprocessing |\n|---|---|---|---|---|---|---|---|---|---|", flush=True)
    # The quick subset first, then the rest of the sample, then the other meshes: a run cut short
    # still covers every robot side by side.
    quick = set(sample(files, meshes, 20))
    todo_meshes = set(files) | (peer_set if "peers" in groups else set())
    for p in sorted(todo_meshes, key=lambda p: (p not in quick, p not in peer_set, p), reverse=args.reverse):
        name = mesh_name(p, meshes, all_files)
        inp = out / "inputs" / (name.replace("/", "__") + ".obj")
        if not inp.exists():
            bench.to_obj(p, inp)
        faces = bench.face_count(inp)
        todo = []
        if "ours" in groups and p in files:
            todo.append(("ours", OURS[1], None))
        if "peers" in groups and p in peer_set:
            todo += [s for s in PEERS]
        for method, label, params in todo:
            group = "ours" if method == "ours" else "peers"
            key = (name, method, label)
            with locked(stores[group]) as rows:   # another run on the same --out may have done it
                if key in have or any((r["mesh"], r["method"], r["setting"]) == key for r in rows):
                    continue
            row = dict(mesh=name, faces=faces, method=method, setting=label)
            row.update(run_ours_row(p, inp, args) if method == "ours" else run_peer_row(method, params, inp, args,
                                                                                        out, name, label))
            with locked(stores[group]) as rows:
                if not any((r["mesh"], r["method"], r["setting"]) == key for r in rows):
                    rows.append(row)
                done[group] = list(rows)
            print(line(row), flush=True)
    rows = done["ours"] + done["peers"]
    if "ours" in groups:
        print(f"[robots] ours: {len(done['ours'])} meshes, {time.perf_counter() - t_start:.0f} s wall in this run "
              "(each decomposed, certified and scored)", flush=True)
    summary = summarize(rows, meshes)
    print("\n".join(summary))
    (out / "robots.md").write_text("\n".join(summary) + "\n\n" + "\n".join(table(rows)) + "\n")


@contextlib.contextmanager
def locked(store):
    """The rows of a store, read and written back under an exclusive lock, so that two runs (e.g. one with
    --reverse) can share one --out and meet halfway without running a mesh twice."""
    with open(store.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        rows = json.loads(store.read_text()) if store.exists() else []
        n = len(rows)
        yield rows
        if len(rows) != n:
            tmp = store.with_suffix(".tmp")
            tmp.write_text(json.dumps(rows, indent=1))
            tmp.replace(store)


def run_ours_row(src, inp, args):
    with tempfile.TemporaryDirectory() as tmp:
        rec = run_ours(src, pathlib.Path(tmp) / "o", args.timeout)
        if rec.get("status") != "ok":
            return dict(error=str(rec.get("error"))[:200])
        worst, over = certificate(pathlib.Path(tmp) / "o", rec["tau_model_units"])
        hobj = pathlib.Path(tmp) / "hulls.obj"
        row = dict(hulls=hulls_obj(pathlib.Path(tmp) / "o", hobj), time=rec["time"], worst=worst, over=over,
                   preprocessing=rec["preprocessing"], tau_convex=rec.get("tau_convex"))
        row.update(bench.metrics(inp, hobj, args.samples))
        return row


def run_peer_row(method, params, inp, args, out, name, label):
    hobj = out / "hulls" / f"{name.replace('/', '__')}__{method}__{label.split()[0]}{label.split()[1]}.obj"
    hobj.parent.mkdir(exist_ok=True)
    r = bench.run_method(method, params, inp, hobj, args.timeout)
    if "error" not in r:
        r.update(bench.metrics(inp, hobj, args.samples))
    return r


def line(r):
    if "error" in r:
        return f"| {r['mesh']} | {r['faces']} | {r['method']} | {r['setting']} | error: {r['error'][:80]} | | | | | |"
    iou = "n/a" if r.get("iou") is None else f"{r['iou']:.3f}"
    worst = f"{r['worst']:.2f}" if "worst" in r else ""
    return (f"| {r['mesh']} | {r['faces']} | {r['method']} | {r['setting']} | {r['hulls']} | "
            f"{100 * r.get('hull_error', float('nan')):.2f} | {iou} | {r['time']:.2f} | {worst} | "
            f"{r.get('preprocessing', '')} |")


def summarize(rows, meshes):
    ours = [r for r in rows if r["method"] == "ours"]
    ok = [r for r in ours if "error" not in r]
    over = sum(r["over"] for r in ok)
    parts = sum(r["hulls"] for r in ok)
    out = [f"Ours at default settings on {len(ours)} meshes: {len(ok)} decomposed, {len(ours) - len(ok)} failed; "
           f"{parts} parts, {over} of them with a hull farther than tau (+1%) from the part by the independent "
           f"measure; worst part hull / tau {max((r['worst'] for r in ok), default=0):.3f}; "
           f"{sum(1 for r in ok if r['preprocessing'].startswith('welded'))} welded, "
           f"{sum(1 for r in ok if r['preprocessing'].startswith('alpha_wrap'))} wrapped; "
           f"{sum(1 for r in ok if r.get('tau_convex'))} certified tau-convex by the core; total time "
           f"{sum(r['time'] for r in ok):.0f} s.", ""]
    keyed = sample_rows(rows)
    if keyed:
        out.append(f"Every method on the {len(keyed)}-mesh sample (medians over the meshes each method "
                   "decomposed; time summed):")
        out.append("")
        out.append("| method | setting | median hulls | median hull error (% diag) | median outside / inside "
                   "(% diag, closed inputs) | total time (s) | failures |")
        out.append("|---|---|---|---|---|---|---|")
        for key in [OURS] + [(m, l) for m, l, _ in PEERS]:
            rs = [d.get(key) for d in keyed.values()]
            good = [r for r in rs if r and "error" not in r]
            med = lambda xs: statistics.median(xs) if xs else float("nan")
            split = [r for r in good if r.get("hull_error_outside") is not None]
            out.append(f"| {key[0]} | {key[1]} | {med([r['hulls'] for r in good]):g} | "
                       f"{100 * med([r['hull_error'] for r in good]):.2f} | "
                       f"{100 * med([r['hull_error_outside'] for r in split]):.2f} / "
                       f"{100 * med([r['hull_error_inside'] for r in split]):.2f} ({len(split)}) | "
                       f"{sum(r['time'] for r in good):.0f} | {len(rs) - len(good)} |")
        out += [""] + front(keyed)
    return out


def front(keyed, ours=OURS):
    """Ours (the rows under key `ours`) against the peers per mesh of the sample, as a user weighs them:
    (hulls, hull error) points, fewer and lower both better; and time against CoACD at its default."""
    good = lambda r: r is not None and "error" not in r
    beats = lambda b, a: (b["hulls"] <= a["hulls"] and b["hull_error"] <= a["hull_error"]
                          and (b["hulls"] < a["hulls"] or b["hull_error"] < a["hull_error"]))
    coacd = ("coacd", "threshold 0.05 (default)")
    peers = [(m, l) for m, l, _ in PEERS]
    mine = [d for d in keyed.values() if good(d.get(ours))]
    pair = [d for d in mine if good(d.get(coacd))]
    if not pair:
        return []
    free = sum(not beats(d[coacd], d[ours]) for d in pair)
    on_front = sum(not any(good(d.get(k)) and beats(d[k], d[ours]) for k in peers) for d in mine)
    med = lambda xs: sorted(xs)[len(xs) // 2]
    t_ours, t_coacd = sum(d[ours]["time"] for d in pair), sum(d[coacd]["time"] for d in pair)
    big = max(pair, key=lambda d: d[ours]["faces"])
    return [f"Per mesh of the sample: ours is not dominated by CoACD 0.05 (fewer or as many hulls at a lower or "
            f"equal hull error) on {free} of {len(pair)} meshes ({100 * free / len(pair):.0f}%), and on or below "
            f"the front of every peer on {on_front} of {len(mine)} ({100 * on_front / len(mine):.0f}%); median "
            f"hulls {med([d[ours]['hulls'] for d in pair])} against CoACD 0.05's "
            f"{med([d[coacd]['hulls'] for d in pair])}; time {t_ours:.0f} s against {t_coacd:.0f} s "
            f"({t_ours / t_coacd:.2f} of it); on the largest mesh ({big[ours]['faces']} faces) "
            f"{big[ours]['time']:.1f} s against {big[coacd]['time']:.1f} s."]


def sample_rows(rows):
    """mesh -> {(method, setting): row} for the meshes the peers ran on."""
    keyed = {}
    for r in rows:
        keyed.setdefault(r["mesh"], {})[(r["method"], r["setting"])] = r
    return {m: d for m, d in sorted(keyed.items()) if any(k[0] != "ours" for k in d)}


def table(rows):
    """The sample side by side (hulls / hull error % diag / seconds per method), then ours on every mesh."""
    keys = [OURS] + [(m, l) for m, l, _ in PEERS]
    cell = lambda r: ("-" if r is None else "error" if "error" in r else
                      f"{r['hulls']} / {100 * r['hull_error']:.2f} / {r['time']:.1f}")
    out = ["Per mesh of the sample: hulls / hull error (% diag) / time (s).", "",
           "| mesh | faces | " + " | ".join(f"{m} {l}" for m, l in keys) + " |",
           "|---|---|" + "---|" * len(keys)]
    for m, d in sample_rows(rows).items():
        faces = next(iter(d.values()))["faces"]
        out.append(f"| {m} | {faces} | " + " | ".join(cell(d.get(k)) for k in keys) + " |")
    out += ["", "Ours on every mesh.", "",
            "| mesh | faces | method | setting | hulls | hull error (% diag) | volume IoU | time (s) | "
            "worst hull / tau | preprocessing |", "|---|---|---|---|---|---|---|---|---|---|"]
    out += [line(r) for r in sorted((r for r in rows if r["method"] == "ours"), key=lambda r: r["mesh"])]
    return out


if __name__ == "__main__":
    sys.exit(main())
