#!/usr/bin/env bash
# Builds the fuzz targets test/fuzz/fuzz_*.cpp with clang++-14 (libFuzzer, AddressSanitizer,
# UndefinedBehaviorSanitizer) straight from the ROS-free sources (core and readers; no catkin), and
# runs each one in turn, starting from its committed corpus (test/fuzz/corpus/<target>/), with its
# dictionary (test/fuzz/<target>.dict) and extra libFuzzer flags (test/fuzz/<target>.options, the
# lines that are not comments) where it has them.
#
#   scripts/fuzz.sh [seconds-per-target]     # default 20 (a CI run)
#
# Environment:
#   DEFORMABLE_SIM_FUZZ_BUILD    build directory (default /tmp/deformable_sim_fuzz)
#   DEFORMABLE_SIM_FUZZ_RESULTS  write a JUnit XML result per target here (fuzz_<target>.xml), as
#                                catkin's test_results directory expects them
#   DEFORMABLE_SIM_FUZZ_TARGETS  the targets to run, e.g. "fuzz_commands" (default: all four)
#   DEFORMABLE_SIM_FUZZ_JOBS     parallel compilations (default 2)
#
# Exits non-zero when a target does not build or finds a crash, a leak, a sanitizer report, a
# timeout, an allocation above the limit or a failed check. The input that did it is kept in
# <build>/<target>/artifacts/ and the log in <build>/<target>/fuzz.log; reproduce it with
# `<build>/<target>/<target> <input>`, then save it in test/fuzz/crashes/<target>/ so that
# test_fuzz_corpus keeps it fixed. Inputs that reached new code stay in <build>/<target>/corpus/.
set -euo pipefail

case "${1:-}" in
  -h|--help)
    echo "usage: scripts/fuzz.sh [seconds-per-target]"
    sed -n '2,/^set -euo/s/^# \{0,1\}//p' "$0"
    exit 0 ;;
esac
seconds=${1:-20}
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${DEFORMABLE_SIM_FUZZ_BUILD:-/tmp/deformable_sim_fuzz}
results=${DEFORMABLE_SIM_FUZZ_RESULTS:-}
read -r -a targets <<< "${DEFORMABLE_SIM_FUZZ_TARGETS:-fuzz_mesh_readers fuzz_scene_file fuzz_commands fuzz_surfaces}"
jobs=${DEFORMABLE_SIM_FUZZ_JOBS:-2}
export PATH=/usr/bin:/bin:$PATH
cxx=clang++-14
command -v "$cxx" > /dev/null || { echo "$cxx not found (apt-get install clang-14 libclang-rt-14-dev)" >&2; exit 1; }

# The ROS-free libraries: deformable_sim_core and the readers of deformable_sim_io (of URDF only
# the visual meshes a scene's surface body may take).
# Paths are relative to the repository (the glob too: expanded after the cd).
cd "$repo"
sources=(src/core/*/*.cpp src/io/mesh_reader.cpp src/io/gmsh_reader.cpp src/io/tetgen_reader.cpp
  src/io/scene_file.cpp src/io/triangle_mesh_reader.cpp src/io/surface_body_reader.cpp
  src/io/urdf_visual_mesh.cpp)
# No OpenMP: the solver's loops run on one thread (bit-identical results, documented). Eigen's
# index checks are off as in a release build: traced by libFuzzer they took half of all time, and
# AddressSanitizer still catches an index past a vector's end.
flags=(-std=c++17 -O1 -gline-tables-only -fno-omit-frame-pointer -Wno-unknown-pragmas
  -DEIGEN_NO_DEBUG -fsanitize=address,undefined -fno-sanitize-recover=undefined
  -I"$repo/include" -I"$repo/src/io" -I/usr/include/eigen3)

# The numerical kernels keep edge coverage but not libFuzzer's tracing of comparisons (loop
# counters there tell the fuzzer nothing about the input).
numeric=(src/core/solvers/block_sparse_matrix.cpp src/core/elements/corotational_elasticity.cpp
  src/core/solvers/linear_solver.cpp src/core/solvers/rigid_mode_coarse_space.cpp
  src/core/base/rotation.cpp src/core/elements/tetrahedron.cpp src/core/bodies/body.cpp
  src/core/outputs/strain.cpp src/core/bodies/reduced_dynamics.cpp
  src/core/geometry/winding_number.cpp src/core/surface_bodies/box_occupancy.cpp)

# True when object $1 (with its .d file) is missing or older than one of its dependencies.
stale() {
  [ -e "$1" ] && [ -e "$1.d" ] || return 0
  local dep
  for dep in $(sed -e 's/^[^:]*://' -e 's/\\$//' "$1.d"); do
    [ "$dep" -nt "$1" ] && return 0
  done
  return 1
}

# $1 source, $2 object. The compiler's output goes to $2.log, shown when it fails.
compile() {
  local coverage=-fsanitize=fuzzer-no-link
  if [[ " ${numeric[*]} " == *" $1 "* ]]; then
    coverage=-fsanitize-coverage=inline-8bit-counters,pc-table
  fi
  "$cxx" "${flags[@]}" "$coverage" -MMD -MF "$2.d" -c "$repo/$1" -o "$2" \
    > "$2.log" 2>&1 || { cat "$2.log" >&2; return 1; }
}

mkdir -p "$build/obj"
# Objects built by another version of the flags above: rebuild everything.
signature="${flags[*]} | ${numeric[*]} | $(declare -f compile)"
if [ "$(cat "$build/signature" 2>/dev/null)" != "$signature" ]; then rm -f "$build"/obj/*.o; fi

# $1 target, $2 seconds taken, $3 failure text (empty: passed), $4 the input that failed (if any).
# One test case, as gtest writes.
write_result() {
  local target=$1 time=$2 failure=$3 failures=0
  [ -n "$failure" ] && failures=1
  mkdir -p "$results"
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo "<testsuites tests=\"1\" failures=\"$failures\" disabled=\"0\" errors=\"0\" time=\"$time\" name=\"AllTests\">"
    echo "  <testsuite name=\"Fuzz\" tests=\"1\" failures=\"$failures\" disabled=\"0\" errors=\"0\" time=\"$time\">"
    echo "    <testcase name=\"$target\" status=\"run\" time=\"$time\" classname=\"Fuzz\">"
    if [ -n "$failure" ]; then
      printf '      <failure message="%s" type=""><![CDATA[%s]]></failure>\n' \
        "$target: $(basename "${4:-none}")" "${failure//]]>/]] >}"
    fi
    echo "    </testcase>"
    echo "  </testsuite>"
    echo "</testsuites>"
  } > "$results/fuzz_$target.xml"
}

echo "== building the fuzz targets in $build"
started=$(date +%s)
objects=()
pids=()
failed=0
for source in "${sources[@]}" "${targets[@]/#/test/fuzz/}"; do
  source=${source%.cpp}.cpp
  object="$build/obj/$(echo "${source%.cpp}" | tr / _).o"
  case "$source" in test/fuzz/*) ;; *) objects+=("$object") ;; esac
  if stale "$object"; then
    compile "$source" "$object" &
    pids+=($!)
    if ((${#pids[@]} >= jobs)); then wait "${pids[0]}" || failed=1; pids=("${pids[@]:1}"); fi
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
build_failed() {
  echo "building the fuzz targets failed" >&2
  if [ -n "$results" ]; then
    for target in "${targets[@]}"; do write_result "$target" 0 "building the fuzz targets failed"; done
  fi
  exit 1
}
((failed == 0)) || build_failed
echo "$signature" > "$build/signature"
rm -f "$build/libdeformable_sim_fuzz.a"
ar rcs "$build/libdeformable_sim_fuzz.a" "${objects[@]}" || build_failed
for target in "${targets[@]}"; do
  mkdir -p "$build/$target"
  "$cxx" "${flags[@]}" -fsanitize=fuzzer "$build/obj/test_fuzz_$target.o" \
    "$build/libdeformable_sim_fuzz.a" -lyaml-cpp -lassimp -lurdfdom_model -o "$build/$target/$target" || build_failed
done
echo "   built in $(($(date +%s) - started)) s"

status=0
for target in "${targets[@]}"; do
  dir="$build/$target"
  rm -rf "$dir/corpus" "$dir/artifacts"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  cp "$repo/test/fuzz/corpus/$target/"* "$dir/corpus/"
  # -rss_limit_mb and -malloc_limit_mb: a reader must not allocate gigabytes for a tiny input.
  # -timeout: a step whose elements turn by radians may take up to Body::kMaxSolves solves, and
  # the sanitizers make them ~50 times slower: an input of 64 commands and ticks can take 25 s
  # (0.5 s in test_fuzz_corpus); a hang still shows.
  options=(-max_total_time="$seconds" -max_len=4096 -timeout=60 -rss_limit_mb=1024
    -malloc_limit_mb=256 -print_final_stats=1 -artifact_prefix="$dir/artifacts/")
  if [ -e "$repo/test/fuzz/$target.dict" ]; then options+=(-dict="$repo/test/fuzz/$target.dict"); fi
  if [ -e "$repo/test/fuzz/$target.options" ]; then
    read -r -a extra <<< "$(grep -v '^#' "$repo/test/fuzz/$target.options" | tr '\n' ' ')"
    options+=("${extra[@]}")
  fi
  echo "== $target: $seconds s"
  start=$(date +%s%N)
  rc=0
  # Leaks inside assimp itself are suppressed (test/fuzz/lsan.supp says which and why).
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    LSAN_OPTIONS=suppressions="$repo/test/fuzz/lsan.supp" \
    "$dir/$target" "${options[@]}" "$dir/corpus" > "$dir/fuzz.log" 2>&1 || rc=$?
  time=$(awk -v start="$start" -v end="$(date +%s%N)" 'BEGIN { printf "%.1f", (end - start) / 1e9 }')
  # The last status line ("#N DONE cov: C ft: F corp: ...") and the executions.
  grep -E "^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE|INITED)" "$dir/fuzz.log" | tail -n 1 || true
  grep -E "^stat::(number_of_executed_units|peak_rss_mb)" "$dir/fuzz.log" || true
  failure=""
  crash=""
  if [ "$rc" -ne 0 ]; then
    status=1
    crash=$(ls "$dir/artifacts/" | head -n 1)
    # The report, printable ASCII only (names in it come from the input).
    failure=$(grep -E -A 30 "^==[0-9]+==ERROR|fuzz finding|runtime error|deadly signal|uncaught|out-of-memory|timeout" \
      "$dir/fuzz.log" | head -n 60 | tr -cd '\11\12\40-\176')
    [ -n "$failure" ] || failure=$(tail -n 40 "$dir/fuzz.log" | tr -cd '\11\12\40-\176')
    failure="crash file: $dir/artifacts/$crash"$'\n'"$failure"
    echo "$target FAILED (exit $rc): log $dir/fuzz.log, input $dir/artifacts/$crash" >&2
    echo "$failure" | head -n 20 >&2
  fi
  if [ -n "$results" ]; then write_result "$target" "$time" "$failure" "$crash"; fi
done
exit "$status"
