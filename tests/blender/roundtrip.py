"""The artist's round trip, headless: build a scene in Blender (a cube as a dynamic body
over a static plane, a sphere filled with goo through `softsub fill`), export, run
softsub through the add-on's Run operator, import, and check every number against the
files softsub wrote; then save the .blend, reopen it and check again.

blender -b --factory-startup --python-exit-code 1 --python roundtrip.py -- \
    --softsub SOFTSUB --zip softsub_blender.zip --work DIR"""
import math
import os
import subprocess
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_test_util import args, check, close, empty_scene, finish, install_addon  # noqa: E402

A = args()
install_addon(A)
from softsub_blender import axes, caches, scenefile  # noqa: E402  (the installed copy)

t0 = time.time()
work = A["work"]
empty_scene()
scene = bpy.context.scene
scene.frame_start = 1
s = scene.softsub
s.scene_path = os.path.join(work, "rt.scene")
s.use_scene_range = False
s.frames = 12
s.substeps = 8
s.width = s.depth = s.height = 12.0

# a static plane, a dynamic cube above it, a sphere to fill with goo
bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, 0.5))
plane = bpy.context.active_object
plane.name = "Plane"
bpy.ops.softsub.make_body(dynamic=False)
bpy.ops.mesh.primitive_cube_add(size=2, location=(-1.5, 0.5, 3.0), rotation=(0.3, 0.2, 0.1))
cube = bpy.context.active_object
cube.name = "Cube"
bpy.ops.softsub.make_body(dynamic=True)
cube.softsub_body.mass = 2.0
cube.softsub_body.initial_linear_velocity = (1.0, 0.0, 0.0)
check(cube.softsub_body.enabled and cube.softsub_body.is_dynamic, "the cube is not a dynamic body")
check(plane.softsub_body.enabled and not plane.softsub_body.is_dynamic, "the plane is not a static body")
bpy.ops.mesh.primitive_uv_sphere_add(radius=1.5, location=(2.5, 0, 3.0))
sphere = bpy.context.active_object
sphere.name = "Ball"
res = bpy.ops.softsub.fill_mesh(spacing=0.5, name="goo")
check(res == {"FINISHED"}, f"fill_mesh: {res}")
goo = bpy.data.objects["goo"]
check(goo.softsub_fluid.enabled, "goo is not a substance")
n_goo = len(goo.data.vertices)
# a sphere of radius 1.5 holds about 4/3 pi 1.5^3 / 0.5^3 = 113 lattice points
check(80 < n_goo < 150, f"the filled sphere has {n_goo} particles")
goo.softsub_fluid.viscosity = 6.0
goo.softsub_fluid.colour = (0.2, 0.8, 0.3)

res = bpy.ops.softsub.run(wait=True)
check(res == {"FINISHED"}, f"run: {res}")
scene_file = os.path.join(work, "rt.scene")
sim_dir = os.path.join(work, "rtSim")

# the exported scene is valid for softsub itself and says what the panel said
p = subprocess.run([A["softsub"], "info", scene_file], capture_output=True, text=True)
check(p.returncode == 0, f"softsub info rt.scene: exit {p.returncode}: {p.stderr}")
p = subprocess.run([A["softsub"], "run", scene_file, "--frames", "0", "--formats", "none"],
                   capture_output=True, text=True)
check(p.returncode == 0, f"softsub run --frames 0: exit {p.returncode}: {p.stderr}")
model = scenefile.read_scene_file(scene_file)
# in the order they were marked: softsub numbers bodies (and default names) by it
check([o["Name"] for o in model["objects"]] == ["Plane", "Cube"], f"objects {[o['Name'] for o in model['objects']]}")
cube_d = model["objects"][1]
check(cube_d["IsDynamic"] and not model["objects"][0]["IsDynamic"], "IsDynamic not written")
check(cube_d["Mass"] == 2.0 and cube_d["Geometry"] == "rtGeo/Cube.obj", f"cube: {cube_d}")
check(close(cube_d["InitialPosition"], (-1.5, 3.0, -0.5), 1e-6), f"cube position {cube_d['InitialPosition']}")
check(close(cube_d["InitialLinearVelocity"], (1.0, 0.0, 0.0), 0), "cube velocity")
# Blender's rotation (0.3, 0.2, 0.1) rad XYZ, mapped to Y up, as softsub builds it back
R_b = axes.euler_xyz_to_matrix(tuple(math.degrees(x) for x in (0.3, 0.2, 0.1)))
q_s = axes.quat_to_softsub(axes.matrix_to_quat(R_b))
R_s = axes.euler_xyz_to_matrix(cube_d["InitialRotation"])
check(all(close(a, b, 1e-6) for a, b in zip(axes.quat_to_matrix(q_s), R_s)), "cube rotation not mapped to Y up")
verts, tris = caches.read_obj(os.path.join(work, "rtGeo", "Cube.obj"))
check(len(verts) == 8 and len(tris) == 12, f"Cube.obj: {len(verts)} vertices, {len(tris)} triangles")
check(model["Simulation"]["Frames"] == 12 and model["Simulation"]["Gravity"] == (0.0, -9.81, 0.0),
      f"simulation {model['Simulation']}")
fl = model["fluids"][0]
check(fl["Name"] == "goo" and len(fl["Particles"]) == n_goo and fl["Viscosity"] == 6.0, "fluid goo")
check(fl["Colour"] == (0.2, 0.8, 0.3), f"colour {fl['Colour']}")  # the shortest text of Blender's floats

# the results: every frame's .sim against the imported keyframes and points
scan = caches.scan_sim_folder(sim_dir)
check(scan["frames"] == list(range(13)), f"frames {scan['frames']}")
goo_sim = bpy.data.objects.get("goo_sim")
check(goo_sim is not None and goo_sim.softsub_cache.kind == "FLUID", "no imported point cloud 'goo_sim'")
check(not goo.visible_get(), "the source substance is still shown over the results")
fc = {(c.data_path, c.array_index): c for c in cube.animation_data.action.fcurves}
check(scene.frame_end == 13, f"frame_end {scene.frame_end}")


def check_frames(label):
    for f in scan["frames"]:
        sim = caches.read_sim(scan["sim"][f])
        ply = caches.read_ply(scan["ply"][f])
        pose = {o["Name"]: o for o in sim["objects"]}
        bf = 1 + f
        loc = [fc[("location", i)].evaluate(bf) for i in range(3)]
        check(close(loc, axes.to_blender(pose["Cube"]["Position"]), 1e-6),
              f"{label}: frame {f}: cube location key {loc} vs .sim {pose['Cube']['Position']}")
        q = [fc[("rotation_quaternion", i)].evaluate(bf) for i in range(4)]
        qs = axes.quat_to_blender(pose["Cube"]["Rotation"])
        if sum(a * b for a, b in zip(q, qs)) < 0:
            qs = tuple(-x for x in qs)
        check(close(q, qs, 1e-6), f"{label}: frame {f}: cube rotation key {q} vs .sim {qs}")
        keys = {c.data_path for c in fc.values() if any(abs(k.co[0] - bf) < 1e-6 for k in c.keyframe_points)}
        check(keys == {"location", "rotation_quaternion"}, f"{label}: frame {f}: keys {keys}")
        scene.frame_set(bf)
        world = cube.matrix_world.translation
        check(close(tuple(world), axes.to_blender(pose["Cube"]["Position"]), 1e-5), f"{label}: cube at frame {bf}")
        pos = sim["fluids"][0]["positions"]
        mesh = goo_sim.data
        check(len(mesh.vertices) == len(pos) // 3 == n_goo, f"{label}: frame {f}: {len(mesh.vertices)} points")
        got = [0.0] * (3 * len(mesh.vertices))
        mesh.vertices.foreach_get("co", got)
        want = []
        for i in range(0, len(pos), 3):
            want.extend(axes.to_blender((pos[i], pos[i + 1], pos[i + 2])))
        check(got == want, f"{label}: frame {f}: point positions differ from the .sim "
                           f"(first {got[:3]} vs {want[:3]})")
        vel = [0.0] * len(got)
        mesh.attributes["velocity"].data.foreach_get("vector", vel)
        c = ply["columns"]
        wantv = []
        for i in range(n_goo):
            wantv.extend(axes.to_blender((c["vx"][i], c["vy"][i], c["vz"][i])))
        check(close(vel, wantv, 1e-6), f"{label}: frame {f}: velocities differ from the .ply")
        ids = [0] * n_goo
        mesh.attributes["id"].data.foreach_get("value", ids)
        check(ids == [int(x) for x in c["id"][:n_goo]], f"{label}: frame {f}: ids differ from the .ply")
        if f == scan["frames"][-1]:
            check(any(abs(v) > 0.1 for v in vel), f"{label}: the goo does not move")
            check(pose["Cube"]["Position"][1] < 3.0 - 0.2, f"{label}: the cube did not fall: {pose['Cube']['Position']}")


check_frames("after import")
# what Blender draws and renders is a point cloud with the velocity and id attributes
scene.frame_set(1 + 6)
dg = bpy.context.evaluated_depsgraph_get()
clouds = [i.object for i in dg.object_instances if i.is_instance and i.object.type == "POINTCLOUD"
          and i.parent and i.parent.name == "goo_sim"]
check(len(clouds) == 1, f"goo_sim evaluates to {len(clouds)} point clouds")
if clouds:
    pc = clouds[0].data
    names = {a.name for a in pc.attributes}
    check(len(pc.points) == n_goo and {"velocity", "id", "radius"} <= names, f"point cloud {len(pc.points)} {names}")
    check(abs(pc.attributes["radius"].data[0].value - 0.25) < 1e-7, "point radius is not ParticleSize / 2")
    sim6 = caches.read_sim(scan["sim"][6])["fluids"][0]["positions"]
    check(close(tuple(pc.points[5].co), axes.to_blender(tuple(sim6[15:18])), 0), "point cloud positions")
blend = os.path.join(work, "rt.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
res = bpy.ops.wm.open_mainfile(filepath=blend)
check(res == {"FINISHED"}, f"reopening {blend}: {res}")
scene = bpy.context.scene
cube = bpy.data.objects["Cube"]
goo_sim = bpy.data.objects["goo_sim"]
fc = {(c.data_path, c.array_index): c for c in cube.animation_data.action.fcurves}
check(scene.softsub.frames == 12 and cube.softsub_body.mass == 2.0, "settings lost in the .blend")
check_frames("after reopening")
# and without the add-on: a fresh Blender opens the file and finds the keyframes
p = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", blend, "--python-expr",
                    "import bpy,sys; o=bpy.data.objects['Cube']; a=o.animation_data.action; "
                    "sys.exit(0 if len(a.fcurves)==7 and len(a.fcurves[0].keyframe_points)==13 "
                    "and 'goo_sim' in bpy.data.objects else 3)", "--python-exit-code", "2"],
                   capture_output=True, text=True)
check(p.returncode == 0, f"a fresh Blender without the add-on cannot read {blend}: exit {p.returncode}\n{p.stdout[-800:]}")
print(f"round trip: {n_goo} particles, {len(scan['frames'])} frames, {time.time() - t0:.1f} s")
finish()
