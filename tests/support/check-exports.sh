#!/usr/bin/env bash
# Runs every DIR/*.py that writes a test level and checks that it writes exactly the .glb
# committed beside it: the committed levels are what their scripts make, with the Blender of
# scripts/packages.txt. Scripts run through Blender's glTF exporter, headless; hand-*.py write
# glTF themselves and run with python3; names with an underscore are modules the others import.
#
#   tests/support/check-exports.sh DIR [--update] [--skip NAME]...
#
# --update rewrites the committed files instead (after changing a script); --skip leaves a
# script out (one whose file is too large to commit, which its test exports at run time).
set -euo pipefail
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ beside the scripts

if [[ $# -lt 1 || ! -d "$1" ]]; then
    echo "check-exports.sh: usage: check-exports.sh DIR [--update] [--skip NAME]..." >&2
    exit 2
fi
here="$(cd "$1" && pwd)"
shift
update=0
skip=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --update) update=1 ;;
        --skip) skip+=("$2"); shift ;;
        *) echo "check-exports.sh: unknown option '$1' (--update, --skip NAME)" >&2; exit 2 ;;
    esac
    shift
done
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
    [[ "$name" == *_* ]] && continue
    for skipped in "${skip[@]+"${skip[@]}"}"; do
        [[ "$name" == "$skipped" ]] && continue 2
    done
    out="$work/$name.glb"
    case "$name" in
        hand-*) command=(python3 "$script" "$out") ;;
        # One thread: Blender computes smooth normals in parallel, and with more threads they
        # came out different in the last bits from one run to the next.
        *) command=("$blender" --background --factory-startup --threads 1 --python-exit-code 1 \
               --python "$script" -- "$out") ;;
    esac
    if ! "${command[@]}" >"$work/$name.log" 2>&1 || [[ ! -s "$out" ]]; then
        echo "check-exports.sh: $script failed; its output:" >&2
        cat "$work/$name.log" >&2
        status=1
        continue
    fi
    committed="$here/$name.glb"
    if [[ $update -eq 1 ]]; then
        cp "$out" "$committed"
        echo "updated $committed"
    elif ! cmp -s "$out" "$committed"; then
        echo "check-exports.sh: $committed is not what $script writes now" \
            "($(stat -c %s "$out") bytes against $(stat -c %s "$committed" 2>/dev/null || echo 0));" \
            "run tests/support/check-exports.sh $here --update (then scripts/prepare-levels.sh" \
            "for a level)" >&2
        status=1
    else
        echo "$name.glb: as committed ($(stat -c %s "$out") bytes)"
    fi
done
exit $status
