#!/usr/bin/env bash
# Renders the README's pictures with luxel-sandbox itself: the sandbox level from two points of
# its scripted camera path, with every lighting term and with each term left out; and the
# cornell and caustics levels with every term and with their caustics alone.
#
#   scripts/readme-pictures.sh [BUILD_DIR]      (default: build; needs BUILD_DIR/bin/luxel-sandbox)
#
# Writes docs/images/sandbox/<view>-<terms>.png.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
sandbox="$build/bin/luxel-sandbox"
if [[ ! -x "$sandbox" ]]; then
    echo "readme-pictures.sh: $sandbox not found; build it first" >&2
    exit 1
fi
out="$root/docs/images/sandbox"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# view name, seconds along the camera path
views=("west:3" "east:12")
# picture name, the terms drawn
variants=("all:all"
          "no-direct:indirect,caustics,specular,emission"
          "no-indirect:direct,caustics,specular,emission"
          "no-caustics:direct,indirect,specular,emission"
          "no-specular:direct,indirect,caustics,emission")
for view in "${views[@]}"; do
    # Every picture of a view at the exposure the full picture metered, so a term left out
    # shows as light missing, not as a brighter exposure.
    exposure=0
    for variant in "${variants[@]}"; do
        name="${view%%:*}-${variant%%:*}"
        # 20 frames with the camera held still: the lighting settles, objects keep moving.
        "$sandbox" --gl egl --size 640x360 --frames 20 --camera fixed --camera-at "${view##*:}" \
            --terms "${variant##*:}" --png-every 0 --exposure "$exposure" --out "$work/$name" \
            > /dev/null 2>&1
        if [[ "$exposure" == 0 ]]; then
            exposure="$(sed -n 's/.*"exposure": *\([0-9.e+-]*\).*/\1/p' "$work/$name/report.json")"
        fi
        cp "$work/$name/frame_0019.png" "$out/$name.png"
        echo "wrote docs/images/sandbox/$name.png"
    done
done

# The thesis scene and the caustics level from their own cameras: every term, and the caustic
# term alone (the light focused by the glass sphere, the brass ring and the water). 40 frames:
# the caustic photons arrive in slices over the first frames.
for level in cornell caustics; do
    exposure=0
    for variant in "all:all" "caustics:caustics"; do
        name="$level-${variant%%:*}"
        "$sandbox" --gl egl --level "$level" --size 640x360 --frames 40 --camera fixed \
            --terms "${variant##*:}" --png-every 0 --exposure "$exposure" --out "$work/$name" \
            > /dev/null 2>&1
        if [[ "$exposure" == 0 ]]; then
            exposure="$(sed -n 's/.*"exposure": *\([0-9.e+-]*\).*/\1/p' "$work/$name/report.json")"
        fi
        cp "$work/$name/frame_0039.png" "$out/$name.png"
        echo "wrote docs/images/sandbox/$name.png"
    done
done
