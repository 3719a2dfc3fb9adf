#!/usr/bin/env bash
# Fuzz lsdem's file readers with libFuzzer (clang-14, ASan + UBSan), see docs/fuzzing.md.
#
#   scripts/fuzz.sh [TARGET|all] [SECONDS]   fuzz one target (or all, one after the other;
#                                            LSDEM_FUZZ_JOBS=2 runs two at once), default 600 s
#   LSDEM_FUZZ_FLAGS="-fork=1 -ignore_crashes=1"   extra libFuzzer flags (here: go on after
#                                            a crash, collecting every reproducer)
#   scripts/fuzz.sh merge [TARGET|all]       minimise fuzz/corpus/TARGET together with the new
#                                            inputs found, in place (regression-* files are kept)
#
# Targets: scene, asset, mesh_obj, mesh_stl, mesh_ply, checkpoint, grains_csv. The build goes
# to build-fuzz/; new inputs and crash, timeout, leak and out-of-memory reproducers to
# build-fuzz/findings/TARGET/.
set -euo pipefail
cd "$(dirname "$0")/.."

all_targets=(scene asset mesh_obj mesh_stl mesh_ply checkpoint grains_csv)
mode=fuzz
if [ "${1:-}" = merge ]; then mode=merge; shift; fi
target=${1:-all}
seconds=${2:-600}
jobs=${LSDEM_FUZZ_JOBS:-1}
if [ "$target" = all ]; then
    targets=("${all_targets[@]}")
elif [[ " ${all_targets[*]} " == *" $target "* ]]; then
    targets=("$target")
else
    echo "lsdem fuzz: unknown target '$target'; use one of: all ${all_targets[*]}" >&2
    exit 2
fi
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "lsdem fuzz: SECONDS must be a whole number" >&2; exit 2; }

# libFuzzer comes with clang's runtime libraries; the normal build does not need either.
bash scripts/install-deps.sh
missing=()
for p in clang-14 libclang-rt-14-dev; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
        missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "lsdem fuzz: installing ${missing[*]}"
    sudo_cmd=()
    [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
    export DEBIAN_FRONTEND=noninteractive
    "${sudo_cmd[@]}" apt-get update -qq
    "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DLSDEM_FUZZ=ON -DLSDEM_WERROR=OFF -DLSDEM_BUILD_TESTS=OFF -DLSDEM_BUILD_BENCHMARKS=OFF \
      -DBUILD_SHARED_LIBS=OFF \
      > /dev/null
cmake --build build-fuzz -j2 --target "${targets[@]/#/fuzz_}"

# OpenVDB 10 leaks part of a tree when a truncated file makes it throw: known, upstream.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
limits=(-rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10)

fuzz_one() {
    local t=$1 out=build-fuzz/findings/$1
    mkdir -p "$out/corpus" "$out/crashes"
    echo "lsdem fuzz: $t for $seconds s (log: $out/fuzz.log)"
    local dict=()
    [ -f "fuzz/$t.dict" ] && dict=(-dict="fuzz/$t.dict")
    # New inputs go to the first folder only; the committed corpus is read, not written. The
    # CPU time (user + system, the fuzzer and its children) goes to the end of the log.
    local TIMEFORMAT="cpu_seconds: %U user + %S system"
    # shellcheck disable=SC2086 # the extra flags are words
    { time build-fuzz/fuzz/fuzz_"$t" "$out/corpus" "fuzz/corpus/$t" "${limits[@]}" \
        "${dict[@]}" ${LSDEM_FUZZ_FLAGS:-} -max_total_time="$seconds" \
        -artifact_prefix="$out/crashes/" -print_final_stats=1 > "$out/fuzz.log" 2>&1 || true
    } 2>> "$out/fuzz.log"
    grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^cpu_seconds" "$out/fuzz.log" |
        sed "s/^/  $t /"
    local found
    found=$(find "$out/crashes" -type f | wc -l)
    echo "  $t: $found reproducer(s) in $out/crashes/"
}

merge_one() {
    local t=$1 merged=build-fuzz/merged/$1
    rm -rf "$merged"
    mkdir -p "$merged" "build-fuzz/findings/$t/corpus"
    # Reproducers of fixed bugs stay whatever coverage they add.
    build-fuzz/fuzz/fuzz_"$t" -merge=1 "${limits[@]}" "$merged" "fuzz/corpus/$t" \
        "build-fuzz/findings/$t/corpus" > "build-fuzz/findings/$t/merge.log" 2>&1
    find "fuzz/corpus/$t" -type f ! -name 'regression-*' -delete
    cp "$merged"/* "fuzz/corpus/$t/"
    # libFuzzer names inputs by their SHA-1: drop the copies of the regression files.
    for r in "fuzz/corpus/$t"/regression-*; do
        [ -e "$r" ] && rm -f "fuzz/corpus/$t/$(sha1sum "$r" | cut -d' ' -f1)"
    done
    echo "lsdem fuzz: fuzz/corpus/$t now holds $(find "fuzz/corpus/$t" -type f | wc -l) files," \
         "$(du -sh "fuzz/corpus/$t" | cut -f1)"
}

if [ "$mode" = merge ]; then
    for t in "${targets[@]}"; do merge_one "$t"; done
    exit 0
fi

running=0
for t in "${targets[@]}"; do
    if [ "$jobs" -ge 2 ]; then
        fuzz_one "$t" &
        running=$((running + 1))
        if [ "$running" -ge "$jobs" ]; then wait -n; running=$((running - 1)); fi
    else
        fuzz_one "$t"
    fi
done
wait
cat <<MSG
lsdem fuzz: done. Reproduce a finding with  build-fuzz/fuzz/fuzz_TARGET FILE
  (or build/fuzz/replay_TARGET FILE in the ordinary build); keep a fixed one as
  fuzz/corpus/TARGET/regression-NAME. Fold the new inputs into the committed corpus with
  scripts/fuzz.sh merge TARGET   (libFuzzer -merge=1: keeps only inputs that add coverage)
MSG
