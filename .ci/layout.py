#!/usr/bin/env python3
"""Layout rules of ARCHITECTURE.md, checked mechanically (called by .ci/check-layout).

The workspace members come from `cargo metadata`, so a new crate is checked without editing
this file. Members are either front crates (the binary, io, engine, sweeps, Python, figures:
they may know file formats) or model crates (everything else: the layers — linalg, core,
statics, dynamics —, wheel-rolling and the topology crates), for which:
- no normal dependency, direct or transitive, on toml, csv or plotters;
- workspace dependencies only on the layers, wheel-rolling and the proc-macro crate
  tensegrity-derive (tbar-wheel may also use michell3d's node parameterisation): topology
  crates never depend on each other;
The layers (every dependency kind, direct or transitive, as `cargo metadata` resolves it):
- faer is a dependency of tensegrity-linalg alone, which depends on no workspace crate;
- tensegrity-core depends on no workspace crate but tensegrity-linalg (its error type);
- tensegrity-statics and tensegrity-dynamics never on each other; wheel-rolling never on
  tensegrity-statics; michell3d and formfind never on tensegrity-dynamics;
Every crate (each library's src/ and the binary's src/): no circle of imports between its files
(circles.py: a file imports another when a `use` or a `crate::`/`super::`/`self::` path names
an item defined there, re-exports followed).
Every library crate (all of crates/): no command-line flag (`--name`) in a string of its
production code: libraries name their own parameters. Everywhere: faer is named only under
crates/tensegrity-linalg/. The CLI (src/): no hand-written SVG, no function over 60 lines, no
file over 300 lines, and at most 8 % of the workspace's production lines (non-blank lines not
starting with //, outside tests/, benches/, examples/ and #[cfg(test)] modules).
"""
import json
import os
import re
import subprocess
import sys

FRONT = {"tensegrity", "tensegrity-io", "tensegrity-engine", "tensegrity-bench", "sweeps", "tensegrity-py",
         "tensegrity-figures"}
LAYERS = {"tensegrity-linalg", "tensegrity-core", "tensegrity-statics", "tensegrity-dynamics"}
# tensegrity-derive: the workspace's proc-macro crate (`#[derive(Columns)]`), no model code
MODEL_MAY_USE = LAYERS | {"wheel-rolling", "tensegrity-derive"}
# (crate, workspace crate it must not reach by any path of dependencies)
FORBIDDEN = [
    ("tensegrity-linalg", "tensegrity-core"),
    ("tensegrity-core", "tensegrity-statics"),
    ("tensegrity-core", "tensegrity-dynamics"),
    ("tensegrity-statics", "tensegrity-dynamics"),
    ("tensegrity-dynamics", "tensegrity-statics"),
    ("wheel-rolling", "tensegrity-statics"),
    ("michell3d", "tensegrity-dynamics"),
    ("formfind", "tensegrity-dynamics"),
]
FAER_ONLY_IN = "tensegrity-linalg"
EXCEPTIONS = {("tbar-wheel", "michell3d")}
FORMATS = {"toml", "csv", "plotters", "usvg", "resvg", "svg2pdf"}
CLI_SHARE = 0.08

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

# faer only in tensegrity-linalg: named in no other file, a dependency of no other member
for top in ["crates", "src", "benches", "tests"]:
    for f in rust_files(top):
        if f.startswith("crates/tensegrity-linalg/"):
            continue
        if re.search(r"\bfaer\b", open(f, encoding="utf-8").read()):
            fail(f"faer is named outside crates/tensegrity-linalg/: {f}")
for name, pkg in sorted(members.items()):
    if name != FAER_ONLY_IN and any(d["name"] == "faer" for d in pkg["dependencies"]):
        fail(f"{name} depends on faer directly (only {FAER_ONLY_IN} may)")

# the layer graph: every dependency kind, followed transitively through workspace members
def reaches(start):
    seen, todo = set(), [start]
    while todo:
        for dep in members[todo.pop()]["dependencies"]:
            d = dep["name"]
            if d in members and d not in seen and d != start:
                seen.add(d)
                todo.append(d)
    return seen


checked = []
for name, banned in FORBIDDEN:
    if name not in members:
        fail(f"the layer {name} is not a workspace member")
        continue
    if banned in reaches(name):
        fail(f"{name} depends on {banned} (directly or through another member)")
    checked.append(f"{name} -/-> {banned}")
print(f"layout: crate graph: faer only in {FAER_ONLY_IN}; " + "; ".join(checked))

# no import circle between the files of one crate
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import circles  # noqa: E402

n_files = n_imports = 0
srcs = [os.path.join(os.path.dirname(p["manifest_path"]), "src") for p in members.values()]
for src in sorted(srcs):
    crate, graph, comps = circles.circles(src)
    n_files += len(crate.files)
    n_imports += sum(len(v) for v in graph.values())
    for comp in comps:
        fail(f"import circle in {os.path.relpath(src, root)}: " + " <-> ".join(comp))
print(f"layout: import circles: {len(srcs)} crates, {n_files} files, {n_imports} imports between files checked")

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
