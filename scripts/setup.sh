#!/usr/bin/env bash
# Set up deformable_sim on a fresh Debian 12 machine: install the Debian packages it needs, build
# it in a catkin workspace, then run the demo or the whole test suite.
#
#   scripts/setup.sh demo   # install, build, run the built-in default scene
#   scripts/setup.sh test   # install, build, run every test; last line "N passed, N failed"
#
# The workspace is $DEFORMABLE_SIM_WS (default ~/deformable_sim_ws); this clone is linked into it.
set -euo pipefail

mode=${1:-demo}
case "$mode" in demo|test) ;; *) echo "usage: $0 demo|test" >&2; exit 2 ;; esac

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ws=${DEFORMABLE_SIM_WS:-$HOME/deformable_sim_ws}
# Debian's python3 must come first: catkin needs its catkin_pkg (a pyenv/conda python has none).
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH

packages=(
  build-essential cmake libgtest-dev libeigen3-dev libyaml-cpp-dev
  ros-core-dev catkin python3-catkin-pkg python3-rostest rosbash
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

echo "== building in $ws"
mkdir -p "$ws/src" "$ws/devel/lib/python3/dist-packages"  # python path trap: see ROS on Debian
ln -sfn "$repo" "$ws/src/deformable_sim"
cd "$ws"
catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 > "$ws/build.log" 2>&1 ||
  { tail -n 60 "$ws/build.log"; echo "build failed (full log: $ws/build.log)" >&2; exit 1; }
set +u; source "$ws/devel/setup.bash"; set -u

if [ "$mode" = demo ]; then
  echo "== running the default scene (a soft cantilever under gravity, 2 s)"
  exec rosrun deformable_sim deformable_sim_run "$repo/config/scenes/cantilever.yaml" --steps 200 --quiet
fi

echo "== running the tests"
rm -rf "$ws/build/test_results"
if ! catkin_make tests -j2 > "$ws/test_build.log" 2>&1; then
  grep -E "error|Error" "$ws/test_build.log" | head -n 40
  echo "building the tests failed (full log: $ws/test_build.log)" >&2
  echo "0 passed, 1 failed"
  exit 1
fi
catkin_make run_tests -j2 > "$ws/test.log" 2>&1 || true  # exits 0 even on failures: judged below
grep -E "^\[  (FAILED|PASSED)  \]|RESULT: " "$ws/test.log" || true
catkin_test_results "$ws/build/test_results" > "$ws/test_summary.txt" 2>&1 && results_ok=1 || results_ok=0
tail -n 3 "$ws/test_summary.txt"
# Count test cases from the result files (catkin's own summary counts suites and cases alike).
read -r passed failed < <(/usr/bin/python3 - "$ws/build/test_results" <<'PY'
import pathlib, sys, xml.etree.ElementTree as ET
passed = failed = 0
for path in pathlib.Path(sys.argv[1]).rglob("*.xml"):
    for case in ET.parse(path).getroot().iter("testcase"):
        if case.find("skipped") is not None:
            continue
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
        else:
            passed += 1
print(passed, failed)
PY
)
if [ "$results_ok" -ne 1 ] && [ "$failed" -eq 0 ]; then failed=1; fi  # e.g. a test binary crashed
if [ "$passed" -eq 0 ] && [ "$failed" -eq 0 ]; then
  echo "no test ran (see $ws/test.log)" >&2
  failed=1
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
