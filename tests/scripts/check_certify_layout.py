#!/usr/bin/env python3
"""ctest: the certificate's wing (src/certify/) keeps its walls. Its files, a header and its source
counted as one component, include each other without a cycle (the vocabulary below the tests,
the tests below the drivers); the vocabulary includes no other file of the wing; and nothing of
the library outside the wing, nor the tools or the Python bindings, includes a file of the wing
(its one public face is include/plateball/isoparallel_certificate.h). Prints each breach and exits 1,
else "certify layout: N components, no include cycle, one public face" and exits 0.
Usage: check_certify_layout.py SOURCE_DIR"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def includes(path):
    with open(path, encoding="utf-8") as f:
        return INCLUDE.findall(f.read())


def sources(root, exts=(".h", ".cc")):
    for directory, _, files in os.walk(root):
        for name in sorted(files):
            if name.endswith(exts):
                yield os.path.join(directory, name)


def wing_graph(src):
    """component ("certify/window") -> the wing's components it includes."""
    graph = {}
    for path in sources(os.path.join(src, "certify")):
        component = os.path.splitext(os.path.relpath(path, src))[0]
        targets = graph.setdefault(component, set())
        for inc in includes(path):
            target = os.path.splitext(inc)[0]
            if inc.startswith("certify/") and target != component:
                targets.add(target)
    return graph


def cycle(graph):
    """One include cycle as a list of components, or None (depth-first search)."""
    state, stack = {}, []

    def visit(v):
        state[v] = "open"
        stack.append(v)
        for w in sorted(graph.get(v, ())):
            if state.get(w) == "open":
                return stack[stack.index(w):] + [w]
            if w not in state:
                found = visit(w)
                if found:
                    return found
        state[v] = "done"
        stack.pop()
        return None

    for v in sorted(graph):
        if v not in state:
            found = visit(v)
            if found:
                return found
    return None


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    root = sys.argv[1]
    src = os.path.join(root, "src")
    graph = wing_graph(src)
    breaches = []
    if not graph:
        breaches.append("src/certify/ holds no source")
    loop = cycle(graph)
    if loop:
        breaches.append("include cycle: " + " -> ".join(loop))
    if graph.get("certify/vocabulary"):
        breaches.append("certify/vocabulary includes " + ", ".join(sorted(graph["certify/vocabulary"])))
    outside = [p for d in ("src", "tools", os.path.join("python", "src")) for p in sources(os.path.join(root, d))
               if not os.path.relpath(p, src).startswith("certify" + os.sep)]
    for path in outside:
        for inc in includes(path):
            if inc.startswith("certify/"):
                breaches.append(f"{os.path.relpath(path, root)} includes {inc} (use plateball/isoparallel_certificate.h)")
    for line in breaches:
        print(line)
    if breaches:
        return 1
    print(f"certify layout: {len(graph)} components, no include cycle, one public face")
    return 0


if __name__ == "__main__":
    sys.exit(main())
