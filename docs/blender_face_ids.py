"""Render a face-id image of an OBJ with Blender, for `sightline compare INPUT --image`.

Usage (Blender 3.x or 4.x, headless):

  blender -b --factory-startup --python docs/blender_face_ids.py -- MESH.obj[.gz] VIEW.cam OUT.png
  sightline compare MESH.obj --cam VIEW.cam --image OUT.png --diff where.png

The image follows sightline's `--fill id` contract: each pixel holds the id of the face seen
at its centre plus one, as 24-bit RGB (r = (id+1)>>16 & 255, g = (id+1)>>8 & 255,
b = (id+1) & 255); background has alpha 0 (transparent film). Face ids are sightline's: the
index of the `f` line in the file, counting every face (sightline uses up the id of a
degenerate face too).

What makes Blender's output exact 8-bit ids, not colours:
- the OBJ is read here, not by Blender's importer, so that face k of the file is face k (the
  importer may split objects, drop or reorder faces); each face's colour is stored on its
  corners as a float colour attribute, value (byte / 255), shown unlit (Workbench, flat
  lighting, attribute colour, no outline, cavity, shadow, specular, or X-ray);
- anti-aliasing off (`display.render_aa = 'OFF'`): one sample per pixel, at its centre;
- no colour management on the way out: view transform 'Raw' (it leaves values as they are;
  'Standard' would apply the sRGB curve), look None, exposure 0, gamma 1, no dithering
  (`render.dither_intensity = 0`), PNG RGBA 8-bit, background transparent (alpha 0).

The camera is the `.cam` file's (`eye`, `target`, `up`, `fovy` (0: orthographic with
`ortho_height`), `near`, `far`, `size`), set as sightline sets it: gluLookAt(eye, target, up),
the vertical field of view fixed (sensor fit vertical), clip start and end at near and far.
Blender's clip start must be positive: an orthographic near <= 0 is raised to 1e-6 (warned).
"""
import gzip
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector


def fail(message):
    print(f"blender_face_ids: error: {message}", file=sys.stderr, flush=True)
    sys.exit(1)


argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(argv) != 3:
    fail("usage: blender -b --factory-startup --python blender_face_ids.py -- MESH.obj VIEW.cam OUT.png")
obj_path, cam_path, out_png = argv


# ---------------------------------------------------------------- the .cam file
def read_cam(path):
    keys = {}
    with open(path, encoding="utf-8-sig") as f:
        for n, line in enumerate(f, 1):
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            try:
                keys[words[0]] = [float(w) for w in words[1:]]
            except ValueError:
                fail(f"{path}:{n}: not numbers: {line.strip()}")
    for k in ("eye", "target", "up", "fovy", "near", "far"):
        if k not in keys:
            fail(f"{path}: no '{k}' line")
    return keys


cam = read_cam(cam_path)
W, H = (int(v) for v in cam.get("size", [1024, 1024])[:2])


# ---------------------------------------------------------------- the OBJ, face k = id k
def read_obj(path):
    opener = gzip.open if path.endswith(".gz") else open
    verts, faces = [], []
    with opener(path, "rt", encoding="utf-8-sig", errors="replace") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                verts.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "f":
                corners = []
                for w in words[1:]:
                    i = int(w.split("/")[0])
                    corners.append(i - 1 if i > 0 else len(verts) + i)
                faces.append(corners)
    return verts, faces


verts, faces = read_obj(obj_path)
# Faces Blender cannot hold (fewer than three distinct corners) are left out, keeping every
# other face's id: the id travels with the face as an attribute.
kept, kept_ids = [], []
for fid, corners in enumerate(faces):
    ring = [c for k, c in enumerate(corners) if c != corners[k - 1]]
    if len(set(ring)) >= 3:
        kept.append(ring)
        kept_ids.append(fid)
print(f"blender_face_ids: {len(faces)} faces read, {len(faces) - len(kept)} left out as degenerate",
      flush=True)

scene = bpy.context.scene
for ob in list(bpy.data.objects):
    bpy.data.objects.remove(ob, do_unlink=True)
mesh = bpy.data.meshes.new("faces")
mesh.from_pydata(verts, [], kept)
ids_attr = mesh.attributes.new("sightline_id", "INT", "FACE")
ids_attr.data.foreach_set("value", kept_ids)
mesh.validate()  # may drop invalid faces; the id attribute stays with the faces kept
ids = [0] * len(mesh.polygons)
mesh.attributes["sightline_id"].data.foreach_get("value", ids)
print(f"blender_face_ids: {len(mesh.polygons)} faces in Blender's mesh", flush=True)

# The colour of face id k: (k + 1) as 24-bit RGB, each byte b as the float b / 255, on every
# corner of the face (colour attributes live on points or corners).
colors = mesh.color_attributes.new("face_id", "FLOAT_COLOR", "CORNER")
loop_colors = [0.0] * (4 * len(mesh.loops))
for poly, fid in zip(mesh.polygons, ids):
    v = fid + 1
    rgba = ((v >> 16) & 255) / 255.0, ((v >> 8) & 255) / 255.0, (v & 255) / 255.0, 1.0
    for loop in range(poly.loop_start, poly.loop_start + poly.loop_total):
        loop_colors[4 * loop:4 * loop + 4] = rgba
colors.data.foreach_set("color", loop_colors)
mesh.color_attributes.active_color = colors
if hasattr(mesh.color_attributes, "render_color_index"):
    mesh.color_attributes.render_color_index = mesh.color_attributes.active_color_index
obj = bpy.data.objects.new("faces", mesh)
scene.collection.objects.link(obj)

# ---------------------------------------------------------------- the camera: gluLookAt
eye, target, up = Vector(cam["eye"]), Vector(cam["target"]), Vector(cam["up"])
forward = (target - eye).normalized()
right = forward.cross(up).normalized()
true_up = right.cross(forward).normalized()
M = Matrix.Identity(4)
for i in range(3):
    M[i][0], M[i][1], M[i][2], M[i][3] = right[i], true_up[i], -forward[i], eye[i]
camd = bpy.data.cameras.new("camera")
camd.sensor_fit = "VERTICAL"
camd.shift_x = camd.shift_y = 0.0
near, far = cam["near"][0], cam["far"][0]
if cam["fovy"][0] > 0:
    camd.type = "PERSP"
    camd.angle_y = math.radians(cam["fovy"][0])
else:
    camd.type = "ORTHO"
    camd.ortho_scale = cam["ortho_height"][0]  # with a vertical sensor fit: the view height
    if near <= 0:
        print(f"blender_face_ids: warning: near {near} raised to 1e-6 (Blender's clip start is positive): "
              "faces behind the camera's plane are clipped, sightline's are not", flush=True)
        near = 1e-6
camd.clip_start, camd.clip_end = near, far
camo = bpy.data.objects.new("camera", camd)
scene.collection.objects.link(camo)
camo.matrix_world = M
scene.camera = camo

# ---------------------------------------------------------------- render settings
r = scene.render
r.engine = "BLENDER_WORKBENCH"
r.resolution_x, r.resolution_y, r.resolution_percentage = W, H, 100
r.pixel_aspect_x = r.pixel_aspect_y = 1.0
r.use_border = False
r.film_transparent = True
r.dither_intensity = 0.0
r.image_settings.file_format = "PNG"
r.image_settings.color_mode = "RGBA"
r.image_settings.color_depth = "8"
r.image_settings.compression = 15
r.filepath = os.path.abspath(out_png)
d = scene.display
d.render_aa = "OFF"
s = d.shading
s.light = "FLAT"
s.color_type = "VERTEX"  # "Attribute" in the interface: the active colour attribute
s.show_object_outline = False
s.show_cavity = False
s.show_shadows = False
s.show_specular_highlight = False
s.show_xray = False
s.show_backface_culling = False
if hasattr(s, "use_dof"):
    s.use_dof = False
vs = scene.view_settings
vs.view_transform = "Raw"
vs.look = "None"
vs.exposure = 0.0
vs.gamma = 1.0
vs.use_curve_mapping = False
scene.display_settings.display_device = "sRGB"
if hasattr(r.image_settings, "color_management"):
    r.image_settings.color_management = "FOLLOW_SCENE"

bpy.ops.render.render(write_still=True)
print(f"blender_face_ids: wrote {out_png} ({W}x{H})", flush=True)
