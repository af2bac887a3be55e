"""The add-on's Blender properties: scene settings (scene.softsub), and per object the
rigid-body (softsub_body), substance (softsub_fluid), fill (softsub_fill) and imported
cache (softsub_cache) settings. Defaults, ranges and tooltips come from the scene
format's table (schema.py, from `softsub schema`); vectors are in Blender's axes (Z up)
and converted on export (axes.py)."""
import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty,
                       FloatVectorProperty, IntProperty, PointerProperty, StringProperty)

from . import axes, schema


def _tip(section, tag, extra=""):
    _, kind, unit, default, allowed, meaning = schema.row(section, tag)
    unit = "" if unit == "-" else f"; {unit}"
    return f"{meaning}{extra} (scene tag {tag}{unit}; default {default}; allowed: {allowed})"


def fprop(section, tag, name=None, default=None, extra="", **kw):
    """A FloatProperty with the tag's default, range and meaning."""
    lo, _, hi, _ = schema.bounds(section, tag)
    d = schema.default(section, tag) if default is None else default
    args = dict(name=name or tag, description=_tip(section, tag, extra), default=float(d), precision=3)
    if lo is not None:
        args["min"] = lo
    if hi is not None:
        args["max"] = hi
    args.update(kw)
    return FloatProperty(**args)


def iprop(section, tag, name=None, **kw):
    lo, _, hi, _ = schema.bounds(section, tag)
    args = dict(name=name or tag, description=_tip(section, tag), default=schema.default(section, tag))
    if lo is not None:
        args["min"] = int(lo)
    if hi is not None:
        args["max"] = int(hi)
    args.update(kw)
    return IntProperty(**args)


def bprop(section, tag, name=None, **kw):
    return BoolProperty(name=name or tag, description=_tip(section, tag), default=schema.default(section, tag), **kw)


def vprop(section, tag, name=None, blender_axes=True, subtype="XYZ", extra="", **kw):
    d = schema.default(section, tag)
    if blender_axes:
        d = axes.to_blender(d)
        extra = extra or ", in Blender's axes (Z up; converted to softsub's Y up on export)"
    return FloatVectorProperty(name=name or tag, description=_tip(section, tag, extra), default=d, size=3,
                               subtype=subtype, precision=3, **kw)


FUNCTION_ITEMS = [
    ("Linear", "Linear", "A clamped straight line: AtZero at r = 0 down to 0 at Cutoff"),
    ("LennardJones", "Lennard-Jones (clamped)", "The seed's shape 4A((s/r)^12 - (s/r)^6), clamped to [Min, Max]"),
    ("LennardJonesForce", "Lennard-Jones force", "The true 12-6 force -dU/dr, not clamped"),
    ("Curve", "Curve", "Piecewise linear through the points r0 f0 r1 f1 ..."),
]

# (property name, function kind, tag)
FUNCTION_PARAMS = [
    ("linear_at_zero", "Linear", "AtZero"), ("linear_cutoff", "Linear", "Cutoff"),
    ("linear_min", "Linear", "Min"), ("linear_max", "Linear", "Max"),
    ("lj_amplitude", "LennardJones", "Amplitude"), ("lj_finite_distance", "LennardJones", "FiniteDistance"),
    ("lj_min", "LennardJones", "Min"), ("lj_max", "LennardJones", "Max"), ("lj_cutoff", "LennardJones", "Cutoff"),
    ("ljf_epsilon", "LennardJonesForce", "Epsilon"), ("ljf_sigma", "LennardJonesForce", "Sigma"),
    ("ljf_cutoff", "LennardJonesForce", "Cutoff"),
]


def _interaction_annotations(velocity_section, linear_cutoff=None):
    ann = {"function": EnumProperty(name="Function", items=FUNCTION_ITEMS, default="Linear")}
    for prop, kind, tag in FUNCTION_PARAMS:
        d = linear_cutoff if (prop == "linear_cutoff" and linear_cutoff is not None) else None
        ann[prop] = fprop(kind, tag, name=tag, default=d)
    ann["curve_points"] = StringProperty(name="Points", description=_tip("Curve", "Points"),
                                         default="0 5 1 0")
    ann["damping"] = fprop(velocity_section, "Damping")
    ann["relative_velocity"] = fprop(velocity_section, "RelativeVelocity")
    return ann


SoftsubInteraction = type("SoftsubInteraction", (bpy.types.PropertyGroup,),
                          {"__annotations__": _interaction_annotations("FluidFluid.velocity")})
# The global fluid/object function's default is Linear with Cutoff 1.5 and
# RelativeVelocity 2 (docs/scene-format.md, "Interactions").
SoftsubInteractionFO = type("SoftsubInteractionFO", (bpy.types.PropertyGroup,),
                            {"__annotations__": _interaction_annotations("FluidObject.velocity", 1.5)})


def _marked_poll(self, obj):
    return obj.softsub_fluid.enabled or obj.softsub_body.enabled


_pair_ann = _interaction_annotations("FluidFluid.velocity")
_pair_ann["a"] = PointerProperty(name="A", type=bpy.types.Object, poll=_marked_poll,
                                 description="First substance or rigid body of the pair")
_pair_ann["b"] = PointerProperty(name="B", type=bpy.types.Object, poll=_marked_poll,
                                 description="Second substance or rigid body (B = A, a substance: replaces "
                                             "its own function and viscosity)")
SoftsubPair = type("SoftsubPair", (bpy.types.PropertyGroup,), {"__annotations__": _pair_ann})


class SoftsubSettings(bpy.types.PropertyGroup):
    scene_path: StringProperty(
        name="Scene file", subtype="FILE_PATH", default="//softsub/shot.scene",
        description="Where Export writes the .scene (its meshes go to <name>Geo/ beside it) and where Run "
                    "simulates it from; the results go to <name>Sim/ beside it")
    use_scene_fps: BoolProperty(name="Use Blender's frame rate", default=True,
                                description="FramesPerSecond = this scene's frame rate (Output properties)")
    fps: fprop("Simulation", "FramesPerSecond", name="Frames per second")
    use_scene_range: BoolProperty(name="Use Blender's frame range", default=True,
                                  description="Frames = End - Start of this scene's frame range; "
                                              "simulation frame 0 is the Start frame")
    frames: iprop("Simulation", "Frames")
    substeps: iprop("Simulation", "Substeps")
    gravity: vprop("Simulation", "Gravity", subtype="ACCELERATION")
    integrator: EnumProperty(name="Integrator", description=_tip("Simulation", "Integrator"),
                             items=[(n, n, "") for n in schema.enum_items("Simulation", "Integrator")],
                             default=schema.default("Simulation", "Integrator"))
    use_container: BoolProperty(name="Container", default=True,
                                description="Walls and a floor around the scene (without: no walls at all)")
    width: fprop("Environment", "Width", extra="; Blender X")
    height: fprop("Environment", "Height", extra="; Blender Z, from the ground up")
    depth: fprop("Environment", "Depth", extra="; Blender Y")
    reflective: bprop("Environment", "Reflective")
    normal_attenuation: fprop("Environment", "NormalAttenuation", name="Restitution")
    tangent_attenuation: fprop("Environment", "TangentAttenuation", name="Friction")
    closed: bprop("Environment", "Closed")
    use_camera: BoolProperty(name="Viewer camera", default=True,
                             description="Write <Camera> (softsub view and render only)")
    eye: vprop("Camera", "Eye")
    vertical_angle: fprop("Camera", "VerticalAngle")
    horizontal_angle: fprop("Camera", "HorizontalAngle")
    fluid_fluid: PointerProperty(type=SoftsubInteraction)
    fluid_object: PointerProperty(type=SoftsubInteractionFO)
    pairs: CollectionProperty(type=SoftsubPair)
    write_pdc: BoolProperty(name="PDC", default=False, description="Also write Maya particle caches (pdc/)")
    write_mesh: BoolProperty(name="Surface meshes", default=False,
                             description="Also mesh each fluid's surface per frame (mesh/*.obj; slow)")
    write_vdb: BoolProperty(name="Surface VDB", default=False,
                            description="Also write each fluid's surface as an OpenVDB level set (vdb/*.vdb)")
    adaptive: BoolProperty(name="Adaptive substeps", default=False,
                           description="softsub run --adaptive: substeps chosen per frame so stiff scenes stay stable")
    import_after_run: BoolProperty(name="Import when done", default=True,
                                   description="Import the results when the run ends")
    set_frame_range: BoolProperty(name="Set frame range on import", default=True,
                                  description="Make the scene's End frame the last simulated frame")
    # shown while a run is going on
    running: BoolProperty(default=False, options={"SKIP_SAVE"})
    run_frame: IntProperty(default=-1, options={"SKIP_SAVE"})
    run_total: IntProperty(default=0, options={"SKIP_SAVE"})


class SoftsubBody(bpy.types.PropertyGroup):
    enabled: BoolProperty(name="Rigid body", default=False,
                          description="This mesh is a softsub rigid body (<Object>)")
    order: IntProperty(name="Order", default=0, min=0,
                       description="Position in the scene file (softsub keeps the scene's order of fluids, fills "
                                   "and bodies: it numbers output and default names)")
    is_dynamic: bprop("Object", "IsDynamic", name="Dynamic")
    mass: fprop("Object", "Mass")
    normal_attenuation: fprop("Object", "NormalAttenuation", name="Restitution")
    tangent_attenuation: fprop("Object", "TangentAttenuation", name="Friction")
    initial_linear_velocity: vprop("Object", "InitialLinearVelocity", name="Initial velocity",
                                   subtype="VELOCITY")
    initial_angular_velocity: vprop("Object", "InitialAngularVelocity", name="Initial spin (deg/s)",
                                    subtype="XYZ")
    shape: EnumProperty(name="Inertia", description=_tip("Object", "Shape"), default="MESH", items=[
        ("MESH", "Mesh (exact)", "The exact inertia of the closed mesh"),
        ("BOX", "Box", "A box's inertia"), ("SPHERE", "Sphere", "A sphere's inertia"),
        ("CYLINDER", "Cylinder", "A cylinder's inertia (axis along Blender Z)"),
        ("CONE", "Cone", "A cone's inertia (axis along Blender Z, base at -height/4)")])
    primitive_only: BoolProperty(
        name="Primitive only", default=False,
        description="Write only the primitive (Shape and Size, no mesh file): the Blender mesh is just its "
                    "picture")
    size: FloatVectorProperty(
        name="Size", size=3, min=0.0, precision=3, default=(0.0, 0.0, 0.0),
        description=_tip("Object", "Size", "; sphere: radius; cone/cylinder: radius, height; box: width (X), "
                                           "height (Z), depth (Y); all 0 with a mesh: fitted"))
    particle_size: FloatProperty(name="Particle size", min=0.0, default=0.0, precision=3,
                                 description=_tip("Object", "ParticleSize", "; 0 here: that default"))


def _update_look(self, context):
    """Colour and particle size changes show at once on the substance's points."""
    from . import display
    obj = self.id_data
    if isinstance(obj, bpy.types.Object) and obj.modifiers.get(display.GROUP):
        display.show_as_points(obj, self.particle_size / 2, tuple(self.colour))


class SoftsubFluid(bpy.types.PropertyGroup):
    enabled: BoolProperty(name="Substance", default=False,
                          description="This object's points (mesh vertices or point cloud) are a softsub fluid")
    order: IntProperty(name="Order", default=0, min=0,
                       description="Position in the scene file (softsub keeps the scene's order of fluids, fills "
                                   "and bodies: it numbers output and default names)")
    interaction_distance: fprop("Fluid", "InteractionDistance")
    amplitude: fprop("Fluid", "Amplitude")
    finite_distance: fprop("Fluid", "FiniteDistance")
    minimum_force: fprop("Fluid", "MinimumForce")
    maximum_force: fprop("Fluid", "MaximumForce")
    viscosity: fprop("Fluid", "Viscosity")
    particle_size: fprop("Fluid", "ParticleSize", update=_update_look)
    particle_mass: fprop("Fluid", "ParticleMass")
    initial_speed: vprop("Fluid", "InitialSpeed", name="Initial velocity", subtype="VELOCITY")
    colour: FloatVectorProperty(name="Colour", subtype="COLOR", size=3, min=0.0, max=1.0,
                                default=schema.default("Fluid", "Colour"), description=_tip("Fluid", "Colour"),
                                update=_update_look)


def _fluid_poll(self, obj):
    return obj.softsub_fluid.enabled


class SoftsubFill(bpy.types.PropertyGroup):
    enabled: BoolProperty(name="Fill volume", default=False,
                          description="This mesh is a <Fill> of a substance: softsub fills it when the scene is read")
    order: IntProperty(name="Order", default=0, min=0,
                       description="Position in the scene file (softsub keeps the scene's order of fluids, fills "
                                   "and bodies: it numbers output and default names)")
    fluid: PointerProperty(name="Substance", type=bpy.types.Object, poll=_fluid_poll,
                           description="The substance the fill's particles belong to")
    shape: EnumProperty(name="Shape", default="MESH", description=_tip("Fill", "Shape"), items=[
        ("BOX", "Box", "The mesh's bounding box (axis-aligned in the world)"),
        ("SPHERE", "Sphere", "A sphere at the object's origin, radius half its largest dimension"),
        ("MESH", "Mesh", "The closed mesh itself (written to <name>Geo/)")])
    spacing: fprop("Fill", "Spacing")
    surface: bprop("Fill.mesh", "Surface", name="Surface only")
    outside_objects: bprop("Fill", "OutsideObjects", name="Outside rigid bodies")


class SoftsubCache(bpy.types.PropertyGroup):
    kind: EnumProperty(name="Kind", default="NONE", items=[
        ("NONE", "None", ""), ("FLUID", "Fluid", "particles of a fluid, per frame"),
        ("SURFACE", "Surface", "a fluid's surface mesh, per frame"),
        ("VOLUME", "Volume", "a fluid's surface level set, per frame"),
        ("BODY", "Body", "a rigid body keyframed from the .sim frames")])
    sim_dir: StringProperty(name="Results folder", subtype="DIR_PATH")
    scene_name: StringProperty(name="Scene")
    item_name: StringProperty(name="Fluid or object")
    frame_offset: IntProperty(name="Blender frame of simulation frame 0")
    last_frame: IntProperty(name="Last simulation frame")


CLASSES = (SoftsubInteraction, SoftsubInteractionFO, SoftsubPair, SoftsubSettings, SoftsubBody, SoftsubFluid,
           SoftsubFill, SoftsubCache)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.Scene.softsub = PointerProperty(type=SoftsubSettings)
    bpy.types.Object.softsub_body = PointerProperty(type=SoftsubBody)
    bpy.types.Object.softsub_fluid = PointerProperty(type=SoftsubFluid)
    bpy.types.Object.softsub_fill = PointerProperty(type=SoftsubFill)
    bpy.types.Object.softsub_cache = PointerProperty(type=SoftsubCache)


def unregister():
    for name in ("softsub_cache", "softsub_fill", "softsub_fluid", "softsub_body"):
        delattr(bpy.types.Object, name)
    del bpy.types.Scene.softsub
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
