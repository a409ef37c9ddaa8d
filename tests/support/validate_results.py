#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Validates result.json files against docs/result.schema.json.

    validate_results.py SCHEMA PATH...

Each PATH is a result.json file or a directory whose *.json files are all checked. Prints every
violation as "file: where: what" and exits 1 when there is one, or when no file was found at all
(a check of nothing must not pass); exits 0 when every file validates.
"""
import json
import pathlib
import sys

import jsonschema


def where(error):
    return "/".join(str(part) for part in error.absolute_path) or "(the record)"


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    schema = json.loads(pathlib.Path(argv[1]).read_text(encoding="utf-8"))
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    validator = validator_class(schema)
    files = []
    for name in argv[2:]:
        path = pathlib.Path(name)
        files += sorted(path.glob("*.json")) if path.is_dir() else [path]
    bad = 0
    for path in files:
        try:
            record = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as e:
            print(f"{path}: not JSON: {e}")
            bad += 1
            continue
        # the deepest errors say what is wrong; a failed if/then names only the branch
        errors = sorted(validator.iter_errors(record), key=lambda e: list(e.absolute_path))
        for error in errors:
            leaves = list(jsonschema.exceptions.best_match([error]).context or []) or [error]
            for leaf in leaves[:3]:
                print(f"{path}: {where(leaf)}: {leaf.message}")
        bad += 1 if errors else 0
    if not files:
        print(f"no result.json to validate in {' '.join(argv[2:])}: the check would pass on nothing")
        return 1
    print(f"{len(files) - bad} of {len(files)} result.json files follow {argv[1]} "
          f"({schema.get('title', '')})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
