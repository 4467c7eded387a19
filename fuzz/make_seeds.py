#!/usr/bin/env python3
"""Writes the generated seed inputs of the fuzz harnesses: deeply nested and large documents that
mutation alone does not reach from small files, and well-formed binary inputs (decomposition cache
entries, OMPL states). Usage: fuzz/make_seeds.py OUT_DIR (one folder per harness is made in it;
fuzz/corpus/ itself to refresh the committed seeds). Deterministic: the same files every run."""
import math
import os
import random
import re
import struct
import sys

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus")
rng = random.Random(1)


def put(harness, name, data):
    os.makedirs(os.path.join(out, harness), exist_ok=True)
    with open(os.path.join(out, harness, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def nested_xml(root, depth):
    return "<%s>" % root + "<a>" * depth + "text" + "</a>" * depth + "</%s>" % root


# URDF: a 300-link chain (long documents, deep kinematic trees) and deep element nesting.
links = ['<link name="l0"/>']
for i in range(1, 300):
    links.append('<link name="l%d"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>' % i)
    links.append('<joint name="j%d" type="revolute"><parent link="l%d"/><child link="l%d"/>'
                 '<origin xyz="0 0 0.1" rpy="0 0 0.1"/><axis xyz="0 1 0"/>'
                 '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>' % (i, i - 1, i))
put("urdf", "chain_300_links.urdf", '<?xml version="1.0"?>\n<robot name="chain">\n' + "\n".join(links) + "\n</robot>\n")
put("urdf", "nested_3000_elements.urdf", nested_xml('robot name="n"', 3000))

# SRDF: the bundled arm's pairs, groups of every kind, a chain of 300 subgroups, 1500 pairs, deep nesting.
arm_links = ["base_link"] + ["link%d" % i for i in range(1, 8)] + ["hand", "left_finger", "right_finger"]
groups = ['<group name="arm"><chain base_link="base_link" tip_link="hand"/></group>',
          '<group name="wrist"><joint name="joint5"/><joint name="joint6"/><joint name="joint7"/></group>',
          '<group name="fingers"><link name="left_finger"/><link name="right_finger"/><passive_joint name="joint1"/></group>',
          '<group name="all"><group name="arm"/><group name="fingers"/></group>']
put("srdf", "groups.srdf", '<?xml version="1.0"?>\n<robot name="deepcheck_arm">\n' + "\n".join(groups) +
    '\n<disable_collisions link1="link1" link2="link2" reason="Adjacent"/>\n</robot>\n')
chain = ['<group name="g0"><joint name="joint1"/></group>']
chain += ['<group name="g%d"><group name="g%d"/><joint name="joint%d"/></group>' % (i, i - 1, 1 + i % 7) for i in range(1, 300)]
put("srdf", "subgroup_chain_300.srdf", '<robot name="deepcheck_arm">\n' + "\n".join(chain) + "\n</robot>\n")
pairs = ['<disable_collisions link1="%s" link2="%s" reason="%s"/>' %
         (rng.choice(arm_links), rng.choice(arm_links), rng.choice(["Adjacent", "Never", "Default", "Always", "User"]))
         for _ in range(1500)]
put("srdf", "pairs_1500.srdf", '<robot name="deepcheck_arm">\n' + "\n".join(pairs) + "\n</robot>\n")
put("srdf", "nested_3000_elements.srdf", nested_xml('robot name="n"', 3000))
put("srdf", "escaped_names.srdf", '<robot name="a&amp;b"><disable_collisions link1="l&lt;1&gt;" link2="&#x41;&#66;"/>'
    '<disable_collisions link1="&quot;q&apos;" link2="link1" reason="User"/><!-- c --><![CDATA[x]]></robot>')

# MoveIt scenes: deep flow and block nesting, 300 objects.
put("moveit_scene", "nested_flow_3000.yaml", "world: {collision_objects: " + "[" * 3000 + "]" * 3000 + "}\n")
put("moveit_scene", "nested_block_300.yaml", "".join("  " * i + "k%d:\n" % i for i in range(300)) + "  " * 300 + "v\n")
objects = []
for i in range(300):
    objects.append("    - header: {frame_id: world}\n      id: box%d\n      primitives: [{type: box, dimensions: [0.1, 0.2, 0.3]}]\n"
                   "      primitive_poses: [{position: [%g, %g, %g], orientation: [0, 0, 0, 1]}]\n" % (i, i * 0.01, 0.5, 0.1))
put("moveit_scene", "objects_300.yaml", "name: big\nworld:\n  collision_objects:\n" + "".join(objects))
put("moveit_scene", "anchors_and_tags.yaml", "name: &n s\nworld:\n  collision_objects:\n    - &o\n      header: {frame_id: !!str world}\n"
    "      id: *n\n      primitives: [{type: sphere, dimensions: [!!float 0.1]}]\n"
    "      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n    - *o\n")

# Problem files: MotionBenchMaker's forms on the harness's scene (objects box and can), large and nested.
put("problems", "variation.yaml", '- names: ["World"]\n  position: [0.1, 0.1, 0.1]\n  orientation: [0, 0, 1.57]\n  type: "uniform"\n'
    '- names: ["box", "can"]\n  position: [0, 0.2, 0]\n  orientation: [0, 0, 0]\n  type: gaussian\n')
query = ("  - objects: [box, can]\n    tag: Front\n    offset:\n      position: [-0.2, 0, 0.05]\n"
         "      orientation: [0, 0.707, 0, 0.707]\n      position_tol: [0.01, 0.01, 0.01]\n"
         "      orientation_tol: [0.01, 0.01, 0.01]\n    attached: \"False\"\n")
put("problems", "queries.yaml", "start_queries:\n" + query.replace("Front", "Top") + "goal_queries:\n" + query)
put("problems", "queries_400.yaml", "goal_queries:\n" + query * 400)
put("problems", "robot.yaml", "urdf: package://deepcheck_arm/urdf/deepcheck_arm.urdf\nsrdf: arm.srdf\nrobot_state:\n  joint_state:\n"
    "    name: [joint1, joint2, joint3, joint4, joint5, joint6, joint7]\n    position: [0, -0.4, 0, -1.6, 0, 1.2, 9]\n")
put("problems", "nested_flow_3000.yaml", "goal_queries: " + "[" * 3000 + "]" * 3000 + "\n")
put("problems", "nested_block_300.yaml", "robot_state:\n" + "".join("  " * (i + 1) + "joint_state:\n" for i in range(300)) + "  " * 301 + "x\n")

# pd input: a shape of many points and many queries.
pts = ["%.17g %.17g %.17g" % (math.cos(t) * math.sin(p), math.sin(t) * math.sin(p), math.cos(p))
       for t, p in ((rng.uniform(0, 6.3), rng.uniform(0, 3.2)) for _ in range(2000))]
q = ["query ball %g %g %g 1 0 0 0 dot 0 0 0 1 0 0 0" % (rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)) for _ in range(300)]
put("pd_input", "ball_2000_points.txt", "shape ball %d\n%s\nshape dot 1\n0 0 0\n%s\n" % (len(pts), "\n".join(pts), "\n".join(q)))

# Configuration lines: 2000 lines, some outside the limits.
lines = [" ".join("%.6g" % rng.uniform(-4, 4) for _ in range(9)) for _ in range(2000)]
put("config_lines", "lines_2000.txt", "--robot arm.urdf --lock joint1=0.5 --lock finger_joint=0.01\n" + "\n".join(lines) + "\n")

# --goal-pose lines.
put("goal_pose", "pose.txt", "--goal-pose hand 0.5 0 0.4 0 0 0 1\n")
put("goal_pose", "pose_tolerances.txt", "--start 0 0 --goal-pose hand 0.5 0 0.4 0 0.7071 0 0.7071 --position-tol 0.01 --orientation-tol 0.05\n")
put("goal_pose", "pose_box.txt", "--goal-pose hand 0.5 0 0.4 1 1 1 1 --position-box 0.1 0.2 0.3 --orientation-tol 3.14\n")
put("goal_pose", "errors.txt", "--goal-pose hand 0 0 0 0 0 0 0 --position-tol 0 --position-box 1 1\n")

# Decomposition cache entries: first byte 0 (the harness writes the key and the checksum) or 1 (as is).
# The versions are read from the sources, so that the whole-file seeds pass the version checks.
def source_constant(path, name):
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", path)) as f:
        return int(re.search(r"constexpr [a-z:0-9_]+ " + name + r" = (\d+);", f.read()).group(1))

cache_versions = (source_constant("decomposition/src/cache.cpp", "kFormatVersion"),
                  source_constant("decomposition/include/deepcheck/decomposition/decomposition.h", "kDecompositionAlgorithmVersion"))

def entry(pieces):
    body = b"DCKDECMP" + struct.pack("<II", *cache_versions) + bytes.fromhex("00112233445566778899aabbccddeeff")
    # The report: 8 counts (triangles, vertices, components, pieces, most piece vertices, holes
    # filled, voids removed, duplicates removed), 9 doubles, the flags.
    body += struct.pack("<8I", 12, 8, 1, len(pieces), max(len(v) for v, _ in pieces), 0, 0, 0)
    body += struct.pack("<9d", 1.7, 0.01, 0.005, 0.003, 0.0, 1.0, 1.0, 1.0, 12.5) + struct.pack("<I", 5)
    body += struct.pack("<I", len(pieces))
    for vertices, triangles in pieces:
        body += struct.pack("<II", len(vertices), len(triangles))
        for v in vertices:
            body += struct.pack("<3d", *v)
        for t in triangles:
            body += struct.pack("<3I", *t)
        body += struct.pack("<dd", 1.0, 0.0)
    return body

def fnv1a(data):
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h

cube = ([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)],
        [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)])
tetra = ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)])
ball = ([(math.cos(t) * math.sin(p), math.sin(t) * math.sin(p), math.cos(p)) for t, p in
         ((rng.uniform(0, 6.3), rng.uniform(0, 3.2)) for _ in range(400))], [(0, 1, 2)] * 50)
for name, pieces in (("cube", [cube]), ("cube_and_tetra", [cube, tetra]), ("ball_400", [ball]), ("pieces_20", [tetra] * 20)):
    e = entry(pieces)
    put("decomposition_cache", name + "_keyed.bin", b"\0" + e)
    put("decomposition_cache", name + "_whole.bin", b"\1" + e + struct.pack("<Q", fnv1a(e)))

# OMPL states (see fuzz_ompl_state.cpp for the encoding).
put("ompl_state", "defaults_pushed.bin", b"\5\0" * 7 + b"\1")
put("ompl_state", "in_limits.bin", b"".join(b"\1" + struct.pack("<H", rng.randrange(65536)) for _ in range(7)) + b"\0")
put("ompl_state", "nan_and_inf.bin", b"\4\0\4\2\4\3\4\11\4\12\4\13\4\14\1")
put("ompl_state", "raw_doubles.bin", b"".join(b"\0" + struct.pack("<d", x) for x in (0.1, -0.4, 1e300, -1.6, 5e-324, 1.2, 0.0)) + b"\1")

# Meshes (first byte: '0' STL, '1' OBJ, '2' COLLADA): a 2000-vertex OBJ, a COLLADA node tree 200 deep.
verts = ["v %.9g %.9g %.9g" % p for p in ((math.cos(t) * math.sin(p), math.sin(t) * math.sin(p), math.cos(p))
                                         for t, p in ((rng.uniform(0, 6.3), rng.uniform(0, 3.2)) for _ in range(2000)))]
faces = ["f %d %d %d" % (rng.randrange(1, 2001), rng.randrange(1, 2001), rng.randrange(1, 2001)) for _ in range(3000)]
put("mesh", "scattered_2000_vertices.obj", "1" + "\n".join(verts + faces) + "\n")
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "mesh", "tetra_mm_mirrored.dae")) as f:
    dae = f.read()
inner = '<node id="n" name="n"><matrix>1 0 0 0.5 0 -1 0 0 0 0 1 0 0 0 0 1</matrix><instance_geometry url="#tri"/></node>'
deep = "".join('<node id="d%d"><translate>0 0 0.01</translate>' % i for i in range(200)) + inner + "</node>" * 200
put("mesh", "collada_nodes_200_deep.dae", dae.replace(inner, deep))

# MoveIt .scene text (newer format): 300 boxes, and one object with a 2000-vertex mesh inline.
boxes = "".join("* box%d\n%.4f %.4f 0.1\n0 0 0 1\n1\nbox\n0.05 0.05 0.05\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
                % (i, rng.uniform(-1, 1), rng.uniform(-1, 1)) for i in range(300))
put("scene_text", "boxes_300.scene", "crowd\n" + boxes + ".\n")
points = [(math.cos(t) * math.sin(p), math.sin(t) * math.sin(p), math.cos(p))
          for t, p in ((rng.uniform(0, 6.3), rng.uniform(0, 3.2)) for _ in range(2000))]
faces = [(i, (i + 1) % 2000, (i + 2) % 2000) for i in range(0, 1998, 3)]
mesh = "mesh\n%d %d\n" % (len(points), len(faces)) + "".join("%.6f %.6f %.6f\n" % p for p in points)
mesh += "".join("%d %d %d\n" % f for f in faces)
put("scene_text", "mesh_2000.scene", "blob\n* blob\n0 0 0.5\n0 0 0 1\n1\n" + mesh + "0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n")
