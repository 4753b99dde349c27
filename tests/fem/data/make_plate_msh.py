#!/usr/bin/env python3
"""Writes plate_with_hole.msh (ASCII Gmsh msh 2.2) and plate_with_hole_v4.msh (msh 4.1): a
6 m x 4 m plate of 1 m quadrilaterals with the 2 m x 2 m square [2, 4] x [1, 3] cut out (no
gmsh binary needed).

Physical line tags: 1 bottom, 2 right, 3 top, 4 left, 5 hole; physical surface 10.
Used by tests/fem/test_far_field_mesh.cc. Run: python3 make_plate_msh.py (writes beside it).
"""
import pathlib

NX, NY = 6, 4
HOLE = (2, 4, 1, 3)  # x0, x1, y0, y1 in cell units


def in_hole(i, j):
    return HOLE[0] <= i < HOLE[1] and HOLE[2] <= j < HOLE[3]


def node(i, j):
    return j * (NX + 1) + i + 1


nodes = [(node(i, j), float(i), float(j)) for j in range(NY + 1) for i in range(NX + 1)]
quads = [(node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1))
         for j in range(NY) for i in range(NX) if not in_hole(i, j)]
lines = []
lines += [(1, node(i, 0), node(i + 1, 0)) for i in range(NX)]
lines += [(2, node(NX, j), node(NX, j + 1)) for j in range(NY)]
lines += [(3, node(i + 1, NY), node(i, NY)) for i in range(NX)]
lines += [(4, node(0, j + 1), node(0, j)) for j in range(NY)]
x0, x1, y0, y1 = HOLE
lines += [(5, node(i, y0), node(i + 1, y0)) for i in range(x0, x1)]
lines += [(5, node(x1, j), node(x1, j + 1)) for j in range(y0, y1)]
lines += [(5, node(i + 1, y1), node(i, y1)) for i in range(x0, x1)]
lines += [(5, node(x0, j + 1), node(x0, j)) for j in range(y0, y1)]

out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", str(len(nodes))]
out += [f"{n} {x:g} {y:g} 0" for n, x, y in nodes]
out += ["$EndNodes", "$Elements", str(len(lines) + len(quads))]
k = 0
for tag, a, b in lines:
    k += 1
    out.append(f"{k} 1 2 {tag} {tag} {a} {b}")
for q in quads:
    k += 1
    out.append(f"{k} 3 2 10 1 {q[0]} {q[1]} {q[2]} {q[3]}")
out.append("$EndElements")
here = pathlib.Path(__file__)
here.with_name("plate_with_hole.msh").write_text("\n".join(out) + "\n")

# msh 4.1: one curve entity per physical line tag, one surface entity; nodes in one block.
v4 = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$Entities", "0 5 1 0"]
for tag in range(1, 6):
    v4.append(f"{tag} 0 0 0 {NX} {NY} 0 1 {tag} 0")
v4.append(f"1 0 0 0 {NX} {NY} 0 1 10 5 1 2 3 4 5")
v4 += ["$EndEntities", "$Nodes", f"1 {len(nodes)} 1 {len(nodes)}", f"2 1 0 {len(nodes)}"]
v4 += [str(n) for n, _, _ in nodes]
v4 += [f"{x:g} {y:g} 0" for _, x, y in nodes]
v4 += ["$EndNodes", "$Elements", f"6 {len(lines) + len(quads)} 1 {len(lines) + len(quads)}"]
k = 0
for tag in range(1, 6):
    block = [(a, b) for t, a, b in lines if t == tag]
    v4.append(f"1 {tag} 1 {len(block)}")
    for a, b in block:
        k += 1
        v4.append(f"{k} {a} {b}")
v4.append(f"2 1 3 {len(quads)}")
for q in quads:
    k += 1
    v4.append(f"{k} {q[0]} {q[1]} {q[2]} {q[3]}")
v4.append("$EndElements")
here.with_name("plate_with_hole_v4.msh").write_text("\n".join(v4) + "\n")
