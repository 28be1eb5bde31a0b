#!/usr/bin/python3
"""Writes a designer's frame (two RGB lights, two materials, a sphere, a torus
and Suzanne) at any size and tessellation, for trying `shadesim config` on a frame nobody tuned
for. Not a tuning input: nothing in the derivation reads it, and no test checks a figure of it.

  tests/make_causes_frame.py OUT.json                      640x360, tessellation 100 and 64
  tests/make_causes_frame.py OUT.json --size 1920x1080 --sphere 300 --torus 200   a 1080p one
  tests/make_causes_frame.py OUT.json --size 160x90 --sphere 40 --torus 24        a small one

Suzanne comes from Debian's assimp-testmodels (/usr/share/assimp/models/BLEND/Suzanne_248.blend).
"""

import argparse
import json
import sys

SUZANNE = "/usr/share/assimp/models/BLEND/Suzanne_248.blend"


def frame(width, height, sphere, torus, unit):
    return {
        "image": {"width": width, "height": height},
        "camera": {"type": "perspective", "position": [0, 1.2, 7], "target": [0, 0.2, 0],
                   "up": [0, 1, 0], "fov_y": 35},
        "lights": [{"direction": [0.6, 0.8, 1], "colour": [1.0, 0.85, 0.7]},
                   {"direction": [-0.7, 0.3, 0.6], "colour": [0.35, 0.45, 0.9]}],
        "ambient_light": 1.0,
        "materials": [
            {"name": "gloss", "ambient": 0.08, "diffuse": [0.6, 0.2, 0.15],
             "specular": [0.6, 0.6, 0.6], "exponent": 80, "unit": unit},
            {"name": "clay", "ambient": 0.12, "diffuse": [0.5, 0.55, 0.6],
             "specular": 0.25, "exponent": 20, "unit": unit},
        ],
        "objects": [
            {"name": "ball", "type": "sphere", "material": "gloss", "radius": 1.0,
             "tessellation": sphere, "transform": {"translate": [-2.2, 0, 0]}},
            {"name": "ring", "type": "torus", "material": "gloss", "major_radius": 0.9,
             "minor_radius": 0.32, "tessellation": torus,
             "transform": {"translate": [2.2, 0, 0], "rotate_deg": [60, 0, 0]}},
            {"name": "suzanne", "type": "mesh", "material": "clay", "file": SUZANNE,
             "transform": {"rotate_deg": [-45, 0, 0]}},
        ],
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n".join(__doc__.split("\n\n")[1:]))
    ap.add_argument("out", help="the scene file to write")
    ap.add_argument("--size", default="640x360", help="WIDTHxHEIGHT (default 640x360)")
    ap.add_argument("--sphere", type=int, default=100, help="sphere tessellation (default 100)")
    ap.add_argument("--torus", type=int, default=64, help="torus tessellation (default 64)")
    ap.add_argument("--unit", default="ideal", help="the materials' specular unit (default ideal)")
    a = ap.parse_args(argv)
    try:
        width, height = (int(v) for v in a.size.lower().split("x"))
    except ValueError:
        ap.error("--size %r: expected WIDTHxHEIGHT, e.g. 640x360" % a.size)
    with open(a.out, "w") as f:
        json.dump(frame(width, height, a.sphere, a.torus, a.unit), f, indent=1)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
