#!/usr/bin/python3
"""Writes the tiny test meshes of tests/data/meshes (regenerate: /usr/bin/python3 make_test_meshes.py).

All shapes are in millimetres (load them with scale 0.001), centred on the origin:
  plane    2000 x 2000 mm square in z = 0 (2 triangles)
  box      400 x 300 x 200 mm (x, y, z), 12 triangles
  cylinder radius 200 mm, height 500 mm, axis z, 96 segments: the polygon's sagitta is
           200 * (1 - cos(pi / 96)) = 0.107 mm, well inside the tests' 1 mm tolerance.
Each shape is written as binary STL, OBJ and ASCII PLY; box also as ASCII STL. empty.stl holds no
facet and garbage.ply is not a mesh (bad-input tests).
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def plane():
    v = [(-1000, -1000, 0), (1000, -1000, 0), (1000, 1000, 0), (-1000, 1000, 0)]
    return v, [(0, 1, 2), (0, 2, 3)]


def box():
    hx, hy, hz = 200, 150, 100
    v = [(sx * hx, sy * hy, sz * hz) for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)]
    # vertex index = (sz>0)*4 + (sy>0)*2 + (sx>0); faces wound outwards
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = []
    for a, b, c, d in quads:
        tris += [(a, b, c), (a, c, d)]
    return v, tris


def cylinder(n=96, r=200.0, h=500.0):
    v = []
    for k in range(n):
        a = 2.0 * math.pi * k / n
        v.append((r * math.cos(a), r * math.sin(a), -h / 2))
        v.append((r * math.cos(a), r * math.sin(a), h / 2))
    bottom, top = len(v), len(v) + 1
    v += [(0.0, 0.0, -h / 2), (0.0, 0.0, h / 2)]
    tris = []
    for k in range(n):
        b0, t0 = 2 * k, 2 * k + 1
        b1, t1 = 2 * ((k + 1) % n), 2 * ((k + 1) % n) + 1
        tris += [(b0, b1, t1), (b0, t1, t0), (bottom, b1, b0), (top, t0, t1)]
    return v, tris


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / length for x in n)


def write_stl_binary(path, v, tris):
    with open(path, "wb") as f:
        f.write(b"casmap test mesh".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            a, b, c = (v[i] for i in t)
            f.write(struct.pack("<12fH", *normal(a, b, c), *a, *b, *c, 0))


def write_stl_ascii(path, v, tris):
    with open(path, "w") as f:
        f.write("solid casmap\n")
        for t in tris:
            a, b, c = (v[i] for i in t)
            f.write("facet normal %g %g %g\n outer loop\n" % normal(a, b, c))
            for p in (a, b, c):
                f.write("  vertex %.6f %.6f %.6f\n" % p)
            f.write(" endloop\nendfacet\n")
        f.write("endsolid casmap\n")


def write_obj(path, v, tris):
    with open(path, "w") as f:
        f.write("# casmap test mesh\n")
        for p in v:
            f.write("v %.6f %.6f %.6f\n" % p)
        for t in tris:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def write_ply(path, v, tris):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\ncomment casmap test mesh\n")
        f.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(v))
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(tris))
        for p in v:
            f.write("%.6f %.6f %.6f\n" % p)
        for t in tris:
            f.write("3 %d %d %d\n" % t)


def main():
    for name, make in (("plane", plane), ("box", box), ("cylinder", cylinder)):
        v, tris = make()
        write_stl_binary(os.path.join(HERE, name + ".stl"), v, tris)
        write_obj(os.path.join(HERE, name + ".obj"), v, tris)
        write_ply(os.path.join(HERE, name + ".ply"), v, tris)
    v, tris = box()
    write_stl_ascii(os.path.join(HERE, "box_ascii.stl"), v, tris)
    with open(os.path.join(HERE, "empty.stl"), "w") as f:
        f.write("solid empty\nendsolid empty\n")
    with open(os.path.join(HERE, "garbage.ply"), "w") as f:
        f.write("this is not a mesh\n\x01\x02\x03\n")


if __name__ == "__main__":
    main()
