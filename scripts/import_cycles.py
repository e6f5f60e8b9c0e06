#!/usr/bin/env python3
"""Report import cycles between the source files of a crate.

A file imports another when one of its own `use` declarations names an
item that the other file *defines*: an item re-exported by a parent module
(`pub use child::Item;`) is followed to the child that defines it, and a
re-export itself (`pub use`, `pub(crate) use`) is the module's facade, not
an import of the file's code; neither is a `mod child;` declaration. Items
named by a path in code (`child::Item::new()`) without a `use` are not
seen.
Test modules (`#[cfg(test)] mod tests { … }` to the end of a file, and
files named `tests.rs`, `proptests.rs` or under `tests/`) are left out:
they may import what they test.

    python3 scripts/import_cycles.py src codec/src

prints each cycle (the files of one strongly connected component) and
exits 1 when there is one.
"""
import os
import re
import sys
from collections import defaultdict

ITEM = re.compile(
    r"^\s*(?:pub(?:\([^)]*\))?\s+)?(?:const\s+fn|async\s+fn|unsafe\s+fn|fn|struct|enum|trait|type|const|static|union|mod|macro_rules!)\s+([A-Za-z_][A-Za-z0-9_]*)",
    re.M,
)
USE = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?use\s+([^;]+);", re.M)
TEST_FILES = ("tests.rs", "proptests.rs")


def strip_tests(text):
    return re.sub(r"#\[cfg\(test\)\]\s*mod\s+\w+\s*\{.*", "", text, flags=re.S)


def expand(tree):
    """`a::{b, c::{d, e}}` -> [[a, b], [a, c, d], [a, c, e]] (paths of names)."""
    tree = re.sub(r"\s+", "", tree)
    out = []

    def walk(prefix, t):
        if t.startswith("{") and t.endswith("}"):
            depth, start = 0, 1
            for i, ch in enumerate(t):
                if ch == "{":
                    depth += 1
                elif ch == "}":
                    depth -= 1
                if (ch == "," and depth == 1) or (ch == "}" and depth == 0):
                    part = t[start:i]
                    if part:
                        walk(prefix, part)
                    start = i + 1
            return
        if "::{" in t:
            head, rest = t.split("::{", 1)
            walk(prefix + head.split("::"), "{" + rest)
            return
        path = prefix + t.split("::")
        path[-1] = path[-1].split("as")[0] if re.match(r".+as[A-Za-z_]", path[-1]) and "as" in path[-1] else path[-1]
        out.append(path)

    walk([], tree)
    return out


class Crate:
    def __init__(self, root):
        self.root = root
        self.files = {}
        for d, _, fs in os.walk(root):
            if os.sep + "bin" in d or os.sep + "tests" in d:
                continue
            for f in fs:
                if f.endswith(".rs") and f not in TEST_FILES:
                    p = os.path.join(d, f)
                    rel = os.path.relpath(p, root)[:-3].split(os.sep)
                    if rel[-1] in ("mod", "lib", "main"):
                        rel = rel[:-1]
                    self.files[tuple(rel)] = strip_tests(open(p, encoding="utf-8").read())
        self.defined = {m: set(ITEM.findall(t)) for m, t in self.files.items()}
        self.uses = {m: [expand(u) for u in USE.findall(t)] for m, t in self.files.items()}
        # The imports the file's own code uses: a re-export (`pub use`,
        # `pub(crate) use`) is the module's facade, not a use of the item.
        private = re.compile(r"^\s*use\s+([^;]+);", re.M)
        self.imports = {m: [expand(u) for u in private.findall(t)] for m, t in self.files.items()}

    def absolute(self, module, path):
        if not path:
            return None
        if path[0] == "crate":
            return path[1:]
        if path[0] == "self":
            return list(module) + path[1:]
        if path[0] == "super":
            base = list(module)
            while path and path[0] == "super":
                base, path = base[:-1], path[1:]
            return base + path
        if tuple(list(module) + [path[0]]) in self.files or path[0] in self.defined.get(module, ()):
            return list(module) + path
        return None  # another crate

    def owner(self, path, seen=()):
        """The file that defines the item `path` names (absolute)."""
        for n in range(len(path), -1, -1):
            module = tuple(path[:n])
            if module not in self.files:
                continue
            rest = path[n:]
            if not rest or rest[0] in ("*", "self"):
                return module
            name = rest[0]
            if name in self.defined[module]:
                return module
            # Re-exported: follow the `use` that brings the name in.
            for tree in self.uses[module]:
                for p in tree:
                    if p[-1] == name and (module, name) not in seen:
                        target = self.absolute(module, p)
                        if target is not None:
                            return self.owner(target + rest[1:], seen + ((module, name),))
            return module
        return None

    def edges(self):
        graph = defaultdict(set)
        for module, trees in self.imports.items():
            for tree in trees:
                for path in tree:
                    target = self.absolute(module, path)
                    if target is None:
                        continue
                    owner = self.owner(target)
                    if owner is not None and owner != module:
                        graph[module].add(owner)
        return graph


def cycles(graph, nodes):
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(component)

    sys.setrecursionlimit(20000)
    for v in nodes:
        if v not in index:
            strong(v)
    return found


def main(roots):
    total = 0
    for root in roots:
        crate = Crate(root)
        for component in cycles(crate.edges(), list(crate.files)):
            total += 1
            names = sorted("/".join(m) or "lib" for m in component)
            print(f"{root}: " + " <-> ".join(names))
    print(f"{total} import cycle{'s' if total != 1 else ''} between files")
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:] or ["src"]))
