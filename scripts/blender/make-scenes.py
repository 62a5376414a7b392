"""Builds raycache's Blender test scenes from nothing, exports each with
Blender's own glTF exporter and renders Cycles references of it.

    blender -b --factory-startup --python scripts/blender/make-scenes.py -- OUTDIR \
        [--scenes a,b,...] [--samples N] [--seed S] [--suffix TEXT] [--no-render] \
        [--no-point-sampled] [--no-exr]

Writes, per scene X: X.glb (the exporter's defaults plus lights and cameras),
X.png (8-bit sRGB through the Standard view transform), X.exr (scene-linear,
half float, ZIP) and X-point.png (the same render with a 0.01 px pixel filter:
one ray per pixel centre as near as Cycles allows, so aliasing's share of a
comparison can be separated). tests/data/blender/README.md states the Cycles
settings below and why they were chosen; keep the two in step.

Blender is a tool for making test data here: the committed files are what
tests use, and nothing in the build or CI runs this script.
"""

import math
import os
import sys

import bpy
from mathutils import Vector

WIDTH, HEIGHT = 320, 240
DEFAULT_SAMPLES = 1024
# The rough gold spheres reflect the point light's highlight onto the
# glossy floor (floor -> rough metal -> light, a path few samples find), so
# that scene gets twice the samples (README.md gives the noise left).
SCENE_SAMPLES = {"metals": 2048}
# The normal-mapped scene carries the MikkTSpace tangents Cycles shades with
# (TANGENT), so a reader need not compute its own to match.
SCENE_EXPORT_OPTIONS = {"textured": dict(export_tangents=True)}
# Glass needs a path in and out of each surface it crosses (a sphere, a slab
# seen through a sphere, a Suzanne's ears); 8 of each leaves no visible cut.
SPECULAR_BOUNCES = 8


# ---------------------------------------------------------------- materials

def principled(name, base, metallic=0.0, roughness=0.5, specular=0.5,
               transmission=0.0, ior=1.5):
    """A Principled BSDF material: the node the glTF exporter maps onto
    glTF's metallic-roughness model (specular 0.5 is glTF's F0 = 0.04)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*base, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Specular"].default_value = specular
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior
    return mat


def checker_image(outdir, squares=8, size=256, light=0.7, dark=0.1):
    """A checker PNG (sRGB-encoded grey levels light and dark), written to
    OUTDIR/checker.png and embedded by the exporter into the .glb."""
    image = bpy.data.images.new("checker", size, size, alpha=False)
    side = size // squares
    pixels = []
    for y in range(size):
        for x in range(size):
            v = light if ((x // side) + (y // side)) % 2 == 0 else dark
            pixels.extend((v, v, v, 1.0))
    image.pixels = pixels
    image.filepath_raw = os.path.join(outdir, "checker.png")
    image.file_format = "PNG"
    image.save()
    return image


def checker_material(image):
    mat = principled("checker-floor", (0.8, 0.8, 0.8), roughness=0.5)
    nodes = mat.node_tree.nodes
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    mat.node_tree.links.new(tex.outputs["Color"],
                            nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def data_image(outdir, name, size, texel):
    """A Non-Color PNG (raw values, no sRGB curve) whose texel (x, y) ->
    (r, g, b) is given; row 0 is the image's bottom, v = 0. Written to
    OUTDIR/NAME.png and embedded by the exporter into the .glb."""
    image = bpy.data.images.new(name, size, size, alpha=False)
    image.colorspace_settings.name = "Non-Color"
    pixels = []
    for y in range(size):
        for x in range(size):
            pixels.extend((*texel(x, y), 1.0))
    image.pixels = pixels
    image.filepath_raw = os.path.join(outdir, name + ".png")
    image.file_format = "PNG"
    image.save()
    return image


# Roughness by tile column and metallic by tile row of the floor's
# metallic-roughness texture (glTF's channels: G roughness, B metallic).
TILE_ROUGHNESS = (0.25, 0.5, 0.8)
TILE_METALLIC = (0.0, 1.0)


def metal_rough_image(outdir, tiles=8, size=256):
    """tiles x tiles tiles: roughness cycles through TILE_ROUGHNESS along
    u, metallic alternates along v; R (glTF's occlusion, unused) is 1."""
    side = size // tiles

    def texel(x, y):
        return (1.0, TILE_ROUGHNESS[(x // side) % len(TILE_ROUGHNESS)],
                TILE_METALLIC[(y // side) % len(TILE_METALLIC)])
    return data_image(outdir, "metal-rough", size, texel)


def bump_normal_image(outdir, bumps=16, size=256, max_slope_deg=40.0):
    """A tangent-space normal map of bumps x bumps spherical caps, one
    centred in each cell, filling 80 % of the cell's width, whose slope
    grows to max_slope_deg at the cap's rim; flat (0, 0, 1) between them.
    +x is the tangent (u), +y the bitangent (v), encoded n * 0.5 + 0.5."""
    side = size / bumps
    rim = 0.4 * side  # the cap's radius in texels
    # The radius of the sphere the cap is cut from: its normal at the rim
    # leans max_slope_deg from the surface's.
    radius = rim / math.sin(math.radians(max_slope_deg))

    def texel(x, y):
        dx = (x + 0.5) % side - side / 2
        dy = (y + 0.5) % side - side / 2
        if dx * dx + dy * dy >= rim * rim:
            n = (0.0, 0.0, 1.0)
        else:
            dz = math.sqrt(radius * radius - dx * dx - dy * dy)
            n = (dx / radius, dy / radius, dz / radius)
        return tuple(c * 0.5 + 0.5 for c in n)
    return data_image(outdir, "bump-normal", size, texel)


def metal_rough_material(name, base, image):
    """Image -> Separate Color -> G to Roughness, B to Metallic: the wiring
    the exporter writes as pbrMetallicRoughness.metallicRoughnessTexture."""
    mat = principled(name, base)
    nodes = mat.node_tree.nodes
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    separate = nodes.new("ShaderNodeSeparateColor")
    separate.mode = "RGB"
    bsdf = nodes["Principled BSDF"]
    links = mat.node_tree.links
    links.new(tex.outputs["Color"], separate.inputs["Color"])
    links.new(separate.outputs["Green"], bsdf.inputs["Roughness"])
    links.new(separate.outputs["Blue"], bsdf.inputs["Metallic"])
    return mat


def normal_mapped_material(name, base, image, roughness=0.5):
    """Image -> Normal Map (tangent space, the UV map, strength 1) ->
    Normal: the wiring the exporter writes as normalTexture."""
    mat = principled(name, base, roughness=roughness)
    nodes = mat.node_tree.nodes
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.space = "TANGENT"
    normal_map.uv_map = "UVMap"
    normal_map.inputs["Strength"].default_value = 1.0
    links = mat.node_tree.links
    links.new(tex.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], nodes["Principled BSDF"].inputs["Normal"])
    return mat


# ---------------------------------------------------------------- objects

def assign(obj, mat):
    obj.data.materials.clear()
    obj.data.materials.append(mat)
    return obj


def plane(size, mat, location=(0, 0, 0), name="floor"):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    return assign(obj, mat)


def sphere(radius, location, mat, name):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16,
                                         radius=radius, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    bpy.ops.object.shade_smooth()
    return assign(obj, mat)


def cube(size, location, mat, name, scale=(1, 1, 1), rotation=(0, 0, 0)):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location,
                                    rotation=rotation, scale=scale)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    return assign(obj, mat)


def aim(obj, target):
    direction = Vector(target) - obj.location
    obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()


def camera(location, target, lens=50.0):
    data = bpy.data.cameras.new("camera")
    data.lens = lens
    data.sensor_width = 36.0
    data.sensor_fit = "AUTO"
    obj = bpy.data.objects.new("camera", data)
    bpy.context.scene.collection.objects.link(obj)
    obj.location = location
    aim(obj, target)
    bpy.context.scene.camera = obj
    return obj


def light(kind, name, energy, location=(0, 0, 0), target=None,
          spot_size_deg=None, spot_blend=None, sun_direction=None):
    """A hard light: point and spot radius 0, sun angle 0 (the shapes a
    Whitted tracer's punctual lights have)."""
    data = bpy.data.lights.new(name, type=kind)
    data.energy = energy
    data.color = (1.0, 1.0, 1.0)
    if kind in ("POINT", "SPOT"):
        data.shadow_soft_size = 0.0
    if kind == "SPOT":
        data.spot_size = math.radians(spot_size_deg)
        data.spot_blend = spot_blend
        data.show_cone = False
    if kind == "SUN":
        data.angle = 0.0
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    obj.location = location
    if target is not None:
        aim(obj, target)
    if sun_direction is not None:
        # A sun shines along its -Z axis: aim from the origin along the
        # direction the light travels.
        obj.location = (0, 0, 0)
        obj.rotation_euler = Vector(sun_direction).to_track_quat("-Z", "Y").to_euler()
    return obj


def black_world():
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    background.inputs["Strength"].default_value = 0.0
    bpy.context.scene.world = world


# ---------------------------------------------------------------- scenes
# Each builds its scene into the current (empty) file. Light energies are
# Blender's: point and spot in W, sun in W/m^2.

# Specular 0: the exporter writes KHR_materials_specular with
# specularColorFactor 0 (F0 = 0) and Cycles reflects nothing specular.
# Roughness 0.25, not 1: Blender's Principled diffuse is Burley's, whose
# retro-reflection grows with roughness; at 0.25 it stays within 0.6 %
# (point) and 3.3 % (sun) of Lambert over these views, at 1 it is up to
# 3.1x Lambert near the horizon (check-lambert.py's formula for that diffuse).
LAMBERT = dict(base=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.25, specular=0.0)


def scene_lambert_point(_outdir):
    plane(40.0, principled("lambert", **LAMBERT))
    light("POINT", "point", 100.0, location=(0.0, 0.0, 3.0))
    camera((0.0, -7.0, 5.0), (0.0, 0.5, 0.0), lens=30.0)


def scene_lambert_sun(_outdir):
    plane(40.0, principled("lambert", **LAMBERT))
    # 45 degrees from the vertical, shining towards +y and down.
    light("SUN", "sun", 1.0, sun_direction=(0.0, 1.0, -1.0))
    camera((0.0, -7.0, 5.0), (0.0, 0.5, 0.0), lens=30.0)


def scene_lambert_spot(_outdir):
    plane(40.0, principled("lambert", **LAMBERT))
    # Straight down from 4 m: a 60 degree cone lights a disc of radius
    # 4 tan 30 = 2.31 m, its edge softened over the outer 30 % of the angle.
    light("SPOT", "spot", 200.0, location=(0.0, 0.0, 4.0),
          target=(0.0, 0.0, 0.0), spot_size_deg=60.0, spot_blend=0.3)
    camera((0.0, -7.0, 5.0), (0.0, 0.5, 0.0), lens=30.0)


def scene_studio(outdir):
    floor = plane(10.0, checker_material(checker_image(outdir)))
    floor.name = "checker-floor"
    sphere(1.0, (-1.6, 0.4, 1.0),
           principled("chrome", (0.9, 0.9, 0.9), metallic=1.0, roughness=0.0),
           "chrome-ball")
    bpy.ops.mesh.primitive_monkey_add(size=1.6, location=(0.7, -0.6, 0.9),
                                      rotation=(0.0, 0.0, math.radians(-15)))
    suzanne = bpy.context.active_object
    suzanne.name = suzanne.data.name = "glass-suzanne"
    bpy.ops.object.shade_smooth()
    assign(suzanne, principled("glass", (1.0, 1.0, 1.0), roughness=0.0,
                               transmission=1.0, ior=1.5))
    cube(1.0, (2.5, 1.0, 0.5), principled("red", (0.8, 0.05, 0.05), roughness=0.5),
         "red-cube", rotation=(0.0, 0.0, math.radians(30)))
    light("POINT", "point-800W", 800.0, location=(4.0, -3.0, 6.0))
    light("SPOT", "spot-1500W", 1500.0, location=(-4.0, -3.0, 7.0),
          target=(-0.5, 0.0, 0.0), spot_size_deg=45.0, spot_blend=0.15)
    light("SUN", "sun-1.5", 1.5, sun_direction=(-0.4, 0.5, -1.0))
    camera((0.0, -9.0, 3.8), (0.2, 0.0, 0.8), lens=40.0)


def scene_metals(_outdir):
    plane(12.0, principled("floor", (0.5, 0.5, 0.5), roughness=0.5))
    for row, (metallic, base) in enumerate(((0.0, (0.1, 0.25, 0.8)),
                                            (1.0, (1.0, 0.77, 0.34)))):
        for column, roughness in enumerate((0.2, 0.5, 0.8)):
            name = f"m{metallic:.0f}-r{roughness:.1f}"
            sphere(0.6, (-1.5 + 1.5 * column, 1.6 * row, 0.6),
                   principled(name, base, metallic=metallic, roughness=roughness),
                   name)
    light("POINT", "point-500W", 500.0, location=(-3.0, -3.0, 5.0))
    light("SUN", "sun-2", 2.0, sun_direction=(-1.0, 0.3, -0.8))
    camera((0.0, -5.5, 5.0), (0.0, 0.8, 0.3), lens=40.0)


def scene_glass(outdir):
    floor = plane(10.0, checker_material(checker_image(outdir)))
    floor.name = "checker-floor"
    glass = principled("glass", (1.0, 1.0, 1.0), roughness=0.0,
                       transmission=1.0, ior=1.5)
    sphere(1.0, (-1.3, 0.0, 1.0), glass, "glass-sphere")
    cube(1.0, (1.4, -0.3, 0.9), glass, "glass-slab", scale=(1.6, 0.3, 1.8),
         rotation=(0.0, 0.0, math.radians(20)))
    light("POINT", "point-600W", 600.0, location=(2.0, -4.0, 6.0))
    light("SUN", "sun-1", 1.0, sun_direction=(0.3, 0.6, -1.0))
    camera((0.0, -7.5, 3.5), (0.0, 0.5, 0.6), lens=40.0)


def scene_textured(outdir):
    plane(8.0, metal_rough_material("metal-rough-floor", (0.7, 0.7, 0.7),
                                    metal_rough_image(outdir)))
    bumps = bump_normal_image(outdir)
    cube(1.4, (1.3, 0.4, 0.7), normal_mapped_material("bumpy-cube", (0.8, 0.35, 0.1), bumps),
         "bumpy-cube", rotation=(0.0, 0.0, math.radians(30)))
    sphere(0.8, (-1.4, 0.6, 0.8),
           normal_mapped_material("bumpy-sphere", (0.15, 0.4, 0.8), bumps),
           "bumpy-sphere")
    light("POINT", "point-300W", 300.0, location=(0.0, 3.5, 3.0))
    light("SUN", "sun-1.5", 1.5, sun_direction=(-0.4, 0.5, -1.0))
    camera((0.0, -7.0, 4.5), (0.0, 0.3, 0.4), lens=40.0)


SCENES = {
    "lambert-point": scene_lambert_point,
    "lambert-sun": scene_lambert_sun,
    "lambert-spot": scene_lambert_spot,
    "studio": scene_studio,
    "metals": scene_metals,
    "glass": scene_glass,
    "textured": scene_textured,
}


# ---------------------------------------------------------------- render

def cycles_settings(samples, seed):
    """The reference settings README.md states: keep them in step."""
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.render.resolution_x = WIDTH
    scene.render.resolution_y = HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.sequencer_colorspace_settings.name = "sRGB"
    c = scene.cycles
    c.device = "CPU"
    c.samples = samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.use_animated_seed = False
    c.pixel_filter_type = "BLACKMAN_HARRIS"
    c.filter_width = 1.5
    c.max_bounces = SPECULAR_BOUNCES
    c.diffuse_bounces = 0
    c.glossy_bounces = SPECULAR_BOUNCES
    c.transmission_bounces = SPECULAR_BOUNCES
    c.transparent_max_bounces = SPECULAR_BOUNCES
    c.volume_bounces = 0
    c.caustics_reflective = False
    c.caustics_refractive = False
    c.blur_glossy = 0.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0


def save(path, fmt):
    settings = bpy.context.scene.render.image_settings
    if fmt == "PNG":
        settings.file_format = "PNG"
        settings.color_mode = "RGB"
        settings.color_depth = "8"
        settings.compression = 100
    else:
        settings.file_format = "OPEN_EXR"
        settings.color_mode = "RGB"
        settings.color_depth = "16"
        settings.exr_codec = "ZIP"
    bpy.data.images["Render Result"].save_render(path, scene=bpy.context.scene)


def render(stem, exr, point_sampled):
    scene = bpy.context.scene
    bpy.ops.render.render()
    save(stem + ".png", "PNG")
    if exr:
        save(stem + ".exr", "EXR")
    if point_sampled:
        # Cycles' smallest filter width: every sample within 0.005 px of
        # the pixel's centre.
        scene.cycles.filter_width = 0.01
        bpy.ops.render.render()
        save(stem + "-point.png", "PNG")
        scene.cycles.filter_width = 1.5


def export(path, options):
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLB",
                              export_lights=True, export_cameras=True, **options)


# ---------------------------------------------------------------- main

# The images the scenes write into OUTDIR for the exporter to embed.
TEXTURE_FILES = ("checker.png", "metal-rough.png", "bump-normal.png")


def parse(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if not args:
        sys.exit("make-scenes: usage: blender -b --factory-startup --python "
                 "make-scenes.py -- OUTDIR [--scenes a,b] [--samples N] [--seed S] "
                 "[--suffix TEXT] [--no-render] [--no-point-sampled] [--no-exr]")
    options = dict(outdir=args[0], scenes=list(SCENES), samples=None,
                   seed=0, suffix="", render=True, point_sampled=True, exr=True)
    i = 1
    while i < len(args):
        a = args[i]
        if a == "--scenes":
            options["scenes"] = args[i + 1].split(",")
            i += 1
        elif a == "--samples":
            options["samples"] = int(args[i + 1])
            i += 1
        elif a == "--seed":
            options["seed"] = int(args[i + 1])
            i += 1
        elif a == "--suffix":
            options["suffix"] = args[i + 1]
            i += 1
        elif a == "--no-render":
            options["render"] = False
        elif a == "--no-point-sampled":
            options["point_sampled"] = False
        elif a == "--no-exr":
            options["exr"] = False
        else:
            sys.exit(f"make-scenes: unknown option {a}")
        i += 1
    for name in options["scenes"]:
        if name not in SCENES:
            sys.exit(f"make-scenes: unknown scene {name} (known: {', '.join(SCENES)})")
    return options


def main():
    o = parse(sys.argv)
    outdir = os.path.abspath(o["outdir"])
    os.makedirs(outdir, exist_ok=True)
    for name in o["scenes"]:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        black_world()
        SCENES[name](outdir)
        cycles_settings(o["samples"] or SCENE_SAMPLES.get(name, DEFAULT_SAMPLES), o["seed"])
        stem = os.path.join(outdir, name)
        export(stem + ".glb", SCENE_EXPORT_OPTIONS.get(name, {}))
        if o["render"]:
            render(stem + o["suffix"], o["exr"], o["point_sampled"])
        print(f"make-scenes: {name} done", flush=True)
    for texture in TEXTURE_FILES:
        path = os.path.join(outdir, texture)
        if os.path.exists(path):
            # Embedded in the .glb files; not needed beside them.
            os.remove(path)


if __name__ == "__main__":
    main()
