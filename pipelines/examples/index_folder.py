#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Index a folder of meshes with the morphex Python module and print the nearest neighbours of one.

    PYTHONPATH=build/python python3 pipelines/examples/index_folder.py FOLDER \
        [--db FOLDER/index.sqlite] [--query NAME] [-k 5] [--scales 8] [--d2-samples 200000]

Every OFF, OBJ, STL and PLY file in FOLDER is described (after an exact repair when it is not a
valid solid) into a SQLite index that `morphex query` and `morphex evaluate` also read; a second run
only describes new or changed files. The query is the mesh named NAME (its file stem), by default
the first in alphabetical order; its neighbours are ranked by the combined descriptor.
"""
import argparse
import sys
from pathlib import Path

import morphex

MESH_SUFFIXES = {".off", ".obj", ".stl", ".ply"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=Path, help="folder of mesh files")
    parser.add_argument("--db", type=Path, help="index file (default: FOLDER/index.sqlite)")
    parser.add_argument("--query", help="name (file stem) of the mesh to query (default: first)")
    parser.add_argument("-k", type=int, default=5, help="number of neighbours")
    parser.add_argument("--scales", type=int, default=8, help="opening and closing radii")
    parser.add_argument("--d2-samples", type=int, default=200000, help="D2 point pairs")
    parser.add_argument("--threads", type=int, help="worker threads (default: all cores)")
    args = parser.parse_args()

    paths = sorted(str(p) for p in args.folder.iterdir() if p.suffix.lower() in MESH_SUFFIXES)
    if not paths:
        sys.exit(f"{args.folder}: no mesh files (.off, .obj, .stl, .ply)")
    # The descriptor pipeline: read each file, then describe it (a repair is added after the read).
    pipeline = {"pipeline": [
        {"type": "read", "path": "${input}"},
        {"type": "describe", "scales": args.scales, "d2_samples": args.d2_samples}]}

    with morphex.Index(args.db or args.folder / "index.sqlite") as index:
        summary = index.add(paths, pipeline=pipeline, threads=args.threads)
        print(f"indexed {summary['indexed']} meshes ({summary['skipped']} up to date, "
              f"{summary['failed']} failed) into {index.path}")
        for path, error in summary["errors"].items():
            print(f"  {path}: {error}", file=sys.stderr)
        query = args.query or index.names()[0]
        print(f"nearest neighbours of {query}:")
        for rank, (name, distance) in enumerate(index.query(query, k=args.k), start=1):
            print(f"{rank:3d}  {name:24s} {distance:10.5f}")


if __name__ == "__main__":
    main()
