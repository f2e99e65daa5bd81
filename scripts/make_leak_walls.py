#!/usr/bin/env python3
"""Writes scenes/leak-walls/wall-<k>v.{obj,json}: two 1 m rooms side by side, open to the front
(z = 1) where the camera stands, separated by a wall k voxels thick for a 128-cell grid over the
scene (k = 0.25, 0.5, 1, 2; issue "What voxel-GI users complain about"). The point light is in
the left room; no light path reaches the right room (the opening faces empty space, and the
environment is black), so the exact image is exactly 0 there and the workbench's leak metric
(core/image_metrics.h) measures what a method puts through the wall.

The grid is fitted to the scene's bounds: x spans 2 + t, so a wall of k cells of a 128-cell grid is
t = 2k / (128 - k) thick.

Also writes scenes/leak-closed/closed-<k>v.{obj,json}: one room 2 m wide, open to the front, lit by
the same point light in its left half, with a sealed hollow box in its right half whose six walls are
k cells thick (t = 2k / 128: the scene spans 2 m in x). The camera is a cut-away one ("near": its near
plane lies inside the box), so the image shows the box's inside — exactly dark in the exact image,
no light path enters a closed mesh — beside the lit room, and the leak metric measures what a method
puts through a closed mesh's walls. Usage: scripts/make_leak_walls.py  (rewrites the files)."""
import json
import os
import sys

if len(sys.argv) != 1:
    sys.exit(print(f"usage: make_leak_walls.py   (no arguments: it rewrites scenes/leak-walls and "
                   f"scenes/leak-closed; got {' '.join(sys.argv[1:])!r})", file=sys.stderr) or 2)

scenes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
root = os.path.join(scenes, "leak-walls")
closed_root = os.path.join(scenes, "leak-closed")
for folder in (root, closed_root):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, os.path.basename(folder) + ".mtl"), "w") as f:
        f.write("newmtl white\nKd 0.7 0.7 0.7\n")


def quad(v, f, corners):
    """A quad (counter-clockwise seen from the side it faces) as two triangles."""
    b = len(v) + 1
    v.extend(corners)
    f.append((b, b + 1, b + 2))
    f.append((b, b + 2, b + 3))


def box(v, f, lo, hi, outward):
    """The six faces of an axis-aligned box, facing out of it (outward) or into it."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    faces = [[(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],  # bottom, facing -y
             [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],  # top, +y
             [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],  # back, -z
             [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],  # front, +z
             [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],  # left, -x
             [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)]]  # right, +x
    for c in faces:
        quad(v, f, c if outward else c[::-1])


def write(folder, name, header, v, f, scene):
    with open(os.path.join(folder, name + ".obj"), "w") as o:
        o.write(header + "# Written by scripts/make_leak_walls.py.\nmtllib %s.mtl\nusemtl white\n"
                % os.path.basename(folder))
        o.writelines("v %.7g %.7g %.7g\n" % p for p in v)
        o.writelines("f %d %d %d\n" % tri for tri in f)
    with open(os.path.join(folder, name + ".json"), "w") as o:
        json.dump(scene, o, indent=2)
        o.write("\n")


LIGHT = [{"type": "point", "position": [0.5, 0.5, 0.5], "intensity": 1.0}]

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
    write(root, name, "# Two rooms open to the front, a wall of %g cells at 128 between them (x %.6f .. %.6f).\n"
          % (k, 1.0, 1 + t), v, f, {
              "meshes": [{"path": name + ".obj"}],
              "lights": LIGHT,
              "camera": {"position": [w / 2, 0.5, 3.2], "target": [w / 2, 0.5, 0.5], "up": [0, 1, 0], "fov_deg": 24},
          })

    # The closed box: outside (1.1, 0.05, 0.1) .. (1.9, 0.85, 0.9), walls t = 2k/128 thick; the camera's
    # near plane (z = 0.8) lies inside it.
    t = 2 * k / 128
    v, f = [], []
    quad(v, f, [(0, 0, 0), (0, 0, 1), (2, 0, 1), (2, 0, 0)])  # floor
    quad(v, f, [(0, 1, 0), (2, 1, 0), (2, 1, 1), (0, 1, 1)])  # ceiling
    quad(v, f, [(0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0)])  # back wall
    quad(v, f, [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)])  # left wall
    quad(v, f, [(2, 0, 0), (2, 0, 1), (2, 1, 1), (2, 1, 0)])  # right wall
    lo, hi = (1.1, 0.05, 0.1), (1.9, 0.85, 0.9)
    box(v, f, lo, hi, True)
    box(v, f, tuple(c + t for c in lo), tuple(c - t for c in hi), False)
    name = "closed-%gv" % k
    write(closed_root, name, "# A room open to the front with a sealed box, walls %g cells thick at 128 (%.6f).\n"
          % (k, t), v, f, {
              "meshes": [{"path": name + ".obj"}],
              "lights": LIGHT,
              "camera": {"position": [1.0, 0.5, 3.2], "target": [1.0, 0.5, 0.5], "up": [0, 1, 0], "fov_deg": 24,
                         "near": 2.4},
          })
