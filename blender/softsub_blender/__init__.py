"""softsub for Blender: mark substances and rigid bodies, export a .scene, run softsub
in a separate process, import the results. See docs/blender.md.

The file formats (scenefile, caches, axes, runner, schema) are plain Python modules
without bpy; everything that touches Blender is in props, bl_scene, results, display,
ops and ui."""

bl_info = {
    "name": "softsub: Soft Substances",
    "author": "softsub",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Soft Substances",
    "description": "Viscous substances and rigid bodies simulated by softsub: export, run, import",
    "doc_url": "https://github.com/softsub/softsub/blob/main/docs/blender.md",
    "category": "Physics",
}

try:
    import bpy
except ImportError:  # the format modules are used without Blender too (tests)
    bpy = None

if bpy is not None:
    from bpy.props import StringProperty

    class SoftsubPreferences(bpy.types.AddonPreferences):
        bl_idname = __name__

        executable: StringProperty(
            name="softsub executable", subtype="FILE_PATH", default="",
            description="Path of the softsub program; empty: 'softsub' found on the PATH")

        def draw(self, context):
            self.layout.prop(self, "executable")
            self.layout.label(text="Empty: 'softsub' on the PATH.")

    def register():
        from . import ops, props, results, ui
        bpy.utils.register_class(SoftsubPreferences)
        props.register()
        ops.register()
        ui.register()
        results.register()

    def unregister():
        from . import ops, props, results, ui
        results.unregister()
        ui.unregister()
        ops.unregister()
        props.unregister()
        bpy.utils.unregister_class(SoftsubPreferences)
