"""Bodies' poses through the add-on, headless (a black-box review, thirty-first session):
a body with a mirroring scale is shown where softsub simulates it after the import; Clear
puts a body back where it was placed, in its own rotation mode; Export starts a body from
that placement, not from imported keyframes, even when the start frame moves; a body in
rotation mode XZY with a delta rotation is exported at the pose the viewport shows; a
pair of two rigid bodies is refused at Export, as softsub refuses it.

blender -b --factory-startup --python-exit-code 1 --python poses.py -- \
    --softsub SOFTSUB --zip softsub_blender.zip --work DIR"""
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_test_util import args, check, close, empty_scene, finish, install_addon  # noqa: E402

A = args()
install_addon(A)
from softsub_blender import bl_scene, scenefile  # noqa: E402  (the installed copy)

work = A["work"]
empty_scene()
scene = bpy.context.scene
scene.frame_start = 1
scene.frame_end = 4
s = scene.softsub
s.scene_path = os.path.join(work, "poses.scene")
s.use_container = False
s.substeps = 8


def world_vertices(obj):
    return [tuple(obj.matrix_world @ v.co) for v in obj.data.vertices]


def same_points(a, b, tol):
    return len(a) == len(b) and all(close(p, q, tol) for p, q in zip(a, b))


# A static cone mirrored in X, a static cone in mode XZY with a delta rotation, and a
# dynamic cube that falls (so something moves).
bpy.ops.mesh.primitive_cone_add(radius1=1, depth=2, location=(0, 0, 3))
mirror = bpy.context.active_object
mirror.name = "mirror"
mirror.scale = (-1, 1, 1.5)
bpy.ops.softsub.make_body(dynamic=False)
bpy.ops.mesh.primitive_cone_add(radius1=1, depth=2, location=(-6, -4, 3))
mirror_xzy = bpy.context.active_object
mirror_xzy.name = "mirror_xzy"
mirror_xzy.rotation_mode = "XZY"
mirror_xzy.rotation_euler = (0.7, 0, 0)
mirror_xzy.scale = (1, -1, 1)
bpy.ops.softsub.make_body(dynamic=False)
bpy.ops.mesh.primitive_cone_add(radius1=1, depth=2, location=(4, 0, 5))
xzy = bpy.context.active_object
xzy.name = "xzy"
xzy.rotation_mode = "XZY"
xzy.rotation_euler = (0.2, 0.3, 0.4)
xzy.delta_rotation_euler = (0, 0, 0.5)
bpy.ops.softsub.make_body(dynamic=False)
bpy.ops.mesh.primitive_cube_add(size=1, location=(-4, 1, 6), rotation=(0.3, 0.2, 0.1))
cube = bpy.context.active_object
cube.name = "cube"
bpy.ops.softsub.make_body(dynamic=True)
bpy.context.view_layer.update()
before = {o.name: world_vertices(o) for o in (mirror, mirror_xzy, xzy, cube)}
cube_placed = (tuple(cube.location), cube.rotation_mode, tuple(cube.rotation_euler))

res = bpy.ops.softsub.run(wait=True)
check(res == {"FINISHED"}, f"run: {res}")
scene.frame_set(scene.frame_start)
# Static bodies are where they were placed, mirrored or turned by a delta rotation.
for o in (mirror, mirror_xzy, xzy):
    check(same_points(world_vertices(o), before[o.name], 1e-4), f"{o.name}: moved by the import")
check(cube.animation_data is not None and cube.animation_data.action is not None, "the cube has no keyframes")
scene.frame_set(scene.frame_end)
check(cube.location.z < cube_placed[0][2] - 0.05, f"the cube did not fall: z {cube.location.z}")

# Export with the imported keys on, from another start frame: the cube starts where it
# was placed, not at a keyframe.
scene.frame_start = 3
model, _ = bl_scene.collect(bpy.context)
scene.frame_start = 1
cube_model = next(o for o in model["objects"] if o["Name"] == "cube")
# Its scale is the panel's 1, not what decomposing its turned matrix leaves.
check(cube_model["UniformScale"] == 1.0, f"UniformScale {cube_model['UniformScale']!r}")
check(close(cube_model["InitialPosition"], (-4.0, 6.0, -1.0), 1e-5),
      f"exported from a keyframe: InitialPosition {cube_model['InitialPosition']}")

# Clear: the cube is back where it was placed, in its own rotation mode.
scene.frame_set(scene.frame_end)
res = bpy.ops.softsub.clear_results()
check(res == {"FINISHED"}, f"clear_results: {res}")
check(cube.animation_data is None or cube.animation_data.action is None, "keyframes left after Clear")
check(cube.rotation_mode == cube_placed[1], f"rotation mode {cube.rotation_mode} after Clear")
check(close(tuple(cube.location), cube_placed[0], 1e-6), f"location {tuple(cube.location)} after Clear")
check(close(tuple(cube.rotation_euler), cube_placed[2], 1e-6), f"rotation {tuple(cube.rotation_euler)} after Clear")
bpy.context.view_layer.update()
check(same_points(world_vertices(cube), before["cube"], 1e-5), "the cube is not where it was placed after Clear")
check("softsub_rest_pose" not in cube, "the remembered pose is left after Clear")

# A substance is exported as the viewport shows it, modifiers applied (its base vertices
# were: 8 points for an Array modifier's 24), also once Run has hidden it.
bpy.ops.mesh.primitive_cube_add(size=1, location=(0, 3, 8))
goo = bpy.context.active_object
goo.name = "goo"
goo.modifiers.new("arr", "ARRAY").count = 3
bpy.ops.softsub.make_substance()
model, _ = bl_scene.collect(bpy.context)
check(len(next(f for f in model["fluids"] if f["Name"] == "goo")["Particles"]) == 24, "goo: not its 24 points")
res = bpy.ops.softsub.run(wait=True)
check(res == {"FINISHED"}, f"run with goo: {res}")
check(goo.hide_get(), "Run did not hide the substance")
model, _ = bl_scene.collect(bpy.context)
check(len(next(f for f in model["fluids"] if f["Name"] == "goo")["Particles"]) == 24,
      "goo: not its 24 points once hidden")
bpy.ops.softsub.clear_results()

# Saved, the .blend keeps the results folder relative to itself, so a copy of the project
# plays its own results (with absolute paths it played the original's).
bpy.ops.wm.save_as_mainfile(filepath=os.path.join(work, "poses.blend"))
res = bpy.ops.softsub.run(wait=True)
check(res == {"FINISHED"}, f"run after saving: {res}")
points = bpy.data.objects.get("goo_sim")
check(points is not None and points.softsub_cache.sim_dir.startswith("//"),
      f"results folder not relative: {points.softsub_cache.sim_dir if points else None}")
if points is not None:
    check(os.path.samefile(bpy.path.abspath(points.softsub_cache.sim_dir), os.path.join(work, "posesSim")),
          "the relative results folder is not the run's")
bpy.ops.softsub.clear_results()

# A pair of two rigid bodies: softsub refuses it, and so does Export, naming both.
pair = s.pairs.add()
pair.a, pair.b = mirror, cube
try:
    bl_scene.collect(bpy.context)
    check(False, "a pair of two rigid bodies was exported")
except scenefile.SceneError as e:
    check("'mirror' and 'cube' are both rigid bodies" in str(e), f"the refusal does not name them: {e}")
s.pairs.remove(len(s.pairs) - 1)

finish()
