"""Generated polygons: stars, combs, a noisy outline (the 2D tests and the polygon benchmark share them)."""

import numpy as np


def star(points=5, r_out=10.0, r_in=4.0):
    t = np.pi / 2 + np.pi * np.arange(2 * points) / points
    r = np.where(np.arange(2 * points) % 2 == 0, r_out, r_in)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def comb(teeth=4, w=1.0, gap=1.0, depth=3.0, base=1.0):
    """A base bar with `teeth` upright teeth (counter-clockwise)."""
    pts = [(0, 0), (teeth * w + (teeth - 1) * gap, 0)]
    x = teeth * w + (teeth - 1) * gap
    for k in range(teeth - 1, -1, -1):
        x0 = k * (w + gap)
        pts += [(x0 + w, base + depth), (x0, base + depth)]
        if k > 0:
            pts += [(x0, base), (x0 - gap, base)]
    pts = [pts[0], pts[1], (x, base)] + pts[2:]
    return np.array(pts, float)


def noisy_blob(n=452, seed=7):
    """A deterministic wavy outline whose every other vertex is pushed in: about n/2 notches."""
    rng = np.random.default_rng(seed)
    t = 2 * np.pi * np.arange(n) / n
    r = 20 * (1 + 0.3 * np.sin(3 * t) + 0.12 * np.sin(7 * t + 1))
    r = r - np.where(np.arange(n) % 2 == 1, 0.35 + 0.25 * rng.random(n), 0.0)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])
