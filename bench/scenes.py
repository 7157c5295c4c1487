#!/usr/bin/env python3
"""Writes the benchmark scenes of issue 13 as case files: seeded, so every run draws the same
triangles, and generated, so no large file is committed.

  scenes.py OUTDIR [--seed N] [--big]

fan_1000         ~4,400 thin triangles fanned around a random centre, the rim (radius 3 in
                 normalized device coordinates) enclosing the 1000x1000 framebuffer: piglit's
                 fan overdraw scene. No varyings (coverage, primitive and depth only).
quad_1024_4vec4  two perspective triangles (w from 1 to 4) filling 1024x1024 exactly, four smooth
                 vec4 varyings.
random_10k_256   10,000 triangles in 256x256, each vertex within 2 to 24 pixels of a random
                 centre, random depth, depth test less, one smooth vec2.
strips_512       64 triangle strips of 256 triangles each over 512x512 (16,384 triangles), jittered
                 vertices with perspective w, in one glDrawElements of 32-bit indices joined by
                 primitive restart, first-vertex convention, a smooth vec2 and a flat float.
big_2048_7vec4   two triangles filling 2048x2048, seven smooth vec4 varyings (memory).
big_4096_7vec4   the same at 4096x4096, only with --big (the GL frame alone is ~1.9 GB).
"""
import argparse
import json
import math
import os
import random


def write(outdir, name, case):
    with open(os.path.join(outdir, name + ".json"), "w") as f:
        json.dump(case, f, separators=(",", ":"))


def fan(rng):
    cx, cy = rng.uniform(-1, 1), rng.uniform(-1, 1)
    n = 4400
    rim = [[cx + 3 * math.cos(2 * math.pi * k / n), cy + 3 * math.sin(2 * math.pi * k / n), 0, 1]
           for k in range(n)]
    vertices = [{"clip": [cx, cy, 0, 1]}] + [{"clip": p} for p in rim]
    triangles = [[0, 1 + k, 1 + (k + 1) % n] for k in range(n)]
    return {"description": "Bench: a fan of %d thin triangles around a random centre, its rim "
                           "enclosing the framebuffer (piglit's fan overdraw)." % n,
            "framebuffer": {"width": 1000, "height": 1000}, "varyings": [],
            "vertices": vertices, "triangles": triangles}


def quad(rng, size, count):
    varyings = [{"name": "v%d" % k, "size": 4} for k in range(count)]
    corners = [(-1, -1, 1.0), (1, -1, 2.0), (1, 1, 4.0), (-1, 1, 3.0)]
    vertices = []
    for x, y, w in corners:
        v = {"clip": [x * w, y * w, rng.uniform(-0.5, 0.5) * w, w]}
        for var in varyings:
            v[var["name"]] = [round(rng.uniform(-100, 100), 3) for _ in range(4)]
        vertices.append(v)
    return {"description": "Bench: two perspective triangles filling %dx%d, %d smooth vec4 "
                           "varyings." % (size, size, count),
            "framebuffer": {"width": size, "height": size}, "varyings": varyings,
            "vertices": vertices, "triangles": [[0, 1, 2], [0, 2, 3]]}


def random_triangles(rng, count, size):
    vertices, triangles = [], []
    for t in range(count):
        cx, cy = rng.uniform(0, size), rng.uniform(0, size)
        for _ in range(3):
            r, a = rng.uniform(2, 24), rng.uniform(0, 2 * math.pi)
            x, y = cx + r * math.cos(a), cy + r * math.sin(a)
            vertices.append({"clip": [round(2 * x / size - 1, 6), round(2 * y / size - 1, 6),
                                      round(rng.uniform(-0.9, 0.9), 6), 1],
                             "c": [round(rng.uniform(0, 1), 5), round(rng.uniform(0, 1), 5)]})
        triangles.append([3 * t, 3 * t + 1, 3 * t + 2])
    return {"description": "Bench: %d random triangles in %dx%d, smooth vec2, depth test less."
                           % (count, size, size),
            "framebuffer": {"width": size, "height": size}, "state": {"depth_func": "less"},
            "varyings": [{"name": "c", "size": 2}], "vertices": vertices,
            "triangles": triangles}


def strips(rng, size, rows, columns):
    vertices, indices = [], []
    for r in range(rows):
        for k in range(columns + 1):
            for side in (0, 1):
                x = -1 + 2 * k / columns + rng.uniform(-0.3, 0.3) / columns
                y = -1 + 2 * (r + side) / rows + rng.uniform(-0.3, 0.3) / rows
                w = rng.uniform(1, 3)
                indices.append(len(vertices))
                vertices.append({"clip": [round(x * w, 6), round(y * w, 6), 0, round(w, 6)],
                                 "c": [round(rng.uniform(0, 1), 5), round(rng.uniform(0, 1), 5)],
                                 "f": r})
        indices.append(4294967295)
    return {"description": "Bench: %d triangle strips of %d triangles over %dx%d in one indexed "
                           "draw joined by primitive restart." % (rows, 2 * columns, size, size),
            "framebuffer": {"width": size, "height": size},
            "state": {"provoking_vertex": "first"},
            "varyings": [{"name": "c", "size": 2}, {"name": "f", "size": 1,
                                                     "interpolation": "flat"}],
            "vertices": vertices,
            "draws": [{"mode": "triangle_strip", "index_type": "unsigned_int",
                       "restart": "fixed_index", "indices": indices[:-1]}]}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("outdir")
    parser.add_argument("--seed", type=int, default=13)
    parser.add_argument("--big", action="store_true")
    args = parser.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    write(args.outdir, "fan_1000", fan(random.Random(args.seed)))
    write(args.outdir, "quad_1024_4vec4", quad(random.Random(args.seed + 1), 1024, 4))
    write(args.outdir, "random_10k_256", random_triangles(random.Random(args.seed + 2), 10000, 256))
    write(args.outdir, "big_2048_7vec4", quad(random.Random(args.seed + 3), 2048, 7))
    write(args.outdir, "strips_512", strips(random.Random(args.seed + 5), 512, 64, 128))
    if args.big:
        write(args.outdir, "big_4096_7vec4", quad(random.Random(args.seed + 4), 4096, 7))


main()
