#!/bin/bash
# The shipped pile's offline step on an idle machine and with one core kept busy beside it (a
# loop of the shell's), as deformable_sim_run reports its mean; medians of N runs each, and their
# ratio. Usage: scripts/busy_core_bench.sh [N=3] [extra deformable_sim_run arguments]
# Needs the workspace sourced (rosrun finds deformable_sim_run).
set -euo pipefail
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,5s/^# \{0,1\}//p' "$0"
  exit 0
fi
runs=${1:-3}
shift || true
scene=$(rospack find deformable_sim)/config/scenes/pile.yaml
step() {
  rosrun deformable_sim deformable_sim_run "$scene" --steps 150 --quiet "$@" 2>&1 |
    sed -n 's/.*: \([0-9.]*\) ms per step (mean).*/\1/p'
}
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
idle=$(for _ in $(seq "$runs"); do step "$@"; done | median)
(while :; do :; done) &
busy_pid=$!
trap 'kill $busy_pid 2>/dev/null' EXIT
busy=$(for _ in $(seq "$runs"); do step "$@"; done | median)
kill $busy_pid
echo "pile, 150 steps: idle ${idle} ms a step, one core busy ${busy} ms ($(echo "$busy / $idle" | bc -l | cut -c1-4)x)"
