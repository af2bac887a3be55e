"""Scenes the command line wrote, imported into Blender and exported again, keep their
parameters: `softsub run --print-scene` (the embedded default scene) and examples with
primitives, rotations, pairs, mesh fills and mesh bodies. For each scene S:

  import S -> export A -> import A (a clean Blender scene) -> export B

and check that softsub reads A and S as the same scene (`softsub info`, every parameter,
particle counts, bounds, mesh paths aside), that our reader finds the same values in A
as in S (single-precision rounding aside), that A's meshes are S's meshes, and that B
is A byte for byte (a fixed point: nothing drifts on repeated round trips).

blender -b --factory-startup --python-exit-code 1 --python reimport.py -- \
    --softsub SOFTSUB --zip softsub_blender.zip --work DIR --source REPO"""
import math
import os
import re
import shutil
import subprocess
import sys

import bpy
import mathutils

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_test_util import args, check, empty_scene, finish, install_addon  # noqa: E402

A = args()
install_addon(A)
from softsub_blender import axes, caches, scenefile  # noqa: E402

work, repo, exe = A["work"], A["source"], A["softsub"]


def info(path):
    p = subprocess.run([exe, "info", path], capture_output=True, text=True)
    check(p.returncode == 0, f"softsub info {path}: exit {p.returncode}: {p.stderr.strip()}")
    lines = p.stdout.splitlines()[1:]  # the first line names the file
    return [re.sub(r"\S+Geo/\S+\.obj", "GEO", l) for l in lines]


def same_value(a, b, tol, where):
    if isinstance(a, dict):
        check(isinstance(b, dict) and set(a) == set(b), f"{where}: keys {sorted(a)} vs {sorted(b or {})}")
        for k in a:
            if k in ("Geometry",):
                continue
            same_value(a[k], b.get(k) if isinstance(b, dict) else None, 1e-4 if k == "InitialRotation" else tol,
                       f"{where}/{k}")
    elif isinstance(a, (list, tuple)):
        check(isinstance(b, (list, tuple)) and len(a) == len(b), f"{where}: {len(a)} items vs {b!r:.80}")
        for i, (x, y) in enumerate(zip(a, b or [])):
            same_value(x, y, tol, f"{where}[{i}]")
    elif isinstance(a, float):
        check(isinstance(b, (float, int)) and abs(a - b) <= tol * max(1.0, abs(a)), f"{where}: {a!r} vs {b!r}")
    else:
        check(a == b, f"{where}: {a!r} vs {b!r}")


def reset():
    empty_scene()
    scene = bpy.context.scene
    scene.property_unset("softsub")
    for m in list(bpy.data.meshes):
        bpy.data.meshes.remove(m)


def roundtrip(label, src_scene):
    d = os.path.join(work, label)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    reset()
    check(bpy.ops.softsub.import_scene(filepath=src_scene) == {"FINISHED"}, f"{label}: import failed")
    scene = bpy.context.scene
    scene.softsub.scene_path = os.path.join(d, "a.scene")
    check(bpy.ops.softsub.export() == {"FINISHED"}, f"{label}: export A failed")
    a_path = os.path.join(d, "a.scene")
    check(info(src_scene) == info(a_path), f"{label}: softsub info differs:\n" +
          "\n".join(x + "\n  vs " + y for x, y in zip(info(src_scene), info(a_path)) if x != y))
    original, exported = scenefile.read_scene_file(src_scene), scenefile.read_scene_file(a_path)
    same_value(original, exported, 1e-6, label)
    # the meshes: the same vertices (Blender holds them in single precision) and triangles
    pairs = [(fo["Geometry"], fe["Geometry"]) for f, g in zip(original["fluids"], exported["fluids"])
             for fo, fe in zip(f["fills"], g["fills"]) if fo["Shape"] == "mesh"]
    pairs += [(o["Geometry"], e["Geometry"]) for o, e in zip(original["objects"], exported["objects"])
              if o.get("Geometry")]
    for rel_o, rel_e in pairs:
        check(rel_e.startswith("aGeo/"), f"{label}: mesh written to {rel_e}, not into aGeo/")
        vo, to = caches.read_obj(os.path.join(os.path.dirname(src_scene), rel_o))
        ve, te = caches.read_obj(os.path.join(d, rel_e))
        check(len(vo) == len(ve), f"{label}: {rel_e}: {len(ve)} vertices, {rel_o} has {len(vo)}")
        check(all(abs(x - y) <= 1e-6 * max(1, abs(x)) for a, b in zip(vo, ve) for x, y in zip(a, b)),
              f"{label}: {rel_e}: vertices moved")
        tri_o = sorted(tuple(sorted(t)) for f in to for t in [(f[0], f[i], f[i + 1]) for i in range(1, len(f) - 1)])
        check(sorted(tuple(sorted(t)) for t in te) == tri_o, f"{label}: {rel_e}: other triangles than {rel_o}")
    # again, from what we wrote: nothing drifts
    reset()
    check(bpy.ops.softsub.import_scene(filepath=a_path) == {"FINISHED"}, f"{label}: import A failed")
    bpy.context.scene.softsub.scene_path = os.path.join(d, "b.scene")
    check(bpy.ops.softsub.export() == {"FINISHED"}, f"{label}: export B failed")
    ta = open(a_path).read().split("\n", 2)[2]  # after the comment line naming the .blend
    tb = open(os.path.join(d, "b.scene")).read().split("\n", 2)[2]
    check(ta.replace("aGeo/", "XGeo/") == tb.replace("bGeo/", "XGeo/"), f"{label}: B differs from A")
    print(f"{label}: same parameters ({len(original['fluids'])} fluids, {len(original['objects'])} objects)",
          flush=True)


# 1. the embedded default scene, as `softsub run --print-scene` writes it
printed = os.path.join(work, "printed.scene")
p = subprocess.run([exe, "run", "--print-scene"], capture_output=True, text=True)
check(p.returncode == 0, "softsub run --print-scene failed")
with open(printed, "w") as f:
    f.write(p.stdout)
roundtrip("print-scene", printed)
# 2. examples and test scenes: primitives and rotations, pairs, mesh fills, mesh bodies, curves
for rel in ("examples/interactions.scene", "examples/goo-torus.scene", "examples/wall-impact.scene",
            "tests/data/scenes/good/objects.scene", "tests/data/scenes/good/two_fluids.scene"):
    roundtrip(os.path.basename(rel)[:-6], os.path.join(repo, rel))

# surfaces: an imported example run with --formats ...,mesh,vdb comes back as a mesh
# sequence and a VDB volume sequence that follow the frames
reset()
check(bpy.ops.softsub.import_scene(filepath=os.path.join(repo, "examples", "honey-drop.scene")) == {"FINISHED"},
      "import honey-drop")
s = bpy.context.scene.softsub
s.scene_path = os.path.join(work, "surf", "hd.scene")
s.frames, s.write_mesh, s.write_vdb = 3, True, True
bpy.context.scene.frame_start = 10
check(bpy.ops.softsub.run(wait=True) == {"FINISHED"}, "run with surfaces")
surf, vol = bpy.data.objects.get("honey_surface"), bpy.data.objects.get("honey_vdb")
check(surf is not None and vol is not None and vol.type == "VOLUME", "surfaces not imported")
# The grid is in softsub's axes; its object must put it where the points and mesh are.
bpy.context.view_layer.update()
for p in ((1.0, 2.0, 3.0), (-4.0, 0.5, 7.0)):
    got = vol.matrix_world @ mathutils.Vector(p)
    want = axes.to_blender(p)
    check(all(abs(got[i] - want[i]) < 1e-6 for i in range(3)), f"volume: softsub {p} shown at {tuple(got)}, not {want}")
for f in range(4):
    bpy.context.scene.frame_set(10 + f)
    verts, faces = caches.read_obj(os.path.join(work, "surf", "hdSim", "mesh", f"honey.{f:04d}.obj"))
    check(len(surf.data.vertices) == len(verts) and len(surf.data.polygons) == len(faces) > 100,
          f"surface at frame {f}: {len(surf.data.vertices)} vertices, the OBJ has {len(verts)}")
    check(abs(surf.data.vertices[0].co.z - verts[0][1]) < 1e-6, f"surface at frame {f}: not in Blender's axes")
    vol.data.grids.load()
    check(os.path.basename(vol.data.grids.frame_filepath) == f"honey.{f:04d}.vdb" and len(vol.data.grids) == 1
          and vol.data.grids[0].name == "honey", f"volume at frame {f}: {vol.data.grids.frame_filepath}")

# a bad scene is refused with the reason and creates nothing
reset()
bad = os.path.join(work, "bad.scene")
with open(bad, "w") as f:
    f.write('<Scene version="1"><Fluid><Name>x</Name><Viscosity>-1</Viscosity>'
            '<Particles>0 0 0</Particles></Fluid></Scene>')
n_before = len(bpy.data.objects)
try:
    res = bpy.ops.softsub.import_scene(filepath=bad)
except RuntimeError as e:
    res = str(e)
check("Viscosity" in str(res) and "allowed: >= 0" in str(res), f"bad scene: {res}")
check(len(bpy.data.objects) == n_before and not bpy.data.collections, "a refused scene left objects behind")
finish()
