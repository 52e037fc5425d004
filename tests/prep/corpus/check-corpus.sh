#!/usr/bin/env bash
# Rebuilds luxel-prep's corpus (tests/prep/corpus/) and checks that every script writes exactly
# the .glb committed beside it: the Blender scripts (*.py but the hand-*.py and the modules)
# through Blender's glTF exporter, headless; the hand-*.py, which write glTF themselves, with
# python3. sphere-100k.py is not committed (over 3 MB): the corpus test exports it at run time.
#
#   tests/prep/corpus/check-corpus.sh [--update]
#
# --update rewrites the committed files instead (after changing a script).
set -euo pipefail
export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ beside the scripts

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
update=0
case "${1:-}" in
    --update) update=1 ;;
    "") ;;
    *) echo "check-corpus.sh: unknown option '$1' (only --update)" >&2; exit 2 ;;
esac
blender="${BLENDER:-$(command -v blender || true)}"
if [[ -z "$blender" ]]; then
    echo "check-corpus.sh: blender not found; scripts/setup.sh installs it (scripts/packages.txt)" >&2
    exit 1
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
status=0
for script in "$here"/*.py; do
    name="$(basename "$script" .py)"
    case "$name" in
        corpus_common|hand_gltf|sphere-100k) continue ;;
        hand-*) command=(python3 "$script" "$work/$name.glb") ;;
        # One thread: Blender computes smooth normals in parallel, and with more threads the
        # terrain's came out different in the last bits from one run to the next.
        *) command=("$blender" --background --factory-startup -t 1 --python-exit-code 1 \
               --python "$script" -- "$work/$name.glb") ;;
    esac
    out="$work/$name.glb"
    if ! "${command[@]}" >"$work/$name.log" 2>&1 || [[ ! -s "$out" ]]; then
        echo "check-corpus.sh: $script failed; its output:" >&2
        cat "$work/$name.log" >&2
        status=1
        continue
    fi
    committed="$here/$name.glb"
    if [[ $update -eq 1 ]]; then
        cp "$out" "$committed"
        echo "updated $committed"
    elif ! cmp -s "$out" "$committed"; then
        echo "check-corpus.sh: $committed is not what $script writes now" \
            "($(stat -c %s "$out") bytes against $(stat -c %s "$committed" 2>/dev/null || echo 0));" \
            "run tests/prep/corpus/check-corpus.sh --update" >&2
        status=1
    else
        echo "$name.glb: as committed ($(stat -c %s "$out") bytes)"
    fi
done
exit $status
