"""Shared by the Blender test scripts: arguments, installing the add-on from its zip
into a throw-away user folder, assertions that name what differs."""
import os
import sys

import bpy


def args():
    """--softsub EXE --zip ZIP --work DIR [--source DIR] after Blender's '--'."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out = {}
    for i in range(0, len(argv) - 1, 2):
        out[argv[i].lstrip("-")] = argv[i + 1]
    for k in ("softsub", "zip", "work"):
        if k not in out:
            raise SystemExit(f"usage: blender -b --python SCRIPT -- --softsub EXE --zip ZIP --work DIR (missing --{k})")
    import shutil
    shutil.rmtree(out["work"], ignore_errors=True)  # each run starts from nothing
    os.makedirs(out["work"])
    return out


def install_addon(a):
    """Installs softsub_blender.zip as a user would (Preferences > Add-ons > Install),
    enables it and points it at the softsub under test."""
    scripts = os.path.join(a["work"], "user-scripts")
    os.makedirs(os.path.join(scripts, "addons"), exist_ok=True)
    os.environ["BLENDER_USER_SCRIPTS"] = scripts
    res = bpy.ops.preferences.addon_install(filepath=a["zip"], overwrite=True, target="DEFAULT")
    check(res == {"FINISHED"}, f"addon_install: {res}")
    import addon_utils
    addon_utils.modules_refresh()
    res = bpy.ops.preferences.addon_enable(module="softsub_blender")
    check(res == {"FINISHED"}, f"addon_enable: {res}")
    installed = os.path.join(bpy.utils.user_resource("SCRIPTS", path="addons"), "softsub_blender", "__init__.py")
    check(os.path.exists(installed), f"the add-on is not installed at {installed}")
    prefs = bpy.context.preferences.addons["softsub_blender"].preferences
    prefs.executable = a["softsub"]
    check(hasattr(bpy.types.Scene, "softsub") and hasattr(bpy.ops.softsub, "run"), "operators not registered")
    import softsub_blender
    check(os.path.dirname(softsub_blender.__file__) == os.path.dirname(installed),
          f"the add-on was loaded from {softsub_blender.__file__}, not from the installed zip")


def empty_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    for c in list(bpy.data.collections):
        bpy.data.collections.remove(c)


FAILURES = []


def check(cond, msg):
    if not cond:
        FAILURES.append(msg)
        print("FAIL:", msg, flush=True)
        if len(FAILURES) > 20:
            finish()
    return cond


def close(a, b, tol):
    return all(abs(x - y) <= tol * max(1.0, abs(x), abs(y)) for x, y in zip(a, b)) and len(a) == len(b)


def finish():
    # os._exit skips Blender's own clean-up, which would remove its session folder
    # (/tmp/blender_XXXXXX): remove it here, or every test run leaves one behind.
    import shutil
    if bpy.app.tempdir:
        shutil.rmtree(bpy.app.tempdir, ignore_errors=True)
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", flush=True)
        sys.stdout.flush()
        os._exit(1)
    print("all checks passed", flush=True)
    sys.stdout.flush()
    os._exit(0)
