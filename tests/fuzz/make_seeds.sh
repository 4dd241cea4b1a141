#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Writes the seed corpora of tests/fuzz/corpus/<target>/ (committed; rerun after a
# format change). The cache-file seeds need the built fuzz_cache_file, which dumps
# the reference cache of its fixed mesh.
# Usage: tests/fuzz/make_seeds.sh [BUILD_DIR]   (default: build-fuzz)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${1:-$root/build-fuzz}"
corpus="$here/corpus"

reference="$(mktemp)"
trap 'rm -f "$reference"' EXIT
SC_FUZZ_WRITE_REFERENCE="$reference" "$build/tests/fuzz/fuzz_cache_file" -runs=0 >/dev/null 2>&1
[[ -s "$reference" ]] || { echo "make_seeds.sh: no reference cache from $build" >&2; exit 1; }

python3 - "$corpus" "$root/tests/data" "$reference" <<'PY'
import os, struct, sys
corpus, data_dir, reference = sys.argv[1:4]

def write(target, name, payload):
    d = os.path.join(corpus, target)
    os.makedirs(d, exist_ok=True)
    if isinstance(payload, str):
        payload = payload.encode()
    with open(os.path.join(d, name), "wb") as f:
        f.write(payload)

# ---- fuzz_add_triangles: kind, then per call {flags, #v, #t, scale exponent,
# coordinates (int8 grid, or raw float/double with flag 2), indices}, then the
# scene's kind flag and two placements (3 int8 positions / 16, 2 rotation bytes).
BOX_V = [(-1,-1,-1),(1,-1,-1),(1,1,-1),(-1,1,-1),(-1,-1,1),(1,-1,1),(1,1,1),(-1,1,1)]
BOX_T = [(0,2,1),(0,3,2),(4,5,6),(4,6,7),(0,1,5),(0,5,4),(1,2,6),(1,6,5),(2,3,7),(2,7,6),(3,0,4),(3,4,7)]
TET_V = [(1,1,1),(-1,-1,1),(-1,1,-1),(1,-1,-1)]
TET_T = [(0,1,2),(0,3,1),(0,2,3),(1,3,2)]

def grid_call(verts, tris, flags=0, scale=32):
    out = bytes([flags, len(verts), len(tris), scale])
    out += bytes((c & 0xff) for v in verts for c in v)
    out += bytes(i for t in tris for i in t)
    return out

def raw_call(verts, tris, use_float, flags=0):
    fmt = "<f" if use_float else "<d"
    out = bytes([flags | 2 | (1 if use_float else 0), len(verts), len(tris), 32])
    out += b"".join(struct.pack(fmt, c) for v in verts for c in v)
    out += bytes(i for t in tris for i in t)
    return out

tail = bytes([0, 40, 0, 0, 0, 0, 8, 8, 8, 30, 90])
empty = bytes([0, 0, 0, 32])
write("fuzz_add_triangles", "box_closed", b"\x00" + grid_call(BOX_V, BOX_T) + empty + tail)
write("fuzz_add_triangles", "box_and_tetra", b"\x00" + grid_call(BOX_V, BOX_T) +
      grid_call([(x+4, y, z) for x, y, z in TET_V], TET_T) + tail)
write("fuzz_add_triangles", "tetra_float", b"\x00" + raw_call(TET_V, TET_T, True) + empty + tail)
write("fuzz_add_triangles", "box_double", b"\x00" + raw_call(BOX_V, BOX_T, False) + empty + tail)
write("fuzz_add_triangles", "box_soup", b"\x01" + grid_call(BOX_V, BOX_T[:7]) + empty + tail)
write("fuzz_add_triangles", "soup_in_closed_scene", b"\x01" + grid_call(TET_V, TET_T) + empty +
      bytes([1]) + tail[1:])
write("fuzz_add_triangles", "tiny_scale", b"\x00" + grid_call(BOX_V, BOX_T, scale=0) + empty + tail)
write("fuzz_add_triangles", "huge_scale", b"\x00" + grid_call(BOX_V, BOX_T, scale=63) + empty + tail)
write("fuzz_add_triangles", "nan_vertex", b"\x00" +
      raw_call([(float("nan"), 0, 0)] + TET_V[1:], TET_T, False) + empty + tail)
write("fuzz_add_triangles", "bad_index", b"\x01" + grid_call(TET_V, [(0, 1, 4)]) + empty + tail)
write("fuzz_add_triangles", "raw_index", b"\x01" + grid_call(TET_V, [(0, 1)]) + b"\xff" +
      struct.pack("<i", -7) + empty + tail)
write("fuzz_add_triangles", "null_and_negative", b"\x00" + grid_call(TET_V, TET_T, flags=4 | 32) +
      grid_call(TET_V, TET_T, flags=8 | 16) + tail)
write("fuzz_add_triangles", "open_closed", b"\x00" + grid_call(BOX_V, BOX_T[:11]) + empty + tail)
write("fuzz_add_triangles", "raw_type", b"\x03" + struct.pack("<i", 0x0103) +
      grid_call(TET_V, TET_T) + empty + tail)

# ---- fuzz_scene_api: scene kind flag, then operations (first byte % 16).
ADD, DELETE, GROUP, UNGROUP, SETT, GETT, ACT_O, ACT_G, ACT_P, ATTR, GATTR, UPDATE, STATUS, OBJT = \
    0, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12, 13, 14, 15

def add(id_, which): return bytes([ADD, id_, which])
def group(gid, id_): return bytes([GROUP, gid, id_])
def move(gid, x, y, z, kind=1, mode=5, use_float=0):
    # gid, type index, axis (3), angle, translation (3), layout, mode, float flag
    return bytes([SETT, gid, kind, 200, 100, 50, 20, x & 0xff, y & 0xff, z & 0xff, 0, mode, use_float])
def update(): return bytes([UPDATE])
def status(i, rev, t): return bytes([STATUS, 3, i, rev, t])

base = add(0, 0) + add(1, 1) + add(2, 2) + group(0, 0) + group(1, 1) + group(2, 2)
write("fuzz_scene_api", "three_groups", b"\x00" + base + move(0, 40, 0, 0) + move(1, -40, 0, 0) +
      update() + status(0, 0, 5) + update())
write("fuzz_scene_api", "penetrating", b"\x00" + base + update() + move(1, 8, 0, 0) + update() +
      move(1, 16, 0, 0) + update())
write("fuzz_scene_api", "static_world", b"\x00" + add(0, 0) + add(1, 2) + group(0, 0) +
      move(0, 60, 0, 0) + update() + move(0, 30, 0, 0) + update())
write("fuzz_scene_api", "soup", b"\x01" + add(0, 3) + add(1, 4) + add(2, 5) + group(0, 0) +
      group(1, 1) + move(0, 50, 0, 0) + update() + move(0, 10, 0, 0) + update())
write("fuzz_scene_api", "activities", b"\x00" + base + bytes([ACT_G, 0, 1, ACT_P, 1, 2, 4,
      ACT_O, 2, 3, ACT_G, 2, 2]) + move(0, 30, 0, 0) + update() + bytes([ACT_P, 0, 1, 5]) + update())
write("fuzz_scene_api", "attributes", b"\x00" + base + bytes([ATTR, 0, 0, 4, ATTR, 7, 1, 3,
      ATTR, 4, 2, 3, ATTR, 9, 1, 2, ATTR, 8, 1, 2, GATTR, 0]) + move(0, 20, 0, 0) + update() +
      move(0, 10, 0, 0) + update())
write("fuzz_scene_api", "nan_transform", b"\x00" + base + move(0, 0, 0, 0, mode=0) + update())
write("fuzz_scene_api", "inf_and_huge", b"\x00" + base + move(1, 0, 0, 0, mode=1) +
      move(2, 0, 0, 0, mode=2) + update())
write("fuzz_scene_api", "matrix_float", b"\x00" + base +
      bytes([SETT, 0, 7, 10, 20, 30, 40, 30, 0, 0, 2, 5, 1]) + update() +
      bytes([GETT, 0, 7, GETT, 6, 6]))
write("fuzz_scene_api", "delete_and_regroup", b"\x00" + base + update() + bytes([DELETE, 1,
      UNGROUP, 2, 2, 0, UNGROUP, 0, 0, 1]) + update() + add(1, 1) + group(3, 1) + update())
write("fuzz_scene_api", "bad_ids", b"\x00" + add(0, 0) + add(0, 1) + bytes([ADD, 7]) +
      struct.pack("<i", -5) + bytes([0]) + add(3, 7) + group(6, 0) + update() +
      bytes([STATUS, 0, 1, 9, STATUS, 1, 0, 3]))
write("fuzz_scene_api", "object_transform", b"\x00" + bytes([OBJT, 0, 1, 10, 10, 10, 30, 60, 0,
      0, 0, 5]) + add(0, 0) + bytes([OBJT, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 5]) + update() + b"\x01")

# ---- fuzz_off_reader: OFF texts.
for name in ("l_prism.off", "open_square.off"):
    with open(os.path.join(data_dir, name), "rb") as f:
        write("fuzz_off_reader", name[:-4], f.read())
box = "OFF\n8 6 0\n" + "".join("%d %d %d\n" % v for v in BOX_V) + \
      "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"
write("fuzz_off_reader", "box_quads", box)
write("fuzz_off_reader", "counts_on_header", "OFF 4 4 6\n1 1 1\n-1 -1 1\n-1 1 -1\n1 -1 -1\n"
      "3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n")
write("fuzz_off_reader", "colours_comments", "OFF # comment\n# another\n4 4 0\n1 1 1\n-1 -1 1\n"
      "-1 1 -1\n1 -1 -1\n3 0 1 2 255 0 0\n3 0 3 1 0 255 0\n3 0 2 3\n3 1 3 2 # done\n")
write("fuzz_off_reader", "inside_out", "OFF\n4 4 0\n1 1 1\n-1 -1 1\n-1 1 -1\n1 -1 -1\n"
      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
write("fuzz_off_reader", "bad_index", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")
write("fuzz_off_reader", "nan", "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
write("fuzz_off_reader", "huge", "OFF\n3 1 0\n1e308 0 0\n-1e308 0 0\n0 1e308 0\n3 0 1 2\n")
write("fuzz_off_reader", "short_face", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n")
write("fuzz_off_reader", "truncated", "OFF\n8 6 0\n0 0 0\n1 0 0\n")
write("fuzz_off_reader", "bad_header", "OFFX\n1 0 0\n")
write("fuzz_off_reader", "negative_counts", "OFF\n-3 -1 0\n")
write("fuzz_off_reader", "degenerate", "OFF\n3 2 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n3 2 1 0\n")

# ---- fuzz_mesh_import: byte 0 modulo 4 picks the format (below); then the file.
def obj(verts, faces, extra=""):
    return "0" + "".join("v %g %g %g\n" % v for v in verts) + extra + \
           "".join("f " + " ".join(str(i + 1) for i in f) + "\n" for f in faces)

def stl_normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    return (u[1]*w[2] - u[2]*w[1], u[2]*w[0] - u[0]*w[2], u[0]*w[1] - u[1]*w[0])

def stl_ascii(verts, tris, name="seed"):
    out = "1solid %s\n" % name
    for t in tris:
        p = [verts[i] for i in t]
        out += " facet normal %g %g %g\n  outer loop\n" % stl_normal(*p)
        out += "".join("   vertex %g %g %g\n" % v for v in p)
        out += "  endloop\n endfacet\n"
    return out + "endsolid %s\n" % name

def stl_binary(verts, tris, count=None):
    out = b"1" + b"binary seed".ljust(80, b"\0")
    out += struct.pack("<I", len(tris) if count is None else count)
    for t in tris:
        p = [verts[i] for i in t]
        out += struct.pack("<3f", *stl_normal(*p))
        out += b"".join(struct.pack("<3f", *v) for v in p) + b"\0\0"
    return out

CUBE_QUADS = [(0,3,2,1),(4,5,6,7),(0,1,5,4),(1,2,6,5),(2,3,7,6),(3,0,4,7)]
write("fuzz_mesh_import", "obj_tetra", obj(TET_V, TET_T))
write("fuzz_mesh_import", "obj_cube_quads", obj(BOX_V, CUBE_QUADS, "o cube\nvn 0 0 1\ns off\n"))
write("fuzz_mesh_import", "obj_relative_indices", "0" + "".join("v %d %d %d\n" % v for v in TET_V) +
      "f -4 -3 -2\nf -4 -1 -3\nf -4 -2 -1\nf -3 -1 -2\n")
write("fuzz_mesh_import", "obj_points_lines", obj(TET_V, TET_T, "p 1\nl 1 2\n"))
write("fuzz_mesh_import", "obj_bad_index", obj(TET_V[:3], [(0, 1, 5)]))
# Debian's assimp 5.2.5 leaks group a's mesh when group b has an index out of range
# (suppressed, tests/fuzz/fuzz_mesh_import.lsan.supp; docs/reliability.md).
write("fuzz_mesh_import", "obj_assimp_leak_later_group", "0g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f 1 2 3\ng b\nf 1 2 9\n")
write("fuzz_mesh_import", "obj_nan", "0v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
write("fuzz_mesh_import", "obj_groups_texcoords", "0g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
      "vt 1 0\nvt 0 1\nf 1/1 2/2 3/3\ng b\nv 0 0 1\nf 1//1 3//1 4//1\n")
write("fuzz_mesh_import", "stl_ascii_tetra", stl_ascii(TET_V, TET_T))
write("fuzz_mesh_import", "stl_ascii_truncated", stl_ascii(TET_V, TET_T)[:120])
write("fuzz_mesh_import", "stl_binary_cube", stl_binary(BOX_V, BOX_T))
write("fuzz_mesh_import", "stl_binary_count_too_big", stl_binary(BOX_V, BOX_T, count=1000))
write("fuzz_mesh_import", "stl_binary_empty", stl_binary(BOX_V, []))
# Byte 0 modulo 4: '0' OBJ, '1' STL, '2' OFF, '3' PLY. The prism in every format, and
# the malformed files of tests/data/malformed/ (assimp aborted on off_fewer_faces,
# spun forever on ply_cut_header, crashed on ply_negative_index).
for prefix, name in (("2", "l_prism.off"), ("3", "l_prism.ply"), ("3", "l_prism_binary.ply"),
                     ("3", "l_prism_binary_be.ply"), ("1", "l_prism.stl"),
                     ("1", "l_prism_binary.stl"), ("0", "l_prism.obj")):
    with open(os.path.join(data_dir, name), "rb") as f:
        write("fuzz_mesh_import", name.replace(".", "_"), prefix.encode() + f.read())
malformed = os.path.join(data_dir, "malformed")
for name in sorted(os.listdir(malformed)):
    prefix = {"obj": "0", "stl": "1", "off": "2", "ply": "3"}[name.rsplit(".", 1)[1]]
    with open(os.path.join(malformed, name), "rb") as f:
        write("fuzz_mesh_import", "malformed_" + name.replace(".", "_"), prefix.encode() + f.read())

# ---- fuzz_cache_file: byte 0 bit 0 = wrap the rest in a valid header.
with open(reference, "rb") as f:
    ref = f.read()
HEADER = 48
payload = ref[HEADER:]
write("fuzz_cache_file", "reference", b"\x00" + ref)
write("fuzz_cache_file", "payload", b"\x01" + payload)
write("fuzz_cache_file", "empty", b"\x00")
write("fuzz_cache_file", "empty_payload", b"\x01")
write("fuzz_cache_file", "header_only", b"\x00" + ref[:HEADER])
write("fuzz_cache_file", "truncated", b"\x00" + ref[:len(ref) // 2])
write("fuzz_cache_file", "payload_truncated", b"\x01" + payload[:len(payload) // 2])
write("fuzz_cache_file", "payload_flipped", b"\x01" + payload[:40] + bytes([payload[40] ^ 0xff]) +
      payload[41:])
write("fuzz_cache_file", "payload_huge_count", b"\x01" + b"\xff" * 16 + payload[16:])
write("fuzz_cache_file", "wrong_version", b"\x00" + ref[:8] + struct.pack("<I", 999) + ref[12:])
write("fuzz_cache_file", "wrong_checksum", b"\x00" + ref[:40] + b"\0" * 8 + ref[48:])
write("fuzz_cache_file", "garbage", b"\x00SCPIECE\0" + bytes(range(64)))
PY
for d in "$corpus"/*/; do echo "$(basename "$d"): $(ls "$d" | wc -l) seeds"; done
