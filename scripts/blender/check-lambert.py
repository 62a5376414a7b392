"""Measures Cycles' light units against the analytic irradiance of the
lambert-* scenes: at a grid of pixels, the ratio of the Cycles EXR's value to
albedo/pi * E, with E = I/d^2 cos(theta) for the point and spot lights
(I = P/(4 pi) W/sr, the glTF exporter's conversion before its 683 lm/W) and
E = S cos(theta) for the sun (S in W/m^2).

    blender -b --factory-startup --python scripts/blender/check-lambert.py -- DATADIR

DATADIR holds lambert-point.exr, lambert-sun.exr and lambert-spot.exr as
make-scenes.py writes them. The scenes are rebuilt with make-scenes.py's own
functions, so the camera and lights are the ones rendered. Two ratios are
printed per pixel: against Lambert, and against Cycles' Principled diffuse
(Burley's, with its retro-reflection at roughness 1), which Blender's
Principled BSDF uses instead of Lambert; a spot pixel is also given with
Cycles' extra cosine to the spot's axis.
"""

import importlib.util
import math
import os
import sys

import bpy
from mathutils import Vector

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("make_scenes", os.path.join(here, "make-scenes.py"))
make_scenes = importlib.util.module_from_spec(spec)
spec.loader.exec_module(make_scenes)

ALBEDO = make_scenes.LAMBERT["base"][1]
ROUGHNESS = make_scenes.LAMBERT["roughness"]


def schlick_weight(c):
    m = min(max(1.0 - c, 0.0), 1.0)
    return m ** 5


def principled_diffuse_factor(n_dot_l, n_dot_v, l_dot_v, roughness):
    """Cycles' Principled diffuse (Burley with separated retro-reflection)
    divided by Lambert's 1/pi."""
    fl, fv = schlick_weight(n_dot_l), schlick_weight(n_dot_v)
    f = (1.0 - 0.5 * fl) * (1.0 - 0.5 * fv)
    rr = roughness * (1.0 + l_dot_v)
    return f + rr * (fl + fv + fl * fv * (rr - 1.0))


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def pixel_ray(scene, cam, px, py):
    """The ray through pixel (px, py)'s centre, py counted from the top."""
    tr, br, bl, tl = cam.data.view_frame(scene=scene)
    u = (px + 0.5) / scene.render.resolution_x
    v = (py + 0.5) / scene.render.resolution_y
    local = tl + (tr - tl) * u + (bl - tl) * v
    origin = cam.matrix_world.translation
    direction = (cam.matrix_world.to_3x3() @ local).normalized()
    return origin, direction


def measure(datadir, name):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    make_scenes.black_world()
    make_scenes.SCENES[name](datadir)
    make_scenes.cycles_settings(16, 0)
    bpy.context.view_layer.update()
    scene = bpy.context.scene
    cam = scene.camera
    lamp = next(o for o in scene.objects if o.type == "LIGHT")
    image = bpy.data.images.load(os.path.join(datadir, name + ".exr"))
    w, h = image.size
    pixels = image.pixels[:]
    ratios, ratios_principled, ratios_axis, blends = [], [], [], []
    print(f"{name}: pixel  Cycles  Lambert  ratio  ratio/Principled-diffuse"
          + ("  ratio/(also cos to axis)" if lamp.data.type == "SPOT" else ""))
    # A spot lights a disc: a finer grid puts pixels in its blend ring too.
    steps = 16 if lamp.data.type == "SPOT" else 8
    for py in range(h // 4, h, h // steps):
        for px in range(w // (2 * steps), w, w // (steps // 2)):
            origin, d = pixel_ray(scene, cam, px, py)
            if d.z >= 0:
                continue
            t = -origin.z / d.z
            p = origin + d * t
            n = Vector((0, 0, 1))
            v = -d
            axis_cos = None
            if lamp.data.type == "SUN":
                l = (lamp.matrix_world.to_3x3() @ Vector((0, 0, 1))).normalized()
                irradiance = lamp.data.energy * max(n.dot(l), 0.0)
            else:
                to_light = lamp.matrix_world.translation - p
                dist = to_light.length
                l = to_light / dist
                intensity = lamp.data.energy / (4.0 * math.pi)
                irradiance = intensity / dist ** 2 * max(n.dot(l), 0.0)
                if lamp.data.type == "SPOT":
                    axis = (lamp.matrix_world.to_3x3() @ Vector((0, 0, -1))).normalized()
                    axis_cos = axis.dot(-l)
                    cos_half = math.cos(lamp.data.spot_size / 2.0)
                    smooth = (1.0 - cos_half) * lamp.data.spot_blend
                    if axis_cos <= cos_half:
                        continue
                    blend = smoothstep(0.0, smooth, axis_cos - cos_half) if smooth > 0 else 1.0
                    if blend < 1.0:
                        blends.append(px)
                    irradiance *= blend
            lambert = ALBEDO / math.pi * irradiance
            if lambert <= 0:
                continue
            # Blender images are stored bottom row first.
            row = h - 1 - py
            cycles = pixels[(row * w + px) * 4 + 1]
            ratio = cycles / lambert
            factor = principled_diffuse_factor(n.dot(l), n.dot(v), l.dot(v), ROUGHNESS)
            ratios.append(ratio)
            ratios_principled.append(ratio / factor)
            line = f"  ({px:3d},{py:3d})  {cycles:.4f}  {lambert:.4f}  {ratio:.4f}  {ratio / factor:.4f}"
            if axis_cos is not None:
                ratios_axis.append(ratio / factor / axis_cos)
                line += f"  {ratio / factor / axis_cos:.4f}"
            print(line)

    def summary(label, values):
        if values:
            mean = sum(values) / len(values)
            print(f"  {label}: mean {mean:.4f}, min {min(values):.4f}, max {max(values):.4f}, n {len(values)}")

    summary("k against Lambert", ratios)
    summary("k against Cycles' Principled diffuse", ratios_principled)
    summary("k against Principled diffuse with the spot's axis cosine", ratios_axis)
    if lamp.data.type == "SPOT":
        print(f"  pixels in the spot's blend ring: {len(blends)}")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 1:
        sys.exit("check-lambert: usage: blender -b --factory-startup --python check-lambert.py -- DATADIR")
    for name in ("lambert-point", "lambert-sun", "lambert-spot"):
        measure(os.path.abspath(args[0]), name)


main()
