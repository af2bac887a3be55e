"""The Run button as an artist presses it: Blender with a window (under xvfb-run), the
modal Run operator started from the 3D viewport, its progress followed while Blender
stays responsive, then a second run stopped half-way with the Stop button. Optionally
writes the docs' screenshots (--screenshots DIR).

xvfb-run -a blender --factory-startup --python-exit-code 1 --python gui_run.py -- \
    --softsub SOFTSUB --zip softsub_blender.zip --work DIR [--screenshots DIR]"""
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_test_util import args, check, empty_scene, finish, install_addon  # noqa: E402

A = args()
install_addon(A)
from softsub_blender import caches  # noqa: E402

work = A["work"]
shots = A.get("screenshots")
state = {"step": "start", "frames_seen": set(), "t": time.time()}


def view3d():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return win, area, region


# The first run's frames: enough that the panel's polls (every 0.05 s) see it at two
# frames at least on a fast or a loaded machine (36 frames were done within one poll, once).
FIRST_RUN = 150


def build():
    empty_scene()
    scene = bpy.context.scene
    s = scene.softsub
    s.scene_path = os.path.join(work, "gui.scene")
    s.use_scene_range = False
    s.frames = FIRST_RUN
    s.substeps = 8
    s.width = s.depth = 14.0
    s.height = 12.0
    bpy.ops.mesh.primitive_plane_add(size=10, location=(0, 0, 0.4), rotation=(0.15, 0, 0))
    bpy.context.active_object.name = "Ramp"
    bpy.ops.softsub.make_body(dynamic=False)
    bpy.ops.mesh.primitive_cube_add(size=2, location=(-2.5, 0, 4.0), rotation=(0.4, 0.3, 0))
    bpy.context.active_object.name = "Crate"
    bpy.ops.softsub.make_body(dynamic=True)
    bpy.context.active_object.softsub_body.mass = 3.0
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.6, location=(1.8, 0, 5.0))
    bpy.context.active_object.name = "Blob"
    bpy.ops.softsub.fill_mesh(spacing=0.4, name="goo")
    goo = bpy.data.objects["goo"]
    goo.softsub_fluid.viscosity = 5.0
    goo.softsub_fluid.amplitude = 40.0
    goo.softsub_fluid.minimum_force = -30.0
    goo.softsub_fluid.colour = (0.25, 0.75, 0.2)
    bpy.ops.softsub.show_container()


def screenshot(name, area=None):
    if not shots:
        return
    os.makedirs(shots, exist_ok=True)
    path = os.path.join(shots, name)
    win, a, region = view3d()
    with bpy.context.temp_override(window=win, area=area or a, region=region):
        bpy.ops.screen.screenshot_area(filepath=path)
    # smaller for the docs: 3/4 size, RGB, most compression
    img = bpy.data.images.load(path)
    img.scale(img.size[0] * 3 // 4, img.size[1] * 3 // 4)
    settings = bpy.context.scene.render.image_settings
    settings.file_format, settings.color_mode, settings.compression = "PNG", "RGB", 100
    img.save_render(path)
    bpy.data.images.remove(img)
    print("screenshot", path, os.path.getsize(path), flush=True)


def tick():
    s = bpy.context.scene.softsub
    win, area, region = view3d()
    step = state["step"]
    if time.time() - state["t"] > 240:
        check(False, f"stuck at step {step}")
        return end()
    if step == "start" and shots:
        # close the splash and open the sidebar's Soft Substances tab as a user would
        win.event_simulate(type="ESC", value="PRESS")
        win.event_simulate(type="ESC", value="RELEASE")
        area.spaces.active.show_region_ui = True
        state["step"] = "tab"
        return 0.5
    if step == "tab":
        ui = next(r for r in area.regions if r.type == "UI")
        x, y = ui.x + ui.width - 8, area.y + area.height - 245
        win.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
        win.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=y)
        win.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x, y=y)
        # and drag the sidebar wider, so the labels are readable
        x, y = ui.x + 1, ui.y + ui.height // 2
        win.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
        win.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=y)
        win.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x - 110, y=y)
        win.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x - 110, y=y)
        state["step"] = "start2"
        return 0.5
    if step in ("start", "start2"):
        build()
        space = area.spaces.active
        space.show_region_ui = True
        ui = next(r for r in area.regions if r.type == "UI")
        if hasattr(ui, "active_panel_category"):
            ui.active_panel_category = "Soft Substances"
        space.region_3d.view_perspective = "PERSP"
        with bpy.context.temp_override(window=win, area=area, region=region):
            bpy.ops.view3d.view_axis(type="FRONT")
            bpy.ops.view3d.view_all()
        space.shading.type = "SOLID"
        space.shading.color_type = "MATERIAL"
        for o in bpy.context.selected_objects:
            o.select_set(False)
        bpy.context.view_layer.objects.active = bpy.data.objects["goo"]
        state["step"] = "shot-setup"
        return 0.5
    if step == "shot-setup":
        screenshot("blender-panel.png")
        with bpy.context.temp_override(window=win, area=area, region=region):
            res = bpy.ops.softsub.run("INVOKE_DEFAULT")
        check(res == {"RUNNING_MODAL"}, f"Run did not start as a modal operator: {res}")
        state["step"] = "running"
        return 0.05
    if step == "running":
        if s.running:
            state["frames_seen"].add(s.run_frame)
            return 0.05
        seen = sorted(x for x in state["frames_seen"] if x >= 0)
        # Two different frames show that the panel follows the run.
        check(len(seen) >= 2, f"the panel showed progress for only frames {seen}")
        goo_sim = bpy.data.objects.get("goo_sim")
        check(goo_sim is not None, "the results were not imported after the run")
        check(bpy.context.scene.frame_end == 1 + FIRST_RUN, f"frame_end {bpy.context.scene.frame_end}")
        bpy.context.scene.frame_set(1 + FIRST_RUN)
        state["step"] = "shot-result"
        return 0.5
    if step == "shot-result":
        screenshot("blender-result.png")
        # a second, long run, stopped from the panel
        s.frames = 2000
        with bpy.context.temp_override(window=win, area=area, region=region):
            bpy.ops.softsub.run("INVOKE_DEFAULT")
        state["step"] = "stopping"
        return 0.05
    if step == "stopping":
        if s.running and s.run_frame >= 3:
            check(bpy.ops.softsub.stop() == {"FINISHED"}, "Stop failed")
            state["step"] = "stopped"
        elif not s.running:
            check(False, "the long run ended before it could be stopped")
            return end()
        return 0.05
    if step == "stopped":
        if s.running:
            return 0.05
        scan = caches.scan_sim_folder(os.path.join(work, "guiSim"))
        last = scan["frames"][-1]
        check(3 <= last < 2000 and last == s.run_frame, f"the stopped run wrote frames 0..{last}, said {s.run_frame}")
        if last < FIRST_RUN:  # the fresh run removed the first run's later frames
            check(not os.path.exists(os.path.join(work, "guiSim", f"gui.{last + 1:04d}.sim")), "a stale frame")
        goo_sim = bpy.data.objects.get("goo_sim")
        check(goo_sim is not None and goo_sim.softsub_cache.last_frame == last,
              "the complete frames of the stopped run were not imported")
        check(bpy.context.scene.frame_end == 1 + last, f"frame_end {bpy.context.scene.frame_end} after a stop")
        return end()
    return None


def end():
    finish()  # prints the verdict, removes Blender's session folder, exits


bpy.app.timers.register(tick, first_interval=0.5)
