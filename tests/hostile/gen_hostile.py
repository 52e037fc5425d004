#!/usr/bin/python3
"""Writes the hostile-input corpus of issue 25: one folder per case under OUT, a shared
OUT/_outside/ folder holding what escape cases point at, and OUT/manifest.json describing
every case (class, description, tools that apply, expected outcome, forbidden paths).

    gen_hostile.py --out DIR [--case REGEX] [--no-big] [--list]

Deterministic: the same generator writes the same bytes. OUT is emptied first (only folders
this generator made: it refuses a non-empty OUT without a manifest.json).
"""

import argparse
import os
import re
import shutil
import sys

sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import hostile_cases  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=False, help="corpus folder (created)")
    parser.add_argument("--case", help="only cases whose name matches this regex")
    parser.add_argument("--no-big", action="store_true",
                        help="leave out the cases of more than a few MB")
    parser.add_argument("--list", action="store_true", help="list the cases and exit")
    args = parser.parse_args()

    hostile_cases.load_all()
    entries = [e for e in hostile_cases.REGISTRY
               if (not args.case or re.search(args.case, e["name"]))
               and not (args.no_big and e["big"])]
    names = [e["name"] for e in hostile_cases.REGISTRY]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        sys.exit("gen_hostile.py: duplicate case names: " + ", ".join(duplicates))
    if args.list:
        for e in entries:
            print("%-40s %-17s %s" % (e["name"], e["class"], e["description"]))
        print("%d cases" % len(entries))
        return 0
    if not args.out:
        parser.error("--out is required")

    root = os.path.abspath(args.out)
    if os.path.isdir(root) and os.listdir(root):
        if not os.path.exists(os.path.join(root, "manifest.json")):
            sys.exit("gen_hostile.py: %s is not empty and holds no manifest.json; refusing to "
                     "clear it" % root)
        shutil.rmtree(root)
    os.makedirs(root, exist_ok=True)
    hostile_cases.write_outside(root)

    items = []
    for entry in entries:
        c = hostile_cases.Case(entry["name"], root)
        os.makedirs(c.dir, exist_ok=True)
        entry["fn"](c)
        if c.main is None:
            sys.exit("gen_hostile.py: case %s wrote no level file" % entry["name"])
        items.append(hostile_cases.manifest_entry(entry, c))
    hostile_cases.save_manifest(root, items)
    counts = {}
    for item in items:
        counts[item["class"]] = counts.get(item["class"], 0) + 1
    print("gen_hostile.py: %d cases in %s (%s)" % (
        len(items), root, ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
