#!/usr/bin/env python3
"""Writes fuzz_mesh's seed corpus (corpus/mesh/): a cube and a lone triangle in each format
Assimp reads for accelviz, ASCII and binary. The first byte of each file picks the
extension in fuzz_mesh.cpp (0 .ply, 1 .stl, 2 .gltf, 3 .glb); the rest is the file."""
import base64, json, os, struct, sys

CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_F = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
          (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
TRI_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
TRI_F = [(0, 1, 2)]

def ply_ascii(v, f):
    s = f"ply\nformat ascii 1.0\nelement vertex {len(v)}\nproperty float x\nproperty float y\nproperty float z\n"
    s += f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n"
    s += "".join(f"{a} {b} {c}\n" for a, b, c in v) + "".join(f"3 {a} {b} {c}\n" for a, b, c in f)
    return s.encode()

def ply_binary(v, f):
    s = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\nproperty float x\nproperty float y\n"
         f"property float z\nelement face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n").encode()
    return s + b"".join(struct.pack("<3f", *p) for p in v) + b"".join(struct.pack("<B3i", 3, *t) for t in f)

def stl_ascii(v, f):
    s = "solid s\n"
    for t in f:
        s += "facet normal 0 0 0\nouter loop\n" + "".join("vertex %g %g %g\n" % v[i] for i in t) + "endloop\nendfacet\n"
    return (s + "endsolid s\n").encode()

def stl_binary(v, f):
    out = b"\0" * 80 + struct.pack("<I", len(f))
    for t in f:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in t) + b"\0\0"
    return out

def gltf_parts(v, f, uri):
    pos = b"".join(struct.pack("<3f", *p) for p in v)
    idx = b"".join(struct.pack("<3I", *t) for t in f)
    lo = [min(p[k] for p in v) for k in range(3)]
    hi = [max(p[k] for p in v) for k in range(3)]
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"byteLength": len(pos) + len(idx)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(v), "type": "VEC3", "min": lo, "max": hi},
                         {"bufferView": 1, "componentType": 5125, "count": 3 * len(f), "type": "SCALAR"}]}
    if uri is not None:
        doc["buffers"][0]["uri"] = uri
    return doc, pos + idx

def gltf_embedded(v, f):
    doc, binary = gltf_parts(v, f, None)
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
    return json.dumps(doc).encode()

def glb(v, f):
    doc, binary = gltf_parts(v, f, None)
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    binary += b"\0" * (-len(binary) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body

def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus", "mesh")
    os.makedirs(out, exist_ok=True)
    writers = [(0, "ply_ascii", ply_ascii), (0, "ply_binary", ply_binary), (1, "stl_ascii", stl_ascii),
               (1, "stl_binary", stl_binary), (2, "gltf", gltf_embedded), (3, "glb", glb)]
    for selector, name, write in writers:
        for mesh_name, (v, f) in {"cube": (CUBE_V, CUBE_F), "triangle": (TRI_V, TRI_F)}.items():
            with open(os.path.join(out, f"{name}_{mesh_name}"), "wb") as fh:
                fh.write(bytes([selector]) + write(v, f))

if __name__ == "__main__":
    main()
