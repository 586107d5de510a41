"""Times trimesh's and Blender's exporters on the mesh Hedra exported
(issue 36, item 2: "compare with trimesh and Blender's exporters on the same
mesh"). Run by bench/export-table with the python of bench/peers-venv.

Usage: peer_exports.py MESH.obj FOLDER ROUNDS

MESH.obj is Hedra's `export --subdivide 1` of the grid (4M quads, 4M
vertices). Each peer reads it once, untimed (trimesh triangulates it into
8M triangles; Blender keeps the quads), then writes STL, OBJ and GLB in
ROUNDS rounds; only the writing is timed, from memory, so a peer's time
leaves out the load and the subdivision that Hedra's rows include. Writes
FOLDER/peers.json: {peer: {format: [seconds per round], format_bytes: size,
version: ...}} (Blender prints its own log on stdout).
"""

import json
import os
import sys
import time


def timed(write):
    start = time.perf_counter()
    write()
    return time.perf_counter() - start


def trimesh_rows(source, folder, rounds):
    import trimesh

    mesh = trimesh.load(source, process=False, force="mesh")
    rows = {}
    for ext in ["stl", "obj", "glb"]:
        path = os.path.join(folder, f"trimesh.{ext}")
        rows[ext] = [timed(lambda: mesh.export(path)) for _ in range(rounds)]
        rows[ext + "_bytes"] = os.path.getsize(path)
        os.remove(path)
    rows["triangles"] = len(mesh.faces)
    rows["version"] = trimesh.__version__
    return rows


def blender_rows(source, folder, rounds):
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.obj_import(filepath=source)
    mesh = bpy.context.selected_objects[0].data
    exports = {
        "stl": lambda path: bpy.ops.wm.stl_export(filepath=path, ascii_format=False),
        "obj": lambda path: bpy.ops.wm.obj_export(
            filepath=path, export_materials=False, export_uv=False, export_normals=False),
        "glb": lambda path: bpy.ops.export_scene.gltf(
            filepath=path, export_format="GLB", export_materials="NONE", export_texcoords=False),
    }
    rows = {}
    for ext, export in exports.items():
        path = os.path.join(folder, f"blender.{ext}")
        rows[ext] = [timed(lambda: export(path)) for _ in range(rounds)]
        rows[ext + "_bytes"] = os.path.getsize(path)
        os.remove(path)
    rows["faces"] = len(mesh.polygons)
    rows["version"] = bpy.app.version_string
    return rows


def main():
    source, folder, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
    peers = {"trimesh": trimesh_rows, "Blender": blender_rows}
    only = os.environ.get("HEDRA_PEERS")
    out = {}
    for name, rows in peers.items():
        if only and name not in only.split(","):
            continue
        out[name] = rows(source, folder, rounds)
    with open(os.path.join(folder, "peers.json"), "w") as f:
        json.dump(out, f)


if __name__ == "__main__":
    main()
