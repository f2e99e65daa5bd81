#!/usr/bin/env python3
"""Writes scenes/leak-walls/wall-<k>v.{obj,json}: two 1 m rooms side by side, open to the front
(z = 1) where the camera stands, separated by a wall k voxels thick for a 128-cell grid over the
scene (k = 0.25, 0.5, 1, 2; issue "What voxel-GI users complain about"). The point light is in
the left room; no light path reaches the right room (the opening faces empty space, and the
environment is black), so the exact image is exactly 0 there and the workbench's leak metric
(core/image_metrics.h) measures what a method puts through the wall.

The grid is fitted to the scene's bounds: x spans 2 + t, so a wall of k cells of a 128-cell grid is
t = 2k / (128 - k) thick. Usage: scripts/make_leak_walls.py  (rewrites the files)."""
import json
import os

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "leak-walls")
os.makedirs(root, exist_ok=True)
with open(os.path.join(root, "leak-walls.mtl"), "w") as f:
    f.write("newmtl white\nKd 0.7 0.7 0.7\n")


def quad(v, f, corners):
    """A quad (counter-clockwise seen from the side it faces) as two triangles."""
    b = len(v) + 1
    v.extend(corners)
    f.append((b, b + 1, b + 2))
    f.append((b, b + 2, b + 3))


for k in (0.25, 0.5, 1, 2):
    t = 2 * k / (128 - k)
    w = 2 + t
    v, f = [], []
    quad(v, f, [(0, 0, 0), (0, 0, 1), (w, 0, 1), (w, 0, 0)])  # floor, facing up
    quad(v, f, [(0, 1, 0), (w, 1, 0), (w, 1, 1), (0, 1, 1)])  # ceiling, facing down
    quad(v, f, [(0, 0, 0), (w, 0, 0), (w, 1, 0), (0, 1, 0)])  # back wall, facing +z
    quad(v, f, [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)])  # left wall, facing +x
    quad(v, f, [(w, 0, 0), (w, 0, 1), (w, 1, 1), (w, 1, 0)])  # right wall, facing -x
    quad(v, f, [(1, 0, 0), (1, 0, 1), (1, 1, 1), (1, 1, 0)])  # the wall's left face, facing -x
    quad(v, f, [(1 + t, 0, 0), (1 + t, 1, 0), (1 + t, 1, 1), (1 + t, 0, 1)])  # its right face, +x
    quad(v, f, [(1, 0, 1), (1 + t, 0, 1), (1 + t, 1, 1), (1, 1, 1)])  # its front edge, facing +z
    name = "wall-%gv" % k
    with open(os.path.join(root, name + ".obj"), "w") as o:
        o.write("# Two rooms open to the front, a wall of %g cells at 128 between them (x %.6f .. %.6f).\n"
                "# Written by scripts/make_leak_walls.py.\nmtllib leak-walls.mtl\nusemtl white\n"
                % (k, 1.0, 1 + t))
        o.writelines("v %.7g %.7g %.7g\n" % p for p in v)
        o.writelines("f %d %d %d\n" % tri for tri in f)
    scene = {
        "meshes": [{"path": name + ".obj"}],
        "lights": [{"type": "point", "position": [0.5, 0.5, 0.5], "intensity": 1.0}],
        "camera": {"position": [w / 2, 0.5, 3.2], "target": [w / 2, 0.5, 0.5], "up": [0, 1, 0], "fov_deg": 24},
    }
    with open(os.path.join(root, name + ".json"), "w") as o:
        json.dump(scene, o, indent=2)
        o.write("\n")
