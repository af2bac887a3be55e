"""Reading what `softsub run` writes (docs/cache-formats.md) and writing the OBJ meshes
a scene names. Pure Python, no bpy.

- `.sim` frames: objects' poses and fluids' positions (read_sim);
- `ply/<scene>.NNNN.ply`: positions, velocities and stable ids of every fluid (read_ply);
- OBJ meshes: read_obj / write_obj;
- a run's output folder: scan_sim_folder lists its frames and surfaces.
"""
import os
import re
import struct
import xml.etree.ElementTree as ET
from array import array


class CacheError(Exception):
    """A cache file or folder that cannot be used; the message names the file."""


def read_sim(path):
    """One .sim frame -> {"frame", "time", "objects": [{Name, UniformScale, Position,
    Rotation (w x y z), Filename}], "fluids": [{Name, positions: array('f') x y z ...}]}
    in softsub's coordinates. Raises CacheError naming the file."""
    name = os.path.basename(path)
    try:
        root = ET.parse(path).getroot()
    except OSError as e:
        raise CacheError(f"cannot read '{path}': {e.strerror}") from None
    except ET.ParseError as e:
        raise CacheError(f"{name}: not a valid .sim file: {e}") from None
    if root.tag != "Simulation":
        raise CacheError(f"{name}: the root element is <{root.tag}>, not <Simulation>")
    try:
        out = {"frame": int(root.get("frame")), "time": float(root.get("time")), "objects": [], "fluids": []}
        for e in root:
            if e.tag == "Object":
                o = {"Name": e.findtext("Name").strip(),
                     "UniformScale": float(e.findtext("UniformScale") or 1),
                     "Position": tuple(float(x) for x in e.findtext("Position").split()),
                     "Rotation": tuple(float(x) for x in e.findtext("Rotation").split()),
                     "Filename": (e.findtext("Filename") or "").strip()}
                if len(o["Position"]) != 3 or len(o["Rotation"]) != 4:
                    raise ValueError(f"object '{o['Name']}': Position needs 3 numbers, Rotation 4")
                out["objects"].append(o)
            elif e.tag == "Fluid":
                n = int(e.findtext("ParticleNumber"))
                pos = array("f", map(float, (e.findtext("Particles") or "").split()))
                if len(pos) != 3 * n:
                    raise ValueError(f"fluid '{e.findtext('Name')}': ParticleNumber {n} but {len(pos) // 3} positions")
                out["fluids"].append({"Name": e.findtext("Name").strip(), "positions": pos})
            else:
                raise ValueError(f"unknown element <{e.tag}>")
    except (TypeError, ValueError, AttributeError) as e:
        raise CacheError(f"{name}: not a valid .sim file: {e}") from None
    return out


_PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
              "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
              "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_ply(path):
    """A binary little-endian PLY point cloud as softsub writes it -> {"fluids": [names],
    "columns": {property: array}} (one value per vertex, file order). Raises CacheError."""
    name = os.path.basename(path)
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise CacheError(f"cannot read '{path}': {e.strerror}") from None
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        raise CacheError(f"{name}: not a PLY file")
    header = data[:end].decode("ascii", "replace").splitlines()
    fluids, props, count, in_vertex = [], [], None, False
    for line in header[1:]:
        w = line.split()
        if not w:
            continue
        if w[0] == "format" and w[1] != "binary_little_endian":
            raise CacheError(f"{name}: format {w[1]} (the add-on reads softsub's binary_little_endian PLY)")
        if w[0] == "comment" and len(w) >= 4 and w[1] == "fluid":
            fluids.append(line.split(None, 3)[3])
        elif w[0] == "element":
            in_vertex = w[1] == "vertex"
            if in_vertex:
                count = int(w[2])
            elif count is not None:
                break
        elif w[0] == "property" and in_vertex:
            if w[1] == "list" or w[1] not in _PLY_TYPES:
                raise CacheError(f"{name}: unsupported vertex property '{line}'")
            props.append((w[2], _PLY_TYPES[w[1]]))
    if count is None:
        raise CacheError(f"{name}: no vertex element")
    fmt = "<" + "".join(t for _, t in props)
    size = struct.calcsize(fmt)
    body = data[end + len(b"end_header\n"):]
    if len(body) < size * count:
        raise CacheError(f"{name}: cut short ({len(body)} bytes for {count} vertices of {size})")
    columns = {p: array("d" if t in "fd" else "q") for p, t in props}
    cols = [columns[p] for p, _ in props]
    for rec in struct.iter_unpack(fmt, body[:size * count]):
        for c, v in zip(cols, rec):
            c.append(v)
    return {"fluids": fluids, "columns": columns, "count": count}


def read_obj(path):
    """Vertices [(x, y, z)] and faces [(i, j, k, ...)] (0-based) of an OBJ file."""
    verts, faces = [], []
    name = os.path.basename(path)
    try:
        with open(path, "r", encoding="utf-8", errors="replace") as f:
            for line in f:
                w = line.split()
                if not w:
                    continue
                if w[0] == "v":
                    verts.append((float(w[1]), float(w[2]), float(w[3])))
                elif w[0] == "f":
                    idx = []
                    for t in w[1:]:
                        i = int(t.split("/")[0])
                        idx.append(i - 1 if i > 0 else len(verts) + i)
                    faces.append(tuple(idx))
    except OSError as e:
        raise CacheError(f"cannot read '{path}': {e.strerror}") from None
    except (ValueError, IndexError) as e:
        raise CacheError(f"{name}: not a valid OBJ file: {e}") from None
    for fc in faces:
        if any(i < 0 or i >= len(verts) for i in fc):
            raise CacheError(f"{name}: a face names a vertex that does not exist")
    return verts, faces


def write_obj(path, name, verts, tris, num):
    """Writes a triangle mesh as OBJ (atomically: temporary file, then rename)."""
    lines = [f"# softsub Blender add-on: {len(verts)} vertices, {len(tris)} triangles", f"o {name}"]
    lines.extend(f"v {num(v[0])} {num(v[1])} {num(v[2])}" for v in verts)
    lines.extend(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}" for t in tris)
    tmp = os.path.join(os.path.dirname(os.path.abspath(path)), f".{os.path.basename(path)}.tmp.{os.getpid()}")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, path)


def read_manifest(path):
    """A frame's manifest -> (frame, [(size, relative path)]), or None if it is cut."""
    try:
        with open(path, "r", encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError:
        return None
    if not lines or not lines[0].startswith("softsub manifest") or "end" not in lines:
        return None
    frame, files = None, []
    for line in lines:
        w = line.split(" ", 2)
        if w[0] == "frame" and len(w) == 2:
            frame = int(w[1])
        elif w[0] == "file" and len(w) == 3:
            files.append((int(w[1]), w[2]))
    return (frame, files) if frame is not None else None


def complete_frames(sim_dir, scene):
    """Frames 0..N of the folder's last run that are complete (manifest and every file
    it lists at its size), or None when the folder has no manifests (not softsub's run
    journal: every .sim counts)."""
    mdir = os.path.join(sim_dir, "manifest")
    if not os.path.isdir(mdir):
        return None
    pat = re.compile(r"^" + re.escape(scene) + r"\.(\d{4,})\.manifest$")
    found = {int(m.group(1)): os.path.join(mdir, f) for f in os.listdir(mdir) for m in [pat.match(f)] if m}
    if not found:
        return None
    done = set()
    f = 0
    while f in found:
        man = read_manifest(found[f])
        if man is None or man[0] != f:
            break
        if any(not os.path.isfile(os.path.join(sim_dir, rel)) or os.path.getsize(os.path.join(sim_dir, rel)) != size
               for size, rel in man[1]):
            break
        done.add(f)
        f += 1
    return done


def scan_sim_folder(sim_dir, scene_name=None):
    """What a run's output folder holds: {"scene": name, "frames": sorted frame numbers
    with a .sim file, "sim": {frame: path}, "ply": {frame: path}, "mesh": {fluid:
    {frame: path}}, "vdb": {fluid: {frame: path}}}. Frames must be 0..N without a gap
    (a run writes them in order), else CacheError."""
    if not os.path.isdir(sim_dir):
        raise CacheError(f"'{sim_dir}' is not a folder")
    sims = {}
    pat = re.compile(r"^(.+)\.(\d{4,})\.sim$")
    for f in os.listdir(sim_dir):
        m = pat.match(f)
        if m and (scene_name is None or m.group(1) == scene_name):
            sims.setdefault(m.group(1), {})[int(m.group(2))] = os.path.join(sim_dir, f)
    if not sims:
        raise CacheError(f"'{sim_dir}' holds no .sim frames" + (f" of scene '{scene_name}'" if scene_name else ""))
    if len(sims) > 1:
        raise CacheError(f"'{sim_dir}' holds frames of several scenes ({', '.join(sorted(sims))}): choose one")
    scene, frames = next(iter(sims.items()))
    complete = complete_frames(sim_dir, scene)
    if complete is not None:
        # softsub's manifests say which frames belong to the last run and are whole; a
        # .sim no manifest lists (an older softsub's rerun left them, or a copy) is not one
        frames = {f: p for f, p in frames.items() if f in complete}
        if not frames:
            raise CacheError(f"'{sim_dir}': no complete frame of '{scene}' (see manifest/)")
    order = sorted(frames)
    if order != list(range(order[0], order[0] + len(order))) or order[0] != 0:
        missing = sorted(set(range(0, order[-1] + 1)) - set(order))
        raise CacheError(f"'{sim_dir}': frames of '{scene}' are not complete (missing {missing[:5]}): "
                         "rerun, or 'softsub run --resume'")
    out = {"scene": scene, "frames": order, "sim": frames, "ply": {}, "mesh": {}, "vdb": {}}
    ply_dir = os.path.join(sim_dir, "ply")
    for f in os.listdir(ply_dir) if os.path.isdir(ply_dir) else []:
        m = re.match(r"^" + re.escape(scene) + r"\.(\d{4,})\.ply$", f)
        if m:
            if int(m.group(1)) in frames:
                out["ply"][int(m.group(1))] = os.path.join(ply_dir, f)
    for kind in ("mesh", "vdb"):
        d = os.path.join(sim_dir, kind)
        ext = ".obj" if kind == "mesh" else ".vdb"
        for f in os.listdir(d) if os.path.isdir(d) else []:
            m = re.match(r"^(.+)\.(\d{4,})" + re.escape(ext) + "$", f)
            if m and int(m.group(2)) in frames:
                out[kind].setdefault(m.group(1), {})[int(m.group(2))] = os.path.join(d, f)
    return out
