#!/usr/bin/env bash
# Runs every tests/levels/blender/*.py through Blender's glTF exporter, headless, and checks that
# it writes exactly the .glb committed beside the script: the committed levels are what the
# scripts make, with the Blender of scripts/packages.txt.
#
#   tests/levels/blender/check-exports.sh [--update]
#
# --update rewrites the committed files instead (after changing a script).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
update=0
case "${1:-}" in
    --update) update=1 ;;
    "") ;;
    *) echo "check-exports.sh: unknown option '$1' (only --update)" >&2; exit 2 ;;
esac
blender="${BLENDER:-$(command -v blender || true)}"
if [[ -z "$blender" ]]; then
    echo "check-exports.sh: blender not found; scripts/setup.sh installs it (scripts/packages.txt)" >&2
    exit 1
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
status=0
for script in "$here"/*.py; do
    name="$(basename "$script" .py)"
    out="$work/$name.glb"
    # One thread: Blender's parallel normals can differ in the last bits between runs.
    if ! "$blender" --background --factory-startup --threads 1 --python-exit-code 1 --python "$script" \
        -- "$out" >"$work/$name.log" 2>&1 || [[ ! -s "$out" ]]; then
        echo "check-exports.sh: $script: Blender failed; its output:" >&2
        cat "$work/$name.log" >&2
        status=1
        continue
    fi
    committed="$here/$name.glb"
    if [[ $update -eq 1 ]]; then
        cp "$out" "$committed"
        echo "updated $committed"
    elif ! cmp -s "$out" "$committed"; then
        echo "check-exports.sh: $committed is not what $script exports now" \
            "($(stat -c %s "$out") bytes against $(stat -c %s "$committed" 2>/dev/null || echo 0));" \
            "run tests/levels/blender/check-exports.sh --update, then scripts/prepare-levels.sh" >&2
        status=1
    else
        echo "$name.glb: as committed ($(stat -c %s "$out") bytes)"
    fi
done
exit $status
