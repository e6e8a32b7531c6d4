#!/usr/bin/env python3
"""Writes telear's shipped URDF arms: two ROS-style packages and their robot files.

  telear_ur6/   a 6-DOF arm of the UR type (no spherical wrist) from the published UR5
                Denavit-Hartenberg parameters, with a parallel two-finger gripper
  telear_arm7/  a 7-DOF redundant arm of the Franka-Panda type from its published modified
                DH parameters, with a two-finger hand
  ur6.yaml, arm7.yaml                 robot files (docs/robot-files.md)
  ur6.marker.yaml, arm7.marker.yaml   registration marker mounts (core/marker_mount.hpp)

Every mesh is made here, from surfaces of revolution (joint housings as cylinders with a
fillet profile, tapered tubes with rounded ends) and boxes, in the frame of the link that
carries it. Visual meshes are COLLADA (.dae, one coloured material per part) or Wavefront
(.obj + .mtl); collision meshes are coarse binary STL, one of them ASCII STL. Each part is a
closed shell with outward (counter-clockwise seen from outside) winding.

Deterministic: the same arguments give the same bytes (no time stamps, fixed number format,
coordinates rounded to 1 micrometre before they are written). Python 3 standard library only.

  /usr/bin/python3 scripts/generate_arms.py [--out data/robots] [--detail 24]

--detail is the number of segments around a visual surface of revolution (fillets and tube
lengths are subdivided in proportion); collision meshes use half of it (at least 8).
"""

import argparse
import math
import os
import struct
import sys

DEFAULT_DETAIL = 24
MIN_DETAIL = 6
MAX_DETAIL = 256

# ---------------------------------------------------------------------------------------------
# Small linear algebra (3-vectors as tuples, 3x3 matrices as row tuples).


def v_add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def v_sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def v_scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def v_dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def v_cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def v_norm(a):
    return math.sqrt(v_dot(a, a))


def v_unit(a):
    n = v_norm(a)
    return (a[0] / n, a[1] / n, a[2] / n)


def m_vec(m, v):
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


def frame_along(axis):
    """A rotation (det +1) whose third column is `axis`: maps local z onto it."""
    d = v_unit(axis)
    a = (1.0, 0.0, 0.0) if abs(d[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = v_unit(v_sub(a, v_scale(d, v_dot(a, d))))
    w = v_cross(d, u)
    return ((u[0], w[0], d[0]), (u[1], w[1], d[1]), (u[2], w[2], d[2]))


# ---------------------------------------------------------------------------------------------
# Shells: (vertices, triangles), triangles as index triples, counter-clockwise from outside.


def revolve(profile, segments):
    """The surface swept by the profile [(r, z), ...] around z. The profile runs from a pole
    (r = 0) at the bottom, outwards and up, to a pole at the top; the result is closed."""
    assert profile[0][0] == 0.0 and profile[-1][0] == 0.0
    rings = profile[1:-1]
    verts = [(0.0, 0.0, profile[0][1])]
    for r, z in rings:
        for j in range(segments):
            t = 2.0 * math.pi * j / segments
            verts.append((r * math.cos(t), r * math.sin(t), z))
    verts.append((0.0, 0.0, profile[-1][1]))
    top = len(verts) - 1
    tris = []

    def ring(k, j):
        return 1 + k * segments + (j % segments)

    for j in range(segments):
        tris.append((0, ring(0, j + 1), ring(0, j)))  # bottom fan: normal -z
    for k in range(len(rings) - 1):
        for j in range(segments):
            a, b = ring(k, j), ring(k, j + 1)
            c, d = ring(k + 1, j + 1), ring(k + 1, j)
            tris.append((a, b, c))  # (b - a) x (c - a) points away from the axis
            tris.append((a, c, d))
    last = len(rings) - 1
    for j in range(segments):
        tris.append((top, ring(last, j), ring(last, j + 1)))  # top fan: normal +z
    return verts, tris


def fillet_profile(r0, r1, length, fillet, arc_steps, length_steps):
    """Profile of a body of revolution from z = 0 to z = length whose radius tapers from r0 to
    r1, with quarter-circle fillets of radius `fillet` where the side meets the flat ends."""
    f = min(fillet, 0.45 * min(r0, r1), 0.45 * length)
    pts = [(0.0, 0.0)]
    for i in range(arc_steps + 1):  # bottom fillet, centre (r0 - f, f), angle -90 .. 0 deg
        phi = -0.5 * math.pi + 0.5 * math.pi * i / arc_steps
        pts.append((r0 - f + f * math.cos(phi), f + f * math.sin(phi)))
    for i in range(1, length_steps):  # straight or tapered side
        s = i / length_steps
        z = f + s * (length - 2.0 * f)
        pts.append((r0 + s * (r1 - r0), z))
    for i in range(arc_steps + 1):  # top fillet, centre (r1 - f, length - f), 0 .. 90 deg
        phi = 0.5 * math.pi * i / arc_steps
        pts.append((r1 - f + f * math.cos(phi), length - f + f * math.sin(phi)))
    pts.append((0.0, length))
    return pts


def transform(shell, rot, origin):
    verts, tris = shell
    return [v_add(m_vec(rot, v), origin) for v in verts], list(tris)


def box_shell(center, size):
    """A box with a vertex set per face, so that flat shading needs no special case."""
    hx, hy, hz = size[0] / 2, size[1] / 2, size[2] / 2
    verts, tris = [], []
    faces = [  # (normal axis, sign): corners counter-clockwise seen from outside
        ((1, 0, 0), [(1, -1, -1), (1, 1, -1), (1, 1, 1), (1, -1, 1)]),
        ((-1, 0, 0), [(-1, 1, -1), (-1, -1, -1), (-1, -1, 1), (-1, 1, 1)]),
        ((0, 1, 0), [(1, 1, -1), (-1, 1, -1), (-1, 1, 1), (1, 1, 1)]),
        ((0, -1, 0), [(-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1)]),
        ((0, 0, 1), [(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]),
        ((0, 0, -1), [(-1, 1, -1), (1, 1, -1), (1, -1, -1), (-1, -1, -1)]),
    ]
    for _, corners in faces:
        base = len(verts)
        for sx, sy, sz in corners:
            verts.append((center[0] + sx * hx, center[1] + sy * hy, center[2] + sz * hz))
        tris.append((base, base + 1, base + 2))
        tris.append((base, base + 2, base + 3))
    return verts, tris


# ---------------------------------------------------------------------------------------------
# Parts of a link: each is one closed shell with a material name.


class Detail:
    def __init__(self, segments, collision):
        self.segments = segments
        # Fillets and lengths subdivide faster than the segments, so that a high --detail
        # (a rendering benchmark) gives dense meshes: ~13k triangles an arm at 24, >100k at 64.
        self.arc_steps = 1 if collision else max(2, segments // 5)
        self.length_div = 0 if collision else max(1, segments * segments // 160)


def housing(center, axis, radius, length, material, fillet=None):
    """A joint housing: a cylinder centred on the joint, along its axis, with rounded rims."""
    return ("tube", center, axis, radius, radius, length, material, fillet)


def tube(p0, p1, r0, r1, material, fillet=None):
    d = v_sub(p1, p0)
    length = v_norm(d)
    c = v_scale(v_add(p0, p1), 0.5)
    return ("tube", c, d, r0, r1, length, material, fillet)


def box(center, size, material):
    return ("box", center, size, material)


def build_part(part, detail):
    if part[0] == "box":
        _, center, size, material = part
        return material, box_shell(center, size)
    _, center, axis, r0, r1, length, material, fillet = part
    if fillet is None:
        fillet = 0.18 * min(r0, r1)
    steps = 1 + int(detail.length_div * length / 0.1) if detail.length_div else 1
    prof = fillet_profile(r0, r1, length, fillet, detail.arc_steps, steps)
    shell = revolve(prof, detail.segments)
    rot = frame_along(axis)
    start = v_sub(center, v_scale(v_unit(axis), length / 2))
    return material, transform(shell, rot, start)


# ---------------------------------------------------------------------------------------------
# Number format and file writers.


def num(x):
    x = round(x, 6)
    if x == 0.0:
        return "0"
    s = "%.6f" % x
    s = s.rstrip("0").rstrip(".")
    return s


def vertex_normals(verts, tris):
    acc = [[0.0, 0.0, 0.0] for _ in verts]
    for a, b, c in tris:
        n = v_cross(v_sub(verts[b], verts[a]), v_sub(verts[c], verts[a]))  # area weighted
        for i in (a, b, c):
            acc[i][0] += n[0]
            acc[i][1] += n[1]
            acc[i][2] += n[2]
    out = []
    for n in acc:
        length = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
        out.append((n[0] / length, n[1] / length, n[2] / length) if length > 0 else (0, 0, 1))
    return out


def write_text(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)


def write_bytes(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


def write_dae(path, name, parts, palette):
    """COLLADA 1.4.1, Z up, metres; one geometry per part, one phong material per colour."""
    used = []
    for material, _ in parts:
        if material not in used:
            used.append(material)
    out = ['<?xml version="1.0" encoding="utf-8"?>',
           '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">',
           "  <asset>",
           "    <contributor><authoring_tool>telear scripts/generate_arms.py</authoring_tool>"
           "</contributor>",
           "    <created>2026-01-01T00:00:00</created>",
           "    <modified>2026-01-01T00:00:00</modified>",
           '    <unit name="meter" meter="1"/>',
           "    <up_axis>Z_UP</up_axis>",
           "  </asset>",
           "  <library_effects>"]
    for m in used:
        r, g, b = palette[m]
        out.append('    <effect id="%s-effect"><profile_COMMON><technique sid="common"><phong>'
                   '<diffuse><color sid="diffuse">%s %s %s 1</color></diffuse>'
                   '<specular><color sid="specular">0.25 0.25 0.25 1</color></specular>'
                   '<shininess><float sid="shininess">24</float></shininess>'
                   "</phong></technique></profile_COMMON></effect>" % (m, num(r), num(g), num(b)))
    out.append("  </library_effects>")
    out.append("  <library_materials>")
    for m in used:
        out.append('    <material id="%s-material" name="%s"><instance_effect url="#%s-effect"/>'
                   "</material>" % (m, m, m))
    out.append("  </library_materials>")
    out.append("  <library_geometries>")
    for k, (material, (verts, tris)) in enumerate(parts):
        gid = "%s-part%d" % (name, k)
        normals = vertex_normals(verts, tris)
        pos = " ".join("%s %s %s" % (num(v[0]), num(v[1]), num(v[2])) for v in verts)
        nrm = " ".join("%s %s %s" % (num(n[0]), num(n[1]), num(n[2])) for n in normals)
        idx = " ".join("%d %d %d" % t for t in tris)
        out.append('    <geometry id="%s-mesh" name="%s"><mesh>' % (gid, gid))
        for kind, data, count in (("positions", pos, len(verts)), ("normals", nrm, len(verts))):
            out.append('      <source id="%s-%s"><float_array id="%s-%s-array" count="%d">%s'
                       '</float_array><technique_common><accessor source="#%s-%s-array" '
                       'count="%d" stride="3"><param name="X" type="float"/><param name="Y" '
                       'type="float"/><param name="Z" type="float"/></accessor>'
                       "</technique_common></source>"
                       % (gid, kind, gid, kind, 3 * count, data, gid, kind, count))
        out.append('      <vertices id="%s-vertices"><input semantic="POSITION" '
                   'source="#%s-positions"/><input semantic="NORMAL" source="#%s-normals"/>'
                   "</vertices>" % (gid, gid, gid))
        out.append('      <triangles material="%s-material" count="%d"><input semantic="VERTEX" '
                   'source="#%s-vertices" offset="0"/><p>%s</p></triangles>'
                   % (material, len(tris), gid, idx))
        out.append("    </mesh></geometry>")
    out.append("  </library_geometries>")
    out.append('  <library_visual_scenes><visual_scene id="Scene" name="Scene">')
    for k, (material, _) in enumerate(parts):
        gid = "%s-part%d" % (name, k)
        out.append('    <node id="%s" name="%s" type="NODE"><instance_geometry url="#%s-mesh">'
                   '<bind_material><technique_common><instance_material symbol="%s-material" '
                   'target="#%s-material"/></technique_common></bind_material>'
                   "</instance_geometry></node>" % (gid, gid, gid, material, material))
    out.append("  </visual_scene></library_visual_scenes>")
    out.append('  <scene><instance_visual_scene url="#Scene"/></scene>')
    out.append("</COLLADA>")
    write_text(path, "\n".join(out) + "\n")


def write_obj(path, name, parts, palette):
    """Wavefront OBJ with per-vertex normals and a .mtl beside it (same base name)."""
    mtl_name = os.path.basename(path)[:-4] + ".mtl"
    used = []
    for material, _ in parts:
        if material not in used:
            used.append(material)
    mtl = ["# %s: materials of %s (telear scripts/generate_arms.py)" % (mtl_name, name)]
    for m in used:
        r, g, b = palette[m]
        mtl += ["newmtl %s" % m, "Ka 0 0 0", "Kd %s %s %s" % (num(r), num(g), num(b)),
                "Ks 0.25 0.25 0.25", "Ns 24", "d 1", "illum 2"]
    write_text(os.path.join(os.path.dirname(path), mtl_name), "\n".join(mtl) + "\n")
    out = ["# %s: visual mesh of link %s in its frame, metres (telear scripts/generate_arms.py)"
           % (os.path.basename(path), name), "mtllib %s" % mtl_name]
    base = 1
    for k, (material, (verts, tris)) in enumerate(parts):
        out.append("o %s-part%d" % (name, k))
        for v in verts:
            out.append("v %s %s %s" % (num(v[0]), num(v[1]), num(v[2])))
        for n in vertex_normals(verts, tris):
            out.append("vn %s %s %s" % (num(n[0]), num(n[1]), num(n[2])))
        out.append("usemtl %s" % material)
        for t in tris:
            a, b, c = (base + i for i in t)
            out.append("f %d//%d %d//%d %d//%d" % (a, a, b, b, c, c))
        base += len(verts)
    write_text(path, "\n".join(out) + "\n")


def facets(parts):
    for _, (verts, tris) in parts:
        for a, b, c in tris:
            p = [tuple(round(x, 6) for x in verts[i]) for i in (a, b, c)]
            n = v_cross(v_sub(p[1], p[0]), v_sub(p[2], p[0]))
            length = v_norm(n)
            n = v_scale(n, 1.0 / length) if length > 0 else (0.0, 0.0, 0.0)
            yield tuple(round(x, 6) for x in n), p


def write_stl_binary(path, name, parts):
    header = ("telear collision mesh %s" % name).encode("ascii")[:80].ljust(80, b" ")
    body = [header, b""]
    count = 0
    for n, p in facets(parts):
        body.append(struct.pack("<12fH", *n, *p[0], *p[1], *p[2], 0))
        count += 1
    body[1] = struct.pack("<I", count)
    write_bytes(path, b"".join(body))


def write_stl_ascii(path, name, parts):
    out = ["solid %s" % name]
    for n, p in facets(parts):
        out.append("  facet normal %s %s %s" % tuple(num(x) for x in n))
        out.append("    outer loop")
        for v in p:
            out.append("      vertex %s %s %s" % tuple(num(x) for x in v))
        out.append("    endloop")
        out.append("  endfacet")
    out.append("endsolid %s" % name)
    write_text(path, "\n".join(out) + "\n")


# ---------------------------------------------------------------------------------------------
# Kinematics shared by the URDF writer and the choice of named configurations.


def rpy_matrix(r, p, y):
    """URDF's rpy: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), \
        math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


class Joint:
    def __init__(self, name, kind, parent, child, xyz=(0, 0, 0), rpy=(0, 0, 0), axis=None,
                 lower=None, upper=None, effort=None, velocity=None, mimic=None, comment=None):
        self.name, self.kind, self.parent, self.child = name, kind, parent, child
        self.xyz, self.rpy, self.axis = xyz, rpy, axis
        self.lower, self.upper, self.effort, self.velocity = lower, upper, effort, velocity
        self.mimic, self.comment = mimic, comment


class Link:
    def __init__(self, name, visual=None, visual_format="dae", collision=None,
                 urdf_material=None, primitive=None, comment=None, visual_rpy=(0, 0, 0),
                 mesh_name=None, ascii_stl=False):
        self.name = name
        self.visual = visual or []  # parts
        self.visual_format = visual_format
        self.collision = collision  # parts, or None: same parts as the visual, coarse
        self.urdf_material = urdf_material  # (name, rgba) or None: the mesh's own colours
        self.primitive = primitive  # ("box", size, xyz) instead of meshes
        self.comment = comment
        self.visual_rpy = visual_rpy
        self.mesh_name = mesh_name or name
        self.ascii_stl = ascii_stl


def num_exact(x):
    """Angles and limits such as pi/2 at full double precision (as xacro writes ${pi/2}), so
    that the joints reproduce the DH chain exactly; round decimals stay short."""
    return num(x) if abs(x - round(x, 6)) < 1e-15 else repr(x)


def fmt_vec(v):
    return " ".join(num_exact(x) for x in v)


def write_urdf(path, robot, header, links, joints, package):
    out = ['<?xml version="1.0" ?>', "<!-- " + header.strip().replace("\n", "\n     ") + " -->",
           '<robot name="%s">' % robot]
    for link in links:
        if link.comment:
            out.append("  <!-- %s -->" % link.comment)
        if not link.visual and not link.primitive:
            out.append('  <link name="%s"/>' % link.name)
            continue
        out.append('  <link name="%s">' % link.name)
        if link.primitive:
            _, size, xyz = link.primitive
            geo = '<box size="%s"/>' % fmt_vec(size)
            out.append("    <visual>")
            out.append('      <origin xyz="%s" rpy="0 0 0"/>' % fmt_vec(xyz))
            out.append("      <geometry>%s</geometry>" % geo)
            mname, rgba = link.urdf_material
            out.append('      <material name="%s"><color rgba="%s"/></material>'
                       % (mname, fmt_vec(rgba)))
            out.append("    </visual>")
            out.append("    <collision>")
            out.append('      <origin xyz="%s" rpy="0 0 0"/>' % fmt_vec(xyz))
            out.append("      <geometry>%s</geometry>" % geo)
            out.append("    </collision>")
        else:
            uri = "package://%s/meshes/visual/%s.%s" % (package, link.mesh_name,
                                                         link.visual_format)
            out.append("    <visual>")
            out.append('      <origin xyz="0 0 0" rpy="%s"/>' % fmt_vec(link.visual_rpy))
            out.append('      <geometry><mesh filename="%s"/></geometry>' % uri)
            if link.urdf_material:
                mname, rgba = link.urdf_material
                out.append('      <material name="%s"><color rgba="%s"/></material>'
                           % (mname, fmt_vec(rgba)))
            out.append("    </visual>")
            out.append("    <collision>")
            out.append('      <origin xyz="0 0 0" rpy="%s"/>' % fmt_vec(link.visual_rpy))
            out.append('      <geometry><mesh filename="package://%s/meshes/collision/%s.stl"/>'
                       "</geometry>" % (package, link.mesh_name))
            out.append("    </collision>")
        out.append("  </link>")
    for j in joints:
        if j.comment:
            out.append("  <!-- %s -->" % j.comment)
        out.append('  <joint name="%s" type="%s">' % (j.name, j.kind))
        out.append('    <parent link="%s"/>' % j.parent)
        out.append('    <child link="%s"/>' % j.child)
        out.append('    <origin xyz="%s" rpy="%s"/>' % (fmt_vec(j.xyz), fmt_vec(j.rpy)))
        if j.axis is not None:
            out.append('    <axis xyz="%s"/>' % fmt_vec(j.axis))
        if j.kind in ("revolute", "prismatic"):
            out.append('    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>'
                       % (num_exact(j.lower), num_exact(j.upper), num(j.effort),
                          num_exact(j.velocity)))
        elif j.kind == "continuous":
            out.append('    <limit effort="%s" velocity="%s"/>' % (num(j.effort), num(j.velocity)))
        if j.mimic:
            out.append('    <mimic joint="%s" multiplier="1" offset="0"/>' % j.mimic)
        out.append("  </joint>")
    out.append("</robot>")
    write_text(path, "\n".join(out) + "\n")


def write_package_xml(path, package, description):
    text = """<?xml version="1.0"?>
<package format="2">
  <name>%s</name>
  <version>1.0.0</version>
  <description>%s</description>
  <maintainer email="telear@example.org">telear</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>urdf</exec_depend>
  <export/>
</package>
""" % (package, description)
    write_text(path, text)


def write_package(out_dir, package, robot, header, links, joints, description):
    root = os.path.join(out_dir, package)
    write_package_xml(os.path.join(root, "package.xml"), package, description)
    write_urdf(os.path.join(root, "urdf", robot + ".urdf"), robot, header, links, joints, package)
    return root


def write_meshes(root, links, palette, detail):
    visual_d = Detail(detail, collision=False)
    coll_d = Detail(max(8, detail // 2), collision=True)
    counts = {"visual": 0, "collision": 0}
    written = set()
    for link in links:
        if not link.visual or link.mesh_name in written:
            continue
        written.add(link.mesh_name)
        vparts = [build_part(p, visual_d) for p in link.visual]
        cparts = [build_part(p, coll_d) for p in (link.collision or link.visual)]
        counts["visual"] += sum(len(t) for _, (_, t) in vparts)
        counts["collision"] += sum(len(t) for _, (_, t) in cparts)
        vpath = os.path.join(root, "meshes", "visual", link.mesh_name + "." + link.visual_format)
        if link.visual_format == "dae":
            write_dae(vpath, link.mesh_name, vparts, palette)
        else:
            write_obj(vpath, link.mesh_name, vparts, palette)
        cpath = os.path.join(root, "meshes", "collision", link.mesh_name + ".stl")
        if link.ascii_stl:
            write_stl_ascii(cpath, link.mesh_name, cparts)
        else:
            write_stl_binary(cpath, link.mesh_name, cparts)
    return counts


def write_marker(path, robot, comment, side_m, xyz, rpy):
    text = ("# The ArUco registration marker of %s (include/telear/core/marker_mount.hpp,\n"
            "# docs/registration.md). Written by scripts/generate_arms.py: edit the script.\n"
            "%s"
            "dictionary: DICT_4X4_50\n"
            "id: 0\n"
            "side_m: %s\n"
            "pose_in_flange:     # in the tip frame (tcp), the chain's last frame\n"
            "  xyz: [%s]\n"
            "  rpy: [%s]\n") % (robot, comment, num(side_m), ", ".join(num(x) for x in xyz),
                                ", ".join(repr(x) for x in rpy))
    write_text(path, text)


def acm_block(robot, pairs):
    """The allowed-collision matrix block of a robot file, as `telear robot acm --robot ROBOT`
    prints it (default options: 2000 samples, seed 13, gripper at 0.5, constant-distance pairs
    allowed); the pairs are what that command found (tests/geometry checks that sampling still
    finds them)."""
    lines = ["# The allowed-collision matrix of %s, found by `telear robot acm` "
             "(docs/collision.md):" % robot,
             "# 2000 random configurations within the joint limits (seed 13), gripper at 0.5, "
             "constant-distance pairs (within 0.1 mm) allowed.",
             "allowed_collisions:"]
    lines += ["  - [%s, %s, %s]" % pair for pair in pairs]
    return lines


def write_robot_file(path, robot, header, package, gripper_open, max_opening, configs, acm):
    lines = [header.rstrip("\n"),
             "name: %s" % robot,
             "urdf: %s/urdf/%s.urdf" % (package, robot),
             'package_paths: ["."]',
             "tip: tcp",
             "gripper:",
             "  joints: [finger_left_joint]   # finger_right_joint is its <mimic>",
             "  closed: [0.0]",
             "  open: [%s]" % num(gripper_open),
             "  max_opening_m: %s" % num(max_opening),
             "named_configurations_deg:"]
    for name, q, why in configs:
        lines.append("  %s: [%s]%s" % (name, ", ".join(num(x) for x in q),
                                       ("   # " + why) if why else ""))
    lines.append("marker: %s.marker.yaml" % robot)
    lines += acm_block(robot, acm)
    write_text(path, "\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# The UR-type 6-DOF arm.

UR_D = [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823]
UR_A = [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0]
UR_ALPHA = [math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0]
UR_NAMES = ["shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"]
UR_LINKS = ["base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
            "wrist_2_link", "wrist_3_link", "tool0"]
UR_TCP_M = 0.1  # tool0 -> tcp, between the finger pads

UR_PALETTE = {
    "body": (0.82, 0.83, 0.84),
    "cap": (0.22, 0.42, 0.72),
    "dark": (0.2, 0.2, 0.22),
    "metal": (0.62, 0.63, 0.65),
}


def ur_joint_origin(i):
    """Origin of URDF joint i+1 (0-based i = 0..5; i = 6 is tool0): the constant part of DH
    row i, Tz(d_i) Tx(a_i) Rx(alpha_i), which is xyz = (a_i, 0, d_i), rpy = (alpha_i, 0, 0)
    (URDF applies the translation, then the rotation). Joint 1's origin is the identity."""
    if i == 0:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    k = i - 1
    return (UR_A[k], 0.0, UR_D[k]), (UR_ALPHA[k], 0.0, 0.0)


def ur_description():
    header = """telear_ur6: a 6-DOF arm of the common UR type (no spherical wrist), made by telear's
scripts/generate_arms.py from the published UR5 Denavit-Hartenberg parameters (standard DH,
T(i-1,i) = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)):
  d = [0.089159, 0, 0, 0.10915, 0.09465, 0.0823] m, a = [0, -0.425, -0.39225, 0, 0, 0] m,
  alpha = [pi/2, 0, 0, pi/2, -pi/2, 0].
How the joints reproduce that chain exactly: the frame of link i is DH frame i-1 turned by q_i
about its z axis; joint i+1's origin is DH row i's constant part Tz(d_i) Tx(a_i) Rx(alpha_i),
i.e. xyz = (a_i, 0, d_i) rpy = (alpha_i, 0, 0), and every axis is z. Since Rz(q) commutes with
Tz(d), the product of the joint transforms is the DH product; tool0 is DH frame 6.
A parallel two-finger gripper sits on the flange; tcp is between its finger pads.
Do not edit: regenerate with /usr/bin/python3 scripts/generate_arms.py."""
    R_SH, L_SH = 0.06, 0.135
    R_EL, L_EL = 0.05, 0.115
    R_WR, L_WR = 0.0425, 0.1
    d1, a2, a3, d4, d5, d6 = UR_D[0], UR_A[1], UR_A[2], UR_D[3], UR_D[4], UR_D[5]
    links = [
        Link("world"),
        Link("base_link", [
            housing((0, 0, 0.0075), (0, 0, 1), 0.09, 0.015, "metal", fillet=0.004),
            housing((0, 0, 0.04), (0, 0, 1), 0.065, 0.06, "body"),
            housing((0, 0, 0.0725), (0, 0, 1), 0.06, 0.007, "cap", fillet=0.003),
        ], comment="links: each mesh is in its link's frame (see the header)"),
        Link("shoulder_link", [
            housing((0, 0, 0.052), (0, 0, 1), R_SH, 0.04, "body"),
            housing((0, 0, d1), (0, -1, 0), R_SH, L_SH, "body"),
            housing((0, -(L_SH / 2 + 0.004), d1), (0, -1, 0), 0.05, 0.01, "cap", fillet=0.004),
        ]),
        Link("upper_arm_link", [
            tube((-0.045, 0, 0), (a2 + 0.04, 0, 0), 0.045, 0.038, "body", fillet=0.01),
            housing((0, 0, -(L_SH / 2 + 0.004)), (0, 0, 1), 0.05, 0.01, "cap", fillet=0.004),
            housing((a2, 0, 0), (0, 0, 1), R_EL, L_EL, "body"),
            housing((a2, 0, -(L_EL / 2 + 0.004)), (0, 0, 1), 0.04, 0.01, "cap", fillet=0.004),
        ]),
        Link("forearm_link", [
            tube((-0.035, 0, 0), (a3 + 0.03, 0, 0), 0.038, 0.032, "body", fillet=0.008),
            housing((0, 0, L_EL / 2 + 0.004), (0, 0, 1), 0.04, 0.01, "cap", fillet=0.004),
            housing((a3, 0, 0.0), (0, 0, 1), R_WR, L_WR, "body"),
            housing((a3, 0, -(L_WR / 2 + 0.003)), (0, 0, 1), 0.034, 0.008, "cap", fillet=0.003),
        ]),
        Link("wrist_1_link", [
            tube((0, 0, 0.045), (0, 0, d4 - 0.03), 0.036, 0.036, "body", fillet=0.006),
            housing((0, 0, d4), (0, -1, 0), R_WR, L_WR, "body"),
            housing((0, -(L_WR / 2 + 0.003), d4), (0, -1, 0), 0.034, 0.008, "cap",
                    fillet=0.003),
        ], visual_format="obj", urdf_material=("ur_grey", (0.82, 0.83, 0.84, 1.0))),
        Link("wrist_2_link", [
            tube((0, 0, 0.045), (0, 0, d5 - 0.03), 0.036, 0.036, "body", fillet=0.006),
            housing((0, 0, d5), (0, 1, 0), R_WR, 0.09, "body"),
            housing((0, 0.048, d5), (0, 1, 0), 0.034, 0.008, "cap", fillet=0.003),
        ], visual_format="obj", urdf_material=("ur_grey", (0.82, 0.83, 0.84, 1.0))),
        Link("wrist_3_link", [
            tube((0, 0, 0.044), (0, 0, d6 - 0.01), 0.033, 0.033, "body", fillet=0.004),
            housing((0, 0, d6 - 0.005), (0, 0, 1), 0.0375, 0.01, "metal", fillet=0.002),
        ], visual_format="obj", urdf_material=("ur_metal", (0.62, 0.63, 0.65, 1.0))),
        Link("tool0", comment="the flange: DH frame 6"),
        Link("gripper_base", [
            housing((0, 0, 0.015), (0, 0, 1), 0.035, 0.03, "dark", fillet=0.004),
            box((0, 0, 0.045), (0.04, 0.13, 0.03), "dark"),
            box((0.041, 0, 0.03), (0.042, 0.02, 0.02), "metal"),
        ], comment="the gripper: its palm and the bracket of the marker plate"),
        Link("finger_left", [
            box((0, 0.008, 0.025), (0.02, 0.016, 0.05), "metal"),
        ], visual_format="obj", mesh_name="finger",
            comment="fingers: one mesh, the right one turned half a turn about z"),
        Link("finger_right", [
            box((0, 0.008, 0.025), (0.02, 0.016, 0.05), "metal"),
        ], visual_format="obj", mesh_name="finger", visual_rpy=(0, 0, math.pi)),
        Link("tcp", comment="the tool centre point between the finger pads: the tip"),
        Link("marker_plate", primitive=("box", (0.004, 0.1, 0.1), (0, 0, 0)),
             urdf_material=("marker_white", (0.95, 0.95, 0.95, 1.0)),
             comment="the plate of the registration marker (ur6.marker.yaml)"),
    ]
    joints = [Joint("world_joint", "fixed", "world", "base_link",
                    comment="the arm stands on the world origin")]
    for i in range(6):
        xyz, rpy = ur_joint_origin(i)
        wrist = i >= 3
        joints.append(Joint(UR_NAMES[i] + "_joint", "revolute", UR_LINKS[i], UR_LINKS[i + 1],
                            xyz, rpy, (0, 0, 1), -2 * math.pi, 2 * math.pi,
                            28.0 if wrist else 150.0, math.pi if wrist else 2.094395))
    xyz, rpy = (UR_A[5], 0.0, UR_D[5]), (UR_ALPHA[5], 0.0, 0.0)
    joints.append(Joint("flange_joint", "fixed", "wrist_3_link", "tool0", xyz, rpy))
    joints.append(Joint("gripper_joint", "fixed", "tool0", "gripper_base"))
    joints.append(Joint("finger_left_joint", "prismatic", "gripper_base", "finger_left",
                        (0, 0, 0.06), (0, 0, 0), (0, 1, 0), 0.0, 0.04, 40.0, 0.1,
                        comment="the fingers open symmetrically; each moves 0..40 mm"))
    joints.append(Joint("finger_right_joint", "prismatic", "gripper_base", "finger_right",
                        (0, 0, 0.06), (0, 0, 0), (0, -1, 0), 0.0, 0.04, 40.0, 0.1,
                        mimic="finger_left_joint"))
    joints.append(Joint("tcp_joint", "fixed", "gripper_base", "tcp", (0, 0, UR_TCP_M)))
    joints.append(Joint("marker_plate_joint", "fixed", "gripper_base", "marker_plate",
                        (0.064, 0, 0.03)))
    return header, links, joints


# ---------------------------------------------------------------------------------------------
# The Panda-type 7-DOF arm (modified DH, Craig: T(i-1,i) = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(q_i)
# Tz(d_i); rows give a_{i-1}, d_i, alpha_{i-1}).

P7_A = [0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088]
P7_D = [0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0]
P7_ALPHA = [0.0, -math.pi / 2, math.pi / 2, math.pi / 2, -math.pi / 2, math.pi / 2, math.pi / 2]
P7_FLANGE_M = 0.107
P7_LOWER = [-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973]
P7_UPPER = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973]
P7_VEL = [2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61]
P7_EFFORT = [87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0]
P7_HAND_FINGER_M = 0.0584
P7_TCP_M = 0.1034  # hand (flange) -> tcp

P7_PALETTE = {
    "white": (0.93, 0.93, 0.92),
    "dark": (0.16, 0.16, 0.18),
    "metal": (0.6, 0.61, 0.63),
}


def p7_joint_origin(i):
    """Origin of joint i+1: Rx(alpha_i) Tx(a_i) Tz(d_i) = xyz (a, -sin(alpha) d, cos(alpha) d),
    rpy (alpha, 0, 0); Rz(q) then turns about the new z, as in the modified DH row."""
    a, d, al = P7_A[i], P7_D[i], P7_ALPHA[i]
    return (a, -math.sin(al) * d, math.cos(al) * d), (al, 0.0, 0.0)


def arm7_description():
    header = """telear_arm7: a 7-DOF redundant arm of the Franka-Panda type, made by telear's
scripts/generate_arms.py from the published modified Denavit-Hartenberg parameters
(Craig's convention, T(i-1,i) = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(q_i) Tz(d_i)):
  d1 = 0.333, d3 = 0.316, a4 = 0.0825, a5 = -0.0825, d5 = 0.384, a7 = 0.088 m, flange 0.107 m,
  alpha = [0, -pi/2, pi/2, pi/2, -pi/2, pi/2, pi/2]; joint limits as published (rad).
Joint i's origin is Rx(alpha_{i-1}) Tx(a_{i-1}) Tz(d_i) = xyz (a, -sin(alpha) d, cos(alpha) d)
rpy (alpha, 0, 0), axis z: link i's frame is DH frame i. A hand with two fingers sits on the
flange turned -45 deg about z; tcp is 0.1034 m past the flange.
Do not edit: regenerate with /usr/bin/python3 scripts/generate_arms.py."""
    R = 0.06
    links = [
        Link("world"),
        Link("link0", [
            housing((0, 0, 0.0075), (0, 0, 1), 0.11, 0.015, "metal", fillet=0.004),
            housing((-0.02, 0, 0.08), (0, 0, 1), 0.075, 0.13, "white"),
            box((-0.09, 0, 0.05), (0.08, 0.1, 0.08), "white"),
        ], comment="links: each mesh is in its link's frame (= modified DH frame i)"),
        Link("link1", [
            housing((0, 0, -0.1), (0, 0, 1), R, 0.2, "white"),
            housing((0, 0, 0), (0, 1, 0), R, 0.13, "white"),
            housing((0, 0.069, 0), (0, 1, 0), 0.045, 0.008, "dark", fillet=0.003),
        ]),
        Link("link2", [
            tube((0, -0.02, 0), (0, -0.15, 0), 0.055, 0.055, "white", fillet=0.01),
            housing((0, 0, -0.069), (0, 0, 1), 0.045, 0.008, "dark", fillet=0.003),
        ]),
        Link("link3", [
            tube((0, 0, -0.17), (0, 0, -0.01), 0.055, 0.05, "white", fillet=0.01),
            tube((0, 0, 0), (0.0825, 0, 0), 0.045, 0.045, "white", fillet=0.008),
            housing((0.0825, 0, 0), (0, -1, 0), 0.055, 0.12, "white"),
            housing((0.0825, -0.064, 0), (0, -1, 0), 0.045, 0.008, "dark", fillet=0.003),
        ]),
        Link("link4", [
            tube((0, 0.0, 0), (-0.0825, 0.0, 0), 0.045, 0.045, "white", fillet=0.008),
            housing((-0.0825, 0, 0), (0, 0, 1), 0.055, 0.12, "white"),
            tube((-0.0825, 0.03, 0), (-0.0825, 0.12, 0), 0.05, 0.05, "dark", fillet=0.006),
        ]),
        Link("link5", [
            tube((0, 0, -0.27), (0, 0, -0.03), 0.05, 0.045, "white", fillet=0.01),
            housing((0, 0, 0), (0, -1, 0), 0.05, 0.11, "white"),
            housing((0, -0.059, 0), (0, -1, 0), 0.04, 0.008, "dark", fillet=0.003),
        ]),
        Link("link6", [
            tube((0, 0, 0), (0.088, 0, 0), 0.042, 0.042, "white", fillet=0.008),
            housing((0.088, -0.01, 0), (0, -1, 0), 0.047, 0.09, "white"),
            housing((0, 0, 0.059), (0, 0, 1), 0.04, 0.008, "dark", fillet=0.003),
        ], visual_format="obj", urdf_material=("panda_white", (0.93, 0.93, 0.92, 1.0))),
        Link("link7", [
            tube((0, 0, 0.035), (0, 0, P7_FLANGE_M - 0.012), 0.038, 0.038, "dark",
                 fillet=0.005),
            housing((0, 0, P7_FLANGE_M - 0.006), (0, 0, 1), 0.045, 0.012, "metal", fillet=0.002),
        ]),
        Link("link8", comment="the flange"),
        Link("hand", [
            housing((0, 0, 0.01), (0, 0, 1), 0.04, 0.02, "dark", fillet=0.003),
            box((0, 0, 0.038), (0.05, 0.2, 0.04), "white"),
            box((0.045, 0, 0.03), (0.04, 0.02, 0.02), "metal"),
        ], visual_format="obj", urdf_material=("panda_white", (0.93, 0.93, 0.92, 1.0)),
            ascii_stl=True, comment="the hand: palm and the bracket of the marker plate"),
        Link("finger_left", [
            box((0, 0.009, 0.025), (0.02, 0.018, 0.05), "dark"),
        ], visual_format="obj", mesh_name="finger",
            comment="fingers: one mesh, the right one turned half a turn about z"),
        Link("finger_right", [
            box((0, 0.009, 0.025), (0.02, 0.018, 0.05), "dark"),
        ], visual_format="obj", mesh_name="finger", visual_rpy=(0, 0, math.pi)),
        Link("tcp", comment="the tool centre point between the finger pads: the tip"),
        Link("marker_plate", primitive=("box", (0.004, 0.1, 0.1), (0, 0, 0)),
             urdf_material=("marker_white", (0.95, 0.95, 0.95, 1.0)),
             comment="the plate of the registration marker (arm7.marker.yaml)"),
    ]
    joints = [Joint("world_joint", "fixed", "world", "link0",
                    comment="the arm stands on the world origin")]
    for i in range(7):
        xyz, rpy = p7_joint_origin(i)
        joints.append(Joint("joint%d" % (i + 1), "revolute", "link%d" % i, "link%d" % (i + 1),
                            xyz, rpy, (0, 0, 1), P7_LOWER[i], P7_UPPER[i], P7_EFFORT[i],
                            P7_VEL[i]))
    joints.append(Joint("flange_joint", "fixed", "link7", "link8", (0, 0, P7_FLANGE_M)))
    joints.append(Joint("hand_joint", "fixed", "link8", "hand", (0, 0, 0),
                        (0, 0, -math.pi / 4)))
    joints.append(Joint("finger_left_joint", "prismatic", "hand", "finger_left",
                        (0, 0, P7_HAND_FINGER_M), (0, 0, 0), (0, 1, 0), 0.0, 0.04, 20.0, 0.2,
                        comment="the fingers open symmetrically; each moves 0..40 mm"))
    joints.append(Joint("finger_right_joint", "prismatic", "hand", "finger_right",
                        (0, 0, P7_HAND_FINGER_M), (0, 0, 0), (0, -1, 0), 0.0, 0.04, 20.0, 0.2,
                        mimic="finger_left_joint"))
    joints.append(Joint("tcp_joint", "fixed", "hand", "tcp", (0, 0, P7_TCP_M)))
    joints.append(Joint("marker_plate_joint", "fixed", "hand", "marker_plate",
                        (0.067, 0, 0.03)))
    return header, links, joints


# ---------------------------------------------------------------------------------------------


ROBOT_FILE_HEADER = """# %s: %s
# A robot file (docs/robot-files.md): the URDF package beside it, the tip, the gripper and the
# named configurations (home and ready: gripper pointing down above a table in front of the
# base, within the limits, away from singularities; checked by tests/data/check_arms.py).
# Written by scripts/generate_arms.py: edit the script and regenerate.
"""

# The marker faces +x of the tip frame on its plate, 0.5 mm proud of the plate's face; the
# marker's x runs along -y of the tip and its y along -z (back up towards the flange), so that
# R = [[0, 0, 1], [-1, 0, 0], [0, -1, 0]] = Rz(-pi/2) Ry(0) Rx(-pi/2).
MARKER_RPY = (-math.pi / 2, 0.0, -math.pi / 2)
MARKER_SIDE_M = 0.08


def generate(out_dir, detail):
    counts = {}
    ur_header, ur_links, ur_joints = ur_description()
    root = write_package(out_dir, "telear_ur6", "ur6", ur_header, ur_links, ur_joints,
                         "A UR-type 6-DOF arm (UR5 DH parameters) with a "
                            "parallel gripper, made by telear's scripts/generate_arms.py.")
    counts["ur6"] = write_meshes(root, ur_links, UR_PALETTE, detail)
    p7_header, p7_links, p7_joints = arm7_description()
    root = write_package(out_dir, "telear_arm7", "arm7", p7_header, p7_links, p7_joints,
                         "A Panda-type 7-DOF redundant arm with a two-finger "
                            "hand, made by telear's scripts/generate_arms.py.")
    counts["arm7"] = write_meshes(root, p7_links, P7_PALETTE, detail)

    # Marker centres in the tip frame: the plate's outer face, 30 mm + plate half height above
    # the gripper base, i.e. (plate x + 2 mm + 0.5 mm, 0, 0.03 - tcp offset).
    write_marker(os.path.join(out_dir, "ur6.marker.yaml"), "the ur6 arm",
                 "# On a plate on the gripper's side, facing +x of the tcp frame.\n",
                 MARKER_SIDE_M, (0.064 + 0.0025, 0.0, 0.03 - UR_TCP_M), MARKER_RPY)
    write_marker(os.path.join(out_dir, "arm7.marker.yaml"), "the arm7 arm",
                 "# On a plate on the hand's side, facing +x of the tcp frame.\n",
                 MARKER_SIDE_M, (0.067 + 0.0025, 0.0, 0.03 - P7_TCP_M), MARKER_RPY)
    write_robot_file(os.path.join(out_dir, "ur6.yaml"), "ur6",
                     ROBOT_FILE_HEADER % ("ur6", "a UR-type 6-DOF arm with a parallel gripper"),
                     "telear_ur6", 0.04, 0.08, UR_CONFIGS, UR_ACM)
    write_robot_file(os.path.join(out_dir, "arm7.yaml"), "arm7",
                     ROBOT_FILE_HEADER % ("arm7", "a Panda-type 7-DOF arm with a hand"),
                     "telear_arm7", 0.04, 0.08, P7_CONFIGS, P7_ACM)
    return counts


UR_CONFIGS = [
    ("zero", [0, 0, 0, 0, 0, 0], "all zero: stretched out along -x (a singular pose)"),
    ("home", [0, -90, -90, -90, 90, 0], "tcp at (0.487, -0.109, 0.332) m, pointing down"),
    ("ready", [-20, -120, -70, -80, 90, 0], "tcp at (0.614, -0.340, 0.207) m, pointing down"),
]
P7_CONFIGS = [
    ("zero", [0, 0, 0, 0, 0, 0, 0], "joint 4's limits exclude 0: out of limits"),
    ("home", [0, -45, 0, -135, 0, 90, 45], "tcp at (0.307, 0, 0.487) m, pointing down"),
    ("ready", [-20, 10, 0, -130, 0, 140, 25], "tcp at (0.502, -0.183, 0.178) m, pointing down"),
]

# The allowed-collision matrices `telear robot acm --robot ur6|arm7` finds: the adjacent pairs
# only (no other pair is in contact in every sample, nor at a constant distance).
UR_ACM = [
    ("base_link", "shoulder_link", "adjacent"),
    ("finger_left", "finger_right", "adjacent"),
    ("finger_left", "gripper_base", "adjacent"),
    ("finger_left", "marker_plate", "adjacent"),
    ("finger_left", "wrist_2_link", "adjacent"),
    ("finger_left", "wrist_3_link", "adjacent"),
    ("finger_right", "gripper_base", "adjacent"),
    ("finger_right", "marker_plate", "adjacent"),
    ("finger_right", "wrist_2_link", "adjacent"),
    ("finger_right", "wrist_3_link", "adjacent"),
    ("forearm_link", "upper_arm_link", "adjacent"),
    ("forearm_link", "wrist_1_link", "adjacent"),
    ("gripper_base", "marker_plate", "adjacent"),
    ("gripper_base", "wrist_2_link", "adjacent"),
    ("gripper_base", "wrist_3_link", "adjacent"),
    ("marker_plate", "wrist_2_link", "adjacent"),
    ("marker_plate", "wrist_3_link", "adjacent"),
    ("shoulder_link", "upper_arm_link", "adjacent"),
    ("wrist_1_link", "wrist_2_link", "adjacent"),
    ("wrist_2_link", "wrist_3_link", "adjacent"),
]
P7_ACM = [
    ("finger_left", "finger_right", "adjacent"),
    ("finger_left", "hand", "adjacent"),
    ("finger_left", "link6", "adjacent"),
    ("finger_left", "link7", "adjacent"),
    ("finger_left", "marker_plate", "adjacent"),
    ("finger_right", "hand", "adjacent"),
    ("finger_right", "link6", "adjacent"),
    ("finger_right", "link7", "adjacent"),
    ("finger_right", "marker_plate", "adjacent"),
    ("hand", "link6", "adjacent"),
    ("hand", "link7", "adjacent"),
    ("hand", "marker_plate", "adjacent"),
    ("link0", "link1", "adjacent"),
    ("link1", "link2", "adjacent"),
    ("link2", "link3", "adjacent"),
    ("link3", "link4", "adjacent"),
    ("link4", "link5", "adjacent"),
    ("link5", "link6", "adjacent"),
    ("link6", "link7", "adjacent"),
    ("link6", "marker_plate", "adjacent"),
    ("link7", "marker_plate", "adjacent"),
]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=None,
                        help="output directory (default: data/robots of this source tree)")
    parser.add_argument("--detail", type=int, default=DEFAULT_DETAIL,
                        help="segments around a visual surface of revolution (default %d)"
                        % DEFAULT_DETAIL)
    args = parser.parse_args(argv)
    if not MIN_DETAIL <= args.detail <= MAX_DETAIL:
        print("generate_arms.py: --detail must be in %d..%d, got %d"
              % (MIN_DETAIL, MAX_DETAIL, args.detail), file=sys.stderr)
        return 2
    out = args.out
    if out is None:
        out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "robots")
    counts = generate(out, args.detail)
    for robot in ("ur6", "arm7"):
        print("%s: %d visual triangles, %d collision triangles"
              % (robot, counts[robot]["visual"], counts[robot]["collision"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
