#!/usr/bin/env bash
# Sets up a Debian 12 machine for luxel and builds it.
#   scripts/setup.sh [--no-build] [--build-dir DIR] [--sanitize]
# Installs every package in scripts/packages.txt with apt-get (idempotent: already installed
# packages are skipped), then configures and builds into build/ (or DIR). Needs root or sudo
# for the install step only.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir="$repo/build"
do_build=1
sanitize=OFF
while [ $# -gt 0 ]; do
    case "$1" in
        --no-build) do_build=0 ;;
        --build-dir) build_dir=$2; shift ;;
        --sanitize) sanitize=ON ;;
        -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
        *) echo "setup.sh: unknown option '$1'" >&2; exit 2 ;;
    esac
    shift
done

say() { printf '[setup] %s\n' "$*"; }

mapfile -t packages < <(grep -v '^\s*#' "$repo/scripts/packages.txt" | sed 's/\s*#.*//' | grep -v '^\s*$')
missing=()
for package in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed'; then
        missing+=("$package")
    fi
done
if ! command -v npm >/dev/null 2>&1; then
    missing+=(npm)
fi

if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -eq 0 ]; then
        as_root=()
    elif command -v sudo >/dev/null 2>&1; then
        as_root=(sudo)
    else
        echo "setup.sh: need root (or sudo) to install: ${missing[*]}" >&2
        exit 1
    fi
    say "installing ${#missing[@]} packages: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    if ! "${as_root[@]}" apt-get update -qq >/tmp/luxel-apt-update.log 2>&1; then
        echo "setup.sh: apt-get update failed:" >&2
        tail -n 20 /tmp/luxel-apt-update.log >&2
        exit 1
    fi
    if ! "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" \
            >/tmp/luxel-apt-install.log 2>&1; then
        # Name the package that failed: retry one by one.
        for package in "${missing[@]}"; do
            if ! "${as_root[@]}" apt-get install -y -qq --no-install-recommends "$package" \
                    >/tmp/luxel-apt-one.log 2>&1; then
                echo "setup.sh: apt-get could not install '$package':" >&2
                tail -n 20 /tmp/luxel-apt-one.log >&2
                exit 1
            fi
        done
    fi
else
    say "all ${#packages[@]} packages already installed"
fi

# The Khronos glTF validator, used by the tests that check every glTF file we write.
if ! [ -f "$repo/tools/node_modules/gltf-validator/package.json" ]; then
    say "installing the Khronos glTF validator (npm)"
    if ! (cd "$repo/tools" && npm ci --no-audit --no-fund --loglevel=error >/tmp/luxel-npm.log 2>&1); then
        echo "setup.sh: npm could not install gltf-validator:" >&2
        tail -n 20 /tmp/luxel-npm.log >&2
        exit 1
    fi
fi

if [ "$do_build" -eq 1 ]; then
    jobs=$(nproc)
    # ccache hits across checkouts at different paths (CI clones afresh each time): hash
    # paths relative to the repository and ignore the working directory.
    export CCACHE_BASEDIR="$repo" CCACHE_NOHASHDIR=1
    say "configuring $build_dir (LUXEL_SANITIZE=$sanitize)"
    mkdir -p "$build_dir"
    # The sanitized build leaves out the Google Benchmark programs: they are timed by hand in
    # the plain build and never run under the sanitizers, and linking ten of them with ASan
    # costs CI minutes.
    benchmarks=ON
    [ "$sanitize" = ON ] && benchmarks=OFF
    cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DLUXEL_SANITIZE="$sanitize" -DLUXEL_BUILD_BENCHMARKS="$benchmarks" >"$build_dir/configure.log" 2>&1 || {
        cat "$build_dir/configure.log" >&2; exit 1; }
    say "building with $jobs jobs"
    cmake --build "$build_dir" -j "$jobs"
    say "done: binaries in $build_dir/bin"
fi
