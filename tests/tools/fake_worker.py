#!/usr/bin/env python3
"""A worker process without GL, speaking run's protocol (cli/workers/workers.hpp), for the worker pool's
own tests (tests/cli/test_worker_pool.cpp): each case passes unless a flag says what goes wrong.

  fake_worker.py [--no-context] [--die-at-start] [--crash-at NAME] [--hang-at NAME]
                 [--garbage-at NAME] [--wrong-index-at NAME] [--images-fail NAME]
                 [--identify-fails] [--log-at-start TEXT] [--compact]

--compact writes each result line as the real worker does (worker.cpp, send_raw_result): no
spaces, "images" only when true, "result" last; the runner reads those without parsing the
line whole.
"""
import argparse
import json
import os
import sys
import time

parser = argparse.ArgumentParser()
parser.add_argument("--no-context", action="store_true")
parser.add_argument("--die-at-start", action="store_true")
parser.add_argument("--crash-at")
parser.add_argument("--hang-at")
parser.add_argument("--garbage-at")
parser.add_argument("--wrong-index-at")
parser.add_argument("--images-fail")
parser.add_argument("--identify-fails", action="store_true")
parser.add_argument("--log-at-start", default="")
parser.add_argument("--compact", action="store_true")
args = parser.parse_args()


def send(message):
    sys.stdout.write((message if isinstance(message, str) else json.dumps(message)) + "\n")
    sys.stdout.flush()


def result(name, status):
    coverage = {k: 0 for k in ("both", "neither", "reference_only", "gl_only", "other_primitive",
                               "boundary", "exact_tie", "within_snapping", "fill_rule", "gaps",
                               "double_hits", "failures")}
    coverage.update(fragments_checked=False, mismatches=[])
    return {"name": name, "description": "fake", "status": status, "outcome": status,
            "message": "from the fake worker", "gl_digest": "", "seconds": 0.001,
            "tolerance": {"mode": "spec", "subpixel_bits": 8, "varying_ulps": 0,
                          "depth_ulps": 0, "allow_boundary": True},
            "coverage": coverage, "channels": []}


if args.log_at_start:
    print(args.log_at_start, file=sys.stderr, flush=True)
options = sys.stdin.readline()
json.loads(options)  # the options line comes first, and is JSON
if args.die_at_start:
    sys.exit(1)
if args.no_context:
    send({"error": "fake: no GL context here"})
    sys.exit(2)
send({"hello": {"vendor": "fake", "renderer": "fake renderer", "version": "4.5 fake",
                "platform": "none", "library": "", "subpixel_bits": 8,
                "initial_provoking_vertex": "last", "primitive_id_from_geometry_shader": False,
                "warnings": [],
                # Its own file stands for the driver's: the model cache keys on their digest.
                "driver_files": [os.path.abspath(__file__)]}})
for line in sys.stdin:
    job = json.loads(line)
    if job.get("identify"):
        if args.identify_fails:
            send({"identify_error": "fake: the probes drew nothing"})
        else:
            send({"identified": {"subpixel_bits": 4, "planes": "snapped",
                                 "tie_break": "top-left"}})
        continue
    name, index = job["name"], job["index"]
    print(f"fake worker: checking {name}", file=sys.stderr, flush=True)
    if name == args.crash_at:
        os.abort()
    if name == args.hang_at:
        while True:
            time.sleep(3600)
    if name == args.garbage_at:
        send("this is not JSON")
        continue
    if name == args.wrong_index_at:
        index += 1000
    failing = name == args.images_fail
    verdict = result(name, "Fail" if failing else "Pass")
    images = failing and job["images"]
    if args.compact:
        send('{"index":%d%s,"result":%s}' % (index, ',"images":true' if images else "",
                                             json.dumps(verdict, separators=(",", ":"))))
    else:
        send({"index": index, "images": images, "result": verdict})
    if failing and job["images"]:
        send({"images_done": index, "images_error": "fake: disk full"})
