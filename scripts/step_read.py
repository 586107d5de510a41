#!/usr/bin/env python3
"""Reads a STEP file with OpenCASCADE (cadquery-ocp, module OCP) and prints
what it understood, as JSON, for plugins/doc/tests/step.rs:

  python3 scripts/step_read.py FILE.step [F0,F1,...]

- "status": the reader's status for the file and for the transfer;
- "valid": BRepCheck_Analyzer's verdict on the whole shape;
- "length_unit": the file's length unit as OpenCASCADE names it, and
  "metres_per_unit" (shapes are converted to metres: every number below
  is in metres);
- "faces": per face its underlying B-spline surface (degrees, knots with
  multiplicities expanded, poles, weights, rational) and "points": the
  surface evaluated at u = u0 + i/N (u1 - u0), v = v0 + j/N (v1 - v0),
  i, j = 0..N (row by row in u), plus "valid" for the face alone;
- "curves": the same for every edge outside a face (curve sets), at
  t = t0 + i/N (t1 - t0) over the edge's range;
- "solids": volume (GProp) and validity of each solid; "shells" and
  "closed_shells": counts;
- "edges": distinct edges bounding faces, and "free_edges": those that
  bound only one face (none on a closed solid; a seam counts as one edge
  used twice by its face).
"""
import json
import sys

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.GeomAbs import GeomAbs_BSplineCurve, GeomAbs_BSplineSurface
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.OCP.collections import Sequence_TCollection_AsciiString
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.OCP.collections import (
    IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as EdgeFaces,
)
from OCP.TopoDS import TopoDS


def xyz(p):
    return [p.X(), p.Y(), p.Z()]


def expanded(knots, mults):
    out = []
    for i in range(1, knots.Length() + 1):
        out += [knots.Value(i)] * mults.Value(i)
    return out


def surface_data(face, fs):
    a = BRepAdaptor_Surface(face, False)
    entry = {"valid": BRepCheck_Analyzer(face).IsValid(), "type": int(a.GetType())}
    if a.GetType() != GeomAbs_BSplineSurface:
        return entry
    s = a.BSpline()
    u0, u1, v0, v1 = s.Bounds()
    nu, nv = s.NbUPoles(), s.NbVPoles()
    entry.update(
        degrees=[s.UDegree(), s.VDegree()],
        knots_u=expanded(s.UKnots(), s.UMultiplicities()),
        knots_v=expanded(s.VKnots(), s.VMultiplicities()),
        size=[nu, nv],
        poles=[xyz(s.Pole(i, j)) for i in range(1, nu + 1) for j in range(1, nv + 1)],
        weights=[s.Weight(i, j) for i in range(1, nu + 1) for j in range(1, nv + 1)],
        rational=s.IsURational() or s.IsVRational(),
        # OpenCASCADE turns a closed direction periodic (fewer poles, other
        # knots, the same points).
        periodic=[s.IsUPeriodic(), s.IsVPeriodic()],
        domain=[u0, u1, v0, v1],
        points=[
            xyz(s.Value(u0 + fu * (u1 - u0), v0 + fv * (v1 - v0)))
            for fu in fs
            for fv in fs
        ],
    )
    return entry


def curve_data(edge, fs):
    a = BRepAdaptor_Curve(edge)
    entry = {"type": int(a.GetType())}
    t0, t1 = a.FirstParameter(), a.LastParameter()
    entry["points"] = [xyz(a.Value(t0 + f * (t1 - t0))) for f in fs]
    entry["range"] = [t0, t1]
    if a.GetType() == GeomAbs_BSplineCurve:
        c = a.BSpline()
        entry.update(
            degree=c.Degree(),
            knots=expanded(c.Knots(), c.Multiplicities()),
            poles=[xyz(c.Pole(i)) for i in range(1, c.NbPoles() + 1)],
            weights=[c.Weight(i) for i in range(1, c.NbPoles() + 1)],
            rational=c.IsRational(),
            periodic=c.IsPeriodic(),
        )
    return entry


def main():
    path = sys.argv[1]
    n = [float(f) for f in sys.argv[2].split(",")] if len(sys.argv) > 2 else [0, 0.25, 0.5, 0.75, 1]
    reader = STEPControl_Reader()
    status = reader.ReadFile(path)
    # Shapes in metres, whatever the file's unit (OpenCASCADE converts;
    # the unit is given in millimetres, and after ReadFile, which resets it).
    reader.SetSystemLengthUnit(1000.0)
    out = {"status": int(status), "read": status == IFSelect_RetDone}
    if status != IFSelect_RetDone:
        print(json.dumps(out))
        return
    lengths, angles, solid_angles = (
        Sequence_TCollection_AsciiString(),
        Sequence_TCollection_AsciiString(),
        Sequence_TCollection_AsciiString(),
    )
    reader.FileUnits(lengths, angles, solid_angles)
    out["length_unit"] = [lengths.Value(i).ToCString() for i in range(1, lengths.Length() + 1)]
    out["roots"] = reader.TransferRoots()
    shape = reader.OneShape()
    out["valid"] = BRepCheck_Analyzer(shape).IsValid()
    faces = []
    e = TopExp_Explorer(shape, TopAbs_FACE)
    while e.More():
        faces.append(surface_data(TopoDS.Face(e.Current()), n))
        e.Next()
    out["faces"] = faces
    curves = []
    e = TopExp_Explorer(shape, TopAbs_EDGE, TopAbs_FACE)
    while e.More():
        curves.append(curve_data(TopoDS.Edge(e.Current()), n))
        e.Next()
    out["curves"] = curves
    solids = []
    e = TopExp_Explorer(shape, TopAbs_SOLID)
    while e.More():
        solid = e.Current()
        props = GProp_GProps()
        # Adaptive integration to a relative error of 1e-10 (the default
        # Gauss rule is off by 4e-4 on a rational sphere).
        BRepGProp.VolumeProperties_s(solid, props, 1e-10)
        solids.append({"volume": props.Mass(), "valid": BRepCheck_Analyzer(solid).IsValid()})
        e.Next()
    out["solids"] = solids
    shells, closed = 0, 0
    e = TopExp_Explorer(shape, TopAbs_SHELL)
    while e.More():
        shells += 1
        closed += 1 if BRep_Tool.IsClosed_s(e.Current()) else 0
        e.Next()
    out["shells"] = shells
    out["closed_shells"] = closed
    edge_faces = EdgeFaces()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces)
    out["edges"] = edge_faces.Extent()
    out["free_edges"] = sum(
        1
        for i in range(1, edge_faces.Extent() + 1)
        if edge_faces.FindFromIndex(i).Extent() == 1
        and not BRep_Tool.IsClosed_s(
            TopoDS.Edge(edge_faces.FindKey(i)), TopoDS.Face(edge_faces.FindFromIndex(i).First())
        )
    )
    print(json.dumps(out))


if __name__ == "__main__":
    main()
