#!/usr/bin/env python3
"""Our settings side by side on the robot corpus's fixed sample (20 meshes by default, the `bench.sh
--robots --quick` subset; `--sample 60` is the peers' sample): for each setting (cut selection, tau, merge_parts), per mesh the hulls, the hull error
(acd_metrics, % of the box diagonal; outside / inside the solid where it is closed), the certificate
(worst part hull / tau, measured independently) and the time, with CoACD 0.05's published row beside.

    python3 scripts/study_settings.py --settings best:2:0,best:2:1,bisector:3:1 [--out out/study.jsonl]

With the peers' published rows (docs/robots/robots-peers.json) it also prints, per setting, the
comparison with the peers that bench_robots' front() prints for the default setting.

A setting is selection:tau:merge (merge 1 or 0), optionally followed by :wrap_alpha:wrap_offset (%).
Rows are appended to --out (a rerun skips the rows it has) and the summary table is printed from them:
medians over the meshes every setting finished.
"""
import argparse
import json
import pathlib
import statistics
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "scripts"))
sys.path.insert(0, str(REPO / "tests"))
import bench  # noqa: E402
import bench_robots as br  # noqa: E402


def run(p, inp, sel, tau, merge, timeout, wrap=()):
    from pymeshlab_acd import batch
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "o"
        opts = dict(batch.DEFAULTS, tau=tau, cut_plane_selection=sel, merge_parts=merge, max_hull_vertices=0,
                    formats=["obj"], timeout=timeout)
        if wrap:
            opts.update(wrap_alpha=float(wrap[0]), wrap_offset=float(wrap[1]))
        rec = batch.run_child(str(p), str(out), opts)
        if rec.get("status") != "ok":
            return dict(error=str(rec.get("error"))[:200])
        worst, over = br.certificate(out, rec["tau_model_units"])
        hobj = pathlib.Path(tmp) / "hulls.obj"
        row = dict(hulls=br.hulls_obj(out, hobj), time=rec["time"], worst=worst, over=over,
                   preprocessing=rec["preprocessing"])
        row.update(bench.metrics(inp, hobj, 50000))
        return row


def summary(rows, settings, peers):
    coacd = {r["mesh"]: r for r in peers if r["method"] == "coacd" and "0.05" in r["setting"]}
    done = {}
    for r in rows:
        done.setdefault(r["mesh"], {})[r["setting"]] = r
    meshes = [m for m, d in done.items() if all(s in d and "error" not in d[s] for s in settings)]
    med = statistics.median
    for label, ms in (("every setting finished", meshes),
                      ("those with a CoACD 0.05 row too", [m for m in meshes if "hulls" in coacd.get(m, {})])):
        print(f"\n{len(ms)} meshes: {label} (medians; time: total)\n")
        print("| setting | hulls | hull error % diag | worst hull / tau | parts over tau | time (s) |")
        print("| --- | --- | --- | --- | --- | --- |")
        for s in settings:
            rs = [done[m][s] for m in ms]
            print(f"| {s} | {med(r['hulls'] for r in rs)} | {100 * med(r['hull_error'] for r in rs):.2f} | "
                  f"{max(r['worst'] for r in rs):.3f} | {sum(r['over'] for r in rs)} | {sum(r['time'] for r in rs):.0f} |")
        if ms and all("hulls" in coacd.get(m, {}) for m in ms):
            cs = [coacd[m] for m in ms]
            print(f"| CoACD 0.05 (published rows) | {med(c['hulls'] for c in cs)} | "
                  f"{100 * med(c['hull_error'] for c in cs):.2f} | | | {sum(c['time'] for c in cs):.0f} |")
    faces = {r["mesh"]: r["faces"] for r in peers}
    for s in settings:
        ours = [dict(d[s], method="ours", setting=s, faces=faces[m]) for m, d in done.items() if s in d and m in faces]
        print(f"\n{s}: " + " ".join(br.front(br.sample_rows(peers + ours), ours=("ours", s))))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--settings", default="best:2:0,best:2:1,bisector:2:1,bisector:3:1")
    ap.add_argument("--out", default=str(REPO / "out" / "study.jsonl"))
    ap.add_argument("--timeout", type=int, default=900)
    ap.add_argument("--sample", type=int, default=20, help="meshes of the peers' sample to run (20 or 60)")
    ap.add_argument("--wrapped-only", action="store_true",
                    help="only the meshes that an earlier row of --out shows alpha wrapped")
    ap.add_argument("--report", action="store_true", help="run nothing: print the summary of the rows kept")
    args = ap.parse_args()
    settings = args.settings.split(",")
    meshes = br.fetch_corpus()
    files = br.corpus(meshes)
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    rows = [json.loads(line) for line in out.read_text().splitlines()] if out.exists() else []
    have = {(r["mesh"], r["setting"]) for r in rows}
    wrapped = {r["mesh"]: "alpha_wrap" in r.get("preprocessing", "") for r in rows if "preprocessing" in r}
    for p in ([] if args.report else sorted(br.sample(files, meshes, args.sample))):
        name = br.mesh_name(p, meshes, files)
        if args.wrapped_only and not wrapped.get(name, True):
            continue
        inp = REPO / "out" / "robots" / "inputs" / (name.replace("/", "__") + ".obj")
        if not inp.exists():
            inp.parent.mkdir(parents=True, exist_ok=True)
            bench.to_obj(p, inp)
        for s in settings:
            if (name, s) in have:
                continue
            sel, tau, merge, *wrap = s.split(":")
            row = dict(mesh=name, setting=s, **run(p, inp, sel, float(tau), merge == "1", args.timeout, wrap))
            rows.append(row)
            with out.open("a") as f:
                f.write(json.dumps(row) + "\n")
            print(json.dumps({k: row.get(k) for k in ("mesh", "setting", "hulls", "hull_error", "time", "worst")}),
                  flush=True)
    summary(rows, settings, json.loads((REPO / "docs" / "robots" / "robots-peers.json").read_text()))


if __name__ == "__main__":
    main()
