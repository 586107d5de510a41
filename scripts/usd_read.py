#!/usr/bin/env python3
"""Reads a USD file with Pixar's usd-core (pxr) and prints JSON.

Usage: scripts/usd_read.py FILE

Output: {"errors": [...], "failed_checks": [...], "warnings": [...],
"prims": [...]}: the errors, failed validators and warnings of usdchecker's
validators (UsdValidation, every registered one), then every prim with its path, type, local transform (row-major
4x4, USD's row-vector convention) and the attributes the Hedra USD tests
compare: Mesh topology, points, subdivision options, creases, corners,
holes, primvars:st; NurbsPatch and NurbsCurves orders, knots, ranges,
counts, points and weights. Exits 2 when the stage cannot be opened.
"""

import json
import sys

from pxr import Usd, UsdGeom, UsdValidation


def plain(value):
    """A pxr value as JSON-able lists of numbers and strings."""
    if value is None:
        return None
    if isinstance(value, (bool, int, float, str)):
        return value
    try:
        return [plain(v) for v in value]
    except TypeError:
        return str(value)


def attr(prim, name):
    a = prim.GetAttribute(name)
    if not a or not a.HasAuthoredValue():
        return None
    return plain(a.Get())


MESH = [
    "points", "faceVertexCounts", "faceVertexIndices", "subdivisionScheme",
    "interpolateBoundary", "triangleSubdivisionRule", "creaseIndices",
    "creaseLengths", "creaseSharpnesses", "cornerIndices", "cornerSharpnesses",
    "holeIndices", "normals", "orientation",
]
PATCH = [
    "uVertexCount", "vVertexCount", "uOrder", "vOrder", "uKnots", "vKnots",
    "uRange", "vRange", "points", "pointWeights",
]
CURVES = ["curveVertexCounts", "order", "knots", "ranges", "points", "pointWeights"]


def describe(prim):
    out = {"path": str(prim.GetPath()), "type": str(prim.GetTypeName())}
    name = prim.GetAttribute("hedra:name")
    if name and name.HasAuthoredValue():
        out["hedra_name"] = name.Get()
    xf = UsdGeom.Xformable(prim)
    if xf:
        m = xf.GetLocalTransformation(Usd.TimeCode.Default())
        out["local"] = [m[i][j] for i in range(4) for j in range(4)]
    names = {"Mesh": MESH, "NurbsPatch": PATCH, "NurbsCurves": CURVES}.get(out["type"], [])
    for name in names:
        out[name] = attr(prim, name)
    if out["type"] == "Mesh":
        # Defaults as pxr resolves them (the schema's fallbacks).
        mesh = UsdGeom.Mesh(prim)
        out["subdivisionSchemeResolved"] = mesh.GetSubdivisionSchemeAttr().Get()
        out["interpolateBoundaryResolved"] = mesh.GetInterpolateBoundaryAttr().Get()
        normals = prim.GetAttribute("normals")
        if normals and normals.HasAuthoredValue():
            out["normalsInterpolation"] = UsdGeom.Primvar(normals).GetInterpolation() \
                if False else normals.GetMetadata("interpolation")
        st = UsdGeom.PrimvarsAPI(prim).GetPrimvar("st")
        if st and st.HasAuthoredValue():
            out["st"] = {
                "values": plain(st.Get()),
                "indices": plain(st.GetIndices()) if st.IsIndexed() else None,
                "interpolation": st.GetInterpolation(),
            }
    return out


def main():
    path = sys.argv[1]
    stage = Usd.Stage.Open(path)
    if stage is None:
        print(json.dumps({"errors": ["cannot open " + path]}))
        sys.exit(2)
    # usdchecker's checks: since USD 25 it runs the UsdValidation
    # framework's validators (UsdUtils.ComplianceChecker is gone).
    registry = UsdValidation.ValidationRegistry()
    validators = registry.GetOrLoadAllValidators()
    found = UsdValidation.ValidationContext(validators).Validate(stage)
    kind = UsdValidation.ValidationErrorType
    def text(e):
        return "%s: %s" % (e.GetIdentifier(), e.GetMessage())
    result = {
        "errors": [text(e) for e in found if e.GetType() == kind.Error],
        "failed_checks": sorted({e.GetIdentifier() for e in found if e.GetType() == kind.Error}),
        "warnings": [text(e) for e in found if e.GetType() == kind.Warn],
        "default_prim": str(stage.GetDefaultPrim().GetPath()) if stage.GetDefaultPrim() else None,
        "prims": [describe(p) for p in stage.Traverse()],
    }
    print(json.dumps(result))


if __name__ == "__main__":
    main()
