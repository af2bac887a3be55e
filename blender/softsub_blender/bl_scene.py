"""Blender objects <-> the scene model (scenefile.py): what Export writes and what
"Import .scene" builds. All axis conversion goes through axes.py."""
import math
import os
import re

import bpy

from . import axes, caches, results, schema, scenefile
from .scenefile import SceneError

num = schema.format_number
_FILE_SAFE = re.compile(r"[^A-Za-z0-9_.-]")
_BAD_OBJECT_NAME = re.compile(r"[/\\\x00-\x1f\x7f]")
SHAPE_TO_SCENE = {"BOX": "box", "SPHERE": "sphere", "CYLINDER": "cylinder", "CONE": "cone", "MESH": "mesh"}


def scene_paths(context):
    """(scene file, scene name, folder, geometry folder, results folder), absolute."""
    settings = context.scene.softsub
    raw = settings.scene_path.strip()
    if not raw:
        raise SceneError("set the scene file (Soft Substances > Scene file)")
    if raw.startswith("//") and not bpy.data.filepath:
        raise SceneError("the scene file is relative to the .blend ('//'), but the .blend is not saved: "
                         "save it first or choose an absolute path")
    path = os.path.abspath(bpy.path.abspath(raw))
    if not path.endswith(".scene"):
        path += ".scene"
    folder, base = os.path.split(path)
    name = base[:-len(".scene")]
    return path, name, folder, os.path.join(folder, name + "Geo"), os.path.join(folder, name + "Sim")


def _evaluated_mesh_data(obj, depsgraph):
    """(vertices in object space, triangles) of the object's evaluated mesh."""
    ev = obj.evaluated_get(depsgraph)
    mesh = ev.to_mesh()
    try:
        mesh.calc_loop_triangles()
        verts = [tuple(v.co) for v in mesh.vertices]
        tris = [tuple(t.vertices) for t in mesh.loop_triangles]
    finally:
        ev.to_mesh_clear()
    return verts, tris


def _object_points(obj, context):
    """World positions of a substance's points: the mesh's vertices with its modifiers
    applied, as the viewport shows them and as bodies and fills take them (the base
    vertices were exported: 8 points for an Array modifier's 24; a review), but for the
    add-on's own display as points, which turns the mesh into a point cloud; or point
    cloud points."""
    mw = obj.matrix_world
    if obj.type == "MESH":
        from . import display
        own = [m for m in obj.modifiers if m.name != display.GROUP and m.show_viewport]
        if not own:
            return [tuple(mw @ v.co) for v in obj.data.vertices]
        shown = obj.modifiers.get(display.GROUP)
        was = shown.show_viewport if shown is not None else None
        try:
            if shown is not None and was:
                shown.show_viewport = False
                context.view_layer.update()
            verts, _ = _evaluated_mesh_data(obj, context.evaluated_depsgraph_get())
        finally:
            if shown is not None and was:
                shown.show_viewport = True
                context.view_layer.update()
        return [tuple(mw @ _vec(v)) for v in verts]
    if obj.type == "POINTCLOUD":
        return [tuple(mw @ p.co) for p in obj.data.points]
    raise SceneError(f"substance '{obj.name}': a {obj.type.lower()} has no points (use a mesh or a point cloud)")


def _rotation_is_own(obj):
    """Whether the object's world rotation is its rotation_euler alone: no delta rotation,
    no enabled constraint (parents are refused), and no negative scale, which the matrix's
    decomposition turns into a half turn (a mirrored body in mode XZY was simulated upside
    down: a review)."""
    return (all(a * b > 0 for a, b in zip(obj.scale, obj.delta_scale))
            and all(abs(x) < 1e-12 for x in obj.delta_rotation_euler)
            and abs(obj.delta_rotation_quaternion[0] - 1) < 1e-12
            and not any(getattr(c, "enabled", True) and not getattr(c, "mute", False) for c in obj.constraints))


def _uniform_scale(scale):
    s = [abs(x) for x in scale]
    return s[0] if max(s) - min(s) <= 1e-6 * max(s) and min(x for x in scale) > 0 else None


def _interaction_model(p):
    params = {}
    for prop, kind, tag in _function_params():
        if kind == p.function:
            params[tag] = getattr(p, prop)
    if p.function == "Curve":
        try:
            params["Points"] = [float(x) for x in p.curve_points.split()]
        except ValueError:
            raise SceneError(f"Curve points '{p.curve_points}': not a list of numbers") from None
    return {"function": p.function, "params": params, "Damping": p.damping, "RelativeVelocity": p.relative_velocity}


def _function_params():
    from .props import FUNCTION_PARAMS
    return FUNCTION_PARAMS


def _set_interaction(p, it):
    p.function = it["function"]
    for prop, kind, tag in _function_params():
        if kind == it["function"]:
            setattr(p, prop, it["params"][tag])
    if it["function"] == "Curve":
        p.curve_points = " ".join(num(x) for x in it["params"]["Points"])
    p.damping = it["Damping"]
    p.relative_velocity = it["RelativeVelocity"]


def _check(section, tag, value, where):
    problem = schema.check_range(section, tag, value)
    if problem:
        raise SceneError(f"{where}/{tag}: {problem}")


def collect(context):
    """The scene model and the meshes to write [(path relative to the scene's folder,
    name, vertices, triangles)], from the marked objects at the scene's start frame."""
    scene = context.scene
    s = scene.softsub
    path, name, folder, geo_dir, _ = scene_paths(context)
    restore = scene.frame_current
    if restore != scene.frame_start:
        scene.frame_set(scene.frame_start)
    try:
        return _collect(context, name)
    finally:
        if scene.frame_current != restore:
            scene.frame_set(restore)


def _collect(context, name):
    scene = context.scene
    s = scene.softsub
    depsgraph = context.evaluated_depsgraph_get()
    model = scenefile.new_scene()
    fps = scene.render.fps / scene.render.fps_base if s.use_scene_fps else s.fps
    frames = scene.frame_end - scene.frame_start if s.use_scene_range else s.frames
    model["Simulation"] = {"FramesPerSecond": fps, "Substeps": s.substeps, "Frames": frames,
                           "Gravity": axes.to_softsub(tuple(s.gravity)), "Integrator": s.integrator}
    for tag in ("FramesPerSecond", "Substeps", "Frames"):
        _check("Simulation", tag, model["Simulation"][tag], "Simulation")
    model["Camera"] = {"Eye": axes.to_softsub(tuple(s.eye)), "VerticalAngle": s.vertical_angle,
                       "HorizontalAngle": s.horizontal_angle} if s.use_camera else None
    if s.use_container:
        model["Environment"] = {"Width": s.width, "Height": s.height, "Depth": s.depth,
                                "Reflective": s.reflective, "NormalAttenuation": s.normal_attenuation,
                                "TangentAttenuation": s.tangent_attenuation, "Closed": s.closed}
        for tag in ("Width", "Height", "Depth", "NormalAttenuation", "TangentAttenuation"):
            _check("Environment", tag, model["Environment"][tag], "Environment")
    else:
        model["Environment"] = None
    meshes = []
    used_files = set()

    def geometry_file(obj_name):
        base = _FILE_SAFE.sub("_", obj_name) or "mesh"
        cand, k = base, 1
        while cand.lower() in used_files:
            k += 1
            cand = f"{base}_{k}"
        used_files.add(cand.lower())
        return f"{name}Geo/{cand}.obj"

    # scene order: the order marks were made (or the imported scene's), then names
    fluids = sorted((o for o in scene.objects if o.softsub_fluid.enabled), key=lambda o: (o.softsub_fluid.order, o.name))
    fills = sorted((o for o in scene.objects if o.softsub_fill.enabled), key=lambda o: (o.softsub_fill.order, o.name))
    bodies = sorted((o for o in scene.objects if o.softsub_body.enabled), key=lambda o: (o.softsub_body.order, o.name))
    for obj in fluids:
        fp = obj.softsub_fluid
        if not fp.enabled or obj.softsub_cache.kind != "NONE":
            continue
        where = f"substance '{obj.name}'"
        if not scenefile.FLUID_NAME.match(obj.name):
            raise SceneError(f"{where}: a substance's name may hold only letters, digits, _ and - (it becomes "
                             "part of file names): rename the object")
        f = scenefile.new_fluid(obj.name)
        f.update({"InteractionDistance": fp.interaction_distance, "Amplitude": fp.amplitude,
                  "FiniteDistance": fp.finite_distance, "MinimumForce": fp.minimum_force,
                  "MaximumForce": fp.maximum_force, "Viscosity": fp.viscosity, "ParticleSize": fp.particle_size,
                  "ParticleMass": fp.particle_mass, "InitialSpeed": axes.to_softsub(tuple(fp.initial_speed)),
                  "Colour": tuple(fp.colour)})
        for tag in scenefile.FLUID_PARAMS:
            if tag != "Particles":
                _check("Fluid", tag, f[tag], where)
        if fp.minimum_force > fp.maximum_force:
            raise SceneError(f"{where}: MinimumForce {num(fp.minimum_force)} is above MaximumForce "
                             f"{num(fp.maximum_force)}")
        f["Particles"] = [axes.to_softsub(p) for p in _object_points(obj, context)]
        for fo in fills:
            if fo.softsub_fill.fluid != obj:
                continue
            fl = fo.softsub_fill
            fwhere = f"{where}: fill '{fo.name}'"
            _check("Fill", "Spacing", fl.spacing, fwhere)
            if fo.type != "MESH":
                raise SceneError(f"{fwhere}: a fill volume must be a mesh")
            mw = fo.matrix_world
            if fl.shape == "BOX":
                pts = [axes.to_softsub(tuple(mw @ v.co)) for v in fo.data.vertices]
                if not pts:
                    raise SceneError(f"{fwhere}: the mesh has no vertices")
                lo = tuple(min(p[i] for p in pts) for i in range(3))
                hi = tuple(max(p[i] for p in pts) for i in range(3))
                f["fills"].append({"Shape": "box", "Min": lo, "Max": hi, "Spacing": fl.spacing,
                                   "OutsideObjects": fl.outside_objects})
            elif fl.shape == "SPHERE":
                radius = max(fo.dimensions) / 2
                _check("Fill.sphere", "Radius", radius, fwhere)
                f["fills"].append({"Shape": "sphere", "Center": axes.to_softsub(tuple(mw.translation)),
                                   "Radius": radius, "Spacing": fl.spacing, "OutsideObjects": fl.outside_objects})
            else:
                verts, tris = _evaluated_mesh_data(fo, depsgraph)
                if not tris:
                    raise SceneError(f"{fwhere}: the mesh has no faces to fill")
                world = [axes.to_softsub(tuple(mw @ _vec(v))) for v in verts]
                rel = geometry_file(fo.name)
                meshes.append((rel, fo.name, world, tris))
                f["fills"].append({"Shape": "mesh", "Geometry": rel, "Surface": fl.surface, "Spacing": fl.spacing,
                                   "OutsideObjects": fl.outside_objects})
        if not f["Particles"] and not f["fills"]:
            raise SceneError(f"{where}: no particles: give the object points, fill a mesh with particles, or "
                             "add a fill volume")
        model["fluids"].append(f)
    for obj in bodies:
        bp = obj.softsub_body
        if not bp.enabled or obj.softsub_cache.kind not in ("NONE", "BODY"):
            continue
        where = f"rigid body '{obj.name}'"
        if _BAD_OBJECT_NAME.search(obj.name):
            raise SceneError(f"{where}: a name may not hold '/', '\\' or control characters: rename the object")
        if obj.parent is not None:
            raise SceneError(f"{where}: has a parent; rigid bodies are placed in world space: unparent it "
                             "(Alt+P, Clear and Keep Transformation)")
        if obj.type != "MESH":
            raise SceneError(f"{where}: only meshes can be rigid bodies")
        o = scenefile.new_object(obj.name)
        # A body showing imported results starts from where it was placed before them,
        # not from a simulated frame at the start frame (results.remember_rest_pose).
        from mathutils import Matrix
        rest = results.rest_matrix_world(obj)
        world = Matrix(rest) if rest is not None else obj.matrix_world
        loc, rot, scale = world.decompose()
        uniform = _uniform_scale(scale)
        # The object's own scale, as the panel holds it, where it is uniform: the
        # decomposition of a turned matrix gave 0.99999994 for 1 (a review). Imports key
        # no scale, so it is also the scale a body was placed with.
        own = [a * b for a, b in zip(obj.scale, obj.delta_scale)]
        if uniform is not None and own[0] > 0 and own[0] == own[1] == own[2]:
            uniform = own[0]
        o["InitialPosition"] = axes.to_softsub(tuple(loc))
        # XZY (what Import .scene sets) maps its angles exactly, but only when they are
        # the whole rotation: a delta rotation or a constraint adds to them (a review: a
        # delta rotation was left out, 0.65 units off).
        if rest is None and obj.rotation_mode == "XZY" and _rotation_is_own(obj):
            o["InitialRotation"] = axes.blender_xzy_to_softsub_euler(tuple(obj.rotation_euler))
        else:
            o["InitialRotation"] = axes.blender_matrix_to_softsub_euler(tuple(tuple(r) for r in rot.to_matrix()))
        o.update({"InitialLinearVelocity": axes.to_softsub(tuple(bp.initial_linear_velocity)),
                  "InitialAngularVelocity": axes.to_softsub(tuple(bp.initial_angular_velocity)),
                  "NormalAttenuation": bp.normal_attenuation, "TangentAttenuation": bp.tangent_attenuation,
                  "Mass": bp.mass, "IsDynamic": bp.is_dynamic})
        for tag in ("Mass", "NormalAttenuation", "TangentAttenuation"):
            _check("Object", tag, o[tag], where)
        if bp.particle_size > 0:
            o["ParticleSize"] = bp.particle_size
        shape = SHAPE_TO_SCENE[bp.shape]
        count = {"sphere": 1, "cone": 2, "cylinder": 2, "box": 3}.get(shape, 0)
        size = list(bp.size[:count])
        if bp.primitive_only:
            if shape == "mesh":
                raise SceneError(f"{where}: 'Primitive only' needs a primitive inertia (box, sphere, cylinder, cone)")
            if uniform is None:
                raise SceneError(f"{where}: a primitive body needs the same positive scale on X, Y and Z "
                                 f"(it is {tuple(round(x, 6) for x in scale)}): set Size instead")
            if any(x <= 0 for x in size):
                raise SceneError(f"{where}: Size needs {count} numbers > 0 for a {shape}")
            o["Shape"], o["Size"], o["UniformScale"] = shape, size, uniform
        else:
            verts, tris = _evaluated_mesh_data(obj, depsgraph)
            if not tris:
                raise SceneError(f"{where}: the mesh has no faces")
            if uniform is not None:
                o["UniformScale"] = uniform
                local = verts
            else:  # bake the scale into the mesh; a mirroring scale turns the triangles over
                o["UniformScale"] = 1.0
                local = [(v[0] * scale[0], v[1] * scale[1], v[2] * scale[2]) for v in verts]
                if scale[0] * scale[1] * scale[2] < 0:
                    tris = [(t[0], t[2], t[1]) for t in tris]
            rel = geometry_file(obj.name)
            meshes.append((rel, obj.name, [axes.to_softsub(v) for v in local], tris))
            o["Geometry"] = rel
            if shape != "mesh":
                o["Shape"] = shape
                if any(x > 0 for x in size):
                    o["Size"] = size
        _check("Object", "UniformScale", o["UniformScale"], where)
        model["objects"].append(o)
    model["FluidFluid"] = _interaction_model(s.fluid_fluid)
    model["FluidObject"] = _interaction_model(s.fluid_object)
    names = {f["Name"] for f in model["fluids"]} | {o["Name"] for o in model["objects"]}
    for i, p in enumerate(s.pairs, 1):
        if p.a is None or p.b is None:
            raise SceneError(f"interaction pair {i}: choose both A and B")
        for end in (p.a, p.b):
            if end.name not in names:
                raise SceneError(f"interaction pair {i}: '{end.name}' is not a substance or rigid body of the scene")
        bodies_named = {o["Name"] for o in model["objects"]}
        if p.a.name in bodies_named and p.b.name in bodies_named:
            raise SceneError(f"interaction pair {i}: '{p.a.name}' and '{p.b.name}' are both rigid bodies, which meet "
                             "by impulses (their Normal and Tangent Attenuation), not by a function: choose a "
                             "substance for one end")
        it = _interaction_model(p)
        it["A"], it["B"] = p.a.name, p.b.name
        model["pairs"].append(it)
    if not model["fluids"] and not model["objects"]:
        raise SceneError("nothing to simulate: mark substances or rigid bodies first")
    return model, meshes


def _vec(v):
    from mathutils import Vector
    return Vector(v)


def export(context):
    """Writes <name>.scene and <name>Geo/*.obj; returns (scene path, model)."""
    path, name, folder, geo_dir, _ = scene_paths(context)
    model, meshes = collect(context)
    os.makedirs(folder, exist_ok=True)
    if meshes:
        os.makedirs(geo_dir, exist_ok=True)
    for rel, obj_name, verts, tris in meshes:
        caches.write_obj(os.path.join(folder, rel), obj_name, verts, tris, num)
    comment = f"written by the softsub Blender add-on from {os.path.basename(bpy.data.filepath) or 'an unsaved .blend'}"
    scenefile.write_scene_file(path, model, comment=comment)
    return path, model


# ---------------------------------------------------------------- import of a .scene

def next_order(group):
    """One more than the highest order of the marked objects of that kind."""
    return 1 + max((getattr(o, group).order for o in bpy.data.objects if getattr(o, group).enabled), default=0)


def unit_sphere(segments=32, rings=16):
    """A UV sphere of radius 1 whose bounding box is exactly [-1, 1] on every axis."""
    verts = [(0.0, 0.0, 1.0)]
    for r in range(1, rings):
        th = math.pi * r / rings
        z = 1.0 if 2 * r == 0 else (0.0 if 2 * r == rings else math.cos(th))
        rr = 1.0 if 2 * r == rings else math.sin(th)
        for s in range(segments):
            ph = 2 * math.pi * s / segments
            c = {0: 1.0, segments // 4: 0.0, segments // 2: -1.0, 3 * segments // 4: 0.0}.get(s, math.cos(ph))
            sn = {0: 0.0, segments // 4: 1.0, segments // 2: 0.0, 3 * segments // 4: -1.0}.get(s, math.sin(ph))
            verts.append((rr * c, rr * sn, z))
    verts.append((0.0, 0.0, -1.0))
    faces = []
    for s in range(segments):
        faces.append((0, 1 + s, 1 + (s + 1) % segments))
    for r in range(rings - 2):
        a, b = 1 + r * segments, 1 + (r + 1) * segments
        for s in range(segments):
            t = (s + 1) % segments
            faces.append((a + s, b + s, b + t, a + t))
    last = len(verts) - 1
    base = 1 + (rings - 2) * segments
    for s in range(segments):
        faces.append((base + s, last, base + (s + 1) % segments))
    return verts, faces


def primitive_mesh(shape, size):
    """A display mesh (Blender axes) of a softsub primitive centred as softsub centres it."""
    if shape == "sphere":
        v, f = unit_sphere()
        r = size[0]
        return [(x * r, y * r, z * r) for x, y, z in v], f
    if shape == "box":
        w, h, d = size  # softsub x, y (up), z -> Blender x, z, y
        hx, hy, hz = w / 2, d / 2, h / 2
        v = [(sx * hx, sy * hy, sz * hz) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
        return v, f
    r, h = size
    n = 32
    if shape == "cylinder":
        z0, z1 = -h / 2, h / 2
        v = [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n), z) for z in (z0, z1)
             for i in range(n)]
        f = [(i, (i + 1) % n, n + (i + 1) % n, n + i) for i in range(n)]
        f += [tuple(reversed(range(n))), tuple(range(n, 2 * n))]
        return v, f
    # cone: softsub centres it on its centre of mass, base at y = -height/4
    v = [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n), -h / 4) for i in range(n)]
    v.append((0.0, 0.0, 3 * h / 4))
    f = [(i, (i + 1) % n, n) for i in range(n)] + [tuple(reversed(range(n)))]
    return v, f


def new_mesh_object(name, verts, faces, collection):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in verts], [], [tuple(f) for f in faces])
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    collection.objects.link(obj)
    if obj.name != name:
        raise SceneError(f"could not name an object '{name}'")
    return obj


def load_scene_meshes(model, folder):
    """Reads every mesh the scene names (before anything is created): {relpath: (verts
    in Blender axes, faces)}."""
    out = {}
    rels = [fl["Geometry"] for f in model["fluids"] for fl in f["fills"] if fl["Shape"] == "mesh"]
    rels += [o["Geometry"] for o in model["objects"] if o.get("Geometry")]
    for rel in rels:
        if rel in out:
            continue
        if os.path.isabs(rel) or ".." in rel.replace("\\", "/").split("/"):
            raise SceneError(f"'{rel}' leaves the scene's folder")
        if not rel.lower().endswith(".obj"):
            raise SceneError(f"'{rel}': the add-on imports OBJ meshes only (convert it, or import it with "
                             "File > Import and mark it by hand)")
        verts, faces = caches.read_obj(os.path.join(folder, rel))
        out[rel] = ([axes.to_blender(v) for v in verts], faces)
    return out


def import_scene(context, path):
    """Builds the scene's substances, fills and rigid bodies in a new collection and sets
    the global settings. Everything is read and checked first: on an error nothing is
    created. Returns the collection."""
    model = scenefile.read_scene_file(path)
    folder = os.path.dirname(os.path.abspath(path))
    name = os.path.basename(path)[:-len(".scene")] if path.endswith(".scene") else os.path.basename(path)
    meshes = load_scene_meshes(model, folder)
    taken = [n for n in [f["Name"] for f in model["fluids"]] + [o["Name"] for o in model["objects"]]
             if n in bpy.data.objects]
    if taken:
        raise SceneError(f"objects named {', '.join(repr(n) for n in taken)} already exist: rename or delete them "
                         "first (names are how the scene refers to substances and bodies)")
    scene = context.scene
    s = scene.softsub
    coll = bpy.data.collections.new(f"softsub {name}")
    scene.collection.children.link(coll)
    sim = model["Simulation"]
    s.use_scene_fps = False
    s.fps = sim["FramesPerSecond"]
    s.use_scene_range = False
    s.frames = sim["Frames"]
    s.substeps = sim["Substeps"]
    s.gravity = axes.to_blender(sim["Gravity"])
    s.integrator = sim["Integrator"]
    s.use_camera = model["Camera"] is not None
    if model["Camera"]:
        s.eye = axes.to_blender(model["Camera"]["Eye"])
        s.vertical_angle = model["Camera"]["VerticalAngle"]
        s.horizontal_angle = model["Camera"]["HorizontalAngle"]
    s.use_container = model["Environment"] is not None
    if model["Environment"]:
        env = model["Environment"]
        s.width, s.height, s.depth = env["Width"], env["Height"], env["Depth"]
        s.reflective, s.closed = env["Reflective"], env["Closed"]
        s.normal_attenuation, s.tangent_attenuation = env["NormalAttenuation"], env["TangentAttenuation"]
    from . import display
    for f in model["fluids"]:
        obj = new_mesh_object(f["Name"], [axes.to_blender(p) for p in f["Particles"]], [], coll)
        fp = obj.softsub_fluid
        fp.enabled = True
        fp.order = next_order("softsub_fluid")
        fp.interaction_distance, fp.amplitude = f["InteractionDistance"], f["Amplitude"]
        fp.finite_distance, fp.minimum_force = f["FiniteDistance"], f["MinimumForce"]
        fp.maximum_force, fp.viscosity = f["MaximumForce"], f["Viscosity"]
        fp.particle_size, fp.particle_mass = f["ParticleSize"], f["ParticleMass"]
        fp.initial_speed = axes.to_blender(f["InitialSpeed"])
        fp.colour = f["Colour"]
        display.show_as_points(obj, f["ParticleSize"] / 2, f["Colour"])
        for j, fill in enumerate(f["fills"], 1):
            fname = f"{f['Name']}_fill{j}"
            if fill["Shape"] == "box":
                lo, hi = axes.to_blender(fill["Min"]), axes.to_blender(fill["Max"])
                lo, hi = tuple(min(a, b) for a, b in zip(lo, hi)), tuple(max(a, b) for a, b in zip(lo, hi))
                v = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
                fo = new_mesh_object(fname, v, [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6),
                                                (0, 2, 6, 4), (1, 5, 7, 3)], coll)
            elif fill["Shape"] == "sphere":
                v, fc = unit_sphere()
                fo = new_mesh_object(fname, v, fc, coll)
                fo.location = axes.to_blender(fill["Center"])
                fo.scale = (fill["Radius"],) * 3
            else:
                v, fc = meshes[fill["Geometry"]]
                fo = new_mesh_object(fname, v, fc, coll)
                fo.softsub_fill.surface = fill["Surface"]
            fo.softsub_fill.enabled = True
            fo.softsub_fill.order = next_order("softsub_fill")
            fo.softsub_fill.fluid = obj
            fo.softsub_fill.shape = fill["Shape"].upper()
            fo.softsub_fill.spacing = fill["Spacing"]
            fo.softsub_fill.outside_objects = fill.get("OutsideObjects", False)
            display.show_as_fill(fo)
    for o in model["objects"]:
        shape = o.get("Shape", "mesh")
        if o.get("Geometry"):
            v, fc = meshes[o["Geometry"]]
        else:
            v, fc = primitive_mesh(shape, o["Size"])
        obj = new_mesh_object(o["Name"], v, fc, coll)
        obj.location = axes.to_blender(o["InitialPosition"])
        obj.rotation_mode = "XZY"
        obj.rotation_euler = axes.softsub_euler_to_blender_xzy(o["InitialRotation"])
        obj.scale = (o["UniformScale"],) * 3
        bp = obj.softsub_body
        bp.enabled = True
        bp.order = next_order("softsub_body")
        bp.is_dynamic, bp.mass = o["IsDynamic"], o["Mass"]
        bp.normal_attenuation, bp.tangent_attenuation = o["NormalAttenuation"], o["TangentAttenuation"]
        bp.initial_linear_velocity = axes.to_blender(o["InitialLinearVelocity"])
        bp.initial_angular_velocity = axes.to_blender(o["InitialAngularVelocity"])
        bp.shape = shape.upper()
        bp.primitive_only = not o.get("Geometry")
        size = list(o.get("Size") or [])
        bp.size = (size + [0.0, 0.0, 0.0])[:3]
        bp.particle_size = o.get("ParticleSize") or 0.0
    _set_interaction(s.fluid_fluid, model["FluidFluid"] or scenefile.default_interaction("FluidFluid"))
    _set_interaction(s.fluid_object, model["FluidObject"] or scenefile.default_interaction("FluidObject"))
    s.pairs.clear()
    for it in model["pairs"]:
        p = s.pairs.add()
        _set_interaction(p, it)
        p.a, p.b = bpy.data.objects[it["A"]], bpy.data.objects[it["B"]]
    display.update_container(context)
    return coll
