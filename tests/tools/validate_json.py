#!/usr/bin/env python3
"""Validates JSON files against a JSON Schema (draft 2020-12), with Debian's python3-jsonschema.
Usage: validate_json.py SCHEMA FILE...  Prints one line per error (file, path in the document,
what is wrong) and exits 1 when any file does not validate, 0 when all do."""
import json
import sys

import jsonschema


def main() -> int:
    schema = json.load(open(sys.argv[1]))
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    bad = 0
    for name in sys.argv[2:]:
        doc = json.load(open(name))
        for error in sorted(validator.iter_errors(doc), key=lambda e: list(e.path)):
            path = "/".join(str(p) for p in error.path) or "(root)"
            print(f"{name}: {path}: {error.message[:200]}")
            bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
