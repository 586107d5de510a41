#!/usr/bin/env python3
"""Manifold (the manifold3d package, pinned in requirements.txt) as the
independent reference for Hedra's booleans (issue 35).

Reads a JSON list of cases on stdin, each
  {"a": {"positions": [[x, y, z], ...], "triangles": [[i, j, k], ...]},
   "b": {...}, "op": "union" | "difference" | "intersection"}
with both operands in one space, and prints a JSON list with, per case,
  {"status": "...", "volume": v, "genus": g, "shells": s, "triangles": t,
   "empty": bool}
computed by Manifold in double precision (Mesh64).
"""
import json
import sys

import manifold3d
import numpy as np


def solid(mesh):
    positions = np.asarray(mesh["positions"], dtype=np.float64).reshape(-1, 3)
    triangles = np.asarray(mesh["triangles"], dtype=np.uint64).reshape(-1, 3)
    return manifold3d.Manifold(manifold3d.Mesh64(positions, triangles))


def boolean(a, b, op):
    if op == "union":
        return a + b
    if op == "difference":
        return a - b
    if op == "intersection":
        return a ^ b
    raise ValueError(f"unknown operation {op!r}")


def main():
    results = []
    for case in json.load(sys.stdin):
        a, b = solid(case["a"]), solid(case["b"])
        status = f"{a.status()} {b.status()}"
        r = boolean(a, b, case["op"])
        results.append(
            {
                "status": f"{status} {r.status()}",
                "volume": r.volume(),
                "genus": r.genus(),
                "shells": len(r.decompose()),
                "triangles": r.num_tri(),
                "empty": r.is_empty(),
            }
        )
    json.dump(results, sys.stdout)


if __name__ == "__main__":
    main()
