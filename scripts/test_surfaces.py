#!/usr/bin/env python3
"""Writes the closed surfaces of the voxelization tests as ASCII STL files, for
deformable_sim_mesh and doc/physics.md ("Bodies from a surface"):

  sphere.stl        radius 0.1 m, 32 rings x 64 segments
  torus.stl         radii 0.1 m and 0.04 m, 64 x 32 quads
  turned_cube.stl   0.1 m cube turned 0.5 rad about (1, 2, 3)
  turned_beam.stl   the reference cantilever (1 x 0.1 x 0.1 m) turned 30 deg about x
"""
import argparse
import math
import os
import sys


def write_stl(path, vertices, triangles):
    with open(path, "w") as out:
        out.write("solid surface\n")
        for a, b, c in triangles:
            pa, pb, pc = vertices[a], vertices[b], vertices[c]
            u = [pb[i] - pa[i] for i in range(3)]
            v = [pc[i] - pa[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in n)) or 1.0
            out.write("facet normal %g %g %g\nouter loop\n" % tuple(x / length for x in n))
            for p in (pa, pb, pc):
                out.write("vertex %.17g %.17g %.17g\n" % tuple(p))
            out.write("endloop\nendfacet\n")
        out.write("endsolid surface\n")


def quad(triangles, a, b, c, d):
    triangles += [(a, b, c), (a, c, d)]


def sphere(radius, rings, segments):
    vertices = [(0.0, 0.0, -radius)]
    for r in range(1, rings):
        polar = math.pi * (1.0 - r / rings)
        for s in range(segments):
            azimuth = 2.0 * math.pi * s / segments
            vertices.append((radius * math.sin(polar) * math.cos(azimuth),
                             radius * math.sin(polar) * math.sin(azimuth),
                             radius * math.cos(polar)))
    vertices.append((0.0, 0.0, radius))
    north = len(vertices) - 1

    def ring(r, s):
        return 1 + (r - 1) * segments + s % segments
    triangles = []
    for s in range(segments):
        triangles.append((0, ring(1, s + 1), ring(1, s)))
        triangles.append((north, ring(rings - 1, s), ring(rings - 1, s + 1)))
        for r in range(1, rings - 1):
            quad(triangles, ring(r, s), ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s))
    return vertices, triangles


def torus(major, minor, around, tube):
    vertices = []
    for i in range(around):
        u = 2.0 * math.pi * i / around
        for j in range(tube):
            v = 2.0 * math.pi * j / tube
            rho = major + minor * math.cos(v)
            vertices.append((rho * math.cos(u), rho * math.sin(u), minor * math.sin(v)))

    def index(i, j):
        return (i % around) * tube + j % tube
    triangles = []
    for i in range(around):
        for j in range(tube):
            quad(triangles, index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1))
    return vertices, triangles


def rotation(axis, angle):
    """Rodrigues' rotation matrix about a unit axis."""
    x, y, z = axis
    c, s, t = math.cos(angle), math.sin(angle), 1.0 - math.cos(angle)
    return [[c + x * x * t, x * y * t - z * s, x * z * t + y * s],
            [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
            [z * x * t - y * s, z * y * t + x * s, c + z * z * t]]


def box(low, high, turn):
    vertices = []
    for corner in range(8):
        p = [high[k] if corner >> k & 1 else low[k] for k in range(3)]
        vertices.append(tuple(sum(turn[r][k] * p[k] for k in range(3)) for r in range(3)))
    triangles = []
    for face in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)):
        quad(triangles, *face)
    return vertices, triangles


def main():
    parser = argparse.ArgumentParser(
        prog="test_surfaces.py", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__)
    parser.add_argument("out_dir", help="where the STL files go (made if missing)")
    out = parser.parse_args(sys.argv[1:]).out_dir
    os.makedirs(out, exist_ok=True)
    norm = math.sqrt(14.0)
    write_stl(os.path.join(out, "sphere.stl"), *sphere(0.1, 32, 64))
    write_stl(os.path.join(out, "torus.stl"), *torus(0.1, 0.04, 64, 32))
    write_stl(os.path.join(out, "turned_cube.stl"),
              *box((0, 0, 0), (0.1, 0.1, 0.1), rotation((1 / norm, 2 / norm, 3 / norm), 0.5)))
    write_stl(os.path.join(out, "turned_beam.stl"),
              *box((0, -0.05, -0.05), (1, 0.05, 0.05), rotation((1, 0, 0), math.pi / 6)))


if __name__ == "__main__":
    main()
