#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds and runs the whole test suite with ctest.
#   scripts/test.sh [--sanitize] [ctest arguments...]
# --sanitize builds into build-sanitize/ with LUXEL_SANITIZE=ON (ASan + UBSan) and runs the
# same tests there. Extra arguments go to ctest, e.g. `scripts/test.sh -L runtime`.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir="$repo/build"
setup_args=()
if [ "${1:-}" = "--sanitize" ]; then
    build_dir="$repo/build-sanitize"
    setup_args=(--sanitize)
    shift
fi

"$repo/scripts/setup.sh" --build-dir "$build_dir" "${setup_args[@]}"
# Headless by default: the suites that need an X server start their own under xvfb-run.
export EGL_PLATFORM=surfaceless
ctest --test-dir "$build_dir" --output-on-failure --no-tests=error -j "$(nproc)" "$@"
