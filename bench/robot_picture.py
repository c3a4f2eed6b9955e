"""The README's robot picture: a robot's visual meshes beside its collision model from
`python -m pymeshlab_acd robot` (each hull its own colour), drawn with matplotlib.

    python bench/robot_picture.py ROBOT.urdf OUT_DIR docs/robot.png
(OUT_DIR: the robot command's output for ROBOT.urdf, written with --resolve-paths.)
"""
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt   # noqa: E402
import numpy as np   # noqa: E402
import yourdfpy   # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection   # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench import read_obj   # noqa: E402


def triangles(scene):
    tris = []
    for node in scene.graph.nodes_geometry:
        T, name = scene.graph[node]
        g = scene.geometry[name]
        V = np.asarray(g.vertices) @ T[:3, :3].T + T[:3, 3]
        F = np.asarray(g.faces)
        if len(F) > 20000:   # enough triangles to see the shape
            F = F[np.linspace(0, len(F) - 1, 20000).astype(int)]
        tris.append(V[F])
    tris = np.concatenate(tris)
    return tris, [(0.7, 0.7, 0.72, 1.0)] * len(tris)


def draw(ax, tris, colours, title):
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True) + 1e-30
    shade = 0.55 + 0.45 * np.abs(n @ light)
    c = np.array(colours)[:, :3] * shade[:, None]
    ax.add_collection3d(Poly3DCollection(tris, facecolors=c, linewidths=0))
    lo, hi = tris.reshape(-1, 3).min(0), tris.reshape(-1, 3).max(0)
    mid, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(mid[0] - r, mid[0] + r)
    ax.set_ylim(mid[1] - r, mid[1] + r)
    ax.set_zlim(mid[2] - r, mid[2] + r)
    ax.view_init(elev=20, azim=-60)
    ax.set_axis_off()
    ax.set_title(title)


def main(urdf, out_dir, png):
    from pymeshlab_acd.robot import resolve
    name = pathlib.Path(urdf).stem
    base = pathlib.Path(urdf).parent
    visual = yourdfpy.URDF.load(urdf, build_scene_graph=True, load_meshes=True,
                                filename_handler=lambda fname: str(resolve(fname, base, {})))
    coll = yourdfpy.URDF.load(str(pathlib.Path(out_dir) / f"{name}.urdf"), build_scene_graph=False,
                              load_meshes=False)
    hulls = []   # (V in the robot's frame, F), every hull file of every link
    for link in coll.link_map.values():
        T = visual.get_transform(link.name, visual.base_link)
        for c in link.collisions:
            if c.geometry.mesh is None or not c.geometry.mesh.filename.startswith("collision/"):
                continue
            O = (c.origin if c.origin is not None else np.eye(4))
            s = np.ones(3) * (c.geometry.mesh.scale if c.geometry.mesh.scale is not None else 1.0)
            V, F = read_obj(pathlib.Path(out_dir) / c.geometry.mesh.filename)
            V, F = np.asarray(V, float), np.asarray(F)
            M = T @ O
            hulls.append(((V * s) @ M[:3, :3].T + M[:3, 3], F))
    fig = plt.figure(figsize=(10, 5), dpi=110)
    t, c = triangles(visual.scene)
    draw(fig.add_subplot(1, 2, 1, projection="3d"), t, c, f"{name}: visual meshes")
    cmap = plt.get_cmap("tab20")
    t = np.concatenate([V[F] for V, F in hulls])
    c = [cmap(k % 20) for k, (V, F) in enumerate(hulls) for _ in F]
    draw(fig.add_subplot(1, 2, 2, projection="3d"), t, c, f"collision: {len(hulls)} convex hulls")
    fig.tight_layout()
    fig.savefig(png)


if __name__ == "__main__":
    main(*sys.argv[1:4])
