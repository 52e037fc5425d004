#!/usr/bin/env bash
# Fuzzes the glTF loader with libFuzzer (clang, ASan + UBSan) for SECONDS (default 60).
#   scripts/fuzz.sh [SECONDS]
# Configures build-fuzz/ with clang and LUXEL_FUZZ=ON LUXEL_SANITIZE=ON, builds only the fuzz
# target and its seed writer, seeds the corpus with the mutation test's scenes and every level
# file of the hostile corpus (tests/hostile: about 370 cases of issue 25), and runs.
# Exits non-zero when the fuzzer finds a crash, a sanitizer report, a leak or a timeout; the
# input that caused it is kept in build-fuzz/gltf-crashes/ (replay: build-fuzz/bin/luxel_gltf_fuzz FILE).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
case "$seconds" in
    ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;;
esac
build_dir="$repo/build-fuzz"
jobs=$(nproc)

for tool in clang clang++; do
    command -v "$tool" >/dev/null 2>&1 || {
        echo "fuzz.sh: $tool not found (scripts/setup.sh installs it)" >&2; exit 1; }
done

mkdir -p "$build_dir"
echo "[fuzz] configuring $build_dir with clang"
cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DLUXEL_FUZZ=ON -DLUXEL_SANITIZE=ON -DLUXEL_BUILD_BENCHMARKS=OFF \
    >"$build_dir/configure.log" 2>&1 || { cat "$build_dir/configure.log" >&2; exit 1; }
echo "[fuzz] building the fuzz target"
cmake --build "$build_dir" --target luxel_gltf_fuzz luxel_gltf_fuzz_seeds -j "$jobs"

seeds="$build_dir/gltf-seeds"
corpus="$build_dir/gltf-corpus"
crashes="$build_dir/gltf-crashes"
mkdir -p "$seeds" "$corpus" "$crashes"
"$build_dir/bin/luxel_gltf_fuzz_seeds" "$seeds"
# The hostile corpus: each case's level file (.gltf or .glb) becomes a seed. The target loads
# from memory with no folder, so a case's external buffers and images are refused there (the
# runner, tests/hostile/run_hostile.py, covers those through the tools); its GLB containers,
# JSON and data: URIs are what the fuzzer mutates. Cases over -max_len would be cut, so the
# big ones are left out.
hostile="$build_dir/hostile-corpus"
/usr/bin/python3 "$repo/tests/hostile/gen_hostile.py" --out "$hostile" --no-big >/dev/null
find "$hostile" -path "$hostile/_outside" -prune -o -type f \( -name '*.gltf' -o -name '*.glb' \) \
    -size -256k -print | while read -r level; do
    case_name=$(basename "$(dirname "$level")")
    cp "$level" "$seeds/hostile-$case_name-$(basename "$level")"
done
echo "[fuzz] $(find "$seeds" -type f | wc -l) seeds ($(find "$seeds" -name 'hostile-*' | wc -l) from the hostile corpus)"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:symbolize=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$repo/tests/support/lsan.supp:print_suppressions=0"
echo "[fuzz] running for $seconds s"
# New inputs go to the corpus (first directory); the seeds are read only. -timeout flags any
# input that takes more than 10 s (a hang), -rss_limit_mb any that balloons memory.
"$build_dir/bin/luxel_gltf_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=262144 -print_final_stats=1 -artifact_prefix="$crashes/" \
    "$corpus" "$seeds"
echo "[fuzz] no crash in $seconds s"
