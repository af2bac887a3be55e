"""The panel's operators: mark, fill, export, run (a separate softsub process, modal,
cancellable), import results, import a .scene, clear."""
import os
import tempfile

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from . import axes, bl_scene, caches, display, results, runner, schema
from .caches import CacheError
from .runner import RunnerError
from .scenefile import FLUID_NAME, SceneError

ERRORS = (SceneError, CacheError, RunnerError, OSError)


def executable(context):
    prefs = context.preferences.addons.get(__package__)
    exe = prefs.preferences.executable.strip() if prefs else ""
    return bpy.path.abspath(exe) if exe else "softsub"


def _selected_meshes(context, types=("MESH",)):
    return [o for o in context.selected_objects if o.type in types]


class SOFTSUB_OT_make_body(bpy.types.Operator):
    """Make the selected meshes softsub rigid bodies (their pose at the start frame is the initial pose)"""
    bl_idname = "softsub.make_body"
    bl_label = "Rigid Body"
    bl_options = {"REGISTER", "UNDO"}

    dynamic: BoolProperty(name="Dynamic", default=True, description="Dynamic (moves) or static (never moves)")

    def execute(self, context):
        objs = _selected_meshes(context)
        if not objs:
            self.report({"ERROR"}, "select one or more meshes")
            return {"CANCELLED"}
        for o in objs:
            if not o.softsub_body.enabled:
                o.softsub_body.order = bl_scene.next_order("softsub_body")
            o.softsub_body.enabled = True
            o.softsub_body.is_dynamic = self.dynamic
            o.softsub_fluid.enabled = False
            o.softsub_fill.enabled = False
        self.report({"INFO"}, f"{len(objs)} rigid bodies ({'dynamic' if self.dynamic else 'static'})")
        return {"FINISHED"}


class SOFTSUB_OT_make_substance(bpy.types.Operator):
    """Make the selected meshes' vertices (or point clouds' points) softsub substances"""
    bl_idname = "softsub.make_substance"
    bl_label = "Substance from Points"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        objs = _selected_meshes(context, ("MESH", "POINTCLOUD"))
        if not objs:
            self.report({"ERROR"}, "select meshes or point clouds")
            return {"CANCELLED"}
        bad = [o.name for o in objs if not FLUID_NAME.match(o.name)]
        for o in objs:
            if not o.softsub_fluid.enabled:
                o.softsub_fluid.order = bl_scene.next_order("softsub_fluid")
            o.softsub_fluid.enabled = True
            o.softsub_body.enabled = False
            o.softsub_fill.enabled = False
        msg = f"{len(objs)} substances"
        if bad:
            self.report({"WARNING"}, msg + f"; rename {', '.join(bad)}: a substance's name may hold only "
                                           "letters, digits, _ and -")
        else:
            self.report({"INFO"}, msg)
        return {"FINISHED"}


class SOFTSUB_OT_fill_mesh(bpy.types.Operator):
    """Fill the active mesh with a lattice of particles (softsub fill) as a new substance"""
    bl_idname = "softsub.fill_mesh"
    bl_label = "Fill with Particles"
    bl_options = {"REGISTER", "UNDO"}

    spacing: FloatProperty(name="Spacing", default=0.5, min=1e-4, precision=3,
                           description="Distance between particles (= their diameter), scene units")
    surface: BoolProperty(name="Surface only", default=False, description="A shell one particle thick")
    name: StringProperty(name="Substance name", default="",
                         description="Name of the new substance (letters, digits, _ and -); "
                                     "default: the mesh's name made valid")
    hide_mesh: BoolProperty(name="Hide the mesh", default=True)

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        src = context.active_object
        if src is None or src.type != "MESH":
            self.report({"ERROR"}, "make a mesh the active object")
            return {"CANCELLED"}
        name = self.name or "".join(c if c.isalnum() or c in "_-" else "_" for c in src.name) + "_goo"
        if not FLUID_NAME.match(name):
            self.report({"ERROR"}, f"'{name}': a substance's name may hold only letters, digits, _ and -")
            return {"CANCELLED"}
        if name in bpy.data.objects:
            self.report({"ERROR"}, f"an object named '{name}' already exists")
            return {"CANCELLED"}
        depsgraph = context.evaluated_depsgraph_get()
        verts, tris = bl_scene._evaluated_mesh_data(src, depsgraph)
        if not tris:
            self.report({"ERROR"}, f"'{src.name}' has no faces to fill")
            return {"CANCELLED"}
        mw = src.matrix_world
        world = [axes.to_softsub(tuple(mw @ bl_scene._vec(v))) for v in verts]
        try:
            with tempfile.TemporaryDirectory(prefix="softsub-fill-") as tmp:
                obj_path, ply_path = os.path.join(tmp, "mesh.obj"), os.path.join(tmp, "fill.ply")
                caches.write_obj(obj_path, src.name, world, tris, schema.format_double)
                cmd = [executable(context), "fill", obj_path, "--spacing", repr(self.spacing), "--out", ply_path,
                       "--quiet"] + (["--surface"] if self.surface else [])
                code, _, err = runner.run_tool(cmd, timeout=600)
                if code != 0:
                    self.report({"ERROR"}, "softsub fill: " + runner.error_line(err, code))
                    return {"CANCELLED"}
                ply = caches.read_ply(ply_path)
        except ERRORS as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        cols = ply["columns"]
        pts = [axes.to_blender((x, y, z)) for x, y, z in zip(cols["x"], cols["y"], cols["z"])]
        if not pts:
            self.report({"ERROR"}, f"no particle fits in '{src.name}' at spacing {self.spacing:g}: lower it")
            return {"CANCELLED"}
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata(pts, [], [])
        obj = bpy.data.objects.new(name, mesh)
        (src.users_collection[0] if src.users_collection else context.scene.collection).objects.link(obj)
        fp = obj.softsub_fluid
        fp.order = bl_scene.next_order("softsub_fluid")
        fp.enabled = True
        # the seed's proportions for a lattice of this step (as `softsub fill --scene-snippet`)
        fp.particle_size = self.spacing
        fp.finite_distance = self.spacing
        fp.interaction_distance = 1.5 * self.spacing
        display.show_as_points(obj, self.spacing / 2, tuple(fp.colour))
        if self.hide_mesh:
            src.hide_set(True)
            src.hide_render = True
        for o in context.selected_objects:
            o.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        self.report({"INFO"}, f"'{name}': {len(pts)} particles")
        return {"FINISHED"}


def _substance_items(self, context):
    items = [(o.name, o.name, "") for o in context.scene.objects if o.softsub_fluid.enabled]
    return items or [("", "(no substance)", "")]


class SOFTSUB_OT_make_fill(bpy.types.Operator):
    """Make the selected meshes fill volumes of a substance: softsub fills them when it reads the scene"""
    bl_idname = "softsub.make_fill"
    bl_label = "Fill Volume"
    bl_options = {"REGISTER", "UNDO"}

    substance: EnumProperty(name="Substance", items=_substance_items)
    shape: EnumProperty(name="Shape", default="MESH", items=[
        ("MESH", "Mesh", "The closed mesh"), ("BOX", "Box", "Its world bounding box"),
        ("SPHERE", "Sphere", "A sphere at its origin, radius half its largest dimension")])
    spacing: FloatProperty(name="Spacing", default=1.0, min=1e-4, precision=3)

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        fluid = bpy.data.objects.get(self.substance)
        objs = [o for o in _selected_meshes(context) if o != fluid]
        if fluid is None or not objs:
            self.report({"ERROR"}, "select meshes and choose a substance")
            return {"CANCELLED"}
        for o in objs:
            f = o.softsub_fill
            if not f.enabled:
                f.order = bl_scene.next_order("softsub_fill")
            f.enabled, f.fluid, f.shape, f.spacing = True, fluid, self.shape, self.spacing
            o.softsub_body.enabled = False
            o.softsub_fluid.enabled = False
            display.show_as_fill(o)
        self.report({"INFO"}, f"{len(objs)} fill volumes of '{fluid.name}'")
        return {"FINISHED"}


class SOFTSUB_OT_unmark(bpy.types.Operator):
    """Remove the softsub marks (rigid body, substance, fill) from the selected objects"""
    bl_idname = "softsub.unmark"
    bl_label = "Unmark"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        for o in context.selected_objects:
            o.softsub_body.enabled = o.softsub_fluid.enabled = o.softsub_fill.enabled = False
        return {"FINISHED"}


class SOFTSUB_OT_export(bpy.types.Operator):
    """Write the scene file and its meshes (<name>.scene, <name>Geo/) for softsub run"""
    bl_idname = "softsub.export"
    bl_label = "Export"

    def execute(self, context):
        try:
            path, model = bl_scene.export(context)
        except ERRORS as e:
            self.report({"ERROR"}, f"export: {e}")
            return {"CANCELLED"}
        self.report({"INFO"}, f"wrote {path}: {len(model['fluids'])} substances, {len(model['objects'])} bodies")
        return {"FINISHED"}


_ACTIVE = {"runner": None}


class SOFTSUB_OT_run(bpy.types.Operator):
    """Export, then simulate with softsub in a separate process (Esc or Stop to stop), then import"""
    bl_idname = "softsub.run"
    bl_label = "Run"

    wait: BoolProperty(name="Wait", default=False, options={"SKIP_SAVE"},
                       description="Block until the run ends (scripts; always so without a window)")

    def _start(self, context):
        path, model = bl_scene.export(context)
        _, name, _, _, sim_dir = bl_scene.scene_paths(context)
        s = context.scene.softsub
        formats = ",".join(["sim", "ply"] + (["pdc"] if s.write_pdc else []) + (["mesh"] if s.write_mesh else [])
                           + (["vdb"] if s.write_vdb else []))
        extra = ["--adaptive"] if s.adaptive else []
        cmd = runner.run_command(executable(context), path, sim_dir, formats, extra)
        self.sim_dir, self.scene_name = sim_dir, name
        self.runner = runner.Runner(cmd, model["Simulation"]["Frames"])
        _ACTIVE["runner"] = self.runner
        s.running, s.run_frame, s.run_total = True, -1, model["Simulation"]["Frames"]

    def _finish(self, context):
        s = context.scene.softsub
        s.running = False
        s.run_frame = self.runner.frame
        _ACTIVE["runner"] = None
        if context.workspace:
            context.workspace.status_text_set(None)
        r = self.runner
        code = r.proc.returncode
        msg = r.message()
        if code not in (0, 130):
            self.report({"ERROR"}, msg)
            return {"CANCELLED"}
        if s.import_after_run and r.frame >= 0:
            try:
                msg += "; " + results.import_results(context, self.sim_dir, self.scene_name)
            except ERRORS as e:
                self.report({"ERROR"}, f"{msg}; import: {e}")
                return {"CANCELLED"}
        # A warning is about the result (it may blow up, an object flies off): it is
        # shown as one, not as a plain "done".
        self.report({"WARNING"} if code == 130 or r.warnings() else {"INFO"}, msg)
        return {"FINISHED"}

    def execute(self, context):
        if _ACTIVE["runner"] is not None:
            self.report({"ERROR"}, "a run is already going on")
            return {"CANCELLED"}
        try:
            self._start(context)
        except ERRORS as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        if self.wait or bpy.app.background or context.window is None:
            self.runner.wait()
            return self._finish(context)
        wm = context.window_manager
        self.timer = wm.event_timer_add(0.2, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def invoke(self, context, event):
        return self.execute(context)

    def modal(self, context, event):
        s = context.scene.softsub
        if event.type == "ESC" and event.value == "PRESS":
            self.runner.cancel()
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        frame = self.runner.poll()
        s.run_frame = frame
        if context.workspace:
            state = "stopping" if self.runner.cancelled else "Esc to stop"
            context.workspace.status_text_set(
                f"softsub: frame {max(frame, 0)}/{self.runner.total} ({100 * self.runner.progress():.0f}%), {state}")
        for area in context.screen.areas if context.screen else []:
            if area.type == "VIEW_3D":
                area.tag_redraw()
        if self.runner.done() is None:
            return {"PASS_THROUGH"}
        self.runner.wait()
        context.window_manager.event_timer_remove(self.timer)
        return self._finish(context)


class SOFTSUB_OT_stop(bpy.types.Operator):
    """Stop the run: softsub finishes the frame in progress and stops; the complete frames are imported"""
    bl_idname = "softsub.stop"
    bl_label = "Stop"

    def execute(self, context):
        r = _ACTIVE["runner"]
        if r is None:
            return {"CANCELLED"}
        r.cancel()
        return {"FINISHED"}


class SOFTSUB_OT_import_results(bpy.types.Operator):
    """Import a results folder (<name>Sim/): bodies keyframed, fluids as point clouds, surfaces"""
    bl_idname = "softsub.import_results"
    bl_label = "Import Results"
    bl_options = {"REGISTER", "UNDO"}

    directory: StringProperty(subtype="DIR_PATH", default="")

    def invoke(self, context, event):
        try:
            self.directory = bl_scene.scene_paths(context)[4] + os.sep
        except SceneError:
            pass
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        d = self.directory or bl_scene.scene_paths(context)[4]
        try:
            msg = results.import_results(context, bpy.path.abspath(d))
        except ERRORS as e:
            self.report({"ERROR"}, f"import: {e}")
            return {"CANCELLED"}
        self.report({"INFO"}, msg)
        return {"FINISHED"}


class SOFTSUB_OT_clear_results(bpy.types.Operator):
    """Remove the imported results (fluids, surfaces, the bodies' imported keyframes)"""
    bl_idname = "softsub.clear_results"
    bl_label = "Clear Results"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        n = results.clear_results()
        for o in context.scene.objects:
            if o.softsub_fluid.enabled:
                o.hide_set(False)
                o.hide_render = False
        self.report({"INFO"}, f"removed {n} imported results")
        return {"FINISHED"}


class SOFTSUB_OT_import_scene(bpy.types.Operator, ImportHelper):
    """Import a softsub .scene: substances, fill volumes, rigid bodies and every setting"""
    bl_idname = "softsub.import_scene"
    bl_label = "Import .scene"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".scene"
    filter_glob: StringProperty(default="*.scene", options={"HIDDEN"})

    def execute(self, context):
        try:
            coll = bl_scene.import_scene(context, self.filepath)
        except ERRORS as e:
            self.report({"ERROR"}, f"import: {e}")
            return {"CANCELLED"}
        self.report({"INFO"}, f"imported {self.filepath} into collection '{coll.name}'")
        return {"FINISHED"}


class SOFTSUB_OT_pair_add(bpy.types.Operator):
    """Add an interaction override between two substances, or a substance and a rigid body"""
    bl_idname = "softsub.pair_add"
    bl_label = "Add Pair"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        context.scene.softsub.pairs.add()
        return {"FINISHED"}


class SOFTSUB_OT_pair_remove(bpy.types.Operator):
    """Remove this interaction pair"""
    bl_idname = "softsub.pair_remove"
    bl_label = "Remove Pair"
    bl_options = {"REGISTER", "UNDO"}

    index: bpy.props.IntProperty()

    def execute(self, context):
        context.scene.softsub.pairs.remove(self.index)
        return {"FINISHED"}


class SOFTSUB_OT_show_container(bpy.types.Operator):
    """Show (or update) the container as a wire box"""
    bl_idname = "softsub.show_container"
    bl_label = "Show Container"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        display.update_container(context)
        return {"FINISHED"}


def menu_import(self, context):
    self.layout.operator(SOFTSUB_OT_import_scene.bl_idname, text="softsub scene (.scene)")


CLASSES = (SOFTSUB_OT_make_body, SOFTSUB_OT_make_substance, SOFTSUB_OT_fill_mesh, SOFTSUB_OT_make_fill,
           SOFTSUB_OT_unmark, SOFTSUB_OT_export, SOFTSUB_OT_run, SOFTSUB_OT_stop, SOFTSUB_OT_import_results,
           SOFTSUB_OT_clear_results, SOFTSUB_OT_import_scene, SOFTSUB_OT_pair_add, SOFTSUB_OT_pair_remove,
           SOFTSUB_OT_show_container)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
