"""The study's meshes that are not robot links: scans and modelled objects, to confirm on what the
defaults were not chosen on (the robot sample is where they were).

  shared      the 17 shared meshes (../shared/data/meshes): scans, figures, CAD, open and closed;
  pymeshlab   pymeshlab's own sample meshes (an airplane, a bunny, a bone, a textured bunny);
  cad         the test suite's CAD solids (tests/support/cad_solids.py);
  objects     household objects and castings modelled here with manifold3d: a cup (the tests'), a mug, gears, a
              genus-3 block, a torus, a hex nut, a pipe tee, a ribbed casting, a pocketed bracket, a bowl.

`meshes(folder)` writes each once as an OBJ into folder and lists (name, path); the makers are
deterministic, so the files are the same on every run.
"""
import math
import os
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(REPO / "tests"))
from support import cad_solids  # noqa: E402
sys.path.insert(0, str(HERE))
from bench_open import load as _load, write_obj as _write  # noqa: E402

SHARED = REPO.parent / "shared" / "data" / "meshes"
PYMESHLAB_SAMPLES = ("airplane.obj", "bunny.obj", "bone.ply", "bunny10k_textured.obj")


def _mf():
    import manifold3d
    return manifold3d


def _revolve(profile, n=64):
    mf = _mf()
    return mf.Manifold.revolve(mf.CrossSection([profile]), n)


def mug():
    """A straight mug r 3.5, 8 high, with a ring handle on its side."""
    mf = _mf()
    body = _revolve([(0, 0), (3.5, 0), (3.5, 8), (3.1, 8), (3.1, 0.4), (0, 0.4)])
    handle = _revolve([(1.6, -0.3), (2.4, -0.3), (2.4, 0.3), (1.6, 0.3)], 48).rotate([90, 0, 0]).translate([4.2, 0, 4])
    return body + (handle - mf.Manifold.cylinder(9, 3.3, 3.3, 64))


def bowl():
    """A hemispherical bowl r 5 with a foot ring."""
    prof = [(0, 0), (2, 0), (2, 0.3)]
    prof += [(5 * math.sin(a), 5.3 - 5 * math.cos(a)) for a in (math.radians(d) for d in range(25, 91, 5))]
    prof += [(4.6 * math.sin(a), 5.3 - 4.6 * math.cos(a)) for a in (math.radians(d) for d in range(90, -1, -5))]
    return _revolve(prof)


def gear24():
    return cad_solids.spur_gear(24)


def gear8():
    return cad_solids.spur_gear(8)


def genus3_block():
    """A block 9 x 3 x 1.5 with three round holes through it."""
    mf = _mf()
    b = mf.Manifold.cube([9, 3, 1.5], True)
    for x in (-3, 0, 3):
        b = b - mf.Manifold.cylinder(3, 0.8, 0.8, 40).translate([x, 0, -1.5])
    return b


def torus():
    return _revolve([(3 + math.cos(a), math.sin(a)) for a in (2 * math.pi * k / 32 for k in range(32))], 64)


def hex_nut():
    """A hex nut across flats 10, 5 thick, bore r 2.6, chamfered by a cone."""
    mf = _mf()
    hexagon = mf.CrossSection([[(5.77 * math.cos(math.pi * k / 3), 5.77 * math.sin(math.pi * k / 3)) for k in range(6)]])
    nut = hexagon.extrude(5) ^ mf.Manifold.cylinder(5, 6.6, 5.0, 64) ^ mf.Manifold.cylinder(5, 5.0, 6.6, 64)
    return nut - mf.Manifold.cylinder(7, 2.6, 2.6, 48).translate([0, 0, -1])


def pipe_tee():
    """Two pipes r 2, wall 0.4, meeting at a right angle."""
    mf = _mf()
    outer = mf.Manifold.cylinder(12, 2, 2, 48, True).rotate([0, 90, 0]) + mf.Manifold.cylinder(6, 2, 2, 48)
    inner = mf.Manifold.cylinder(13, 1.6, 1.6, 48, True).rotate([0, 90, 0]) + mf.Manifold.cylinder(7, 1.6, 1.6, 48)
    return outer - inner


def ribbed_casting():
    """A hollow box casting 10 x 6 x 4 open below, with three ribs inside and two bosses on top."""
    mf = _mf()
    c = mf.Manifold.cube([10, 6, 4]) - mf.Manifold.cube([9, 5, 3.5]).translate([0.5, 0.5, -0.01])
    for x in (2.5, 5, 7.5):
        c = c + mf.Manifold.cube([0.3, 5, 3.5]).translate([x - 0.15, 0.5, 0])
    for x in (2.5, 7.5):
        boss = mf.Manifold.cylinder(1.5, 1.2, 1.2, 40).translate([x, 3, 4])
        c = c + boss - mf.Manifold.cylinder(6, 0.5, 0.5, 32).translate([x, 3, 0.5])
    return c


def pocket_bracket():
    """An L-bracket with two blind pockets in its base and a slot in its wall."""
    mf = _mf()
    b = mf.Manifold.cube([8, 5, 1.2]) + mf.Manifold.cube([1.2, 5, 6])
    for x in (2.5, 5.5):
        b = b - mf.Manifold.cube([2, 3, 1]).translate([x, 1, 0.6])
    return b - mf.Manifold.cube([2, 1.5, 3]).translate([-0.5, 1.75, 2])


OBJECTS = {f.__name__: f for f in (cad_solids.cup, mug, bowl, gear24, gear8, genus3_block, torus, hex_nut, pipe_tee,
                                   ribbed_casting, pocket_bracket)}


def sources():
    """(name, maker) of every mesh of the set; a maker returns (vertices, faces)."""
    import pymeshlab
    out = [("shared/" + p.stem, lambda p=p: _load(p)) for p in sorted(SHARED.iterdir()) if p.suffix in (".obj", ".ply")]
    samples = pathlib.Path(pymeshlab.__file__).parent / "tests" / "sample_meshes"
    out += [("pymeshlab/" + pathlib.Path(n).stem, lambda n=n: _load(samples / n)) for n in PYMESHLAB_SAMPLES]
    out += [("cad/" + n, lambda n=n: cad_solids.make(n)) for n in sorted(cad_solids.SOLIDS)]
    out += [("objects/" + n, lambda f=f: cad_solids._arrays(f())) for n, f in sorted(OBJECTS.items())]
    return out


def meshes(folder):
    """(name, obj path) of every mesh of the set, written into folder once."""
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    out = []
    for name, make in sources():
        path = folder / (name.replace("/", "__") + ".obj")
        if not path.exists():
            tmp = path.with_suffix(".tmp.obj")
            _write(tmp, *make())
            os.replace(tmp, path)
        out.append((name, path))
    return out


if __name__ == "__main__":
    import bench
    for name, path in meshes(sys.argv[1] if len(sys.argv) > 1 else REPO / "out" / "objects" / "inputs"):
        print(name, bench.face_count(path))
