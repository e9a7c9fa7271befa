#!/usr/bin/env bash
# Set up deformable_sim on a fresh Debian 12 machine: install the Debian packages it needs, build
# it in a catkin workspace, then run the demo or the whole test suite.
#
#   scripts/setup.sh demo          # install, build, run the node headless (roscore included) on
#                                  # the built-in default scene, pushed back and forth; live stats
#   scripts/setup.sh demo --rviz   # the same with rviz
#   scripts/setup.sh test          # install, build, run every test; last line "N passed, N failed"
#
# The workspace is $DEFORMABLE_SIM_WS (default ~/deformable_sim_ws); this clone is linked into it.
# DEFORMABLE_SIM_DEMO_SECONDS stops the demo after that many seconds (default: run until Ctrl-C).
set -euo pipefail

mode=${1:-demo}
rviz=false
usage="usage: $0 demo [--rviz] | test"
case "$mode" in
  demo|test) ;;
  -h|--help) echo "$usage"; sed -n '2,/^set -euo/s/^# \{0,1\}//p' "$0"; exit 0 ;;
  *) echo "$usage" >&2; exit 2 ;;
esac
if [ "${2:-}" = "--rviz" ]; then rviz=true; fi

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ws=${DEFORMABLE_SIM_WS:-$HOME/deformable_sim_ws}
# Debian's python3 must come first: catkin needs its catkin_pkg (a pyenv/conda python has none).
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH

packages=(
  build-essential cmake libgtest-dev libeigen3-dev libyaml-cpp-dev libbenchmark-dev
  libbullet-dev pkg-config
  ros-core-dev catkin python3-catkin-pkg python3-rostest rosbash
  libtf2-ros-dev libstd-srvs-dev libdiagnostic-updater-dev liburdfdom-dev libassimp-dev
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  python3-geometry-msgs python3-visualization-msgs python3-std-srvs python3-tf2-msgs
  python3-tf2-ros python3-diagnostic-msgs python3-sensor-msgs ros-robot-state-publisher
  librosbag-dev libtf2-msgs-dev libtf2-eigen-dev python3-rosbag
  libceres-dev
)
# rviz for the demo when asked; rviz under Xvfb with imagemagick for the screenshot test; clang
# with libFuzzer for the fuzz targets (scripts/fuzz.sh).
if [ "$mode" = test ]; then
  packages+=(rviz xvfb imagemagick x11-utils python3-numpy python3-matplotlib clang-14
    libclang-rt-14-dev)
fi
if [ "$rviz" = true ]; then packages+=(rviz); fi
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
  export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
  roslaunch deformable_sim demo.launch rviz:="$rviz" > "$ws/demo.log" 2>&1 &
  launch=$!
  trap 'kill -INT $launch 2>/dev/null; wait $launch 2>/dev/null' EXIT
  cat <<EOF
== deformable_sim_node is running the built-in default scene: a soft foam cantilever clamped at
   x = 0, sagging under gravity and pushed back and forth at its tip (roslaunch log: $ws/demo.log).
   In another terminal (after: source $ws/devel/setup.bash):
     rostopic echo /deformable_sim/stats                   # solver, energy, real-time factor
     rostopic echo -n 1 /deformable_sim/state              # every node's position and velocity
     rostopic pub -1 /deformable_sim/wrench geometry_msgs/WrenchStamped \\
       '{header: {frame_id: beam/tip}, wrench: {force: {z: -2.0}}}'   # push the tip down
     rosservice call /deformable_sim/pause                 # pause, step, resume, reset
     rviz -d $repo/config/deformable_sim.rviz              # or: $0 demo --rviz
   Live stats (Ctrl-C stops the demo):
EOF
  sleep 3
  if [ -n "${DEFORMABLE_SIM_DEMO_SECONDS:-}" ]; then
    timeout -s INT "$DEFORMABLE_SIM_DEMO_SECONDS" rosrun deformable_sim print_stats || true
  else
    rosrun deformable_sim print_stats
  fi
  exit 0
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
# A short fuzz run of each target (clang, libFuzzer), one JUnit result per target beside the others.
echo "== fuzzing (${DEFORMABLE_SIM_FUZZ_SECONDS:-15} s per target; log: $ws/fuzz.log)"
DEFORMABLE_SIM_FUZZ_BUILD="$ws/fuzz" DEFORMABLE_SIM_FUZZ_RESULTS="$ws/build/test_results/deformable_sim" \
  bash "$repo/scripts/fuzz.sh" "${DEFORMABLE_SIM_FUZZ_SECONDS:-15}" > "$ws/fuzz.log" 2>&1 || true
grep -E "^== fuzz_|^#[0-9]+|FAILED" "$ws/fuzz.log" || true
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
