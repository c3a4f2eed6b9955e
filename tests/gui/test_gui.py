"""The real MeshLab GUI, driven like a user under Xvfb (run by scripts/run_gui_test.sh).

MeshLab starts on the bundled bunny in a throw-away HOME holding only our plugin and pre-seeded
first-run answers. xdotool sends real key presses and clicks: Filters menu, our submenu entry, the tau
field, Apply. A preloaded Qt hook (qt_probe.cpp) reports where entries are on screen and what the layer
panel and log show, so the test clicks by name, not by memorised pixels. Screenshots of the menu, the
dialog and the coloured parts are kept in $ACD_GUI_SHOTS (default out/gui).
"""
import colorsys
import json
import os
import re
import shutil
import subprocess
import time
from datetime import date
from pathlib import Path

import pytest

EXE = os.environ.get("ACD_MESHLAB_GUI")
PROBE_SO = os.environ.get("ACD_GUI_PROBE_SO")
PLUGIN = os.environ.get("ACD_GUI_PLUGIN", os.environ.get("ACD_PLUGIN"))
SHOTS = Path(os.environ.get("ACD_GUI_SHOTS", "out/gui")).resolve()
MENU = "Remeshing, Simplification and Reconstruction"
ENTRY = "Convex Decomposition: Approximate Convex Decomposition"
TAU = "6"

pytestmark = pytest.mark.skipif(not (EXE and PROBE_SO and PLUGIN),
                                reason="run through scripts/run_gui_test.sh (needs the GUI build)")


class Gui:
    def __init__(self, tmp: Path, display: str):
        self.tmp, self.display = tmp, display
        self.env = dict(os.environ, DISPLAY=display)
        self.probe = tmp / "probe.json"

    def xdo(self, *args):
        subprocess.run(["xdotool", *args], env=self.env, check=True, timeout=30)

    def state(self):
        try:
            return json.loads(self.probe.read_text())
        except (OSError, ValueError):
            return None

    def wait(self, what, pred, timeout=60.0):
        """Poll the probe until pred(state) gives something truthy; fail with `what` otherwise."""
        end = time.time() + timeout
        while time.time() < end:
            s = self.state()
            if s is not None:
                if any(w["class"] == "QMessageBox" for w in s["windows"]):
                    self.shot("message.png")
                    pytest.fail(f"MeshLab shows a message box while waiting for {what}: "
                                + " | ".join(l["text"] for l in s["labels"]))
                got = pred(s)
                if got:
                    return got
            if self.proc.poll() is not None:
                pytest.fail(f"MeshLab exited (rc {self.proc.returncode}) while waiting for {what}")
            time.sleep(0.25)
        self.shot("timeout.png")
        pytest.fail(f"timed out waiting for {what}")

    def click(self, rect, button="1", repeat=1):
        x, y, w, h = rect
        self.xdo("mousemove", "--sync", str(x + w // 2), str(y + h // 2))
        self.xdo("click", "--repeat", str(repeat), "--delay", "80", button)

    def shot(self, name):
        SHOTS.mkdir(parents=True, exist_ok=True)
        subprocess.run(["import", "-window", "root", str(SHOTS / name)], env=self.env, check=True, timeout=60)


def entry(state, title_pred, text):
    for m in state["menus"]:
        for e in m["entries"]:
            if e["text"] == text and title_pred(m["title"]):
                return e
    return None


def layers(state):
    for t in state["trees"]:
        if t["name"] == "meshTreeWidget":
            return [row for row in t["items"]]
    return []


@pytest.fixture
def start_meshlab(tmp_path):
    """Starts MeshLab on a file (once per test) under its own Xvfb; returns the Gui driver."""
    home = tmp_path / "home"
    plugins = home / ".local/share/VCG/MeshLab_64bit_dp/MeshLabExtraPlugins/2025.07d"
    plugins.mkdir(parents=True)
    shutil.copy(PLUGIN, plugins)
    # Pre-seed the first-run answers: no statistics question, no online version check.
    conf = home / ".config/VCG"
    conf.mkdir(parents=True)
    today = date.today()
    (conf / "MeshLab_64bit_dp.conf").write_text(
        "[General]\ninformativeShown=true\n"
        f"lastTimeMeshLabVersionCheckedOnStart={today.strftime('%a %b')} {today.day} {today.year}\n")
    running = []

    def start(path):
        # Xvfb picks a free display and writes its number when it is ready.
        xvfb = subprocess.Popen(["Xvfb", "-displayfd", "1", "-screen", "0", "1600x1000x24", "-nolisten", "tcp"],
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        display = ":" + xvfb.stdout.readline().strip()
        g = Gui(tmp_path, display)
        env = dict(g.env, HOME=str(home), LIBGL_ALWAYS_SOFTWARE="1", LD_PRELOAD=PROBE_SO,
                   ACD_GUI_PROBE=str(g.probe), XDG_RUNTIME_DIR=str(tmp_path))
        log = open(tmp_path / "meshlab.log", "w")
        g.proc = subprocess.Popen([EXE, str(path)], env=env, cwd=tmp_path, stdout=log, stderr=subprocess.STDOUT)
        running.append((g, xvfb, log))
        return g

    yield start
    for g, xvfb, log in running:
        g.proc.terminate()
        try:
            g.proc.wait(10)
        except subprocess.TimeoutExpired:
            g.proc.kill()
        xvfb.terminate()
        xvfb.wait(10)
        log.close()
        print((tmp_path / "meshlab.log").read_text()[-3000:])


@pytest.fixture
def gui(start_meshlab):
    import pymeshlab
    return start_meshlab(Path(pymeshlab.__file__).parent / "tests/sample_meshes/bunny.obj")


def maximise(gui):
    win = subprocess.run(["xdotool", "search", "--name", "^MeshLab 2025"], env=gui.env, capture_output=True,
                         text=True).stdout.split()[0]
    gui.xdo("windowmove", "--sync", win, "0", "0")
    gui.xdo("windowsize", "--sync", win, "1600", "1000")
    gui.xdo("windowfocus", "--sync", win)
    time.sleep(1.5)


def test_decompose_through_the_filter_menu(gui):
    # MeshLab is up with the bunny as its one layer.
    gui.wait("the bunny layer", lambda s: [r for r in layers(s) if r[2]["text"] == "bunny"], timeout=120)
    maximise(gui)
    view = gui.state()["views"][0]
    gui.shot("before.png")

    # Filters menu (Alt+L, its accelerator), then our submenu, then our entry.
    gui.xdo("key", "alt+l")
    sub = gui.wait("the Filters menu", lambda s: entry(s, lambda t: t == "Filters", MENU))
    gui.click(sub["rect"])
    ours = gui.wait(f"'{ENTRY}' in Filters > {MENU}", lambda s: entry(s, lambda t: t == MENU, ENTRY), timeout=15)
    gui.xdo("mousemove", "--sync", str(ours["rect"][0] + 40), str(ours["rect"][1] + ours["rect"][3] // 2))
    time.sleep(0.8)
    gui.shot("menu.png")
    gui.click(ours["rect"])

    # The dialog: every parameter labelled, with a tooltip; set tau.
    def tau_field(s):
        label = next((l for l in s["labels"] if l["text"].startswith("Concavity tolerance")), None)
        apply = next((b for b in s["buttons"] if b["name"] == "applyPushButton"), None)
        if not label or not apply:
            return None
        cy = label["rect"][1] + label["rect"][3] / 2
        row = [f for f in s["fields"] if abs(f["rect"][1] + f["rect"][3] / 2 - cy) < 12 and f["rect"][0] > label["rect"][0]]
        return (label, row[0], apply, s) if row else None
    label, field, apply, s = gui.wait("the filter dialog's tau field", tau_field, timeout=15)
    for name in ("Unit of tau", "Cutting plane", "Maximum number of parts", "Preprocessing", "Time limit (s)"):
        shown = [l for l in s["labels"] if l["text"] == name]
        assert shown, f"parameter label {name!r} missing from the dialog"
        assert shown[0]["tooltip"], f"parameter {name!r} has no tooltip"
    gui.click(field["rect"], repeat=3)
    gui.xdo("key", "ctrl+a")
    gui.xdo("type", "--delay", "50", TAU)
    gui.xdo("key", "Tab")
    gui.wait(f"tau = {TAU} in the field", lambda s: any(f["text"] == TAU for f in s["fields"]), timeout=10)
    time.sleep(0.5)
    gui.shot("dialog.png")
    gui.click(apply["rect"])

    # New layers appear, one per part, and the log reports the same count.
    def done(s):
        m = re.search(r"Approximate convex decomposition: (\d+) parts", s["log"])
        return (int(m.group(1)), s) if m else None
    parts, s = gui.wait("the decomposition's log line", done, timeout=300)
    rows = gui.wait("the part layers", lambda s: [r for r in layers(s) if r[2]["text"].startswith("acd_")]
                    if len([r for r in layers(s) if r[2]["text"].startswith("acd_")]) == parts else None, timeout=30)
    assert parts >= 2, s["log"]
    print(f"GUI: {parts} part layers: {[r[2]['text'] for r in rows]}")

    # Close the dialog, hide the input (its eye icon, column 0) so the parts show, take the picture:
    # the parts must bring colours the grey bunny on MeshLab's blue background did not have.
    gui.click(next(b for b in gui.state()["buttons"] if b["name"] == "closePushButton")["rect"])
    bunny = [r for r in layers(gui.state()) if r[2]["text"].split()[0] == "bunny"][0]
    gui.click(bunny[0]["rect"])
    time.sleep(2)
    gui.shot("result.png")
    new = hue_bins(SHOTS / "result.png", view) - hue_bins(SHOTS / "before.png", view)
    print(f"GUI: {len(new)} hue bins (of 36) added by the parts")
    assert len(new) >= min(parts, 4), f"only {len(new)} new hues visible in {SHOTS / 'result.png'}"


def hue_bins(png: Path, viewport):
    """Saturated hue bins (of 36) covering at least 0.2% of the viewport."""
    x, y, w, h = viewport
    out = subprocess.run(["convert", str(png), "-crop", f"{w}x{h}+{x}+{y}", "-sample", "50%", "-depth", "8",
                          "txt:-"], capture_output=True, text=True, check=True).stdout
    bins = [0] * 36
    n = 0
    for line in out.splitlines()[1:]:
        m = re.search(r":\s*\((\d+),(\d+),(\d+)", line)
        if not m:
            continue
        hue, light, sat = colorsys.rgb_to_hls(*(int(c) / 255 for c in m.groups()))
        n += 1
        if sat > 0.35 and 0.15 < light < 0.9:
            bins[min(35, int(hue * 36))] += 1
    return {i for i, b in enumerate(bins) if b > 0.002 * n}


def test_exported_project_opens_with_one_layer_per_part(start_meshlab, tmp_path):
    """The .mlp written by `decompose --export` opens in the GUI: one layer per part."""
    import sys
    out = tmp_path / "export"
    p = subprocess.run([sys.executable, "-m", "pymeshlab_acd", "decompose", "--demo", "--tau", "6", "--out", str(out),
                        "--export", "--no-progress"], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    parts = json.loads((out / "summary.json").read_text())["parts"]
    gui = start_meshlab(out / "export" / "bunny.mlp")
    rows = gui.wait(f"{parts} part layers", lambda s: [r for r in layers(s) if r[2]["text"].startswith("acd_")]
                    if len(layers(s)) == parts else None, timeout=120)
    assert all(r[2]["text"].startswith("acd_") for r in rows)
    maximise(gui)
    view = gui.state()["views"][0]
    gui.shot("project.png")
    hues = hue_bins(SHOTS / "project.png", view)
    print(f"GUI: the exported project opened with {len(rows)} layers, {len(hues)} hue bins")
    assert len(hues) >= min(parts, 4)
