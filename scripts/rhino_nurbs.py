#!/usr/bin/env python3
"""openNURBS (the rhino3dm package, pinned in requirements.txt) as the
independent reference for Hedra's NURBS curves and surfaces (issue 35).

Reads JSON on stdin:
  {"curves": [{"degree": p, "knots": [full vector, n + p + 1],
               "points": [[x, y, z], ...], "weights": [...],
               "params": [t, ...], "insert": u}],
   "surfaces": [{"degrees": [p, q], "knots_u": [...], "knots_v": [...],
                 "size": [nu, nv], "points": [... nu * nv, v fastest],
                 "weights": [...], "params": [[u, v], ...], "insert_u": u}]}
and prints, per curve, the points and first and second derivatives at the
parameters, the control polygon after inserting a knot, and the values of
the curve raised by one degree; per surface, the points and unit normals at
the parameters, the control net after inserting a knot in u, and the values
of the surface raised by one degree in u. openNURBS stores knots without the first and last of the
full vector and control points in homogeneous form (x·w, y·w, z·w, w).
"""
import json
import sys

import rhino3dm


def homogeneous(p, w):
    return rhino3dm.Point4d(p[0] * w, p[1] * w, p[2] * w, w)


def euclidean(q):
    return [q.X / q.W, q.Y / q.W, q.Z / q.W], q.W


def curve(c):
    n, p = len(c["points"]), c["degree"]
    nc = rhino3dm.NurbsCurve(3, True, p + 1, n)
    for i, (pt, w) in enumerate(zip(c["points"], c["weights"])):
        nc.Points[i] = homogeneous(pt, w)
    for i, k in enumerate(c["knots"][1:-1]):
        nc.Knots[i] = k
    assert nc.IsValid, "openNURBS finds the curve invalid"
    return nc


def curve_net(nc):
    pts = [euclidean(nc.Points[i]) for i in range(len(nc.Points))]
    return {
        "knots": [nc.Knots[i] for i in range(len(nc.Knots))],
        "points": [p for p, _ in pts],
        "weights": [w for _, w in pts],
    }


def xyz(v):
    return [v.X, v.Y, v.Z]


def curve_values(nc, params):
    out = {"points": [], "d1": [], "d2": []}
    for t in params:
        p, d1, d2 = nc.DerivativeAt(t, 2)
        out["points"].append(xyz(p))
        out["d1"].append(xyz(d1))
        out["d2"].append(xyz(d2))
    return out


def curve_result(c):
    out = curve_values(curve(c), c["params"])
    inserted = curve(c)
    assert inserted.Knots.InsertKnot(c["insert"], 1)
    out["inserted"] = curve_net(inserted)
    # openNURBS raises the degree through Bézier spans, so its knot vector
    # is not the smallest one: the elevated curve is compared by its values.
    elevated = curve(c)
    assert elevated.IncreaseDegree(c["degree"] + 1)
    assert elevated.Degree == c["degree"] + 1
    out["elevated"] = curve_values(elevated, c["params"])
    return out


def surface(s):
    (p, q), (nu, nv) = s["degrees"], s["size"]
    ns = rhino3dm.NurbsSurface.Create(3, True, p + 1, q + 1, nu, nv)
    for i in range(nu):
        for j in range(nv):
            k = i * nv + j
            ns.Points[(i, j)] = homogeneous(s["points"][k], s["weights"][k])
    for i, k in enumerate(s["knots_u"][1:-1]):
        ns.KnotsU[i] = k
    for i, k in enumerate(s["knots_v"][1:-1]):
        ns.KnotsV[i] = k
    assert ns.IsValid, "openNURBS finds the surface invalid"
    return ns


def surface_net(ns):
    nu, nv = ns.Points.CountU, ns.Points.CountV
    pts = [euclidean(ns.Points.GetControlPoint(i, j)) for i in range(nu) for j in range(nv)]
    return {
        "knots_u": [ns.KnotsU[i] for i in range(len(ns.KnotsU))],
        "size": [nu, nv],
        "points": [p for p, _ in pts],
        "weights": [w for _, w in pts],
    }


def surface_values(ns, params):
    out = {"points": [], "normals": []}
    for u, v in params:
        out["points"].append(xyz(ns.PointAt(u, v)))
        out["normals"].append(xyz(ns.NormalAt(u, v)))
    return out


def surface_result(s):
    out = surface_values(surface(s), s["params"])
    inserted = surface(s)
    assert inserted.KnotsU.InsertKnot(s["insert_u"], 1)
    out["inserted"] = surface_net(inserted)
    elevated = surface(s)
    assert elevated.IncreaseDegreeU(s["degrees"][0] + 1)
    out["elevated"] = surface_values(elevated, s["params"])
    return out


def main():
    data = json.load(sys.stdin)
    json.dump(
        {
            "curves": [curve_result(c) for c in data["curves"]],
            "surfaces": [surface_result(s) for s in data["surfaces"]],
        },
        sys.stdout,
    )


if __name__ == "__main__":
    main()
