"""Check that exported .glb files import and animate correctly in Blender.

Install (Blender as a Python module; bpy 5.0.1 is the newest wheel for CPython 3.11):
    /root/.pyenv/versions/3.11.7/bin/python -m venv /tmp/bpyenv
    /tmp/bpyenv/bin/pip install bpy==5.0.1
Run:
    /tmp/bpyenv/bin/python xtask/viewers/blender_check.py FILE.glb... [--render DIR] [--ground-tol M]
(or `blender -b -P xtask/viewers/blender_check.py -- FILE.glb...` with a Blender binary).

For each file: empty scene, glTF import, then checks one armature, one skinned
mesh driven by it, one non-skinned terrain mesh, at least one action with finite
keys, and at the first/middle/last frame of the active (first) action: finite
skinned vertices, a bounding box that moves (root motion) and the creature's
closest vertex within --ground-tol of the terrain (downward ray casts).
Exits 1 if any check fails on any file.
"""
import argparse
import math
import os
import sys

import bpy  # must come first: it puts Blender's own modules (addon_utils, mathutils) on sys.path
import addon_utils
from mathutils import Vector
from mathutils.bvhtree import BVHTree


class CheckError(Exception):
    pass


def check(cond, msg):
    if not cond:
        raise CheckError(msg)


def skinned_world_verts(ob):
    """World-space vertex positions of `ob` after modifiers (armature skinning)."""
    dg = bpy.context.evaluated_depsgraph_get()
    ob_eval = ob.evaluated_get(dg)
    me = ob_eval.to_mesh()
    mw = ob_eval.matrix_world.copy()
    verts = [mw @ v.co for v in me.vertices]
    ob_eval.to_mesh_clear()
    return verts


def action_fcurves(act):
    """All F-curves of an action: layered/slotted actions (Blender 4.4+) or legacy ones."""
    if getattr(act, "layers", None):
        return [fc for ly in act.layers for st in ly.strips for cb in st.channelbags for fc in cb.fcurves]
    return list(getattr(act, "fcurves", []))


def height_above(bvh, terrain, p):
    """Height of world point p above the terrain surface under it (None if no terrain below/above)."""
    inv = terrain.matrix_world.inverted()
    # Cast from just above the terrain's top (not 1e4: the BVH is float32) so points below the surface count too.
    top = max(p.z, max((terrain.matrix_world @ Vector(c)).z for c in terrain.bound_box)) + 1.0
    origin = inv @ Vector((p.x, p.y, top))
    direction = (inv.to_3x3() @ Vector((0, 0, -1))).normalized()
    hit, _normal, _index, _dist = bvh.ray_cast(origin, direction)
    return None if hit is None else p.z - (terrain.matrix_world @ hit).z


def check_file(path, args):
    # 1. Empty scene (factory settings also drop any previous import), then import.
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon_utils.enable("io_scene_gltf2", default_set=True)
    try:
        res = bpy.ops.import_scene.gltf(filepath=path)
    except RuntimeError as e:
        raise CheckError(f"import failed: {e}")
    check(res == {"FINISHED"}, f"import returned {res}")
    scene = bpy.context.scene

    # 2. Objects. Only those in the view layer count: the importer puts glTF nodes that are in no
    # scene into an excluded 'Orphan Nodes' collection, and its bone-shape Icosphere in a hidden one.
    objects = [o for o in bpy.context.view_layer.objects if not all(c.hide_render for c in o.users_collection)]
    ignored = [o.name for o in bpy.data.objects if o.name not in bpy.context.view_layer.objects]
    if ignored:
        print(f"  ignored (not in the glTF scene): {ignored}")
    print("  objects:")
    for ob in objects:
        extra = ""
        if ob.type == "MESH":
            mods = [f"{m.type}->{getattr(m, 'object', None) and m.object.name}" for m in ob.modifiers]
            extra = f" verts={len(ob.data.vertices)} faces={len(ob.data.polygons)} modifiers={mods}"
        print(f"    {ob.name!r} type={ob.type} parent={ob.parent and ob.parent.name!r}{extra}")

    arms = [o for o in objects if o.type == "ARMATURE"]
    check(len(arms) == 1, f"expected exactly 1 armature, found {len(arms)}")
    arm = arms[0]
    check(len(arm.data.bones) > 0, "armature has no bones")
    print(f"  armature {arm.name!r}: {len(arm.data.bones)} bones")

    def skinned_by_arm(o):
        return any(m.type == "ARMATURE" and m.object == arm for m in o.modifiers)

    meshes = [o for o in objects if o.type == "MESH"]
    skinned = [o for o in meshes if skinned_by_arm(o)]
    plain = [o for o in meshes if not any(m.type == "ARMATURE" for m in o.modifiers)]
    check(len(skinned) >= 1, "no mesh has an Armature modifier targeting the armature")
    check(len(plain) >= 1, "no non-skinned mesh (terrain) found")
    skin, terrain = skinned[0], max(plain, key=lambda o: len(o.data.vertices))
    print(f"  skinned mesh {skin.name!r}: {len(skin.data.vertices)} verts, parent={skin.parent and skin.parent.name!r}")
    print(f"  terrain mesh {terrain.name!r}: {len(terrain.data.vertices)} verts")

    # 3. Actions.
    check(len(bpy.data.actions) > 0, "no action imported")
    for act in bpy.data.actions:
        for fc in action_fcurves(act):
            bad = [k.co[0] for k in fc.keyframe_points if not all(map(math.isfinite, k.co))]
            if bad:
                raise CheckError(f"action {act.name!r}: non-finite key on {fc.data_path}[{fc.array_index}] at frame {bad[0]:g}")
        fps = scene.render.fps / scene.render.fps_base
        print(f"  action {act.name!r}: frames {act.frame_range[0]:g}..{act.frame_range[1]:g}"
              f" ({(act.frame_range[1] - act.frame_range[0]) / fps:.3f} s at {fps:g} fps)")

    dg = bpy.context.evaluated_depsgraph_get()
    bvh = BVHTree.FromObject(terrain.evaluated_get(dg), dg)
    check(arm.animation_data is not None and arm.animation_data.action is not None,
          "armature has no active action after import")
    act = arm.animation_data.action  # the importer makes the first animation active
    f0, f1 = math.ceil(act.frame_range[0]), math.floor(act.frame_range[1])
    frames = [f0, (f0 + f1) // 2, f1]

    # Size of the creature at rest, used for relative tolerances.
    scene.frame_set(f0)
    rest = skinned_world_verts(skin)
    size = max(max(v[i] for v in rest) - min(v[i] for v in rest) for i in range(3))
    tol = args.ground_tol if args.ground_tol is not None else 0.1 * size
    print(f"  evaluating action {act.name!r} on {skin.name!r} (creature size {size:.3f}, ground tol {tol:.3f})")

    centers, terrain_mw = [], terrain.matrix_world.copy()
    for f in frames:
        scene.frame_set(f)
        verts = skinned_world_verts(skin)
        check(all(math.isfinite(c) for v in verts for c in v), f"non-finite skinned vertex at frame {f}")
        lo = Vector([min(v[i] for v in verts) for i in range(3)])
        hi = Vector([max(v[i] for v in verts) for i in range(3)])
        centers.append((lo + hi) / 2)
        low = min(verts, key=lambda v: v.z)
        h_low = height_above(bvh, terrain, low)
        # Closest approach to the ground over all vertices (the foot that is planted).
        hs = [h for h in (height_above(bvh, terrain, v) for v in verts) if h is not None]
        check(h_low is not None and hs, f"frame {f}: no terrain under the creature at ({low.x:.2f}, {low.y:.2f})")
        clearance = min(hs)
        print(f"    frame {f:4d}: bbox min=({lo.x:.3f},{lo.y:.3f},{lo.z:.3f}) max=({hi.x:.3f},{hi.y:.3f},{hi.z:.3f})"
              f"  lowest vertex z={low.z:.3f} height above terrain={h_low:+.4f}  min clearance={clearance:+.4f}")
        check(terrain.matrix_world == terrain_mw, f"frame {f}: terrain moved with the animation")
        check(abs(clearance) <= tol, f"frame {f}: creature not on the terrain (min clearance {clearance:+.4f}, tol {tol:.3f})")
    moved = (centers[-1] - centers[0]).length
    moved_mid = (centers[1] - centers[0]).length
    print(f"  bbox centre moved {moved_mid:.3f} (first->middle), {moved:.3f} (first->last)")
    check(max(moved, moved_mid) > 0.01 * size, "skinned bounding box does not move (no root motion?)")

    if args.render:
        for frame in (frames[1], frames[-1]):
            render(path, args.render, skin, frame, centers[0], centers[-1], size)


def render(path, out_dir, skin, frame, c_first, c_last, size):
    """Small Cycles CPU render at `frame`, camera looking at the creature from the side of its path."""
    scene = bpy.context.scene
    scene.frame_set(frame)
    verts = skinned_world_verts(skin)
    centre = sum(verts, Vector()) / len(verts)
    fwd = (c_last - c_first)
    fwd.z = 0
    fwd = fwd.normalized() if fwd.length > 1e-6 else Vector((0, 1, 0))
    side = fwd.cross(Vector((0, 0, 1)))
    cam_data = bpy.data.cameras.new("check_cam")
    cam_data.lens = 35
    cam = bpy.data.objects.new("check_cam", cam_data)
    cam.location = centre + size * (2.2 * side + 1.2 * fwd + 1.0 * Vector((0, 0, 1)))
    cam.rotation_euler = (centre - cam.location).to_track_quat("-Z", "Y").to_euler()
    sun = bpy.data.objects.new("check_sun", bpy.data.lights.new("check_sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(40), math.radians(20), math.radians(30))
    for ob in (cam, sun):
        scene.collection.objects.link(ob)
    scene.camera = cam
    if scene.world is None:
        scene.world = bpy.data.worlds.new("check_world")
    scene.world.color = (0.6, 0.65, 0.7)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.render.resolution_x, scene.render.resolution_y = 480, 320
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    os.makedirs(out_dir, exist_ok=True)
    scene.render.filepath = os.path.join(os.path.abspath(out_dir),
                                         os.path.splitext(os.path.basename(path))[0] + f"_blender_f{frame}.png")
    try:
        bpy.ops.render.render(write_still=True)
    except RuntimeError as e:
        raise CheckError(f"render failed: {e}")
    print(f"  rendered {scene.render.filepath}")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+", help=".glb files to check")
    ap.add_argument("--render", metavar="DIR", help="also render two PNGs per file (middle and last frame) into DIR")
    ap.add_argument("--ground-tol", type=float, default=None,
                    help="max |distance| of the closest vertex to the terrain (default 10%% of creature size; "
                         "use inf for fliers and swimmers)")
    args = ap.parse_args(argv)
    print(f"Blender {bpy.app.version_string}")
    failed = []
    for path in args.files:
        print(f"== {path}")
        try:
            check_file(os.path.abspath(path), args)
            print("  OK")
        except CheckError as e:
            print(f"  FAIL: {e}")
            failed.append(path)
    if failed:
        print(f"FAILED: {len(failed)} of {len(args.files)} file(s): {', '.join(failed)}")
        sys.exit(1)
    print(f"all {len(args.files)} file(s) OK")


if __name__ == "__main__":
    main()
