#!/usr/bin/env python3
"""The shape of the house (issue 47): the largest source files, the include
arrows between host/ folders (a pair that includes each other is a cycle),
and the lines of each method's solver.
  python3 scripts/house_metrics.py [ROOT]   (default: this checkout)"""
import os
import re
import sys

root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
sources = []
for top in ("host", "kernels"):
    for d, _, files in os.walk(os.path.join(root, top)):
        sources += [os.path.join(d, f) for f in files if f.endswith((".hpp", ".cpp", ".cu", ".cuh", ".in"))]
lines = {os.path.relpath(p, root): sum(1 for _ in open(p, errors="replace")) for p in sources}
print("largest files:")
for p, n in sorted(lines.items(), key=lambda kv: -kv[1])[:8]:
    print("  %5d  %s" % (n, p))
arrows = {}
for p in sources:
    rel = os.path.relpath(p, root).split(os.sep)
    if rel[0] != "host" or len(rel) < 3:
        continue
    for m in re.finditer(r'#include "host/([a-z_]+)/', open(p, errors="replace").read()):
        if m.group(1) != rel[1]:
            arrows.setdefault((rel[1], m.group(1)), set()).add("/".join(rel))
print("include arrows between host/ folders (files):")
print("  " + ", ".join("%s->%s %d" % (a, b, len(f)) for (a, b), f in sorted(arrows.items())))
cycles = sorted({tuple(sorted(k)) for k in arrows if (k[1], k[0]) in arrows})
print("  folders that include each other: " + (", ".join("%s<->%s" % c for c in cycles) if cycles else "none"))
print("method solvers (lines):")
for m in ("common/particle_solver.hpp", "tlsph/tlsph_solver.hpp", "ulsph/ulsph_solver.hpp", "rkpm/rkpm_solver.hpp",
          "coupled/coupled_solver.hpp"):
    print("  %5d  host/solver/%s" % (lines.get("host/solver/" + m, 0), m))
print("scene readers (lines): " + ", ".join("%s %d" % (os.path.basename(p), n) for p, n in sorted(lines.items())
                                             if p.startswith("host/scene/") and p.endswith("_reader.cpp")))
