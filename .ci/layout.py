#!/usr/bin/env python3
"""Layout rules of ARCHITECTURE.md, checked mechanically (called by .ci/check-layout).

The workspace members come from `cargo metadata`, so a new crate is checked without editing
this file. Members are either front crates (the binary, io, engine, sweeps, Python, figures:
they may know file formats) or model crates (everything else: the core, wheel-rolling and the
topology crates), for which:
- no normal dependency, direct or transitive, on toml, csv or plotters;
- workspace dependencies only on tensegrity-core and wheel-rolling (tbar-wheel may also use
  michell3d's node parameterisation): topology crates never depend on each other;
Every library crate (all of crates/): no command-line flag (`--name`) in a string of its
production code: libraries name their own parameters. Everywhere: faer is named only under crates/tensegrity-core/src/linalg/. The CLI (src/): no
hand-written SVG, no function over 60 lines, no file over 300 lines, and at most 10 % of the
workspace's production lines (non-blank lines not starting with //, outside tests/, benches/,
examples/ and #[cfg(test)] modules).
"""
import json
import os
import re
import subprocess
import sys

FRONT = {"tensegrity", "tensegrity-io", "tensegrity-engine", "sweeps", "tensegrity-py",
         "tensegrity-figures"}
MODEL_MAY_USE = {"tensegrity-core", "wheel-rolling"}
EXCEPTIONS = {("tbar-wheel", "michell3d")}
FORMATS = {"toml", "csv", "plotters", "usvg", "resvg", "svg2pdf"}
CLI_SHARE = 0.10

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.chdir(root)
failures = []


def fail(msg):
    failures.append(msg)


def production_lines(path):
    """Non-blank, non-comment lines outside #[cfg(test)] items."""
    count, skip_depth, pending = 0, None, False
    depth = 0
    for line in open(path, encoding="utf-8"):
        s = line.strip()
        if skip_depth is None and s.startswith("#[cfg(test)]"):
            pending = True
            continue
        if pending:
            if s.endswith(";"):
                pending = False
                continue
            if "{" in s:
                skip_depth, pending = depth, False
        opened = line.count("{") - line.count("}")
        if skip_depth is not None:
            depth += opened
            if depth <= skip_depth:
                skip_depth = None
            continue
        depth += opened
        if s and not s.startswith("//"):
            count += 1
    return count


def rust_files(top):
    for d, _, files in os.walk(top):
        if "/target" in d or "/." in d:
            continue
        for f in files:
            if f.endswith(".rs"):
                yield os.path.join(d, f)


meta = json.loads(subprocess.run(
    ["cargo", "metadata", "--no-deps", "--format-version", "1", "--offline"],
    check=True, capture_output=True, text=True).stdout)
members = {p["name"]: p for p in meta["packages"]}
model = sorted(n for n in members if n not in FRONT)

# faer only under the core's linalg/
for top in ["crates", "src", "benches", "tests"]:
    for f in rust_files(top):
        if f.startswith("crates/tensegrity-core/src/linalg/"):
            continue
        if re.search(r"\bfaer\b", open(f, encoding="utf-8").read()):
            fail(f"faer is named outside crates/tensegrity-core/src/linalg/: {f}")

for name in model:
    pkg = members[name]
    crate_dir = os.path.dirname(pkg["manifest_path"])
    for dep in pkg["dependencies"]:
        if dep.get("kind") is None and dep["name"] in members and dep["name"] != name:
            if dep["name"] not in MODEL_MAY_USE and (name, dep["name"]) not in EXCEPTIONS:
                fail(f"model crate {name} depends on the workspace crate {dep['name']}")
    tree = subprocess.run(
        ["cargo", "tree", "-p", name, "-e", "normal", "--prefix", "none", "--offline"],
        capture_output=True, text=True).stdout
    used = sorted({line.split()[0] for line in tree.splitlines() if line.split()} & FORMATS)
    if used:
        fail(f"model crate {name} depends on {', '.join(used)}")
# every library (all of crates/) names its own parameters, never a command-line flag
for name, pkg in sorted(members.items()):
    crate_dir = os.path.dirname(pkg["manifest_path"])
    if os.path.abspath(crate_dir) == os.path.abspath(root):
        continue
    src = os.path.join(crate_dir, "src")
    for f in rust_files(src):
        in_test = False
        for i, line in enumerate(open(f, encoding="utf-8"), 1):
            s = line.strip()
            if s.startswith("#[cfg(test)]"):
                in_test = True
            if in_test or s.startswith("//"):
                continue
            for lit in re.findall(r'"(?:[^"\\]|\\.)*"', line):
                if re.search(r"[\"\s(`]--[a-z]", lit):
                    fail(f"{os.path.relpath(f, root)}:{i}: a library names a CLI flag: {lit}")


# the CLI: no hand-written SVG, short functions and files, a small share of the code
fn_re = re.compile(r"^( *)(pub(\([a-z]+\))? )?(const )?(async )?fn [A-Za-z0-9_]+")
for f in rust_files("src"):
    lines = open(f, encoding="utf-8").read().split("\n")
    if len(lines) - 1 > 300:
        fail(f"{f}: {len(lines) - 1} lines (the CLI keeps files under 300)")
    start = None
    for i, line in enumerate(lines):
        if re.search(r"<svg|<polyline|<path ", line):
            fail(f"{f}:{i + 1}: hand-written SVG in src/")
        m = fn_re.match(line)
        if m and start is None:
            indent, start, name = m.group(1), i, line.strip()
        elif start is not None and line == indent + "}":
            if i - start + 1 > 60:
                fail(f"{f}:{start + 1}: {i - start + 1} lines: {name}")
            start = None

total = cli = 0
for top in ["src", "crates"]:
    for f in rust_files(top):
        parts = f.split(os.sep)
        if any(p in ("tests", "benches", "examples") for p in parts):
            continue
        n = production_lines(f)
        total += n
        if top == "src":
            cli += n
share = cli / total if total else 0.0
print(f"layout: the CLI is {cli} of {total} production lines ({100 * share:.1f} %)")
if share > CLI_SHARE:
    fail(f"the CLI is {100 * share:.1f} % of the production lines (at most {100 * CLI_SHARE:.0f} %)")

for msg in failures:
    print("layout:", msg)
if failures:
    sys.exit(1)
print(f"layout: ok ({len(model)} model crates: {', '.join(model)})")
