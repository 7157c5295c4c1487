#!/usr/bin/env python3
"""A `run --worker-wrapper` for the tests of crash, timeout and interrupt handling: it starts the
real worker (its arguments), passes the protocol's lines both ways, and plays a hung driver where
it is told to, so that no test hook lives in glrefcheck itself.

  worker_proxy.py [--stall-case RE] [--stall-images RE] [--stall-hello] [--crash-on-identify]
                  [--pidfile F] CMD...

--stall-case RE    a job for a case whose name fully matches RE is held back: the worker never
                   gets it, as if its driver hung before the verdict.
--stall-images RE  the verdict of such a case reaches the runner, then nothing more: as if the
                   driver hung writing its heatmaps.
--stall-hello      the worker's hello (its GL context made) never reaches the runner: as if the
                   driver hung making its context.
--pidfile F        on stalling, this proxy's pid (the runner's child) is written to F, so that a
                   test can kill it (a Crash) or signal the runner.
--crash-on-identify  abort on the runner's request to identify the implementation.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import threading
import time

parser = argparse.ArgumentParser()
parser.add_argument("--stall-case")
parser.add_argument("--stall-images")
parser.add_argument("--stall-hello", action="store_true")
parser.add_argument("--crash-on-identify", action="store_true")
parser.add_argument("--pidfile")
parser.add_argument("command", nargs=argparse.REMAINDER)
args = parser.parse_args()

worker = subprocess.Popen(args.command, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
stalled = threading.Event()


def stall():
    """Stops passing anything on, for good; says so in the pid file."""
    stalled.set()
    if args.pidfile:
        with open(args.pidfile + ".tmp", "w") as f:
            f.write(f"{os.getpid()}\n")
        os.rename(args.pidfile + ".tmp", args.pidfile)
    while True:
        time.sleep(3600)


def matches(pattern, name):
    return pattern is not None and isinstance(name, str) and re.fullmatch(pattern, name)


def message(line):
    try:
        m = json.loads(line)
        return m if isinstance(m, dict) else {}
    except ValueError:
        return {}


def to_worker():
    for line in sys.stdin.buffer:
        if stalled.is_set():
            stall()
        m = message(line)
        if args.crash_on_identify and m.get("identify"):
            os.abort()
        if matches(args.stall_case, m.get("name")):
            stall()
        worker.stdin.write(line)
        worker.stdin.flush()
    worker.stdin.close()  # end of input: the worker finishes


def to_runner():
    for line in worker.stdout:
        if stalled.is_set():
            stall()
        m = message(line)
        if args.stall_hello and "hello" in m:
            stall()
        sys.stdout.buffer.write(line)
        sys.stdout.buffer.flush()
        result = m.get("result") if isinstance(m.get("result"), dict) else {}
        if m.get("images") and matches(args.stall_images, result.get("name")):
            stall()


threading.Thread(target=to_worker, daemon=True).start()
to_runner()
code = worker.wait()
# Ends as the worker ended: a crash stays a crash.
if code < 0:
    os.kill(os.getpid(), -code)
sys.exit(code)
