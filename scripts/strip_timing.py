"""Reads a JSON report on stdin, drops the fields that time the run (not the result) and
writes it back sorted and indented, for scripts/results-snapshot."""
import json
import re
import sys

TIMING = re.compile(r"(^|_)(elapsed|wall|seconds_per|time_s|cpu_s|runtime|timing|duration)($|_)")


def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if not TIMING.search(k)}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v


text = sys.stdin.read()
try:
    data = json.loads(text)
except json.JSONDecodeError:
    # several JSON documents, one per line
    data = [json.loads(line) for line in text.splitlines() if line.strip()]
json.dump(strip(data), sys.stdout, indent=1, sort_keys=True)
sys.stdout.write("\n")
