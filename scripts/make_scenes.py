#!/usr/bin/python3
"""Writes casmap's scene files: the 16 obstacle courses of Ye & Borenstein's Table I, an indoor
course like the paper's Fig. 6, and an outdoor scene with a seeded rough-ground mesh.

Regenerate (deterministic, byte-identical output):  /usr/bin/python3 scripts/make_scenes.py
Needs only numpy (Debian python3-numpy). See docs/scenes.md for the layout rules.
"""
import os
import struct

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")

# Table I of the paper (columns: parallelepipeds 1-4, cylinder, poles), read from the paper's
# tab-separated table text.
TABLE_I = {
    1: ([2, 3], False, [1, 2, 3, 4, 5, 7, 9]),
    2: ([3], False, [1, 2, 3, 4, 5, 6, 7, 9]),
    3: ([], False, [1, 2, 3, 4, 5, 6, 7, 9]),
    4: ([2, 4], True, [1, 2, 4, 6]),
    5: ([1, 2], False, [1, 2, 3, 4, 6]),
    6: ([1, 2], True, [1, 2, 3, 4, 6]),
    7: ([1, 2], True, [1, 2, 3, 4, 5, 6, 7]),
    8: ([2, 4], True, [1, 2, 3, 4, 5, 6, 7, 8, 9]),
    9: ([2, 4], False, [1, 2, 3, 4, 5, 6, 7, 8, 9]),
    10: ([2, 3, 4], False, [1, 2, 3, 4, 5, 7, 9]),
    11: ([1, 2, 3], False, [1, 2, 3, 4, 5, 7, 9]),
    12: ([2, 4], False, [1, 2, 3, 4, 5, 7, 9]),
    13: ([2, 3], False, [1, 2, 3, 4, 5, 6, 7, 9]),
    14: ([1, 2, 3], False, []),
    15: ([2, 3, 4], False, []),
    16: ([2, 3], False, []),
}

# Printed dimensions (mm): parallelepipeds L x W x H (our x, y, z), cylinder, poles.
BOX_MM = {1: (530, 559, 462), 2: (413, 456, 414), 3: (400, 343, 213), 4: (514, 540, 327)}
CYLINDER_MM = (411, 459)  # diameter, height
POLE_DIAMETER_MM = {1: 24, 2: 21, 3: 19, 4: 15, 5: 11, 6: 9, 7: 6, 8: 4.5, 9: 2.5}
POLE_LENGTH_MM = 914

# Fixed slots (world x, y in m), the same in every course.
POLE_X = 2.0125
POLE_Y = {9: 0.1875, 8: -0.1875, 7: 0.3625, 6: -0.3625, 5: 0.5375, 4: -0.5375, 3: 0.7125,
          2: -0.7125, 1: 0.8875}
BOX_XY = {1: (3.0, -0.5), 2: (3.0, 0.5), 3: (4.11, -0.5), 4: (4.11, 0.5)}
CYLINDER_XY = (5.2, 0.0)

# Diffuse reflectivity at 905 nm: assumptions (the paper names no materials), see docs/scenes.md.
R_FLOOR, R_BOX, R_CYLINDER, R_POLE = 0.3, 0.6, 0.5, 0.45

LAYOUT = """\
# Layout (our choice: the paper prints no positions), the same slots in all 16 courses:
# - World frame REP-103, z up, metres; the floor's top is z = 0. The table's linear axis runs
#   along world +x at y = 0 and the sensor starts near x = 0, looking ahead (+x).
# - Map region = the paper's N = 200 rows along x by M = 80 cols across y, 25 mm cells:
#   x in [1, 6) m, y in [-1, 1) m, i.e. `casmap truth --grid 1.0,-1.0,0.025,200,80`.
#   Every object lies inside it.
# - Poles: one row across the track at x = 2.0125 m, 0.175 m (7 cells) apart on cell centres,
#   thinnest nearest the axis on alternating sides (#9 +0.1875, #8 -0.1875, #7 +0.3625,
#   #6 -0.3625, #5 +0.5375, #4 -0.5375, #3 +0.7125, #2 -0.7125, #1 +0.8875 m), so each pole
#   stands inside one 25 mm cell and no 5 x 5 filter window holds two poles.
# - Parallelepipeds (printed L x W x H as x x y x z): #1 at (3.0, -0.5), #2 at (3.0, +0.5),
#   #3 at (4.11, -0.5), #4 at (4.11, +0.5); the cylinder at (5.2, 0.0). No box edge lies on a
#   cell boundary; objects are at least 0.5 m apart along x.
# - Reflectivity (assumed, docs/scenes.md): floor 0.3, boxes 0.6, cylinder 0.5, poles 0.45.
"""


def fmt(v):
    return ("%.6f" % v).rstrip("0").rstrip(".")


def box(name, size, xyz, refl, rpy=None, terrain=False):
    lines = ["  - name: %s" % name,
             "    box: {size_m: [%s]}" % ", ".join(fmt(s) for s in size),
             "    pose: {xyz_m: [%s], rpy_deg: [%s]}" % (
                 ", ".join(fmt(c) for c in xyz), ", ".join(fmt(a) for a in (rpy or (0, 0, 0)))),
             "    reflectivity: %s" % fmt(refl)]
    if terrain:
        lines.append("    terrain: true")
    return "\n".join(lines) + "\n"


def cylinder(name, radius, height, xyz, refl):
    return ("  - name: %s\n    cylinder: {radius_m: %s, height_m: %s}\n"
            "    pose: {xyz_m: [%s], rpy_deg: [0, 0, 0]}\n    reflectivity: %s\n" % (
                name, fmt(radius), fmt(height), ", ".join(fmt(c) for c in xyz), fmt(refl)))


def course_objects(boxes, has_cylinder, poles):
    text = box("floor", (14.0, 8.0, 0.02), (3.0, 0.0, -0.01), R_FLOOR, terrain=True)
    for b in boxes:
        l, w, h = (d / 1000.0 for d in BOX_MM[b])
        x, y = BOX_XY[b]
        text += box("parallelepiped%d" % b, (l, w, h), (x, y, h / 2), R_BOX)
    if has_cylinder:
        d, h = (v / 1000.0 for v in CYLINDER_MM)
        text += cylinder("cylinder", d / 2, h, (CYLINDER_XY[0], CYLINDER_XY[1], h / 2), R_CYLINDER)
    for p in poles:
        length = POLE_LENGTH_MM / 1000.0
        text += cylinder("pole%d" % p, POLE_DIAMETER_MM[p] / 2000.0, length,
                         (POLE_X, POLE_Y[p], length / 2), R_POLE)
    return text


def describe(boxes, has_cylinder, poles):
    parts = []
    if boxes:
        parts.append("parallelepipeds " + ", ".join("#%d" % b for b in boxes))
    if has_cylinder:
        parts.append("the cylinder")
    if poles:
        parts.append("poles " + ", ".join("#%d" % p for p in poles))
    return "; ".join(parts)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def write_courses():
    for n, (boxes, has_cylinder, poles) in TABLE_I.items():
        head = ("# Obstacle course %d of Ye & Borenstein, Table I: %s.\n"
                "# Dimensions as printed in the paper. Generated by scripts/make_scenes.py.\n"
                % (n, describe(boxes, has_cylinder, poles)))
        write(os.path.join(ROOT, "courses", "course%02d.yaml" % n),
              head + LAYOUT + "objects:\n" + course_objects(boxes, has_cylinder, poles))


def write_indoor():
    head = """\
# Indoor course like the paper's Fig. 6 (course 4 set up in a lab): course 4's objects
# (parallelepipeds #2 and #4, the cylinder, poles #1, #2, #4, #6) in their course slots, inside
# a 10 m x 6 m room with 2.5 m walls, plus a door-stop step and a trash can, so that every beam
# of a vehicle- or table-mounted scanner has a return. Generated by scripts/make_scenes.py.
# Map region as in the courses: x in [1, 6) m, y in [-1, 1) m.
# Reflectivity (assumed): floor 0.3, walls 0.7 (white paint), other objects as in the courses.
"""
    boxes, has_cylinder, poles = TABLE_I[4]
    text = course_objects(boxes, has_cylinder, poles)
    text += box("wall_back", (0.1, 6.0, 2.5), (-2.05, 0.0, 1.25), 0.7)
    text += box("wall_front", (0.1, 6.0, 2.5), (8.05, 0.0, 1.25), 0.7)
    text += box("wall_left", (10.2, 0.1, 2.5), (3.0, 3.05, 1.25), 0.7)
    text += box("wall_right", (10.2, 0.1, 2.5), (3.0, -3.05, 1.25), 0.7)
    text += box("step", (0.3, 1.2, 0.08), (6.6, -1.6, 0.04), 0.4)
    text += cylinder("trash_can", 0.18, 0.6, (6.8, 1.7, 0.3), 0.35)
    write(os.path.join(ROOT, "indoor.yaml"), head + "objects:\n" + text)


def rough_ground(seed=20240601, x_range=(-2.0, 10.0), y_range=(-3.0, 0.4), step=0.1):
    """Heightfield: 12 random plane waves (4.3 cm RMS together) plus +-1 cm roughness, 0 at the curb."""
    rng = np.random.RandomState(seed)
    xs = np.arange(x_range[0], x_range[1] + step / 2, step)
    ys = np.arange(y_range[0], y_range[1] + step / 2, step)
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    z = np.zeros_like(gx)
    for _ in range(12):  # smooth undulation: random plane waves, wavelengths 0.6 to 4 m
        k = 2 * np.pi / rng.uniform(0.6, 4.0)
        a = rng.uniform(0, 2 * np.pi)
        z += 0.03 / np.sqrt(12) * 2 * np.sin(k * (np.cos(a) * gx + np.sin(a) * gy) + rng.uniform(0, 6.3))
    z += rng.uniform(-0.01, 0.01, size=z.shape)  # fine roughness
    z *= np.clip((y_range[1] - gy) / 0.3, 0.0, 1.0)  # meets the curb's foot at z = 0
    nx, ny = len(xs), len(ys)
    verts = np.stack([gx.ravel(), gy.ravel(), z.ravel()], axis=1).astype("<f4")
    faces = []
    for i in range(nx - 1):
        for j in range(ny - 1):
            a, b, c, d = i * ny + j, (i + 1) * ny + j, (i + 1) * ny + j + 1, i * ny + j + 1
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def write_ply_binary(path, verts, faces):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\n"
                 "comment casmap rough ground, scripts/make_scenes.py, metres, z up\n"
                 "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(verts), len(faces))).encode())
        f.write(verts.tobytes())
        for t in faces:
            f.write(struct.pack("<B3i", 3, *t))


def write_outdoor():
    verts, faces = rough_ground()
    write_ply_binary(os.path.join(ROOT, "meshes", "rough_ground.ply"), verts, faces)
    head = """\
# Outdoor scene for the vehicle (paper's Fig. 9, right): rough ground (a seeded mesh from
# scripts/make_scenes.py: smooth undulations of 4 cm RMS (extremes about +-13 cm) plus +-1 cm
# roughness on a 0.1 m grid, x in [-2, 10], y in [-3, 0.4]) marked terrain: true for the
# vehicle rig, a 0.15 m concrete curb along
# y in [0.4, 0.55], a sidewalk slab (top 0.12 m) beyond it, a lamp post and two rocks.
# The vehicle drives along +x near y = -1; map region x in [1, 6) m, y in [-1, 1) m.
# Reflectivity (assumed): soil 0.2, concrete 0.35, lamp post 0.3, rocks 0.25.
"""
    text = ("  - name: ground\n    mesh: meshes/rough_ground.ply\n    scale: 1.0\n"
            "    pose: {xyz_m: [0, 0, 0], rpy_deg: [0, 0, 0]}\n    reflectivity: 0.2\n"
            "    terrain: true\n")
    text += box("curb", (12.0, 0.15, 0.25), (4.0, 0.475, 0.025), 0.35)
    text += box("sidewalk", (12.0, 2.0, 0.22), (4.0, 1.55, 0.01), 0.35)
    text += cylinder("lamp_post", 0.06, 3.0, (4.5, 1.2, 1.62), 0.3)
    text += box("rock1", (0.25, 0.2, 0.15), (3.2, -0.4, 0.05), 0.25, rpy=(5, -8, 30))
    text += box("rock2", (0.18, 0.3, 0.1), (5.1, 0.1, 0.03), 0.25, rpy=(-6, 4, -20))
    write(os.path.join(ROOT, "outdoor.yaml"), head + "objects:\n" + text)


if __name__ == "__main__":
    os.makedirs(os.path.join(ROOT, "courses"), exist_ok=True)
    os.makedirs(os.path.join(ROOT, "meshes"), exist_ok=True)
    write_courses()
    write_indoor()
    write_outdoor()
