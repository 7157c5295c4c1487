#!/usr/bin/env python3
"""Writes random clip-heavy scenes with the depth test as case files (issue 44's check of
fragment counts free of hidden depth contests): seeded, so every run draws the same triangles.

  clip-scenes.py OUTDIR [--seeds FIRST:COUNT] [--triangles N] [--size PIXELS]

Each scene: N triangles (default 2,000) whose clip coordinates are x, y in [-3w, 3w],
z in [-1.2w, 1.2w], w in [0.2, 3.2], in a SIZE x SIZE framebuffer (default 512), depth test
less, one smooth float. Most triangles cross a clip plane, and many overlap with depths within
rounding of each other.
"""
import argparse
import json
import os
import random


def scene(seed, triangles, size):
    rng = random.Random(seed)
    vertices = []
    for _ in range(3 * triangles):
        w = rng.uniform(0.2, 3.2)
        vertices.append({"clip": [rng.uniform(-3, 3) * w, rng.uniform(-3, 3) * w,
                                  rng.uniform(-1.2, 1.2) * w, w],
                         "v": rng.uniform(-1, 1)})
    return {"description": "Random clip-heavy scene, seed %d: %d triangles with x, y in [-3w, 3w], "
                           "z in [-1.2w, 1.2w], w in [0.2, 3.2], depth test less."
                           % (seed, triangles),
            "framebuffer": {"width": size, "height": size},
            "state": {"depth_func": "less"},
            "varyings": [{"name": "v", "size": 1}],
            "vertices": vertices}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--seeds", default="1:20", help="FIRST:COUNT (default 1:20)")
    parser.add_argument("--triangles", type=int, default=2000)
    parser.add_argument("--size", type=int, default=512)
    args = parser.parse_args()
    first, count = (int(x) for x in args.seeds.split(":"))
    os.makedirs(args.outdir, exist_ok=True)
    for seed in range(first, first + count):
        with open(os.path.join(args.outdir, "clip_scene_%d.json" % seed), "w") as f:
            json.dump(scene(seed, args.triangles, args.size), f, separators=(",", ":"))


if __name__ == "__main__":
    main()
