"""Robustness fuzz test: >= 1000 generated bad or random meshes through every filter.

Cases (tests/support/fuzz_cases.py) run in child processes, so a crash (signal) or a hang is observed and
counted instead of killing pytest; the child is restarted after the offending case. Every case must
either be refused with the message meant for its mutation (an open mesh as open, NaN as NaN, ...;
an internal error or a message meant for another defect is a violation) or return parts that pass
the partition checks (closed parts, positive volumes summing to the input's, or, where its holes were
filled, a boundary holding every input vertex; input layer untouched), measured here.
"""
import collections
import os
import pathlib
import queue
import subprocess
import sys
import threading

from support import fuzz_cases
from support.fuzz_cases import kind_of

HANG_SECONDS = 120     # one case (both filters, <= 24 parts, 20 s time limit) takes well under this
WORKERS = max(1, min(2, os.cpu_count() or 1))

def drive(first, last, cache, results):
    """Run cases first..last-1 in a child, restarting it after a crash or a hang."""
    here = pathlib.Path(__file__).resolve().parent
    i = first
    while i < last:
        p = subprocess.Popen([sys.executable, "-m", "support.fuzz_cases", "child", cache, str(i), str(last)],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, cwd=here)
        lines = queue.Queue()
        threading.Thread(target=lambda: ([lines.put(x) for x in p.stdout], lines.put(None)), daemon=True).start()
        current = None
        while True:
            try:
                line = lines.get(timeout=HANG_SECONDS)
            except queue.Empty:
                p.kill()
                p.wait()
                results[current if current is not None else i] = ("hang", "")
                i = (current if current is not None else i) + 1
                break
            if line is None:
                rc = p.wait()
                if current is not None:   # started and never finished: this case killed the child
                    results[current] = ("crash", f"exit status {rc}")
                    i = current + 1
                else:
                    i = last
                break
            n, status, *rest = line.rstrip("\n").split(" ", 2)
            if status == "start":
                current = int(n)
            else:
                results[int(n)] = (status, rest[0] if rest else "")
                current = None


def test_fuzz_bad_and_random_meshes(tmp_path):
    assert fuzz_cases.CASES >= 1000   # 1200 without the shared meshes, 1680 with them
    results = {}
    step = (fuzz_cases.CASES + WORKERS - 1) // WORKERS
    threads = [threading.Thread(target=drive, args=(a, min(a + step, fuzz_cases.CASES), str(tmp_path), results))
               for a in range(0, fuzz_cases.CASES, step)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()

    counts = collections.Counter(kind for kind, _ in results.values())
    errors = collections.Counter(kind_of(d) for k, d in results.values() if k == "error")
    print(f"\nfuzz: {len(results)} cases, {counts['ok']} decomposed and checked, {counts['error']} refused "
          f"with a message, {counts['violation']} violations, crashes = {counts['crash']}, hangs = {counts['hang']}")
    for kind, n in errors.most_common():
        print(f"  error {kind}: {n}")
    print(f"  bases: {', '.join(fuzz_cases.BASES)}")
    bad = {i: r for i, r in sorted(results.items()) if r[0] in ("crash", "hang", "violation", "harness")}
    for i, r in list(bad.items())[:20]:
        print(f"  case {i} {fuzz_cases.case(i)}: {r}")
    assert len(results) == fuzz_cases.CASES
    assert not bad, f"{len(bad)} cases crashed, hung or broke a check (replay: cd tests && python -m support.fuzz_cases run N)"
