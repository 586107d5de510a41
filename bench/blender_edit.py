"""Blender's figures beside the frame bench's rows (issue 36, item 1):
the same edits timed in Blender as a Python module (bpy, from
bench/requirements-peers.txt; run with the python of bench/peers-venv).

Usage: blender_edit.py FOLDER ROUNDS

Blender in background mode draws nothing, so each row times the operator
or the dependency-graph update that a frame of the same drag runs, not a
whole frame:

- G on 10 % of the vertices of a 1000 x 1000 grid (1M faces), in edit mode:
  one `transform.translate` of the selection;
- an extrude of 1,000 faces of that grid: one `mesh.extrude_region_move`;
- one vertex of a 316 x 316 grid (99,856 faces) moved under a Subdivision
  Surface modifier at level 2 (on the CPU): the dependency graph updated
  and the subdivided mesh read, which makes Blender subdivide it;
- one of two UV spheres of 198,024 triangles moved under a Boolean
  modifier (union, Manifold solver): the evaluated mesh updated;
- opening the 1M-quad grid from an OBJ (`wm.obj_import`).

Prints a Markdown table: median and worst milliseconds over ROUNDS.
"""

import os
import statistics
import sys
import time

import bpy  # first: bpy makes Blender's other modules (bmesh) importable

import bmesh


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def grid(faces_per_side, name="Grid"):
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=faces_per_side, y_subdivisions=faces_per_side, size=2.0)
    obj = bpy.context.active_object
    obj.name = name
    return obj


def timed(action, rounds):
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        action()
        times.append((time.perf_counter() - start) * 1e3)
    return times


def g_on_a_tenth(rounds):
    reset()
    obj = grid(1000)
    faces = len(obj.data.polygons)
    bpy.ops.object.mode_set(mode="EDIT")
    bm = bmesh.from_edit_mesh(obj.data)
    for v in bm.verts:
        v.select_set(v.index % 10 == 0)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data)
    return faces, timed(lambda: bpy.ops.transform.translate(value=(0.001, 0.0, 0.0)), rounds)


def extrude_a_thousand(rounds):
    reset()
    obj = grid(1000)
    faces = len(obj.data.polygons)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_mode(type="FACE")
    times = []
    for _ in range(rounds):
        bpy.ops.mesh.select_all(action="DESELECT")
        bm = bmesh.from_edit_mesh(obj.data)
        bm.faces.ensure_lookup_table()
        for f in bm.faces[:1000]:
            f.select_set(True)
        bmesh.update_edit_mesh(obj.data)
        start = time.perf_counter()
        bpy.ops.mesh.extrude_region_move(TRANSFORM_OT_translate={"value": (0.0, 0.0, 0.1)})
        times.append((time.perf_counter() - start) * 1e3)
    return faces, times


def subdivision_drag(rounds):
    reset()
    # Blender defers the last Subdivision Surface modifier to the GPU when it
    # can; with no viewport nothing would be subdivided. On the CPU, as
    # Hedra's preview is.
    bpy.context.preferences.system.use_gpu_subdivision = False
    obj = grid(316)
    faces = len(obj.data.polygons)
    modifier = obj.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = 2
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    vertex = obj.data.vertices[len(obj.data.vertices) // 2]

    def move():
        vertex.co.z += 0.001
        obj.data.update()
        depsgraph.update()
        # The modifier's result is made when it is read (as drawing reads
        # it): the update alone leaves it to be subdivided later.
        return len(obj.evaluated_get(depsgraph).data.vertices)

    return faces, timed(move, rounds)


def boolean_drag(rounds):
    reset()
    spheres = []
    for offset in [(0.0, 0.0, 0.0), (0.3, 0.2, 0.1)]:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=446, ring_count=223, radius=1.0, location=offset)
        spheres.append(bpy.context.active_object)
    a, b = spheres
    modifier = a.modifiers.new("Boolean", "BOOLEAN")
    modifier.operation = "UNION"
    modifier.object = b
    if "MANIFOLD" in {item.identifier for item in modifier.bl_rna.properties["solver"].enum_items}:
        modifier.solver = "MANIFOLD"
    b.hide_set(True)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    triangles = sum(len(p.vertices) - 2 for s in spheres for p in s.data.polygons)

    def move():
        b.location.x += 0.001
        depsgraph.update()

    return triangles, timed(move, rounds), modifier.solver


def open_obj(folder, rounds):
    reset()
    obj = grid(1000)
    path = os.path.join(folder, "blender-grid.obj")
    bpy.ops.wm.obj_export(filepath=path, export_materials=False, export_uv=False, export_normals=False)
    faces = len(obj.data.polygons)

    def load():
        reset()
        bpy.ops.wm.obj_import(filepath=path)

    times = timed(load, rounds)
    os.remove(path)
    return faces, times


def main():
    folder, rounds = sys.argv[1], int(sys.argv[2])
    rows = []
    faces, t = g_on_a_tenth(rounds)
    rows.append((f"G on 10 % of the vertices of a {faces:,}-face grid (`transform.translate`)", t))
    faces, t = extrude_a_thousand(rounds)
    rows.append((f"extrude of 1,000 faces of a {faces:,}-face grid (`mesh.extrude_region_move`)", t))
    faces, t = subdivision_drag(rounds)
    rows.append((f"one vertex of a {faces:,}-face grid moved, Subdivision Surface level 2 on the CPU (depsgraph update, result read)", t))
    triangles, t, solver = boolean_drag(rounds)
    rows.append((f"operand of a Boolean union moved, 2 × {triangles // 2:,} triangles, {solver} solver "
                 f"(depsgraph update)", t))
    faces, t = open_obj(folder, max(1, rounds // 5))
    rows.append((f"open a {faces:,}-quad grid from OBJ (`wm.obj_import`)", t))
    print(f"Blender {bpy.app.version_string} (bpy), background mode, {rounds} rounds; milliseconds.\n")
    print("| row | median ms | worst ms |")
    print("|---|---:|---:|")
    for name, t in rows:
        print(f"| {name} | {statistics.median(t):.1f} | {max(t):.1f} |")


if __name__ == "__main__":
    main()
