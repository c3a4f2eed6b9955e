"""Render a decomposed mesh for the README: the input beside its collision hulls, each hull in its own
colour (matplotlib, no display needed). Usage: python3 bench/render_part.py MESH OUT.png [TAU%]"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pymeshlab  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import pymeshlab_acd  # noqa: E402


def draw(ax, meshes, colours, light):
    for (V, F), c in zip(meshes, colours):
        tri = V[F]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
        shade = 0.45 + 0.55 * np.clip(n @ light, 0, 1)
        ax.add_collection3d(Poly3DCollection(tri, facecolors=np.clip(np.outer(shade, c), 0, 1), linewidths=0))


def main(src, dst, tau=2.0):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(src)
    V, F = ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()
    hulls, parts, res = pymeshlab_acd.convex_decomposition(V, F, tau=tau, preprocessing="auto", return_parts=True)
    light = np.array([0.4, -0.5, 0.75]) / np.linalg.norm([0.4, -0.5, 0.75])
    rng = np.random.default_rng(3)
    colours = [matplotlib.colors.hsv_to_rgb([h, 0.55, 0.95]) for h in rng.permutation(len(hulls)) / len(hulls)]
    fig = plt.figure(figsize=(8, 3.6), dpi=110)
    lo, hi = V.min(0), V.max(0)
    for k, (title, meshes, cs) in enumerate((("input", [(V, F)], [np.array([0.8, 0.8, 0.82])]),
                                              (f"{len(hulls)} hulls, tau {tau:g}%", hulls, colours))):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        draw(ax, meshes, cs, light)
        c, r = (lo + hi) / 2, 0.62 * (hi - lo).max() / 2   # the box is seen at an angle: fill the frame
        ax.set_xlim(c[0] - r, c[0] + r), ax.set_ylim(c[1] - r, c[1] + r), ax.set_zlim(c[2] - r, c[2] + r)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=25, azim=-60)
        ax.set_axis_off()
        ax.set_title(title, fontsize=10)
    fig.subplots_adjust(left=0, right=1, bottom=0, top=0.93, wspace=0)
    fig.savefig(dst)
    print(f"{dst}: {len(hulls)} hulls, farthest hull {res['max_hull_distance']:.3g} from its part "
          f"(tau {res['tau_model_units']:.3g}), tau_convex {res['tau_convex']}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], *(float(x) for x in sys.argv[3:4]))
