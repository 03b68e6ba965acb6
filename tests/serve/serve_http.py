#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""`morphex serve` over HTTP on 127.0.0.1: the listing, queries by name (the same ranking as
`morphex query`), an upload, a glb and a thumbnail that parse, and bad requests (a huge upload,
path traversal, a malformed mesh, an unknown mesh, ...) answered with 4xx and a message, after
which the server still serves. Uploads leave nothing in the temporary folder; SIGTERM stops it.

Usage: serve_http.py MORPHEX DATA_DIR WORK_DIR"""
import gzip
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import urllib.parse
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serve_common import Server, check, fail, make_index, multipart, run  # noqa: E402


def cli_query(morphex, index, target, kind="combined", metric="l1", k=5):
    out = run([morphex, "query", "--db", index, target, "-k", str(k), "--json",
               "--descriptor", kind, "--metric", metric])
    return [(n["name"], n["distance"]) for n in json.loads(out)["neighbours"]]


def served_ranking(answer):
    return [(n["name"], n["distance"]) for n in answer["neighbours"]]


def check_glb(content):
    """glTF 2.0 binary: header, a JSON chunk and a BIN chunk that agree (glTF spec, "GLB File
    Format Specification"): lengths, accessor counts, min/max bounds, indices in range."""
    magic, version, length = struct.unpack_from("<III", content, 0)
    check(magic == 0x46546C67 and version == 2, "glb: bad magic or version")
    check(length == len(content), f"glb: header length {length}, file {len(content)}")
    json_length, json_type = struct.unpack_from("<II", content, 12)
    check(json_type == 0x4E4F534A and json_length % 4 == 0, "glb: the first chunk is not JSON")
    gltf = json.loads(content[20:20 + json_length])
    bin_at = 20 + json_length
    bin_length, bin_type = struct.unpack_from("<II", content, bin_at)
    check(bin_type == 0x004E4942, "glb: the second chunk is not BIN")
    check(bin_at + 8 + bin_length == length, "glb: chunks do not fill the file")
    check(gltf["asset"]["version"] == "2.0", "glb: asset version")
    check(gltf["buffers"][0]["byteLength"] <= bin_length, "glb: buffer longer than its chunk")
    binary = content[bin_at + 8:]
    positions, indices = gltf["accessors"][0], gltf["accessors"][1]
    check(positions["componentType"] == 5126 and positions["type"] == "VEC3", "glb: positions")
    check(indices["componentType"] == 5125 and indices["type"] == "SCALAR", "glb: indices")
    view = gltf["bufferViews"][positions["bufferView"]]
    points = struct.unpack_from(f"<{3 * positions['count']}f", binary, view.get("byteOffset", 0))
    for axis in range(3):
        values = points[axis::3]
        check(min(values) == struct.unpack("<f", struct.pack("<f", positions["min"][axis]))[0] and
              max(values) == struct.unpack("<f", struct.pack("<f", positions["max"][axis]))[0],
              "glb: accessor min/max are not the bounds of the positions")
    view = gltf["bufferViews"][indices["bufferView"]]
    faces = struct.unpack_from(f"<{indices['count']}I", binary, view.get("byteOffset", 0))
    check(indices["count"] % 3 == 0 and max(faces) < positions["count"], "glb: indices")
    return positions["count"], indices["count"] // 3


def check_png(content, size):
    """A PNG of size x size RGBA pixels, every chunk's CRC right; returns the pixel rows."""
    check(content[:8] == b"\x89PNG\r\n\x1a\n", "png: signature")
    at, chunks, packed = 8, [], b""
    while at < len(content):
        length, kind = struct.unpack_from(">I4s", content, at)
        data = content[at + 8:at + 8 + length]
        crc, = struct.unpack_from(">I", content, at + 8 + length)
        check(zlib.crc32(kind + data) == crc, f"png: bad CRC in {kind}")
        chunks.append(kind)
        if kind == b"IHDR":
            check(struct.unpack(">IIBBBBB", data) == (size, size, 8, 6, 0, 0, 0), "png: IHDR")
        if kind == b"IDAT":
            packed += data
        at += 12 + length
    check(chunks[0] == b"IHDR" and chunks[-1] == b"IEND", f"png: chunks {chunks}")
    raw = zlib.decompress(packed)
    check(len(raw) == size * (1 + 4 * size), "png: image data size")
    rows = [raw[y * (1 + 4 * size) + 1:(y + 1) * (1 + 4 * size)] for y in range(size)]
    check(all(raw[y * (1 + 4 * size)] == 0 for y in range(size)), "png: filter types")
    return rows


def test_listing(server, index):
    info = server.json("/api/info")
    check(info["meshes"] == 12 and info["failed"] == 1, f"info counts: {info}")
    check(info["read_only"] is True and info["labels"] is True, f"info: {info}")
    check(set(info["kinds"]) == {"combined", "morphology", "granulometry", "pattern_spectrum",
                                 "spatial", "d2"}, f"info kinds: {info['kinds']}")
    meshes = server.json("/api/meshes")
    names = [m["name"] for m in meshes]
    check(names == sorted(f"{f}-{i}" for f in ["bar", "ell", "frame", "plus", "steps", "tee"]
                          for i in range(2)), f"listing: {names}")
    check(all(m["class"] == m["name"].split("-")[0] for m in meshes), "listing: classes")
    failures = server.json("/api/failures")
    check(len(failures) == 1 and failures[0]["name"] == "sheet" and
          "bounds no volume" in failures[0]["error"], f"failures: {failures}")
    return {m["name"]: m["id"] for m in meshes}, failures[0]["id"]


def test_queries(server, morphex, index, ids):
    for kind, metric in [("combined", "l1"), ("d2", "chi2"), ("granulometry", "l2")]:
        params = urllib.parse.urlencode({"name": "tee-1", "k": 5, "kind": kind, "metric": metric})
        answer = server.json("/api/query?" + params)
        expected = cli_query(morphex, index, "tee-1", kind, metric)
        check(served_ranking(answer) == expected,
              f"query {kind}/{metric}: served {served_ranking(answer)}, morphex query {expected}")
        check([n["id"] for n in answer["neighbours"]] == [ids[n] for n, _ in expected], "query ids")
    by_id = server.json(f"/api/query?id={ids['tee-1']}&k=5")
    check(served_ranking(by_id) == cli_query(morphex, index, "tee-1"), "query by id")
    check(by_id["query"]["name"] == "tee-1" and by_id["query"]["class"] == "tee", "query echo")
    mesh = server.json(f"/api/mesh/{ids['tee-1']}")
    curves = mesh["curves"]
    check(len(curves["granulometry"]) == 8 and len(curves["anti_granulometry"]) == 8 and
          len(curves["pattern_spectrum"]) == 8, f"curves: {curves}")
    check(abs(curves["open_radii"][0] - 0.05) < 1e-12 and abs(curves["open_radii"][-1] - 0.6) < 1e-12,
          "curves: opening radii")
    check(mesh["descriptors"]["granulometry"] == curves["granulometry"] + curves["anti_granulometry"],
          "curves split the stored granulometry vector")


def test_uploads(server, morphex, index, collection, tmpdir):
    copy = os.path.join(os.path.dirname(index), "copy-of-tee.off")
    shutil.copy(os.path.join(collection, "tee-1.off"), copy)
    expected = cli_query(morphex, index, copy)
    check(expected[0] == ("tee-1", 0.0), f"morphex query of a copy: {expected}")
    content = open(copy, "rb").read()
    body, headers = multipart("mesh", "my tee.off", content)
    answer = server.json("/api/query?k=5", method="POST", body=body, headers=headers)
    check(served_ranking(answer) == expected, f"upload: {served_ranking(answer)} vs {expected}")
    check(answer["query"]["name"] == "my tee.off" and answer["query"]["upload"] is True, "upload echo")
    check(answer["query"]["thumbnail"].startswith("data:image/png;base64,"), "upload thumbnail")
    check(len(answer["curves"]["granulometry"]) == 8, "upload curves")
    # The file as the body, gzip-compressed, its name in ?filename=.
    answer = server.json("/api/query?k=5&filename=" + urllib.parse.quote("tee.OFF.gz"),
                         method="POST", body=gzip.compress(content))
    check(served_ranking(answer) == expected, "gzip upload")
    check(os.listdir(tmpdir) == [], f"uploads left files behind: {os.listdir(tmpdir)}")


def test_files(server, ids, failed_id):
    status, head, content = server.request("GET", f"/api/mesh/{ids['frame-0']}.glb")
    check(status == 200 and head["Content-Type"] == "model/gltf-binary", f"glb: {status} {head}")
    vertices, faces = check_glb(content)
    check(faces == 32, f"glb: frame-0 has 32 faces, got {faces}")
    status, head, content = server.request("GET", f"/api/thumb/{ids['frame-0']}.png")
    check(status == 200 and head["Content-Type"] == "image/png", f"thumbnail: {status} {head}")
    rows = check_png(content, 96)
    alphas = [row[x * 4 + 3] for row in rows for x in range(96)]
    check(alphas[0] == 0 and alphas[-1] == 0, "thumbnail: corners are background")
    check(sum(a == 255 for a in alphas) > 96 * 96 // 10, "thumbnail: the mesh covers little")
    # A mesh that failed but was read can be looked at.
    status, _, content = server.request("GET", f"/api/thumb/{failed_id}.png")
    check(status == 200, f"thumbnail of the failed mesh: {status}")
    check_png(content, 96)


def test_bad_requests(server, ids, failed_id, data):
    # Path traversal, plain and percent-encoded: no route matches, nothing is read.
    for path in ["/api/mesh/../../etc/passwd", "/api/mesh/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
                 "/api/mesh/..%2F..%2F..%2Fetc%2Fpasswd.glb", "/api/thumb/%2e%2e/%2e%2e/etc/passwd.png",
                 "/three/../../../../etc/passwd", "/three/%2e%2e%2f%2e%2e%2fbuild/three.min.js",
                 f"/api/mesh/{ids['bar-0']}.glb/../../../../etc/passwd", "//etc/passwd",
                 "/api/mesh/-1", "/api/mesh/1e3", "/api/mesh/99999999999999999999999"]:
        status, _, content = server.request("GET", path)
        check(status in (400, 404), f"{path}: status {status}")
        check(b"root:" not in content and json.loads(content)["error"], f"{path}: {content[:200]!r}")
    # Unknown meshes.
    check("no indexed mesh has the id" in server.error("/api/mesh/9999", 404), "unknown id")
    server.error("/api/mesh/9999.glb", 404)
    server.error("/api/thumb/9999.png", 404)
    check("nosuch: no indexed mesh" in server.error("/api/query?name=nosuch", 404), "unknown name")
    # A request path names no file: a mesh file's path is not a name.
    server.error("/api/query?name=" + urllib.parse.quote("/etc/passwd"), 404)
    check("failed when it was indexed" in server.error(f"/api/query?id={failed_id}", 422), "failed")
    # Bad parameters.
    server.error("/api/query?name=tee-1&k=0", 400)
    server.error("/api/query?name=tee-1&k=abc", 400)
    server.error("/api/query?name=tee-1&kind=bogus", 400)
    server.error("/api/query?name=tee-1&metric=bogus", 400)
    server.error("/api/query", 400)
    # Uploads over the limit (1 MiB here): 413, as a body and as a form, whether just over (the
    # server reads it, then refuses) or far over (refused by its declared length, not kept).
    for size in [1100000, 20000000]:
        huge = b"OFF\n" + b"0 0 0\n" * (size // 6)
        check("larger than the limit" in
              server.error("/api/query?filename=huge.off", 413, "POST", huge), "huge upload")
        body, headers = multipart("mesh", "huge.off", huge)
        server.error("/api/query", 413, "POST", body, headers)
    # A malformed mesh: the reader's message, naming the upload (not the temporary file).
    body, headers = multipart("mesh", "broken.off", open(os.path.join(data, "truncated.off"), "rb").read())
    message = server.error("/api/query", 422, "POST", body, headers)
    check(message.startswith("broken.off: ") and "morphex-upload" not in message, message)
    message = server.error("/api/query?filename=junk.stl", 422, "POST", b"solid x\nfacet nonsense\n")
    check("junk.stl" in message, message)
    check("not a mesh file name" in server.error("/api/query?filename=run.sh", 415, "POST", b"OFF\n"),
          "extension")
    server.error("/api/query?filename=empty.off", 400, "POST", b"")
    server.error("/api/query", 400, "POST", b"OFF\n")  # no name
    body, headers = multipart("file", "a.off", b"OFF\n")
    server.error("/api/query", 400, "POST", body, headers)  # not the field 'mesh'
    # A chunked body (unbounded for httplib), another site's page, another Host, other methods.
    server.error("/api/query?filename=a.off", 411, "POST", b"4\r\nOFF\n\r\n0\r\n\r\n",
                 {"Transfer-Encoding": "chunked"})
    server.error("/api/query?filename=a.off", 403, "POST", b"OFF\n", {"Origin": "http://evil.test"})
    server.error("/api/info", 403, headers={"Host": "evil.test:80"})
    server.error("/api/info", 405, method="DELETE")
    # A request that is not HTTP.
    with socket.create_connection(("127.0.0.1", server.port), timeout=30) as raw:
        raw.sendall(b"GARBAGE\r\n\r\n")
        check(raw.recv(100).startswith(b"HTTP/1.1 400"), "garbage request")


def main():
    morphex, data, work = sys.argv[1:4]
    index, collection = make_index(morphex, data, work)
    tmpdir = os.path.join(work, "tmp")
    os.makedirs(tmpdir)
    server = Server(morphex, index, "--labels", os.path.join(collection, "labels.cla"),
                    "--max-upload-mb", "1", tmpdir=tmpdir)
    try:
        ids, failed_id = test_listing(server, index)
        test_queries(server, morphex, index, ids)
        test_uploads(server, morphex, index, collection, tmpdir)
        test_files(server, ids, failed_id)
        test_bad_requests(server, ids, failed_id, data)
        # A second server cannot take the port (httplib's default SO_REUSEPORT would share it).
        try:
            second = subprocess.run([morphex, "serve", "--db", index, "--port", str(server.port)],
                                    capture_output=True, text=True, timeout=20)
        except subprocess.TimeoutExpired:
            fail("a second server listened on the same port")
        check(second.returncode == 2 and "already in use" in second.stderr,
              f"second server: exit {second.returncode}: {second.stderr}")
        # Still serving after every refusal.
        check(len(server.json("/api/meshes")) == 12, "listing after the bad requests")
        check(served_ranking(server.json("/api/query?name=tee-1&k=5")) ==
              cli_query(morphex, index, "tee-1"), "query after the bad requests")
        check(os.listdir(tmpdir) == [], f"refused uploads left files: {os.listdir(tmpdir)}")
        # A mesh file changed since it was indexed is not shown as the indexed mesh.
        with open(os.path.join(collection, "bar-0.off"), "a") as f:
            f.write("# edited\n")
        check("changed since it was indexed" in server.error(f"/api/mesh/{ids['bar-0']}.glb", 409),
              "changed file")
        server.stop()
    finally:
        server.kill()
    print("serve over HTTP: listing, queries, uploads, glb, thumbnails and bad requests ok")


if __name__ == "__main__":
    main()
