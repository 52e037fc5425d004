#!/usr/bin/env python3
# The indirect relRMSE of one luxel-bench run's light maps against another run's reference, from
# two --dump-maps files of levels with the same light-map layout (the same level with and
# without portals, say): luxel-bench's own measure (area-weighted over every texel and channel),
# for when a level's own reference is too noisy to judge it.
#
#   scripts/compare-map-dumps.py MAPS.json REFERENCE.json
#
# Exit 1 when a file cannot be read or the layouts differ, 2 for a bad command line.
import json
import math
import sys


def texels(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)["texels"]
    except (OSError, ValueError, KeyError) as e:
        sys.stderr.write("compare-map-dumps: %s: %s\n" % (path, e))
        sys.exit(1)


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: compare-map-dumps.py MAPS.json REFERENCE.json\n")
        sys.exit(2)
    maps = texels(sys.argv[1])
    reference = texels(sys.argv[2])
    same = len(maps) == len(reference) and all(
        (m["surface"], m["x"], m["y"]) == (r["surface"], r["x"], r["y"])
        for m, r in zip(maps, reference))
    if not same:
        sys.stderr.write("compare-map-dumps: the two files have different light-map layouts\n")
        sys.exit(1)
    error = 0.0
    norm = 0.0
    for m, r in zip(maps, reference):
        for c in range(3):
            error += r["area"] * (m["indirect"][c] - r["ref_indirect"][c]) ** 2
            norm += r["area"] * r["ref_indirect"][c] ** 2
    if not norm > 0.0:
        sys.stderr.write("compare-map-dumps: the reference is black\n")
        sys.exit(1)
    print("indirect relRMSE %.4f over %d texels" % (math.sqrt(error / norm), len(maps)))


main()
