"""Import circles between the files of one crate.

A file imports another when one of its `use` paths or inline `crate::`/`super::`/`self::`
paths names an item defined there; re-exports (`pub use`) are followed to the file that
defines the item and are not themselves imports. Prints each crate's file count, edge count
and every strongly connected component of more than one file."""
import os
import re


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r'"(?:[^"\\]|\\.)*"', '""', text)
    return "\n".join(line.split("//")[0] for line in text.split("\n"))


def strip_tests(text):
    """Drop #[cfg(test)] items (unit tests may use anything of their file's parent): a
    braced item to its closing brace, any other (a `use`, a field, a match arm) to the end of
    its line."""
    out, i = [], 0
    lines = text.split("\n")
    while i < len(lines):
        if lines[i].strip().startswith("#[cfg(test)]"):
            i += 1
            while i < len(lines) and lines[i].strip().startswith("#["):
                i += 1
            depth, started = 0, False
            while i < len(lines):
                line = lines[i]
                depth += line.count("{") - line.count("}")
                started = started or "{" in line
                i += 1
                if started and depth <= 0:
                    break
                if not started and line.rstrip().endswith((";", ",")):
                    break
            continue
        out.append(lines[i])
        i += 1
    return "\n".join(out)


def expand(tree):
    """Paths of a use tree `a::b::{c, d::{e, f}}` (without `as` renames)."""
    tree = tree.strip()
    m = re.match(r"^(.*?)\{(.*)\}$", tree, re.S)
    if not m:
        return [re.sub(r"\s+as\s+\w+$", "", tree).strip()]
    prefix, inner = m.group(1), m.group(2)
    parts, depth, cur = [], 0, ""
    for ch in inner:
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        depth += ch == "{"
        depth -= ch == "}"
        cur += ch
    parts.append(cur)
    out = []
    for p in parts:
        if p.strip():
            for e in expand(p):
                out.append(prefix + e if e != "self" else prefix.rstrip(":"))
    return out


class Crate:
    def __init__(self, src):
        self.src = src
        self.files = {}  # module path tuple -> file
        for d, _, fs in os.walk(src):
            for f in fs:
                if not f.endswith(".rs"):
                    continue
                path = os.path.join(d, f)
                rel = os.path.relpath(path, src)[:-3].split(os.sep)
                if rel[-1] in ("lib", "main", "mod"):
                    rel = rel[:-1]
                mod = tuple(rel)
                if rel and rel[0] == "bin":
                    continue
                self.files[mod] = path
        self.text = {m: strip_tests(strip_comments(open(p, encoding="utf-8").read()))
                     for m, p in self.files.items()}
        self.reexports = {m: self._reexports(m) for m in self.files}

    def absolute(self, mod, path):
        segs = [s for s in path.replace(" ", "").split("::") if s]
        if not segs:
            return None
        if segs[0] == "crate":
            return segs[1:]
        if segs[0] == "self":
            return list(mod) + segs[1:]
        if segs[0] == "super":
            base = list(mod)
            while segs and segs[0] == "super":
                base = base[:-1]
                segs = segs[1:]
            return base + segs
        # a path relative to this module: a child module
        if tuple(list(mod) + segs[:1]) in self.files:
            return list(mod) + segs
        return None

    def _uses(self, mod):
        text = self.text[mod]
        for m in re.finditer(r"\b(pub(?:\([^)]*\))?\s+)?use\s+([^;]+);", text):
            for p in expand(m.group(2)):
                yield bool(m.group(1)), p

    def _reexports(self, mod):
        out = {}
        for public, p in self._uses(mod):
            if not public:
                continue
            a = self.absolute(mod, p)
            if a:
                out[a[-1]] = a
        return out

    def resolve(self, segs, depth=0):
        """The file defining the item at absolute path segs."""
        for k in range(len(segs), -1, -1):
            mod = tuple(segs[:k])
            if mod in self.files:
                rest = segs[k:]
                if rest and depth < 8 and rest[0] in self.reexports[mod]:
                    target = self.reexports[mod][rest[0]]
                    if target != list(segs):
                        return self.resolve(target + rest[1:], depth + 1)
                return mod
        return None

    def edges(self):
        out = {m: set() for m in self.files}
        for mod in self.files:
            paths = [p for public, p in self._uses(mod) if not public]
            body = re.sub(r"\b(pub(?:\([^)]*\))?\s+)?use\s+[^;]+;", "", self.text[mod])
            paths += re.findall(r"\b((?:crate|super|self)(?:::\w+)+)", body)
            for p in paths:
                a = self.absolute(mod, p)
                if a is None:
                    continue
                target = self.resolve(a)
                if target is not None and target != mod:
                    out[mod].add(target)
        return out


def sccs(graph):
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(comp)

    import sys
    sys.setrecursionlimit(10000)
    for v in graph:
        if v not in index:
            visit(v)
    return out


def circles(src):
    c = Crate(src)
    g = c.edges()
    comps = sccs(g)
    return c, g, [sorted(os.path.relpath(c.files[m], os.path.dirname(src)) for m in comp) for comp in comps]


if __name__ == "__main__":
    import sys
    for src in sys.argv[1:]:
        c, g, comps = circles(src)
        print(src, len(c.files), "files", sum(len(v) for v in g.values()), "imports", len(comps), "circles")
        for comp in comps:
            print("   ", " <-> ".join(comp))


def explain(src):
    """Each import inside a circle, with the paths that make it."""
    c, g, comps = circles(src)
    inside = set()
    for comp in sccs(g):
        inside |= set(comp)
    for mod in c.files:
        if mod not in inside:
            continue
        paths = [p for public, p in c._uses(mod) if not public]
        body = re.sub(r"\b(pub(?:\([^)]*\))?\s+)?use\s+[^;]+;", "", c.text[mod])
        paths += re.findall(r"\b((?:crate|super|self)(?:::\w+)+)", body)
        for p in sorted(set(paths)):
            a = c.absolute(mod, p)
            if a is None:
                continue
            t = c.resolve(a)
            if t is not None and t != mod and t in inside:
                print(f"  {os.path.relpath(c.files[mod], src)} -> {os.path.relpath(c.files[t], src)}  ({p})")
