#!/usr/bin/python3
"""Validates OCPBench records against results/record.schema.json (Debian's python3-jsonschema).

Usage: validate_records.py --schema results/record.schema.json [--min-records N] PATH...

Each PATH is a record file (a JSON object: `ocpbench solve --json`), a JSON Lines file of records
(records*.jsonl), or a directory searched recursively for both (every *.json holding an object with
"schema_version", every records*.jsonl). Exits 1 naming the file, the line and the failing field
for the first invalid record of each file, or when fewer than N records were checked (so that an
empty snapshot cannot pass); 2 on bad usage.
"""
import argparse
import json
import os
import sys

try:
    import jsonschema
except ImportError:  # pragma: no cover
    print("validate_records: python3-jsonschema is not installed (apt-get install python3-jsonschema)",
          file=sys.stderr)
    sys.exit(2)


class ParseFailure:
    """A line that is not JSON at all: reported like a schema violation."""

    def __init__(self, message):
        self.message = message


def files_under(path):
    if os.path.isfile(path):
        yield path
        return
    for root, _, names in os.walk(path):
        for name in sorted(names):
            if name.endswith(".jsonl") and name.startswith("records"):
                yield os.path.join(root, name)
            elif name.endswith(".json"):
                yield os.path.join(root, name)


def records_of(path):
    """(line number, record) pairs; line 0 for a whole-file record."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if path.endswith(".jsonl"):
        for number, line in enumerate(text.splitlines(), 1):
            if line.strip():
                try:
                    yield number, json.loads(line)
                except json.JSONDecodeError as e:
                    yield number, ParseFailure(str(e))
        return
    try:
        value = json.loads(text)
    except json.JSONDecodeError:
        return
    if isinstance(value, dict) and "schema_version" in value:
        yield 0, value


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--schema", required=True)
    parser.add_argument("--min-records", type=int, default=1)
    parser.add_argument("paths", nargs="+")
    args = parser.parse_args()
    with open(args.schema, encoding="utf-8") as f:
        schema = json.load(f)
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    validator = validator_class(schema)
    checked, failures = 0, 0
    for root in args.paths:
        if not os.path.exists(root):
            continue
        for path in files_under(root):
            for line, record in records_of(path):
                checked += 1
                if isinstance(record, ParseFailure):
                    failures += 1
                    print(f"{path}:{line}: not JSON: {record.message}", file=sys.stderr)
                    continue
                errors = sorted(validator.iter_errors(record), key=lambda e: list(e.path))
                if errors:
                    failures += 1
                    e = errors[0]
                    where = "/".join(str(p) for p in e.path) or "(record)"
                    print(f"{path}:{line}: {where}: {e.message[:300]}", file=sys.stderr)
    print(f"validate_records: {checked} records checked, {failures} invalid")
    if failures:
        return 1
    if checked < args.min_records:
        print(f"validate_records: expected at least {args.min_records} records", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
