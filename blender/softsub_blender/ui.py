"""The "Soft Substances" tab of the 3D viewport's sidebar (N)."""
import bpy

from .props import FUNCTION_PARAMS


class SoftsubPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Soft Substances"


class SOFTSUB_PT_main(SoftsubPanel, bpy.types.Panel):
    bl_label = "Soft Substances"

    def draw(self, context):
        s = context.scene.softsub
        col = self.layout.column(align=True)
        col.label(text="Mark selected:")
        row = col.row(align=True)
        row.operator("softsub.make_body", text="Rigid Body", icon="MESH_CUBE").dynamic = True
        row.operator("softsub.make_body", text="Static", icon="MESH_PLANE").dynamic = False
        row = col.row(align=True)
        row.operator("softsub.make_substance", text="Substance", icon="OUTLINER_OB_POINTCLOUD")
        row.operator("softsub.fill_mesh", text="Fill with Particles", icon="MOD_PARTICLES")
        row = col.row(align=True)
        row.operator("softsub.make_fill", text="Fill Volume", icon="MOD_WIREFRAME")
        row.operator("softsub.unmark", text="Unmark", icon="X")
        self.layout.separator()
        self.layout.prop(s, "scene_path")
        if s.running:
            box = self.layout.box()
            box.label(text=f"Running: frame {max(s.run_frame, 0)} / {s.run_total}", icon="TIME")
            box.operator("softsub.stop", icon="CANCEL")
        else:
            row = self.layout.row(align=True)
            row.operator("softsub.export", icon="EXPORT")
            row.operator("softsub.run", icon="PLAY")
        row = self.layout.row(align=True)
        row.operator("softsub.import_results", icon="IMPORT")
        row.operator("softsub.clear_results", text="Clear", icon="TRASH")
        self.layout.operator("softsub.import_scene", icon="FILE_FOLDER")


class SOFTSUB_PT_object(SoftsubPanel, bpy.types.Panel):
    bl_label = "Active Object"
    bl_parent_id = "SOFTSUB_PT_main"

    @classmethod
    def poll(cls, context):
        return context.active_object is not None

    def draw(self, context):
        o = context.active_object
        lay = self.layout
        if o.softsub_cache.kind != "NONE":
            c = o.softsub_cache
            lay.label(text=f"Imported {c.kind.lower()} '{c.item_name}' of '{c.scene_name}'", icon="INFO")
            lay.prop(c, "sim_dir")
            lay.prop(c, "frame_offset")
        if o.softsub_body.enabled:
            b = o.softsub_body
            lay.label(text=f"Rigid body '{o.name}'", icon="MESH_CUBE")
            lay.prop(b, "is_dynamic")
            col = lay.column(align=True)
            col.prop(b, "mass")
            col.prop(b, "normal_attenuation")
            col.prop(b, "tangent_attenuation")
            lay.prop(b, "initial_linear_velocity")
            lay.prop(b, "initial_angular_velocity")
            lay.prop(b, "shape")
            if b.shape != "MESH":
                lay.prop(b, "primitive_only")
                lay.prop(b, "size")
            lay.prop(b, "particle_size")
        elif o.softsub_fluid.enabled:
            f = o.softsub_fluid
            lay.label(text=f"Substance '{o.name}'", icon="OUTLINER_OB_POINTCLOUD")
            col = lay.column(align=True)
            for p in ("amplitude", "finite_distance", "minimum_force", "maximum_force", "interaction_distance"):
                col.prop(f, p)
            col = lay.column(align=True)
            for p in ("viscosity", "particle_size", "particle_mass"):
                col.prop(f, p)
            lay.prop(f, "initial_speed")
            lay.prop(f, "colour")
        elif o.softsub_fill.enabled:
            f = o.softsub_fill
            lay.label(text=f"Fill volume '{o.name}'", icon="MOD_WIREFRAME")
            lay.prop(f, "fluid")
            lay.prop(f, "shape")
            lay.prop(f, "spacing")
            if f.shape == "MESH":
                lay.prop(f, "surface")
            lay.prop(f, "outside_objects")
        elif o.softsub_cache.kind == "NONE":
            lay.label(text="Not part of the simulation")


class SOFTSUB_PT_simulation(SoftsubPanel, bpy.types.Panel):
    bl_label = "Simulation"
    bl_parent_id = "SOFTSUB_PT_main"

    def draw(self, context):
        s = context.scene.softsub
        lay = self.layout
        lay.prop(s, "use_scene_fps")
        if not s.use_scene_fps:
            lay.prop(s, "fps")
        lay.prop(s, "use_scene_range")
        if not s.use_scene_range:
            lay.prop(s, "frames")
        lay.prop(s, "substeps")
        lay.prop(s, "adaptive")
        lay.prop(s, "gravity")
        lay.prop(s, "integrator")
        lay.label(text="Also write:")
        row = lay.row(align=True)
        row.prop(s, "write_pdc", toggle=True)
        row.prop(s, "write_mesh", toggle=True)
        row.prop(s, "write_vdb", toggle=True)
        lay.prop(s, "import_after_run")
        lay.prop(s, "set_frame_range")


class SOFTSUB_PT_container(SoftsubPanel, bpy.types.Panel):
    bl_label = "Container"
    bl_parent_id = "SOFTSUB_PT_main"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context):
        self.layout.prop(context.scene.softsub, "use_container", text="")

    def draw(self, context):
        s = context.scene.softsub
        lay = self.layout
        lay.active = s.use_container
        col = lay.column(align=True)
        col.prop(s, "width")
        col.prop(s, "depth")
        col.prop(s, "height")
        col = lay.column(align=True)
        col.prop(s, "normal_attenuation")
        col.prop(s, "tangent_attenuation")
        lay.prop(s, "closed")
        lay.prop(s, "reflective")
        lay.operator("softsub.show_container", icon="CUBE")


def draw_interaction(lay, p):
    lay.prop(p, "function")
    col = lay.column(align=True)
    if p.function == "Curve":
        col.prop(p, "curve_points")
    for prop, kind, _ in FUNCTION_PARAMS:
        if kind == p.function:
            col.prop(p, prop)
    col = lay.column(align=True)
    col.prop(p, "damping")
    col.prop(p, "relative_velocity")


class SOFTSUB_PT_interactions(SoftsubPanel, bpy.types.Panel):
    bl_label = "Interactions"
    bl_parent_id = "SOFTSUB_PT_main"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        s = context.scene.softsub
        lay = self.layout
        box = lay.box()
        box.label(text="Between two substances (FluidFluid)")
        draw_interaction(box, s.fluid_fluid)
        box = lay.box()
        box.label(text="Substance and rigid body (FluidObject)")
        draw_interaction(box, s.fluid_object)
        for i, p in enumerate(s.pairs):
            box = lay.box()
            row = box.row()
            row.label(text=f"Pair {i + 1}")
            row.operator("softsub.pair_remove", text="", icon="X").index = i
            row = box.row(align=True)
            row.prop(p, "a", text="")
            row.prop(p, "b", text="")
            draw_interaction(box, p)
        lay.operator("softsub.pair_add", icon="ADD")


class SOFTSUB_PT_camera(SoftsubPanel, bpy.types.Panel):
    bl_label = "Viewer Camera"
    bl_parent_id = "SOFTSUB_PT_main"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context):
        self.layout.prop(context.scene.softsub, "use_camera", text="")

    def draw(self, context):
        s = context.scene.softsub
        self.layout.active = s.use_camera
        self.layout.prop(s, "eye")
        self.layout.prop(s, "vertical_angle")
        self.layout.prop(s, "horizontal_angle")


CLASSES = (SOFTSUB_PT_main, SOFTSUB_PT_object, SOFTSUB_PT_simulation, SOFTSUB_PT_container,
           SOFTSUB_PT_interactions, SOFTSUB_PT_camera)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
