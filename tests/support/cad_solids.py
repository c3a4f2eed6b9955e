"""CAD-shaped test solids made with manifold3d (exact, closed, oriented): the low-poly parts with long
edges, slots, bores and flanges that robot and machine models are built from. Each maker returns
(vertices, faces) as numpy arrays."""
import math

import numpy as np


def _mf():
    import manifold3d
    return manifold3d


def _cyl(h, r, n=32):
    return _mf().Manifold.cylinder(h, r, r, n)


def _cube(size, center=False):
    return _mf().Manifold.cube(size, center)


def _arrays(solid):
    m = solid.to_mesh()
    return np.asarray(m.vert_properties, float)[:, :3].copy(), np.asarray(m.tri_verts, np.int32).copy()


def keyway():
    """Shaft r 4, 36 long, with a keyway 2 wide and 1.2 deep, closed at both ends."""
    shaft = _cyl(36, 4).translate([0, 0, -18])
    return shaft - _cube([2, 4, 20], True).translate([0, 4.8, 0])


def keyway_open():
    """The keyway run out through both ends of the shaft."""
    shaft = _cyl(36, 4).translate([0, 0, -18])
    return shaft - _cube([2, 4, 40], True).translate([0, 4.8, 0])


def plate():
    """Plate 4 x 2 x 0.4 with two through-holes r 0.35."""
    return (_cube([4, 2, 0.4], True) - _cyl(1, 0.35, 48).translate([-1, 0, -0.5])
            - _cyl(1, 0.35, 48).translate([1, 0, -0.5]))


def flange():
    """Flange r 5, 0.6 thick, bore r 1.5 and 6 bolt holes r 0.4 on a 3.4 circle."""
    f = _cyl(0.6, 5, 64) - _cyl(0.6, 1.5, 48)
    for k in range(6):
        a = math.radians(60 * k)
        f = f - _cyl(0.8, 0.4, 24).translate([3.4 * math.cos(a), 3.4 * math.sin(a), -0.1])
    return f


def bracket():
    """L-bracket 6 x 4, 0.6 thick, 5 high, with a hole r 0.8 in its base."""
    return (_cube([6, 4, 0.6]) + _cube([0.6, 4, 5])) - _cyl(1, 0.8).translate([3.5, 2, -0.2])


def pocket():
    """Box 6 x 4 x 3 with a blind pocket 4 x 2 x 1 in its top."""
    return _cube([6, 4, 3], True) - _cube([4, 2, 2], True).translate([0, 0, 1])


def through_slot():
    """Block 6 x 3 x 1 with a slot 3 x 0.8 through it."""
    return _cube([6, 3, 1], True) - _cube([3, 0.8, 2], True)


def d_flat_shaft():
    """Shaft r 2, 20 long, with a flat 0.6 deep along half its length."""
    return _cyl(20, 2, 40) - _cube([4, 2, 10], True).translate([0, 2.4, 15])


def stepped_shaft():
    """Three coaxial cylinders r 3, 2, 1.2, lengths 10, 10, 6."""
    return _cyl(10, 3, 48) + _cyl(10, 2, 40).translate([0, 0, 10]) + _cyl(6, 1.2, 32).translate([0, 0, 20])


def belt_pulley():
    """Timing-belt pulley: hub r 3, 4 long, between flanges r 3.6 chamfered onto it (48 facets)."""
    profile = [(0, 0), (3.6, 0), (3.6, 0.5), (3.0, 0.8), (3.0, 3.2), (3.6, 3.5), (3.6, 4), (0, 4)]
    return _mf().Manifold.revolve(_mf().CrossSection([profile]), 48)


def spur_gear(teeth=14):
    """Spur gear: root r 3, tip r 3.6, 1 thick, bore r 1 (trapezoidal teeth)."""
    cs = _mf().CrossSection
    pts = []
    for k in range(teeth):
        a = 2 * math.pi * k / teeth
        s = 2 * math.pi / teeth
        for da, r in ((0.0, 3.0), (0.2 * s, 3.6), (0.45 * s, 3.6), (0.65 * s, 3.0)):
            pts.append((r * math.cos(a + da), r * math.sin(a + da)))
    gear = cs([pts]).extrude(1.0)
    return gear - _cyl(2, 1.0, 32).translate([0, 0, -0.5])


def t_slot_rail():
    """Rail 4 x 4, 12 long, with a T-slot (neck 1 wide, 1 deep; head 2.4 wide, 0.8 deep) along its top."""
    rail = _cube([4, 4, 12], True)
    neck = _cube([1, 1.2, 14], True).translate([0, 1.6, 0])
    head = _cube([2.4, 0.8, 14], True).translate([0, 0.6, 0])
    return rail - neck - head


def bossed_plate():
    """Plate 60 x 40 x 4 with a low square boss on its top: 20 x 20 at the base, 5 x 5 at the top, 2 high
    (its sides 15 degrees from the plate)."""
    mf = _mf()
    boss = mf.Manifold.extrude(mf.CrossSection.square([20, 20], True), 2.0, 0, 0.0, [0.25, 0.25])
    return _cube([60, 40, 4], True).translate([0, 0, 2]) + boss.translate([0, 0, 4])


def cup():
    """A cup: r 4 at the rim, 3 at the foot, 9 high, walls 0.4 thick (a thin shell of revolution)."""
    profile = [(0, 0), (3, 0), (4, 9), (3.6, 9), (2.65, 0.4), (0, 0.4)]
    return _mf().Manifold.revolve(_mf().CrossSection([profile]), 64)


SOLIDS = {
    "keyway": keyway, "keyway_open": keyway_open, "plate": plate, "flange": flange, "bracket": bracket,
    "pocket": pocket, "through_slot": through_slot, "d_flat_shaft": d_flat_shaft,
    "stepped_shaft": stepped_shaft, "belt_pulley": belt_pulley, "spur_gear": spur_gear, "t_slot_rail": t_slot_rail,
    "bossed_plate": bossed_plate,
}
# Thin shells, for the cut search's tests (many parts at small tau: not in the certificate's sweep).
SHELLS = {"cup": cup}


def make(name):
    """(vertices, faces) of the named solid."""
    return _arrays({**SOLIDS, **SHELLS}[name]())
