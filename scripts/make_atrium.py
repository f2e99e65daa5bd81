#!/usr/bin/env python3
"""Writes scenes/atrium.{obj,json}: an outdoor scene of the kind no method was tuned for (issue 64) —
a 20 m square court, walls 10 m high and 0.5 m thick, under a 0.5 m roof slab with an 8 m square
opening, lit by a sun through the opening and seen from inside looking up, so that the opening's
rim stands against the sky (the environment, a constant blue) with the sun behind it. A directional
light's VPLs start on a disk as wide as the scene's bounding sphere; few of them enter the opening,
so a method that draws them from a fixed point set gets the light through the opening wrong by
whatever that set puts there. Usage: scripts/make_atrium.py  (rewrites the two files)."""
import json
import os
import sys

if len(sys.argv) != 1:
    sys.exit(print(f"usage: make_atrium.py   (no arguments: it rewrites scenes/atrium.obj and .json; got "
                   f"{' '.join(sys.argv[1:])!r})", file=sys.stderr) or 2)

vertices, faces = [], []


def quad(a, b, c, d):
    i = len(vertices)
    vertices.extend([a, b, c, d])
    faces.extend([(i + 1, i + 2, i + 3), (i + 1, i + 3, i + 4)])


def box(x0, x1, y0, y1, z0, z1):
    """An axis-aligned box, its six faces wound outwards."""
    quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))
    quad((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0))
    quad((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1))
    quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))
    quad((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0))
    quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))


box(-10, 10, -0.5, 0, -10, 10)  # the floor
box(-10, -9.5, 0, 10, -10, 10), box(9.5, 10, 0, 10, -10, 10)  # the walls
box(-9.5, 9.5, 0, 10, -10, -9.5), box(-9.5, 9.5, 0, 10, 9.5, 10)
box(-10, 10, 10, 10.5, -10, -4), box(-10, 10, 10, 10.5, 4, 10)  # the roof around an 8 m opening
box(-10, -4, 10, 10.5, -4, 4), box(4, 10, 10, 10.5, -4, 4)

scenes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
with open(os.path.join(scenes, "atrium.obj"), "w") as f:
    f.write("# scripts/make_atrium.py\n")
    for v in vertices:
        f.write("v %g %g %g\n" % v)
    for t in faces:
        f.write("f %d %d %d\n" % t)
scene = {
    "meshes": [{"path": "atrium.obj"}],
    "lights": [{"type": "directional", "direction": [0.35, -1.0, 0.2], "irradiance": [3, 3, 2.8]}],
    "environment": {"color": [0.35, 0.45, 0.7]},
    "camera": {"position": [-6, 2, 6], "target": [2, 10, -2], "up": [0, 1, 0], "fov_deg": 70},
}
with open(os.path.join(scenes, "atrium.json"), "w") as f:
    json.dump(scene, f, indent=2)
    f.write("\n")
