#!/bin/sh
# Runs every libFuzzer target for SECONDS each (default 60) over its seeds: the project's own
# files and the regression corpus (tests/fuzz/corpus/TARGET, which the replay tests read too).
# Builds the fuzz build first (clang, -DAF_FUZZ=ON, in build-fuzz or $AF_FUZZ_BUILD) if needed.
# New inputs go to BUILD/corpus/TARGET, crashes to BUILD/artifacts/TARGET/, logs to BUILD/logs/.
# Exits nonzero if any target found a crash, a leak, a hang or a sanitizer report.
#
# usage: fuzz/run.sh [SECONDS] [TARGET...]
set -eu

root=$(cd "$(dirname "$0")/.." && pwd)
build=${AF_FUZZ_BUILD:-$root/build-fuzz}
seconds=${1:-60}
[ $# -gt 0 ] && shift
targets=${*:-af_parser_fuzz md5_fuzz def_fuzz map_fuzz console_fuzz}

if [ ! -f "$build/CMakeCache.txt" ]; then
    launcher=""
    command -v ccache >/dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAF_FUZZ=ON \
        -DAF_BUILD_TESTS=OFF -DAF_BUILD_TOOLS=OFF -DAF_BUILD_BENCH=OFF $launcher
fi
# shellcheck disable=SC2086
cmake --build "$build" -j"${AF_JOBS:-2}" --target $targets

# The seed folders of each target, as in tests/fuzz/CMakeLists.txt.
seeds() {
    case $1 in
    af_parser_fuzz) echo "$root/tests/golden $root/af" ;;
    md5_fuzz) echo "$root/models/humanoid $root/models/chain $root/models/lamp" ;;
    def_fuzz) echo "$root/def" ;;
    map_fuzz) echo "$root/maps $root/tests/golden" ;;
    console_fuzz) echo "$root/tests/console/scripts" ;;
    esac
}

failed=""
mkdir -p "$build/logs"
for target in $targets; do
    corpus="$build/corpus/$target"
    artifacts="$build/artifacts/$target"
    regression="$root/tests/fuzz/corpus/$target"
    mkdir -p "$corpus" "$artifacts"
    [ -d "$regression" ] || regression=""
    log="$build/logs/$target.log"
    echo "== $target: $seconds s (log: $log)"
    # shellcheck disable=SC2046
    if "$build/fuzz/$target" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$artifacts/" "$corpus" $regression $(seeds "$target") >"$log" 2>&1; then
        :
    else
        failed="$failed $target"
    fi
    grep -E '^#[0-9]+[[:space:]]+DONE' "$log" || tail -n 30 "$log"
    grep -E '^stat::number_of_executed_units' "$log" || true
done

if [ -n "$failed" ]; then
    echo "failed:$failed (inputs in $build/artifacts/)"
    exit 1
fi
echo "all targets ran $seconds s without a finding"
