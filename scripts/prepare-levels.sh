#!/usr/bin/env bash
# Regenerates the prepared levels, assets/levels/prepared/<name>.glb, from
# assets/levels/<name>.glb and tests/levels/blender/<name>.glb with luxel-prep's default settings, and the page pictures in
# docs/images/prep/. A test (tests/prep/levels_test.cpp) checks the committed files against a
# fresh run, so run this after changing luxel-prep or a level.
#
#   scripts/prepare-levels.sh [BUILD_DIR]     (default: build; needs BUILD_DIR/bin/luxel-prep)
#
# The JSON reports and every page picture go to BUILD_DIR/prep-reports/.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
prep="$build/bin/luxel-prep"
if [[ ! -x "$prep" ]]; then
    echo "prepare-levels.sh: $prep not found; build it first: cmake --build $build --target luxel-prep" >&2
    exit 1
fi

prepared="$root/assets/levels/prepared"
reports="$build/prep-reports"
images="$root/docs/images/prep"
mkdir -p "$prepared" "$reports" "$images"

# The built-in levels, and the levels Blender's exporter made (tests/levels/blender/).
for level in "$root"/assets/levels/*.glb "$root"/tests/levels/blender/*.glb; do
    name="$(basename "$level" .glb)"
    "$prep" "$level" -o "$prepared/$name.glb" --report "$reports/$name.json"
done

# A few pages for people to look at: the thesis scene, the level of many flat surfaces, and
# the curved one.
rm -f "$images"/*.png
cp "$reports/cornell.page0.png" "$images/cornell.page0.png"
cp "$reports/two-rooms.page0.png" "$images/two-rooms.page0.png"
cp "$reports/caustics.page0.png" "$images/caustics.page0.png"
cp "$reports/caustics.page1.png" "$images/caustics.page1.png"
cp "$reports/furnace.page0.png" "$images/furnace.page0.png"
cp "$reports/sandbox.page0.png" "$images/sandbox.page0.png"
echo "prepared levels in $prepared, reports in $reports, pictures in $images"
