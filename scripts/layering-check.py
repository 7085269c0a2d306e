#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""Keeps the C code's structure what daemon/src/README.md says it is.

Usage: layering-check.py [ROOT]     (ROOT: the checkout; default: this one)

1. daemon/src's folders are layers, bottom to top as LAYERS lists them.
   A file may include headers of its own folder and of folders below it,
   never above; an include of a daemon header names its folder
   ("store/record_pair.h"), so the include line itself shows the layer.
   main.c, in daemon/src itself, is above every folder. `chip/` and
   `store/` are beside each other: neither includes the other. An
   include with a ".." in it is refused (it would hide its layer).
2. No include circle between units anywhere in the C code we write
   (daemon, drivers, HAL, libraries). A unit is a .c file with its
   header of the same name; a header "X_internal.h" belongs to unit X
   (the unit's private interface); a header without a .c is a unit.

Exit status 0 when both hold; 1 with every violation listed (file, line,
what it includes, why it is refused); 2 on a usage error.
"""
import os
import re
import sys

LAYERS = ['common', 'chip', 'store', 'ftest', 'magn', 'commands', 'service']
DAEMON_SRC = 'daemon/src'
# Where units are looked for circles: the project's own C code
CIRCLE_ROOTS = ['daemon', 'drivers/iio/imu/as9888', 'hal', 'lib']
# "name" and <name>: an angle include can reach daemon/src too (-I)
INCLUDE = re.compile(r'^\s*#\s*include\s+["<]([^">]+)[">]', re.M)
# Layers beside each other: (includer, included) refused both ways
APART = {('store', 'chip'), ('chip', 'store')}


def c_files(root, top):
    for d, _, names in os.walk(os.path.join(root, top)):
        for n in sorted(names):
            if n.endswith(('.c', '.h')):
                yield os.path.relpath(os.path.join(d, n), root)


def includes(root, path):
    with open(os.path.join(root, path), encoding='utf-8') as f:
        text = f.read()
    for m in INCLUDE.finditer(text):
        yield text.count('\n', 0, m.start()) + 1, m.group(1)


def layer_of(path):
    """The folder's rank, len(LAYERS) for main.c, None outside the layers."""
    rel = os.path.relpath(path, DAEMON_SRC)
    parts = rel.split(os.sep)
    if len(parts) == 1:
        return len(LAYERS) if parts[0] == 'main.c' else None
    return LAYERS.index(parts[0]) if parts[0] in LAYERS else None


def check_layers(root):
    bad = []
    files = list(c_files(root, DAEMON_SRC))
    by_name = {}
    for f in files:
        by_name.setdefault(os.path.basename(f), []).append(f)
    for f in files:
        rank = layer_of(f)
        if rank is None:
            bad.append(f'{f}: in no layer (daemon/src/README.md lists them)')
            continue
        for line, inc in includes(root, f):
            if '..' in inc.split('/'):
                bad.append(f'{f}:{line}: "{inc}": no ".." in an include (name the folder)')
                continue
            folder = inc.split('/')[0] if '/' in inc else None
            if folder is None:
                if inc in by_name:
                    bad.append(f'{f}:{line}: "{inc}" is a daemon header: name its folder')
                continue
            if folder not in LAYERS:
                continue
            if not os.path.isfile(os.path.join(root, DAEMON_SRC, inc)):
                bad.append(f'{f}:{line}: "{inc}" is no file')
            elif LAYERS.index(folder) > rank:
                bad.append(f'{f}:{line}: "{inc}" is above this file\'s layer '
                           f'({folder} over {LAYERS[rank] if rank < len(LAYERS) else "main"})')
            elif rank < len(LAYERS) and (LAYERS[rank], folder) in APART:
                bad.append(f'{f}:{line}: "{inc}": {LAYERS[rank]}/ and {folder}/ '
                           'are beside each other, neither includes the other')
    return bad


def unit_of(path):
    stem = os.path.splitext(path)[0]
    if stem.endswith('_internal'):
        return stem[:-len('_internal')]
    return stem


def resolve(root, src, inc, headers):
    """The headers an include can name: beside the file, else every header
    whose path ends with it (without the build's include folders the one
    the compiler takes is not known: an arrow to each, so that no circle
    through either is missed)."""
    here = os.path.normpath(os.path.join(os.path.dirname(src), inc))
    if os.path.isfile(os.path.join(root, here)):
        return [here]
    return [h for h in headers if h == inc or h.endswith('/' + inc)]


def check_circles(root):
    files = [f for top in CIRCLE_ROOTS if os.path.isdir(os.path.join(root, top))
             for f in c_files(root, top)]
    headers = [f for f in files if f.endswith('.h')]
    edges = {}
    for f in files:
        u = unit_of(f)
        edges.setdefault(u, {})
        for line, inc in includes(root, f):
            for h in resolve(root, f, inc, headers):
                v = unit_of(h)
                if v != u:
                    edges[u].setdefault(v, f'{f}:{line}')
    # Tarjan's strongly connected components
    index, low, stack, on, comps = {}, {}, [], set(), []

    def visit(u):
        index[u] = low[u] = len(index)
        stack.append(u)
        on.add(u)
        for v in edges.get(u, {}):
            if v not in index:
                visit(v)
                low[u] = min(low[u], low[v])
            elif v in on:
                low[u] = min(low[u], index[v])
        if low[u] == index[u]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == u:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for u in sorted(edges):
        if u not in index:
            visit(u)
    bad = []
    for comp in comps:
        ties = [f'{edges[u][v]} -> {v}' for u in comp for v in edges[u] if v in comp]
        bad.append('include circle: ' + ' <-> '.join(comp) + ' (' + '; '.join(ties) + ')')
    return bad


def main():
    if len(sys.argv) > 2:
        print(__doc__.split('\n\n')[1], file=sys.stderr)
        return 2
    root = sys.argv[1] if len(sys.argv) == 2 else \
        os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if not os.path.isdir(os.path.join(root, DAEMON_SRC)):
        print(f'layering-check: {root} has no {DAEMON_SRC}', file=sys.stderr)
        return 2
    bad = check_layers(root) + check_circles(root)
    for b in bad:
        print(f'layering-check: {b}', file=sys.stderr)
    if bad:
        return 1
    print(f'layering-check: {DAEMON_SRC} keeps its layers ({" < ".join(LAYERS)} < main.c; '
          f'{" and ".join(sorted(APART)[0])} apart); '
          f'no include circle in {", ".join(CIRCLE_ROOTS)}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
