"""The .scene file: a plain-data model, a reader and a writer. Pure Python, no bpy.

The model is dictionaries keyed by the scene format's own tag names (docs/scene-format.md),
in softsub's coordinates (Y up):

    scene = {"Simulation": {...}, "Camera": {...} or None, "Environment": {...} or None,
             "fluids": [fluid], "objects": [obj],
             "FluidFluid": interaction or None, "FluidObject": interaction or None,
             "pairs": [interaction with "A" and "B"]}
    fluid = {"Name": .., "Viscosity": .., ..., "Particles": [(x, y, z)], "fills": [fill]}
    fill = {"Shape": "box"|"sphere"|"mesh", "Spacing": .., "Min"/"Max" | "Center"/"Radius"
            | "Geometry"/"Surface"}
    obj = {"Name": .., "Geometry"?: .., "Shape"?: .., "Size"?: [..], "ParticleSize"?: ..,
           "UniformScale": .., "InitialPosition": .., ...}
    interaction = {"function": "Linear"|..., "params": {tag: value}, "Damping": ..,
                   "RelativeVelocity": ..}

The reader fills in every default, so two scenes that mean the same thing give equal
models. The writer writes every field explicitly (as softsub's own writer does).
"""
import re
import xml.etree.ElementTree as ET

from . import schema


class SceneError(Exception):
    """A scene that cannot be read or written; the message names the element."""


FLUID_PARAMS = [t for t in schema.tags("Fluid") if t not in ("Name", "NumberOfParticles", "Particles")]
OBJECT_OPTIONAL = ("Name", "Geometry", "Shape", "Size", "ParticleSize")
OBJECT_PARAMS = [t for t in schema.tags("Object") if t not in OBJECT_OPTIONAL]
FILL_TAGS = {"box": ["Min", "Max"], "sphere": ["Center", "Radius"], "mesh": ["Geometry", "Surface"]}
FILL_COMMON = [t for t in schema.tags("Fill") if t != "Shape"]  # Spacing, OutsideObjects
FLUID_NAME = re.compile(r"^[A-Za-z0-9_-]+$")


def defaults(section):
    return {t: schema.default(section, t) for t in schema.tags(section)}


def default_interaction(which):
    """The seed's global functions: FluidFluid Linear(5, 1, 0, 5); FluidObject Linear(5,
    1.5, 0, 5) with RelativeVelocity 2; a Pair's velocity terms are 0."""
    params = defaults("Linear")
    if which == "FluidObject":
        params["Cutoff"] = 1.5
        return {"function": "Linear", "params": params, "Damping": 0.0, "RelativeVelocity": 2.0}
    return {"function": "Linear", "params": params, "Damping": 0.0, "RelativeVelocity": 0.0}


def new_scene():
    """A scene with every setting at its default and no fluid or object."""
    return {"Simulation": defaults("Simulation"), "Camera": defaults("Camera"),
            "Environment": defaults("Environment"), "fluids": [], "objects": [],
            "FluidFluid": default_interaction("FluidFluid"),
            "FluidObject": default_interaction("FluidObject"), "pairs": []}


def new_fluid(name):
    f = {"Name": name}
    f.update({t: schema.default("Fluid", t) for t in FLUID_PARAMS})
    f["Particles"] = []
    f["fills"] = []
    return f


def new_object(name):
    o = {"Name": name}
    o.update({t: schema.default("Object", t) for t in OBJECT_PARAMS})
    return o


# ---------------------------------------------------------------- reading

def _where(path):
    return "/".join(path)


def _children(elem, path, allowed, repeatable=()):
    """{tag: element} of elem's children, refusing unknown and repeated tags."""
    out = {}
    for c in elem:
        if not isinstance(c.tag, str):
            continue
        if c.tag not in allowed:
            raise SceneError(f"{_where(path)}: unknown element <{c.tag}> (allowed: {', '.join(allowed)})")
        if c.tag in repeatable:
            out.setdefault(c.tag, []).append(c)
        elif c.tag in out:
            raise SceneError(f"{_where(path)}/{c.tag}: given twice")
        else:
            out[c.tag] = c
    return out


def _value(section, tag, elem, path):
    kind = schema.row(section, tag)[1]
    try:
        v = schema.parse_value(kind, elem.text or "")
    except ValueError as e:
        raise SceneError(f"{_where(path)}/{tag}: {e}") from None
    if kind in ("real", "int", "vec3", "colour") or tag == "Size":
        problem = schema.check_range(section, tag, v)
        if problem:
            raise SceneError(f"{_where(path)}/{tag}: {problem}")
    return v


def _section(elem, section, path, extra=()):
    tags = schema.tags(section)
    kids = _children(elem, path, tags + list(extra))
    values = {}
    for t in tags:
        d = schema.default(section, t)
        values[t] = _value(section, t, kids[t], path) if t in kids else d
    return values, kids


def _interaction(elem, path, which):
    kids = _children(elem, path, list(schema.FUNCTION_KINDS) + ["Damping", "RelativeVelocity", "A", "B"])
    funcs = [k for k in schema.FUNCTION_KINDS if k in kids]
    if len(funcs) != 1:
        raise SceneError(f"{_where(path)}: needs exactly one function element (allowed: {', '.join(schema.FUNCTION_KINDS)})")
    kind = funcs[0]
    params, _ = _section(kids[kind], kind, path + [kind])
    if kind == "Curve" and params["Points"] is None:
        raise SceneError(f"{_where(path)}/Curve: Points is required")
    vsec = "FluidObject.velocity" if which == "FluidObject" else "FluidFluid.velocity"
    out = {"function": kind, "params": params}
    for t in ("Damping", "RelativeVelocity"):
        out[t] = _value(vsec, t, kids[t], path) if t in kids else schema.default(vsec, t)
    if which == "Pair":
        for t in ("A", "B"):
            if t not in kids:
                raise SceneError(f"{_where(path)}: <{t}> is required")
            out[t] = (kids[t].text or "").strip()
    elif "A" in kids or "B" in kids:
        raise SceneError(f"{_where(path)}: <A> and <B> belong in a <Pair>")
    return out


def read_scene_text(text, name="scene"):
    """Parses scene XML into the model (defaults filled in). Raises SceneError."""
    if isinstance(text, bytes):
        text = text.decode("utf-8-sig")
    # softsub's reader (pugixml) accepts "--" inside comments (examples/softsub-demo.scene
    # has one); Python's expat does not, so comments are blanked first, lines kept.
    text = re.sub(r"<!--.*?-->", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise SceneError(f"{name}: XML: {e}") from None
    if root.tag != "Scene":
        raise SceneError(f"{name}: the root element is <{root.tag}>, not <Scene>")
    path = [name]
    top = _children(root, path, ["Simulation", "Camera", "Environment", "Fluid", "Object", "Interactions"],
                    repeatable=("Fluid", "Object"))
    scene = new_scene()
    scene["Simulation"] = _section(top["Simulation"], "Simulation", path + ["Simulation"])[0] \
        if "Simulation" in top else defaults("Simulation")
    scene["Camera"] = _section(top["Camera"], "Camera", path + ["Camera"])[0] if "Camera" in top else None
    scene["Environment"] = _section(top["Environment"], "Environment", path + ["Environment"])[0] \
        if "Environment" in top else None
    for i, fe in enumerate(top.get("Fluid", []), 1):
        fpath = path + [f"Fluid[{i}]"]
        values, kids = _section(fe, "Fluid", fpath, extra=("Fill",))
        if not values["Name"] or not FLUID_NAME.match(values["Name"]):
            raise SceneError(f"{_where(fpath)}/Name: '{values['Name']}' (allowed: letters, digits, _ and -)")
        fpath[-1] = f"Fluid '{values['Name']}'"
        fluid = new_fluid(values["Name"])
        for t in FLUID_PARAMS:
            fluid[t] = values[t]
        fluid["Particles"] = values["Particles"] or []
        if "NumberOfParticles" in kids and values["NumberOfParticles"] != len(fluid["Particles"]):
            raise SceneError(f"{_where(fpath)}/NumberOfParticles: {values['NumberOfParticles']} but "
                             f"{len(fluid['Particles'])} positions are given")
        for j, fill_e in enumerate([c for c in fe if c.tag == "Fill"], 1):
            fill_path = fpath + [f"Fill[{j}]"]
            shape_e = fill_e.find("Shape")
            shape = (shape_e.text or "").strip() if shape_e is not None else None
            if shape not in FILL_TAGS:
                raise SceneError(f"{_where(fill_path)}/Shape: '{shape}' (allowed: box, sphere, mesh)")
            sec = f"Fill.{shape}"
            kids_f = _children(fill_e, fill_path, ["Shape"] + FILL_COMMON + FILL_TAGS[shape])
            fill = {"Shape": shape}
            for t in FILL_COMMON:
                fill[t] = _value("Fill", t, kids_f[t], fill_path) if t in kids_f else schema.default("Fill", t)
            for t in FILL_TAGS[shape]:
                fill[t] = _value(sec, t, kids_f[t], fill_path) if t in kids_f else schema.default(sec, t)
            if shape == "mesh" and not fill["Geometry"]:
                raise SceneError(f"{_where(fill_path)}: a mesh fill needs <Geometry>")
            fluid["fills"].append(fill)
        scene["fluids"].append(fluid)
    for i, oe in enumerate(top.get("Object", []), 1):
        opath = path + [f"Object[{i}]"]
        kids = _children(oe, opath, schema.tags("Object"))
        obj = {"Name": (kids["Name"].text or "").strip() if "Name" in kids else f"object{i}"}
        for t in ("Geometry", "Shape"):
            if t in kids:
                obj[t] = (kids[t].text or "").strip()
        for t in ("Size", "ParticleSize"):
            if t in kids:
                obj[t] = _value("Object", t, kids[t], opath)
        for t in OBJECT_PARAMS:
            obj[t] = _value("Object", t, kids[t], opath) if t in kids else schema.default("Object", t)
        if "Geometry" not in obj and "Shape" not in obj:
            raise SceneError(f"{_where(opath)}: needs <Geometry> or a primitive <Shape> with <Size>")
        scene["objects"].append(obj)
    if "Interactions" in top:
        ipath = path + ["Interactions"]
        kids = _children(top["Interactions"], ipath, ["FluidFluid", "FluidObject", "Pair"], repeatable=("Pair",))
        for which in ("FluidFluid", "FluidObject"):
            if which in kids:
                scene[which] = _interaction(kids[which], ipath + [which], which)
        for j, pe in enumerate(kids.get("Pair", []), 1):
            scene["pairs"].append(_interaction(pe, ipath + [f"Pair[{j}]"], "Pair"))
    return scene


def read_scene_file(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise SceneError(f"cannot read '{path}': {e.strerror}") from None
    import os
    return read_scene_text(data, os.path.basename(path))


# ---------------------------------------------------------------- writing

def _fmt_value(kind, v, num):
    if kind == "bool":
        return "true" if v else "false"
    if kind == "int":
        return str(int(v))
    if kind == "real":
        return num(v)
    if kind in ("vec3", "colour", "real list"):
        return " ".join(num(x) for x in v)
    return str(v)


def _xml_text(s):
    return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def write_scene_text(scene, num=schema.format_number, comment=None):
    """The scene as .scene XML, every field written explicitly. num formats a real
    (default: shortest text of the single-precision value, what Blender holds)."""
    out = ['<?xml version="1.0" encoding="UTF-8"?>']
    if comment:
        out.append("<!-- " + comment.replace("--", "- -") + " -->")
    out.append('<Scene version="1">')

    def section(name, section_key, values, indent="  ", only=None):
        out.append(f"{indent}<{name}>")
        for t in only or schema.tags(section_key):
            kind = schema.row(section_key, t)[1]
            out.append(f"{indent}  <{t}>{_xml_text(_fmt_value(kind, values[t], num))}</{t}>")
        out.append(f"{indent}</{name}>")

    section("Simulation", "Simulation", scene["Simulation"])
    if scene.get("Camera") is not None:
        section("Camera", "Camera", scene["Camera"])
    if scene.get("Environment") is not None:
        section("Environment", "Environment", scene["Environment"])
    for f in scene["fluids"]:
        if not FLUID_NAME.match(f["Name"] or ""):
            raise SceneError(f"fluid '{f['Name']}': a fluid's name may hold only letters, digits, _ and - "
                             "(it becomes part of file names)")
        out.append("  <Fluid>")
        out.append(f"    <Name>{f['Name']}</Name>")
        for t in FLUID_PARAMS:
            if t == "Particles":
                continue
            kind = schema.row("Fluid", t)[1]
            out.append(f"    <{t}>{_fmt_value(kind, f[t], num)}</{t}>")
        pts = f.get("Particles") or []
        out.append(f"    <NumberOfParticles>{len(pts)}</NumberOfParticles>")
        if pts:
            out.append("    <Particles>")
            out.extend(f"      {num(p[0])} {num(p[1])} {num(p[2])}" for p in pts)
            out.append("    </Particles>")
        for fill in f.get("fills", []):
            shape = fill["Shape"]
            out.append("    <Fill>")
            out.append(f"      <Shape>{shape}</Shape>")
            for t in FILL_TAGS[shape]:
                kind = schema.row(f"Fill.{shape}", t)[1]
                out.append(f"      <{t}>{_xml_text(_fmt_value(kind, fill[t], num))}</{t}>")
            out.append(f"      <Spacing>{num(fill['Spacing'])}</Spacing>")
            if fill.get("OutsideObjects"):  # written only when true, as softsub's writer does
                out.append("      <OutsideObjects>true</OutsideObjects>")
            out.append("    </Fill>")
        out.append("  </Fluid>")
    for o in scene["objects"]:
        out.append("  <Object>")
        out.append(f"    <Name>{_xml_text(o['Name'])}</Name>")
        for t in ("Geometry", "Shape"):
            if o.get(t) is not None:
                out.append(f"    <{t}>{_xml_text(o[t])}</{t}>")
        if o.get("Size") is not None:
            out.append(f"    <Size>{' '.join(num(x) for x in o['Size'])}</Size>")
        if o.get("ParticleSize") is not None:
            out.append(f"    <ParticleSize>{num(o['ParticleSize'])}</ParticleSize>")
        for t in OBJECT_PARAMS:
            kind = schema.row("Object", t)[1]
            out.append(f"    <{t}>{_fmt_value(kind, o[t], num)}</{t}>")
        out.append("  </Object>")

    def interaction(name, it, indent="    "):
        out.append(f"{indent}<{name}>")
        if name == "Pair":
            out.append(f"{indent}  <A>{_xml_text(it['A'])}</A>")
            out.append(f"{indent}  <B>{_xml_text(it['B'])}</B>")
        kind = it["function"]
        out.append(f"{indent}  <{kind}>")
        for t in schema.tags(kind):
            k = schema.row(kind, t)[1]
            out.append(f"{indent}    <{t}>{_fmt_value(k, it['params'][t], num)}</{t}>")
        out.append(f"{indent}  </{kind}>")
        out.append(f"{indent}  <Damping>{num(it['Damping'])}</Damping>")
        out.append(f"{indent}  <RelativeVelocity>{num(it['RelativeVelocity'])}</RelativeVelocity>")
        out.append(f"{indent}</{name}>")

    out.append("  <Interactions>")
    interaction("FluidFluid", scene["FluidFluid"] or default_interaction("FluidFluid"))
    interaction("FluidObject", scene["FluidObject"] or default_interaction("FluidObject"))
    for p in scene["pairs"]:
        interaction("Pair", p)
    out.append("  </Interactions>")
    out.append("</Scene>")
    return "\n".join(out) + "\n"


def write_scene_file(path, scene, **kw):
    """Writes atomically: a temporary file beside the target, then a rename."""
    import os
    text = write_scene_text(scene, **kw)
    tmp = os.path.join(os.path.dirname(os.path.abspath(path)), f".{os.path.basename(path)}.tmp.{os.getpid()}")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
