#!/usr/bin/env python3
"""MeshLab (the pymeshlab package, pinned in requirements.txt) as the
independent reference for Hedra's decimation (issue 35): its quadric edge
collapse is one of the peers, and its Hausdorff filter measures every
candidate, Hedra's and the peers', the same way.

Reads one JSON request on stdin and prints one JSON answer.

  {"op": "sample", "name": "bunny.obj"}
      One of pymeshlab's sample meshes (tests/sample_meshes), with duplicate
      vertices merged, unreferenced ones dropped and non-manifold vertices
      split (MeshLab's own repairs), so that it is a manifold input:
      {"positions": [[x, y, z], ...], "triangles": [[i, j, k], ...]}

  {"op": "compare", "input": "in.ply", "target_faces": n,
   "samples": s, "candidates": {"label": "result.ply", ...}}
      Adds MeshLab's own result ("MeshLab quadric": quadric edge collapse to
      n faces, MeshLab's defaults otherwise) and measures each candidate
      against the input:
      {"label": {"faces": f, "hausdorff": h, "mean": m, "genus": g,
                 "holes": b, "shells": c}, ...}
      h is the symmetric Hausdorff distance (the larger of both ways), m the
      mean of both ways' mean distances, both sampled (every vertex plus s
      points on the faces) and divided by the input's bounding-box
      diagonal; g, b and c are MeshLab's genus, border-loop count and
      connected-component count ("input" gives the input's). Each
      candidate is measured in a process of its own ("measure" below):
      MeshLab's sampler draws from one random generator per process, so
      measured in turn, a candidate's samples would depend on how many
      were drawn for the candidates before it, and a change of one result
      would move the figures of the others.

  {"op": "measure", "input": "in.ply", "candidate": "result.ply",
   "samples": s}
      One candidate's measures, as "compare" gives them.
"""
import json
import os
import subprocess
import sys
import tempfile

import pymeshlab


def sample(name):
    folder = os.path.join(os.path.dirname(pymeshlab.__file__), "tests", "sample_meshes")
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(os.path.join(folder, name))
    ms.meshing_merge_close_vertices(threshold=pymeshlab.PercentageValue(0.0))
    ms.meshing_remove_duplicate_faces()
    ms.meshing_remove_unreferenced_vertices()
    ms.meshing_repair_non_manifold_edges()
    ms.meshing_repair_non_manifold_vertices()
    m = ms.current_mesh()
    return {
        "positions": m.vertex_matrix().tolist(),
        "triangles": m.face_matrix().tolist(),
    }


def measures(ms, index, input_index, samples, diagonal):
    """Topology of mesh `index` and its two-way sampled distance to the input."""
    ms.set_current_mesh(index)
    topology = ms.get_topological_measures()
    faces = ms.current_mesh().face_number()
    big = pymeshlab.PureValue(10.0 * diagonal)
    ways = [
        ms.get_hausdorff_distance(
            sampledmesh=a, targetmesh=b, samplevert=True, sampleface=True,
            samplenum=samples, maxdist=big,
        )
        for a, b in ((index, input_index), (input_index, index))
    ]
    return {
        "faces": faces,
        "hausdorff": max(w["max"] for w in ways) / diagonal,
        "mean": sum(w["mean"] for w in ways) / 2.0 / diagonal,
        "genus": topology["genus"],
        "holes": topology["number_holes"],
        "shells": topology["connected_components_number"],
    }


def measure(request):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(request["input"])
    input_index = ms.current_mesh_id()
    diagonal = ms.current_mesh().bounding_box().diagonal()
    ms.load_new_mesh(request["candidate"])
    index = ms.current_mesh_id()
    return measures(ms, index, input_index, int(request["samples"]), diagonal)


def measure_alone(input_path, candidate, samples):
    """`measure` in a fresh process (see "compare" in the module's doc)."""
    request = {"op": "measure", "input": input_path, "candidate": candidate, "samples": samples}
    out = subprocess.run(
        [sys.executable, __file__],
        input=json.dumps(request),
        stdout=subprocess.PIPE,
        text=True,
        check=True,
    )
    return json.loads(out.stdout)


def compare(request):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(request["input"])
    input_index = ms.current_mesh_id()
    candidates = dict(request["candidates"])
    with tempfile.TemporaryDirectory() as folder:
        ms.generate_copy_of_current_mesh()
        ms.meshing_decimation_quadric_edge_collapse(targetfacenum=int(request["target_faces"]))
        candidates["MeshLab quadric"] = os.path.join(folder, "meshlab.ply")
        ms.save_current_mesh(candidates["MeshLab quadric"], binary=True)
        samples = int(request["samples"])
        answer = {
            label: measure_alone(request["input"], path, samples)
            for label, path in candidates.items()
        }
    ms.set_current_mesh(input_index)
    topology = ms.get_topological_measures()
    answer["input"] = {
        "faces": ms.current_mesh().face_number(),
        "genus": topology["genus"],
        "holes": topology["number_holes"],
        "shells": topology["connected_components_number"],
    }
    return answer


def main():
    request = json.load(sys.stdin)
    if request["op"] == "sample":
        answer = sample(request["name"])
    elif request["op"] == "compare":
        answer = compare(request)
    elif request["op"] == "measure":
        answer = measure(request)
    else:
        raise ValueError(f"unknown op {request['op']!r}")
    json.dump(answer, sys.stdout)


if __name__ == "__main__":
    main()
