"""Polygons with holes in and out of pymeshlab, for generate_polygon_approximate_convex_decomposition.

Input formats (``read_loops``), each giving a list of closed loops (outer boundaries and holes, in any
orientation; nesting decides which is which):

* ``.poly`` (the format of the paper authors' acd2d test polygons): the number of chains, then per chain
  a line ``n out`` or ``n in``, n lines ``x y``, and a line of n 1-based indices giving the vertex order.
  Text after ``#`` is a comment.
* ``.svg``: every ``<polygon points=...>``, and every ``<path d=...>`` made of straight segments
  (M, L, H, V, Z and their relative forms; each subpath is a loop). Curves are refused.
* plain text (any other name): one ``x y`` pair per line, loops separated by blank lines.

Output: ``write_svg`` draws the input outline and the pieces, each filled in its own colour.
"""
import colorsys
import re

import numpy as np


def read_loops(path):
    path = str(path)
    text = open(path, encoding="utf-8").read()
    if path.lower().endswith(".poly"):
        return _read_poly(text)
    if path.lower().endswith(".svg"):
        return _read_svg(text)
    return _read_plain(text)


def _read_poly(text):
    tokens = []
    for line in text.splitlines():
        tokens += line.split("#", 1)[0].split()
    pos = 0

    def take():
        nonlocal pos
        if pos >= len(tokens):
            raise ValueError("truncated .poly file")
        pos += 1
        return tokens[pos - 1]
    loops = []
    for _ in range(int(take())):
        n, kind = int(take()), take()
        if kind not in ("out", "in"):
            raise ValueError(f"chain kind must be 'out' or 'in', got {kind!r}")
        pts = [(float(take()), float(take())) for _ in range(n)]
        order = [int(take()) - 1 for _ in range(n)]
        loops.append(np.array([pts[i] for i in order], float))
    return loops


def _read_plain(text):
    loops, cur = [], []
    for line in text.splitlines() + [""]:
        line = line.split("#", 1)[0].strip()
        if not line:
            if cur:
                loops.append(np.array(cur, float))
                cur = []
            continue
        x, y = line.replace(",", " ").split()[:2]
        cur.append((float(x), float(y)))
    return loops


def _read_svg(text):
    loops = []
    for pts in re.findall(r'<polygon[^>]*\spoints="([^"]*)"', text):
        v = [float(t) for t in re.split(r"[\s,]+", pts.strip()) if t]
        loops.append(np.array(v, float).reshape(-1, 2))
    for d in re.findall(r'<path[^>]*\sd="([^"]*)"', text):
        loops += _svg_path(d)
    # SVG's y axis points down: flip it so counter-clockwise means the same as in the file's picture
    return [l * np.array([1.0, -1.0]) for l in loops]


def _svg_path(d):
    loops, cur, pos, start = [], [], np.zeros(2), np.zeros(2)
    tokens = re.findall(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", d)
    i, cmd = 0, None
    while i < len(tokens):
        if tokens[i].isalpha():
            cmd = tokens[i]
            i += 1
            if cmd in "Zz":
                if cur:
                    loops.append(np.array(cur))
                cur, pos = [], start.copy()
                continue
        if cmd is None or cmd not in "MmLlHhVv":
            raise ValueError(f"SVG path command {cmd!r} is not a straight segment (only M, L, H, V, Z)")
        rel = cmd.islower()
        if cmd in "Hh":
            x = float(tokens[i]); i += 1
            pos = np.array([pos[0] + x if rel else x, pos[1]])
        elif cmd in "Vv":
            y = float(tokens[i]); i += 1
            pos = np.array([pos[0], pos[1] + y if rel else y])
        else:
            p = np.array([float(tokens[i]), float(tokens[i + 1])]); i += 2
            pos = pos + p if rel else p
        if cmd in "Mm":
            if cur:
                loops.append(np.array(cur))
            cur, start = [], pos.copy()
            cmd = "l" if rel else "L"   # further pairs after M are line-tos
        cur.append(pos.copy())
    if cur:
        loops.append(np.array(cur))
    return [l[:-1] if len(l) > 1 and np.allclose(l[0], l[-1]) else l for l in loops]


def loops_to_mesh(loops, z=0.0):
    """Vertices (in the plane z) and edges of closed loops, for an edge-mesh layer."""
    V, E, n = [], [], 0
    for l in loops:
        l = np.asarray(l, float)
        V.append(np.column_stack([l, np.full(len(l), z)]))
        E += [(n + i, n + (i + 1) % len(l)) for i in range(len(l))]
        n += len(l)
    return np.vstack(V), np.array(E, np.int32)


def colour(i):
    r, g, b = colorsys.hsv_to_rgb((0.13 + 0.61803398875 * i) % 1.0, 0.65, 0.95)
    return f"#{int(r * 255):02x}{int(g * 255):02x}{int(b * 255):02x}"


def write_svg(path, outline, pieces, size=800):
    """The input loops (black) and each piece (triangles in the plane: (V2, F)) in its own colour."""
    allpts = np.vstack([np.asarray(l, float) for l in outline])
    lo, hi = allpts.min(0), allpts.max(0)
    scale = (size - 20) / max(hi - lo)
    tr = lambda p: ((p[0] - lo[0]) * scale + 10, (hi[1] - p[1]) * scale + 10)
    w, h = tr((hi[0], lo[1]))
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w + 10:.0f}" height="{h + 10:.0f}">']
    for k, (V2, F) in enumerate(pieces):
        c = colour(k)
        for t in F:
            pts = " ".join("%.2f,%.2f" % tr(V2[i]) for i in t)
            out.append(f'<polygon points="{pts}" fill="{c}" stroke="{c}" stroke-width="0.5"/>')
    for l in outline:
        pts = " ".join("%.2f,%.2f" % tr(p) for p in l)
        out.append(f'<polygon points="{pts}" fill="none" stroke="black" stroke-width="1"/>')
    out.append("</svg>")
    open(path, "w").write("\n".join(out))
