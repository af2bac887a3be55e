#!/usr/bin/env python3
"""Packs the add-on into softsub_blender.zip (Edit > Preferences > Add-ons > Install).

    python3 blender/make_zip.py [OUTPUT.zip]     (default: ./softsub_blender.zip)
"""
import os
import sys
import zipfile

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "softsub_blender.zip")
tmp = out + ".tmp"
with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
    src = os.path.join(here, "softsub_blender")
    for name in sorted(os.listdir(src)):
        if name.endswith(".py"):
            info = zipfile.ZipInfo(f"softsub_blender/{name}", date_time=(2024, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            with open(os.path.join(src, name), "rb") as f:
                z.writestr(info, f.read())
os.replace(tmp, out)
print(out)
