#!/usr/bin/env python3
"""Validates report.json files against docs/report.schema.json (JSON Schema 2020-12),
then checks what a schema cannot say: the verdict agrees with the warnings, the file is
UTF-8, and no string holds an absolute path.

usage: validate_report.py <schema> <report.json>...   (exit 77 without python3-jsonschema)
"""
import json
import sys

try:
    import jsonschema
except ImportError:
    print("python3-jsonschema not installed (apt-get install python3-jsonschema): skipped")
    sys.exit(77)

schema = json.load(open(sys.argv[1], encoding="utf-8"))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
failed = 0
for path in sys.argv[2:]:
    raw = open(path, "rb").read()
    try:
        report = json.loads(raw.decode("utf-8"))  # strict: a stray byte fails here
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        print(f"FAIL: {path}: not UTF-8 JSON: {e}")
        failed += 1
        continue
    errors = sorted(validator.iter_errors(report), key=lambda e: list(e.path))
    for e in errors[:5]:
        print(f"FAIL: {path}: {'/'.join(map(str, e.path))}: {e.message}")
    failed += bool(errors)
    unsafe = [w for w in report["warnings"] if w["severity"] == "unsafe"]
    if (report["verdict"]["status"] == "PASS") != (not unsafe):
        print(f"FAIL: {path}: verdict {report['verdict']['status']} with {len(unsafe)} unsafe warnings")
        failed += 1
    if len(report["verdict"]["reasons"]) != len(unsafe):
        print(f"FAIL: {path}: {len(report['verdict']['reasons'])} reasons for {len(unsafe)} unsafe warnings")
        failed += 1

    def strings(node):
        if isinstance(node, str):
            yield node
        elif isinstance(node, dict):
            for v in node.values():
                yield from strings(v)
        elif isinstance(node, list):
            for v in node:
                yield from strings(v)

    for s in strings({k: v for k, v in report.items() if k != "job"}):
        if s.startswith("/") or "/tmp/" in s or "/home/" in s or "/work/" in s:
            print(f"FAIL: {path}: an absolute path in the report: {s[:80]}")
            failed += 1
            break
print(f"{len(sys.argv) - 2 - failed} passed, {failed} failed")
sys.exit(1 if failed else 0)
