#!/usr/bin/env bash
# Regenerates the accuracy chart of the README: runs deformable_sim_bench's full sweep (about ten
# minutes on one core of a quiet machine) and plots it into test/data/bench/.
#
#   scripts/accuracy_chart.sh [PATH/TO/deformable_sim_bench]
#
# The default binary is the one `scripts/setup.sh test` builds:
# ${DEFORMABLE_SIM_WS:-~/deformable_sim_ws}/devel/lib/deformable_sim/deformable_sim_bench.
# Writes accuracy.csv, machine.txt (CPU model, thread count, load, commit), the PNGs and
# advice.md (the budget table and every case's Pareto front).
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH  # Debian's python3, which has python3-matplotlib

case "${1:-}" in
  -h|--help)
    echo "usage: scripts/accuracy_chart.sh [PATH/TO/deformable_sim_bench]"
    sed -n '2,/^set -euo/s/^# \{0,1\}//p' "$0"
    exit 0 ;;
esac

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=$repo/test/data/bench
bench=${1:-${DEFORMABLE_SIM_WS:-$HOME/deformable_sim_ws}/devel/lib/deformable_sim/deformable_sim_bench}
if [ ! -x "$bench" ]; then
  echo "no $bench: build it first (bash scripts/setup.sh test, or catkin_make)" >&2
  exit 1
fi
/usr/bin/python3 -c "import matplotlib" 2>/dev/null ||
  { echo "python3-matplotlib is missing: apt-get install python3-matplotlib" >&2; exit 1; }

mkdir -p "$out"
model=$(lscpu | sed -n 's/^Model name: *//p' | head -n 1)
load=$(cut -d ' ' -f 1-3 /proc/loadavg)
commit=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)
echo "Measured on: $model, 1 thread, $(date -u +%Y-%m-%d), load average at start $load, commit $commit" \
  > "$out/machine.txt"
cat "$out/machine.txt"
OMP_NUM_THREADS=1 "$bench" --repeat 3 --out "$out/accuracy.csv"
/usr/bin/python3 "$repo/scripts/plot_accuracy.py" "$out/accuracy.csv" "$out"
