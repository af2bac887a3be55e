"""How substances, fills and the container look in the viewport and in renders."""
import bpy

GROUP = "softsub points"
CONTAINER = "softsub container"


def points_group():
    """Geometry nodes: mesh vertices -> a point cloud of the given radius and material.
    Mesh to Points keeps the vertices' attributes (velocity, id)."""
    ng = bpy.data.node_groups.get(GROUP)
    if ng is not None:
        return ng
    ng = bpy.data.node_groups.new(GROUP, "GeometryNodeTree")
    ng.inputs.new("NodeSocketGeometry", "Geometry")
    radius = ng.inputs.new("NodeSocketFloat", "Radius")
    radius.default_value, radius.min_value = 0.5, 0.0
    ng.inputs.new("NodeSocketMaterial", "Material")
    ng.outputs.new("NodeSocketGeometry", "Geometry")
    gin = ng.nodes.new("NodeGroupInput")
    gout = ng.nodes.new("NodeGroupOutput")
    to_points = ng.nodes.new("GeometryNodeMeshToPoints")
    set_mat = ng.nodes.new("GeometryNodeSetMaterial")
    gin.location, to_points.location, set_mat.location, gout.location = (-400, 0), (-150, 0), (100, 0), (350, 0)
    ng.links.new(gin.outputs["Geometry"], to_points.inputs["Mesh"])
    ng.links.new(gin.outputs["Radius"], to_points.inputs["Radius"])
    ng.links.new(to_points.outputs["Points"], set_mat.inputs["Geometry"])
    ng.links.new(gin.outputs["Material"], set_mat.inputs["Material"])
    ng.links.new(set_mat.outputs["Geometry"], gout.inputs["Geometry"])
    return ng


def fluid_material(name, colour):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    mat.diffuse_color = (colour[0], colour[1], colour[2], 1.0)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = (colour[0], colour[1], colour[2], 1.0)
        bsdf.inputs["Roughness"].default_value = 0.3
    return mat


def show_as_points(obj, radius, colour):
    """Draws and renders a mesh's vertices as spheres of the particle radius."""
    ng = points_group()
    mod = obj.modifiers.get(GROUP) or obj.modifiers.new(GROUP, "NODES")
    mod.node_group = ng
    mat = fluid_material(f"softsub {obj.name}", colour)
    mod[ng.inputs["Radius"].identifier] = float(radius)
    mod[ng.inputs["Material"].identifier] = mat
    if not obj.data.materials:
        obj.data.materials.append(mat)


def show_as_fill(obj):
    obj.display_type = "WIRE"
    obj.hide_render = True


def update_container(context):
    """A wire box object showing the container (never exported, never rendered)."""
    s = context.scene.softsub
    obj = bpy.data.objects.get(CONTAINER)
    if not s.use_container:
        if obj is not None:
            bpy.data.objects.remove(obj)
        return
    hx, hy = s.width / 2, s.depth / 2
    verts = [(x, y, z) for x in (-hx, hx) for y in (-hy, hy) for z in (0.0, s.height)]
    if obj is None:
        mesh = bpy.data.meshes.new(CONTAINER)
        mesh.from_pydata(verts, [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7),
                                 (0, 4), (1, 5), (2, 6), (3, 7)], [])
        obj = bpy.data.objects.new(CONTAINER, mesh)
        context.scene.collection.objects.link(obj)
        obj.hide_render = True
        obj.hide_select = True
    else:
        for v, co in zip(obj.data.vertices, verts):
            v.co = co
        obj.data.update()
