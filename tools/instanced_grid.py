#!/usr/bin/env python3
"""Writes a scene file placing one mesh SIDE x SIDE times on a grid (each copy turned about y by
a different angle and scaled a little), for racing `tlas` against the flattened scene:

    python3 tools/instanced_grid.py --mesh ../shared/meshes/stanford_bunny.obj --side 10 \
        --out /tmp/bunnies.toml
    accelbench run --scenes /tmp/bunnies.toml --indices bvh8,tlas --rays primary,incoherent

The mesh path is written as given, relative to the output file's directory unless absolute.
"""

import argparse
import os


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mesh", required=True, help="mesh file (OBJ, PLY, glTF)")
    ap.add_argument("--side", type=int, default=10, help="instances per grid row (default 10)")
    ap.add_argument("--spacing", type=float, default=1.0, help="grid step, in mesh units")
    ap.add_argument("--out", required=True, help="scene file to write")
    a = ap.parse_args()
    if a.side < 1:
        ap.error("--side must be at least 1")
    out_dir = os.path.dirname(os.path.abspath(a.out))
    mesh = a.mesh if os.path.isabs(a.mesh) else os.path.relpath(os.path.abspath(a.mesh), out_dir)
    half = (a.side - 1) * a.spacing / 2
    lines = [
        f"# {a.side} x {a.side} instances of {os.path.basename(a.mesh)}, by tools/instanced_grid.py",
        f'name = "instanced_grid_{a.side}"',
        "",
        "[object.mesh]",
        f'path = "{mesh}"',
    ]
    for row in range(a.side):
        for col in range(a.side):
            k = row * a.side + col
            lines += [
                "",
                "[[instance]]",
                'object = "mesh"',
                f"translate = [{col * a.spacing - half:.4f}, 0, {row * a.spacing - half:.4f}]",
                f"rotate = {{ axis = [0, 1, 0], degrees = {(k * 47) % 360} }}",
                f"scale = {0.8 + 0.4 * ((k * 7) % 10) / 10:.2f}",
            ]
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
