#!/usr/bin/env python3
"""Our settings side by side on the robot corpus's fixed sample (20 meshes by default, the `bench.sh
--robots --quick` subset; `--sample 60` is the peers' sample), or with `--set objects` on meshes that are
not robot links (bench/object_set.py: scans, figures, CAD solids, modelled household objects): for each setting (cut selection, tau, merge_parts), per mesh the hulls, the hull error
(acd_metrics, % of the box diagonal; outside / inside the solid where it is closed), the certificate
(worst part hull / tau, measured independently) and the time, with CoACD 0.05's published row beside.

    python3 bench/study_settings.py --settings best:2:0,best:2:1,bisector:3:1 [--out out/study.jsonl]
    python3 bench/study_settings.py --set objects --settings bisector_or_face:2.5:1,coacd:0.05

With the peers' published rows (bench/results/robots/robots-peers.json) it also prints, per setting, the
comparison with the peers that bench_robots' front() prints for the default setting.

A setting is selection:tau:merge (merge 1 or 0), optionally followed by :wrap_alpha:wrap_offset (%);
`coacd:THRESHOLD` runs CoACD itself on the same machine (scored alike), `vhacd:RESOLUTION` V-HACD 4, so that times compare with
ours run for run: the summary then gives each of our settings' time against it, in all and on the
largest mesh, and how each of our settings fares against it mesh by mesh: on how many meshes CoACD is as
good or better in both hulls and error (errors within 2% count as equal, "dominated"), total hulls and
median errors side by side.
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
sys.path.insert(0, str(REPO / "bench"))
sys.path.insert(0, str(REPO / "tests"))
import bench  # noqa: E402
import bench_robots as br  # noqa: E402
import object_set  # noqa: E402


def run(p, inp, sel, tau, merge, timeout, wrap=(), cut_search=None):
    from pymeshlab_acd import batch
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "o"
        opts = dict(batch.DEFAULTS, tau=tau, cut_plane_selection=sel, merge_parts=merge, max_hull_vertices=0,
                    formats=["obj"], timeout=timeout, cache=False)   # timed: decomposed every time
        if cut_search:
            opts["cut_search"] = cut_search
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


# A peer's setting prefix: its method in bench.run_method and its one parameter.
PEERS = {"coacd": ("coacd", lambda x: {"threshold": float(x)}),
         "vhacd": ("vhacd4", lambda x: {"resolution": int(float(x))})}


def run_peer(setting, inp, timeout):
    """A peer's row (`coacd:THRESHOLD`, `vhacd:RESOLUTION`), scored as ours are."""
    prefix, value = setting.split(":")
    method, params = PEERS[prefix]
    with tempfile.TemporaryDirectory() as tmp:
        hobj = pathlib.Path(tmp) / "hulls.obj"
        r = bench.run_method(method, params(value), inp, hobj, timeout)
        if "error" in r:
            return dict(error=r["error"])
        row = dict(hulls=r["hulls"], time=r["time"], worst=None, over=0)
        row.update(bench.metrics(inp, hobj, 50000))
        return row


def plot(done, settings, title, path):
    """Hulls against hull error, one point per mesh and setting, each setting's medians as a large mark."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for k, s in enumerate(settings):
        rs = [d[s] for d in done.values() if "hull_error" in d.get(s, {})]
        if not rs:
            continue
        c = plt.cm.tab10.colors[k % 10]
        ax.scatter([r["hulls"] for r in rs], [max(1e-3, 100 * r["hull_error"]) for r in rs], s=12, color=c, alpha=0.45)
        ax.scatter([statistics.median(r["hulls"] for r in rs)], [100 * statistics.median(r["hull_error"] for r in rs)],
                   s=160, color=c, edgecolor="black", marker="*",
                   label=f"{s}: {sum(r['hulls'] for r in rs)} hulls in all, {len(rs)} meshes")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("hulls")
    ax.set_ylabel("hull error (% of the diagonal; exact pieces at 0.001)")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def time_against(done, ours, theirs):
    """Our setting's time against a `coacd:` setting's run on this machine, over the meshes both did."""
    both = [d for d in done.values() if "hull_error" in d.get(ours, {}) and "hull_error" in d.get(theirs, {})]
    if not both:
        return ""
    t, c = sum(d[ours]["time"] for d in both), sum(d[theirs]["time"] for d in both)
    big = max(both, key=lambda d: d[theirs]["faces"])
    return (f"{ours}: time against {theirs} run here, on the {len(both)} meshes both decomposed: {t:.0f} s "
            f"against {c:.0f} s ({t / c:.2f} of it); on the largest ({big[theirs]['faces']} faces) "
            f"{big[ours]['time']:.1f} s against {big[theirs]['time']:.1f} s ({big[ours]['time'] / big[theirs]['time']:.2f}).")


def dominated(o, c, band=0.02):
    """c is as good as o in hulls and error and better in one (errors within `band` of each other tie)."""
    tie = abs(c["hull_error"] - o["hull_error"]) <= band * max(c["hull_error"], o["hull_error"])
    no_worse = c["hulls"] <= o["hulls"] and (tie or c["hull_error"] < o["hull_error"])
    return no_worse and (c["hulls"] < o["hulls"] or not tie)


def against(done, ours, theirs):
    """Mesh by mesh against a `coacd:` setting run here: dominated count, total hulls, median errors."""
    both = [d for d in done.values() if "hull_error" in d.get(ours, {}) and "hull_error" in d.get(theirs, {})]
    if not both:
        return ""
    med = statistics.median
    dom = [d for d in both if dominated(d[ours], d[theirs])]
    h, c = sum(d[ours]["hulls"] for d in both), sum(d[theirs]["hulls"] for d in both)
    return (f"{ours} against {theirs}, {len(both)} meshes: dominated on {len(dom)} "
            f"({100 * (1 - len(dom) / len(both)):.0f}% not dominated); hulls {h} against {c} ({h / c:.2f} of it); "
            f"median error {100 * med(d[ours]['hull_error'] for d in both):.2f}% against "
            f"{100 * med(d[theirs]['hull_error'] for d in both):.2f}% of the diagonal")


def table(done, settings, ms, label, coacd):
    """Medians per setting over the meshes ms (time: total), CoACD 0.05's published rows beside."""
    med = statistics.median
    if not ms:
        return
    print(f"\n{len(ms)} meshes: {label} (medians; time: total)\n")
    print("| setting | hulls | hull error % diag | worst hull / tau | parts over tau | time (s) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for s in settings:
        rs = [done[m][s] for m in ms]
        worst = [r["worst"] for r in rs if r["worst"] is not None]   # none for CoACD's rows
        print(f"| {s} | {med(r['hulls'] for r in rs)} | {100 * med(r['hull_error'] for r in rs):.2f} | "
              f"{format(max(worst), '.3f') if worst else ''} | {sum(r['over'] for r in rs)} | "
              f"{sum(r['time'] for r in rs):.0f} |")
    if ms and all("hulls" in coacd.get(m, {}) for m in ms):
        cs = [coacd[m] for m in ms]
        print(f"| CoACD 0.05 (published rows) | {med(c['hulls'] for c in cs)} | "
              f"{100 * med(c['hull_error'] for c in cs):.2f} | | | {sum(c['time'] for c in cs):.0f} |")


def summary(rows, settings, peers, faces=None, plot_to=None, title=""):
    coacd = {r["mesh"]: r for r in peers if r["method"] == "coacd" and "0.05" in r["setting"]}
    faces = faces or {r["mesh"]: r["faces"] for r in peers}
    done = {}
    for r in rows:
        done.setdefault(r["mesh"], {})[r["setting"]] = dict(r, faces=faces.get(r["mesh"], 0))
    meshes = [m for m, d in done.items() if all(s in d and "error" not in d[s] for s in settings)]
    if plot_to:
        plot({m: done[m] for m in meshes}, settings, title, plot_to)
    table(done, settings, meshes, "every setting finished", coacd)
    if coacd:
        table(done, settings, [m for m in meshes if "hulls" in coacd.get(m, {})], "those with a CoACD 0.05 row too", coacd)
    for s in (s for s in settings if not s.startswith("coacd")):
        if peers:
            ours = [dict(d[s], method="ours", setting=s) for m, d in done.items() if s in d and m in faces]
            print(f"\n{s}: " + " ".join(br.front(br.sample_rows(peers + ours), ours=("ours", s))))
        for c in (c for c in settings if c.startswith("coacd")):
            print(time_against(done, s, c))
            print(against(done, s, c))


OBJECTS = REPO / "out" / "objects" / "inputs"


def inputs(which, sample):
    """(name, source file, OBJ file) of the set's meshes."""
    if which == "objects":
        return [(n, p, p) for n, p in object_set.meshes(OBJECTS)]
    meshes = br.fetch_corpus()
    files = br.corpus(meshes)
    out = []
    for p in sorted(br.sample(files, meshes, sample)):
        name = br.mesh_name(p, meshes, files)
        inp = REPO / "out" / "robots" / "inputs" / (name.replace("/", "__") + ".obj")
        if not inp.exists():
            inp.parent.mkdir(parents=True, exist_ok=True)
            bench.to_obj(p, inp)
        out.append((name, p, inp))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--settings", default="best:2:0,best:2:1,bisector:2:1,bisector:3:1")
    ap.add_argument("--out", default=str(REPO / "out" / "study.jsonl"))
    ap.add_argument("--timeout", type=int, default=900)
    ap.add_argument("--cut-search", choices=("fast", "thorough"),
                    help="our settings' cut_search (default: the product's); rows do not record it, so keep "
                         "them in a file of their own")
    ap.add_argument("--sample", type=int, default=20, help="meshes of the peers' sample to run (20 or 60)")
    ap.add_argument("--set", choices=("robots", "objects"), default="robots",
                    help="the robot corpus's sample, or the meshes that are not robot links (bench/object_set.py)")
    ap.add_argument("--wrapped-only", action="store_true",
                    help="only the meshes that an earlier row of --out shows alpha wrapped")
    ap.add_argument("--report", action="store_true", help="run nothing: print the summary of the rows kept")
    ap.add_argument("--plot", help="also plot hulls against error per setting (PNG path)")
    args = ap.parse_args()
    settings = args.settings.split(",")
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    rows = [json.loads(line) for line in out.read_text().splitlines()] if out.exists() else []
    have = {(r["mesh"], r["setting"]) for r in rows}
    wrapped = {r["mesh"]: "alpha_wrap" in r.get("preprocessing", "") for r in rows if "preprocessing" in r}
    for name, p, inp in ([] if args.report else inputs(args.set, args.sample)):
        if args.wrapped_only and not wrapped.get(name, True):
            continue
        for s in settings:
            if (name, s) in have:
                continue
            if s.split(":")[0] in PEERS:
                row = dict(mesh=name, setting=s, **run_peer(s, inp, args.timeout))
            else:
                sel, tau, merge, *wrap = s.split(":")
                row = dict(mesh=name, setting=s, **run(p, inp, sel, float(tau), merge == "1", args.timeout, wrap,
                                                         args.cut_search))
            rows.append(row)
            with out.open("a") as f:
                f.write(json.dumps(row) + "\n")
            print(json.dumps({k: row.get(k) for k in ("mesh", "setting", "hulls", "hull_error", "time", "worst")}),
                  flush=True)
    if args.set == "objects":
        summary(rows, settings, [], {n: bench.face_count(p) for n, p in object_set.meshes(OBJECTS)}, args.plot,
                "meshes that are not robot links (bench/object_set.py)")
    else:
        summary(rows, settings, json.loads((REPO / "bench" / "results" / "robots" / "robots-peers.json").read_text()),
                plot_to=args.plot, title=f"the robot sample ({args.sample} meshes)")


if __name__ == "__main__":
    main()
