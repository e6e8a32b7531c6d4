#!/usr/bin/env python3
"""Checks telear's shipped URDF arms (data/robots/telear_ur6, telear_arm7 and their robot
files) against scripts/generate_arms.py and against what an arm must be:

- regenerating into a temporary directory gives the shipped files byte for byte, and nothing
  shipped is missing from the generator's output; a bad --detail is refused with a message;
- every mesh (COLLADA, OBJ, binary and ASCII STL) is closed, each edge shared by exactly two
  triangles running it in opposite directions (consistent winding), with positive signed
  volume (outward normals), and the triangle budgets hold;
- each URDF parses, every mesh URI exists, the tree has the gripper with its <mimic>;
- forward kinematics of the URDF reproduces the published DH chains (written here
  independently of the generator) at random configurations;
- the named configurations home and ready are within limits, non-singular, with the gripper
  pointing down above the table in front of the base; the marker lies on its plate.

Usage: check_arms.py SOURCE_DIR   (standard library + PyYAML, run with /usr/bin/python3)
"""

import filecmp
import math
import os
import random
import struct
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

import yaml

SOURCE_DIR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                             os.path.join(os.path.dirname(__file__), "..", ".."))
ROBOTS = os.path.join(SOURCE_DIR, "data", "robots")
GENERATOR = os.path.join(SOURCE_DIR, "scripts", "generate_arms.py")
ARMS = {"ur6": "telear_ur6", "arm7": "telear_arm7"}

# ---------------------------------------------------------------------------------------------
# Mesh readers: each returns a list of shells, a shell being (positions, triangles).


def read_dae(path):
    ns = {"c": "http://www.collada.org/2005/11/COLLADASchema"}
    root = ET.parse(path).getroot()
    shells = []
    for geo in root.findall(".//c:library_geometries/c:geometry", ns):
        mesh = geo.find("c:mesh", ns)
        vertices = mesh.find("c:vertices", ns)
        pos_id = [i.get("source")[1:] for i in vertices.findall("c:input", ns)
                  if i.get("semantic") == "POSITION"][0]
        src = [s for s in mesh.findall("c:source", ns) if s.get("id") == pos_id][0]
        floats = [float(x) for x in src.find("c:float_array", ns).text.split()]
        pts = [tuple(floats[i:i + 3]) for i in range(0, len(floats), 3)]
        tris_el = mesh.find("c:triangles", ns)
        stride = len(tris_el.findall("c:input", ns))
        idx = [int(x) for x in tris_el.find("c:p", ns).text.split()]
        assert len(idx) == 3 * stride * int(tris_el.get("count")), path
        v = idx[0::stride]
        shells.append((pts, [tuple(v[i:i + 3]) for i in range(0, len(v), 3)]))
    return shells


def read_obj(path):
    shells, pts = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "o":
                shells.append([])
            elif w[0] == "v":
                pts.append(tuple(float(x) for x in w[1:4]))
            elif w[0] == "f":
                shells[-1].append(tuple(int(x.split("/")[0]) - 1 for x in w[1:]))
    return [(pts, tris) for tris in shells]


def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    pts, tris = [], []
    if data.startswith(b"solid"):
        for line in data.decode("ascii").splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                pts.append(tuple(float(x) for x in w[1:4]))
    else:
        (count,) = struct.unpack_from("<I", data, 80)
        assert len(data) == 84 + 50 * count, "%s: size does not match its count" % path
        for k in range(count):
            vals = struct.unpack_from("<12f", data, 84 + 50 * k)
            pts += [tuple(vals[3:6]), tuple(vals[6:9]), tuple(vals[9:12])]
    tris = [(i, i + 1, i + 2) for i in range(0, len(pts), 3)]
    return [(pts, tris)]


def read_head(path):
    with open(path, "rb") as f:
        return f.read(5)


def read_mesh(path):
    ext = os.path.splitext(path)[1].lower()
    return {".dae": read_dae, ".obj": read_obj, ".stl": read_stl}[ext](path)


def shell_defects(pts, tris):
    """Welds equal positions, then returns (problems, signed volume)."""
    weld, ids = {}, []
    for p in pts:
        ids.append(weld.setdefault(p, len(weld)))
    directed = {}
    problems = []
    volume = 0.0
    for t in tris:
        a, b, c = (ids[i] for i in t)
        if len({a, b, c}) < 3:
            problems.append("degenerate triangle %s" % (t,))
            continue
        for e in ((a, b), (b, c), (c, a)):
            directed[e] = directed.get(e, 0) + 1
        p, q, r = pts[t[0]], pts[t[1]], pts[t[2]]
        volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
                   p[2] * (q[0] * r[1] - q[1] * r[0])) / 6.0
    for (a, b), n in directed.items():
        if n != 1:
            problems.append("edge %d-%d run %d times the same way (inconsistent winding)"
                            % (a, b, n))
        if directed.get((b, a), 0) != 1:
            problems.append("edge %d-%d has no opposite (open surface)" % (a, b))
    return problems, volume


# ---------------------------------------------------------------------------------------------
# URDF kinematics, written from the URDF's own definition.


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def rpy_rot(r, p, y):
    cr, sr, cp, sp, cy, sy = (math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y),
                              math.sin(y))
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr], [-sp, cp * sr, cp * cr]]


def homog(rot, xyz):
    return [rot[0] + [xyz[0]], rot[1] + [xyz[1]], rot[2] + [xyz[2]], [0, 0, 0, 1]]


def axis_angle(axis, q):
    x, y, z = axis
    c, s, t = math.cos(q), math.sin(q), 1 - math.cos(q)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]


def vec(text, default="0 0 0"):
    return [float(x) for x in (text if text is not None else default).split()]


class Urdf:
    def __init__(self, path):
        self.path = path
        self.root = ET.parse(path).getroot()
        self.joints = {}
        for j in self.root.findall("joint"):
            o = j.find("origin")
            lim = j.find("limit")
            mim = j.find("mimic")
            self.joints[j.get("name")] = {
                "type": j.get("type"), "parent": j.find("parent").get("link"),
                "child": j.find("child").get("link"),
                "T": homog(rpy_rot(*vec(o.get("rpy") if o is not None else None)),
                           vec(o.get("xyz") if o is not None else None)),
                "axis": vec(j.find("axis").get("xyz")) if j.find("axis") is not None else None,
                "lower": float(lim.get("lower")) if lim is not None and lim.get("lower") else None,
                "upper": float(lim.get("upper")) if lim is not None and lim.get("upper") else None,
                "mimic": mim.get("joint") if mim is not None else None}
        self.links = {l.get("name"): l for l in self.root.findall("link")}
        self.parent_joint = {j["child"]: name for name, j in self.joints.items()}

    def chain(self, tip):
        """Joint names from the root to `tip`."""
        out, link = [], tip
        while link in self.parent_joint:
            name = self.parent_joint[link]
            out.append(name)
            link = self.joints[name]["parent"]
        return list(reversed(out))

    def movable(self, tip):
        return [n for n in self.chain(tip) if self.joints[n]["type"] != "fixed"]

    def fk(self, tip, q, frames=False):
        T = homog([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, 0, 0])
        qi = iter(q)
        out = []
        for name in self.chain(tip):
            j = self.joints[name]
            T = mat_mul(T, j["T"])
            if j["type"] != "fixed":
                T = mat_mul(T, homog(axis_angle(j["axis"], next(qi)), [0, 0, 0]))
                out.append(T)
        return (T, out) if frames else T


def std_dh(d, a, alpha, q):
    T = homog([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, 0, 0])
    for i, qi in enumerate(q):
        ct, st, ca, sa = math.cos(qi), math.sin(qi), math.cos(alpha[i]), math.sin(alpha[i])
        T = mat_mul(T, [[ct, -st * ca, st * sa, a[i] * ct], [st, ct * ca, -ct * sa, a[i] * st],
                        [0, sa, ca, d[i]], [0, 0, 0, 1]])
    return T


def mod_dh(a, d, alpha, q, flange):
    T = homog([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, 0, 0])
    for i, qi in enumerate(list(q) + [0.0]):
        ai, di, al = (a[i], d[i], alpha[i]) if i < len(q) else (0.0, flange, 0.0)
        ct, st, ca, sa = math.cos(qi), math.sin(qi), math.cos(al), math.sin(al)
        T = mat_mul(T, [[ct, -st, 0, ai], [st * ca, ct * ca, -sa, -sa * di],
                        [st * sa, ct * sa, ca, ca * di], [0, 0, 0, 1]])
    return T


def max_diff(A, B):
    return max(abs(A[i][j] - B[i][j]) for i in range(3) for j in range(4))


def jacobian(urdf, tip, q):
    T, frames = urdf.fk(tip, q, frames=True)
    p = [T[0][3], T[1][3], T[2][3]]
    names = urdf.movable(tip)
    cols = []
    for name, F in zip(names, frames):
        z = [F[0][0] * 0 + sum(F[r][c] * urdf.joints[name]["axis"][c] for c in range(3))
             for r in range(3)]
        o = [F[0][3], F[1][3], F[2][3]]
        r = [p[k] - o[k] for k in range(3)]
        cols.append([z[1] * r[2] - z[2] * r[1], z[2] * r[0] - z[0] * r[2],
                     z[0] * r[1] - z[1] * r[0]] + z)
    return [[cols[c][r] for c in range(len(cols))] for r in range(6)]


def min_singular_value(J):
    """sqrt of the smallest eigenvalue of J J^T (Jacobi rotations on the 6x6 matrix)."""
    n = len(J)
    A = [[sum(J[i][k] * J[j][k] for k in range(len(J[0]))) for j in range(n)] for i in range(n)]
    for _ in range(100):
        off = sum(A[i][j] ** 2 for i in range(n) for j in range(n) if i != j)
        if off < 1e-24:
            break
        for p in range(n):
            for q in range(p + 1, n):
                if abs(A[p][q]) < 1e-30:
                    continue
                theta = (A[q][q] - A[p][p]) / (2 * A[p][q])
                t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1))
                c = 1 / math.sqrt(t * t + 1)
                s = t * c
                for k in range(n):
                    akp, akq = A[k][p], A[k][q]
                    A[k][p], A[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):
                    apk, aqk = A[p][k], A[q][k]
                    A[p][k], A[q][k] = c * apk - s * aqk, s * apk + c * aqk
    return math.sqrt(max(0.0, min(A[i][i] for i in range(n))))


# ---------------------------------------------------------------------------------------------


class GeneratorOutput(unittest.TestCase):
    def test_regenerating_gives_the_shipped_files_byte_for_byte(self):
        with tempfile.TemporaryDirectory() as tmp:
            run = subprocess.run([sys.executable, GENERATOR, "--out", tmp],
                                 capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stderr)
            generated = sorted(os.path.relpath(os.path.join(d, f), tmp)
                               for d, _, fs in os.walk(tmp) for f in fs)
            self.assertGreater(len(generated), 40)
            shipped = sorted(
                os.path.relpath(os.path.join(d, f), ROBOTS)
                for pkg in ARMS.values() for d, _, fs in os.walk(os.path.join(ROBOTS, pkg))
                for f in fs) + sorted(r + s for r in ARMS for s in (".yaml", ".marker.yaml"))
            self.assertEqual(sorted(shipped), generated,
                             "shipped and generated file lists differ")
            _, mismatch, errors = filecmp.cmpfiles(ROBOTS, tmp, generated, shallow=False)
            self.assertEqual(mismatch + errors, [],
                             "differ from the generator's output: regenerate with "
                             "/usr/bin/python3 scripts/generate_arms.py")

    def test_a_bad_detail_is_refused_with_a_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            run = subprocess.run([sys.executable, GENERATOR, "--out", tmp, "--detail", "2"],
                                 capture_output=True, text=True)
            self.assertEqual(run.returncode, 2)
            self.assertIn("--detail must be in 6..256, got 2", run.stderr)
            self.assertEqual(os.listdir(tmp), [])

    def test_more_detail_gives_more_triangles(self):
        with tempfile.TemporaryDirectory() as tmp:
            run = subprocess.run([sys.executable, GENERATOR, "--out", tmp, "--detail", "12"],
                                 capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stderr)
            coarse = os.path.join(tmp, "telear_ur6", "meshes", "visual", "upper_arm_link.dae")
            fine = os.path.join(ROBOTS, "telear_ur6", "meshes", "visual", "upper_arm_link.dae")
            count = lambda p: sum(len(t) for _, t in read_mesh(p))
            self.assertLess(2 * count(coarse), count(fine))


class Meshes(unittest.TestCase):
    def mesh_files(self, pkg, kind):
        folder = os.path.join(ROBOTS, pkg, "meshes", kind)
        return sorted(os.path.join(folder, f) for f in os.listdir(folder)
                      if f.endswith((".dae", ".obj", ".stl")))

    def test_every_mesh_is_closed_consistently_wound_and_outward(self):
        checked = 0
        for pkg in ARMS.values():
            for kind in ("visual", "collision"):
                for path in self.mesh_files(pkg, kind):
                    for k, (pts, tris) in enumerate(read_mesh(path)):
                        problems, volume = shell_defects(pts, tris)
                        self.assertEqual(problems[:3], [], "%s shell %d" % (path, k))
                        self.assertGreater(volume, 1e-8, "%s shell %d is inside out" % (path, k))
                        checked += 1
        self.assertGreater(checked, 60)

    def test_the_checker_sees_a_hole_and_a_flipped_triangle(self):
        pts, tris = read_mesh(os.path.join(ROBOTS, "telear_ur6", "meshes", "visual",
                                           "finger.obj"))[0]
        self.assertEqual(shell_defects(pts, tris)[0], [])
        self.assertTrue(any("open surface" in p for p in shell_defects(pts, tris[1:])[0]))
        flipped = [(t[0], t[2], t[1]) if k == 0 else t for k, t in enumerate(tris)]
        self.assertTrue(any("inconsistent" in p for p in shell_defects(pts, flipped)[0]))
        inverted = [(t[0], t[2], t[1]) for t in tris]
        self.assertLess(shell_defects(pts, inverted)[1], 0)

    def test_formats_and_budgets(self):
        total_bytes = 0
        for pkg in ARMS.values():
            exts = set()
            visual = 0
            for path in self.mesh_files(pkg, "visual"):
                exts.add(os.path.splitext(path)[1])
                visual += sum(len(t) for _, t in read_mesh(path))
            self.assertEqual(exts, {".dae", ".obj"}, pkg)
            self.assertTrue(3000 <= visual <= 15000, "%s: %d visual triangles" % (pkg, visual))
            for path in self.mesh_files(pkg, "collision"):
                n = sum(len(t) for _, t in read_mesh(path))
                self.assertLessEqual(n, 600, path)
            for d, _, fs in os.walk(os.path.join(ROBOTS, pkg)):
                total_bytes += sum(os.path.getsize(os.path.join(d, f)) for f in fs)
        self.assertLess(total_bytes, 4 * 1024 * 1024)
        ascii_stl = [p for pkg in ARMS.values() for p in self.mesh_files(pkg, "collision")
                     if read_head(p) == b"solid"]
        self.assertGreaterEqual(len(ascii_stl), 1)


class Urdfs(unittest.TestCase):
    def urdf(self, robot):
        return Urdf(os.path.join(ROBOTS, ARMS[robot], "urdf", robot + ".urdf"))

    def test_package_and_mesh_uris_resolve(self):
        for robot, pkg in ARMS.items():
            self.assertEqual(ET.parse(os.path.join(ROBOTS, pkg, "package.xml")).getroot()
                             .find("name").text, pkg)
            u = self.urdf(robot)
            uris = [m.get("filename") for m in u.root.iter("mesh")]
            self.assertGreater(len(uris), 15)
            for uri in uris:
                self.assertTrue(uri.startswith("package://%s/meshes/" % pkg), uri)
                path = os.path.join(ROBOTS, pkg, uri[len("package://%s/" % pkg):])
                self.assertTrue(os.path.isfile(path), uri)
            colours = [m for m in u.root.iter("material") if m.find("color") is not None]
            self.assertGreater(len(colours), 0, robot)
            self.assertGreater(len([v for v in u.root.iter("visual")
                                    if v.find("material") is None]), 0, robot)

    def test_tree_root_leaves_gripper_and_mimic(self):
        for robot in ARMS:
            u = self.urdf(robot)
            roots = set(u.links) - set(u.parent_joint)
            self.assertEqual(roots, {"world"})
            leaves = set(u.links) - {j["parent"] for j in u.joints.values()}
            self.assertIn("tcp", leaves)
            self.assertGreater(len(leaves), 2, robot)
            self.assertEqual(len(u.movable("tcp")), 6 if robot == "ur6" else 7)
            left, right = u.joints["finger_left_joint"], u.joints["finger_right_joint"]
            self.assertEqual((left["type"], right["type"]), ("prismatic", "prismatic"))
            self.assertEqual(right["mimic"], "finger_left_joint")
            self.assertEqual([a + b for a, b in zip(left["axis"], right["axis"])], [0, 0, 0])
            self.assertEqual((left["lower"], left["upper"]), (0.0, 0.04))

    def test_ur6_reproduces_the_published_ur5_dh_chain(self):
        d = [0.089159, 0, 0, 0.10915, 0.09465, 0.0823]
        a = [0, -0.425, -0.39225, 0, 0, 0]
        alpha = [math.pi / 2, 0, 0, math.pi / 2, -math.pi / 2, 0]
        u = self.urdf("ur6")
        rng = random.Random(7)
        for _ in range(50):
            q = [rng.uniform(-math.pi, math.pi) for _ in range(6)]
            self.assertLess(max_diff(u.fk("tool0", q), std_dh(d, a, alpha, q)), 1e-9)
        for name in u.movable("tcp"):
            j = u.joints[name]
            self.assertAlmostEqual(j["upper"], 2 * math.pi, places=5)

    def test_arm7_reproduces_the_published_modified_dh_chain(self):
        a = [0, 0, 0, 0.0825, -0.0825, 0, 0.088]
        d = [0.333, 0, 0.316, 0, 0.384, 0, 0]
        alpha = [0, -math.pi / 2, math.pi / 2, math.pi / 2, -math.pi / 2, math.pi / 2,
                 math.pi / 2]
        u = self.urdf("arm7")
        rng = random.Random(11)
        for _ in range(50):
            q = [rng.uniform(-2.5, 2.5) for _ in range(7)]
            self.assertLess(max_diff(u.fk("link8", q), mod_dh(a, d, alpha, q, 0.107)), 1e-9)
        tcp = u.fk("tcp", [0] * 7)
        self.assertAlmostEqual(tcp[2][3], 0.333 + 0.316 + 0.384 - 0.107 - 0.1034, places=9)


class RobotFiles(unittest.TestCase):
    def test_named_configurations_are_good_working_poses(self):
        for robot, pkg in ARMS.items():
            with open(os.path.join(ROBOTS, robot + ".yaml")) as f:
                spec = yaml.safe_load(f)
            u = Urdf(os.path.join(ROBOTS, spec["urdf"]))
            self.assertEqual(spec["package_paths"], ["."])
            self.assertEqual(spec["tip"], "tcp")
            self.assertEqual(spec["gripper"]["joints"], ["finger_left_joint"])
            self.assertAlmostEqual(spec["gripper"]["max_opening_m"],
                                   2 * (spec["gripper"]["open"][0] - spec["gripper"]["closed"][0]))
            joints = [u.joints[n] for n in u.movable("tcp")]
            configs = spec["named_configurations_deg"]
            self.assertTrue({"zero", "home", "ready"} <= set(configs), robot)
            self.assertEqual(configs["zero"], [0] * len(joints))
            for name in ("home", "ready"):
                q = [math.radians(x) for x in configs[name]]
                self.assertEqual(len(q), len(joints))
                for qi, j in zip(q, joints):
                    self.assertTrue(j["lower"] <= qi <= j["upper"], "%s %s" % (robot, name))
                T, frames = u.fk("tcp", q, frames=True)
                where = "%s %s: tcp at %s" % (robot, name, [round(T[i][3], 3) for i in range(3)])
                self.assertLess(T[2][2], -0.999, where + " does not point down")
                self.assertTrue(0.25 < T[0][3] < 0.8 and abs(T[1][3]) < 0.4, where)
                self.assertTrue(0.1 < T[2][3] < 0.7, where)
                for F in frames[1:]:  # joint 1 turns on the base itself
                    self.assertGreater(F[2][3], 0.05, where + ": a joint is below the table")
                self.assertGreater(min_singular_value(jacobian(u, "tcp", q)), 0.05, where)

    def test_the_singularity_check_sees_a_singular_pose(self):
        u = Urdf(os.path.join(ROBOTS, "telear_ur6", "urdf", "ur6.urdf"))
        self.assertLess(min_singular_value(jacobian(u, "tcp", [0.3, -1.0, 1.2, -0.4, 0.0, 0.5])),
                        1e-6)  # q5 = 0: wrist axes 4 and 6 parallel

    def test_the_marker_lies_on_its_plate_facing_out(self):
        for robot, pkg in ARMS.items():
            with open(os.path.join(ROBOTS, robot + ".marker.yaml")) as f:
                m = yaml.safe_load(f)
            self.assertEqual((m["dictionary"], m["id"]), ("DICT_4X4_50", 0))
            u = Urdf(os.path.join(ROBOTS, pkg, "urdf", robot + ".urdf"))
            q = [0.3] * len(u.movable("tcp"))
            T_tcp = u.fk("tcp", q)
            T_marker = mat_mul(T_tcp, homog(rpy_rot(*m["pose_in_flange"]["rpy"]),
                                            m["pose_in_flange"]["xyz"]))
            T_plate = u.fk("marker_plate", q)
            size = vec(u.links["marker_plate"].find("visual/geometry/box").get("size"))
            self.assertLess(m["side_m"], min(size[1], size[2]))
            # the marker centre, in the plate frame: on its +x face, 0..1 mm proud
            rel = [T_marker[k][3] - T_plate[k][3] for k in range(3)]
            local = [sum(T_plate[k][i] * rel[k] for k in range(3)) for i in range(3)]
            self.assertTrue(0 <= local[0] - size[0] / 2 <= 0.001, "%s: %s" % (robot, local))
            self.assertAlmostEqual(local[1], 0, places=9)
            self.assertAlmostEqual(local[2], 0, places=9)
            # the marker's z is the plate's +x
            for k in range(3):
                self.assertAlmostEqual(T_marker[k][2], T_plate[k][0], places=9)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
