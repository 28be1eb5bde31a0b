#!/usr/bin/env bash
# Runs one of the bench scripts once at a tiny size and checks that it ends with its figures
# (a bench script nothing runs breaks unnoticed).
# The figures themselves are not judged (machines here are noisy): the script must exit 0 and
# print its closing line.
#
#   tests/bench_scripts_check.sh SCRIPT BUILD_DIR
#
# SCRIPT is the name under scripts/. The scripts read their build dir from $SHADESIM_BUILD_DIR;
# their work folders go under BUILD_DIR/bench-scripts-check/SCRIPT.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SCRIPT BUILD_DIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd)
script=$1
export SHADESIM_BUILD_DIR=$(cd "$2" && pwd)
work=$SHADESIM_BUILD_DIR/bench-scripts-check/$script
rm -rf "$work"
mkdir -p "$work"
log=$work/log.txt

# Each script's tiny run and the line its report ends with (an extended regex); `also`: other
# lines it must print.
also=()
case $script in
  throughput-table)  # cycles per pixel of one scene's own unit per variant (no RTL, no Yosys)
    args=("$here/scenes/sphere.json")
    expect='^\| sphere \| .*\|$' ;;
  bench)  # every Google Benchmark executable, one repetition of a short minimum time
    export BENCH_REPS=1
    args=(--benchmark_min_time=0.01)
    expect='^== specular_bench' ;;
  bench-cosim)  # Verilator C++, SystemC and Icarus on a 32x32 stream, once each
    args=(--size 32 --repeats 1 --icarus-repeats 1 --work "$work/run")
    expect='^ratio cpp/icarus ' ;;
  bench-cosim-ab)  # this tree against HEAD (a git worktree and its build), 32x32, once each side
    args=(--baseline HEAD --size 32 --repeats 1)
    expect='^ratio .* A/B: ' ;;
  bench-cycles)  # the estimate against co-simulation, twice (Google Benchmark medians need 2)
    args=(--scene "$here/scenes/sphere.json" --repeats 2 --work "$work/run")
    expect='^ratio co-simulation / estimate ' ;;
  bench-explore)  # the width-point benchmark and explore on the sphere, twice each (with one
    export RUNS=2  # repetition Google Benchmark prints no median, and the script prints nothing)
    args=()
    also=('^BM_ExplorePoint.*_median ')
    expect='^median .* points; target ' ;;
  bench-scaling)  # the smallest points (64x64, 320x180; 1k and 3k triangles at 320x180) once,
    args=(--quick)  # every command; the model benchmark at a short minimum time
    also=('^res-64x64 +64x64 +[0-9]+ +[0-9]+ +[0-9]+ \| +[0-9.]+ +[0-9]+ \| '
          '^tri-3k +320x180 ' '^model: [0-9.]+ M pixels/s per core ')
    expect='^bench-scaling: 4 scene\(s\), 0 timeout\(s\)$' ;;
  bench-new-config)  # one never-built configuration of the sphere, quick Verilator build
    args=(--scene "$here/scenes/sphere.json" --repeats 1 --opt quick)
    expect='^new configuration on sphere.json, cpp backend: median ' ;;
  *) echo "bench_scripts_check: unknown script '$script'" >&2; exit 2 ;;
esac

start=$(date +%s)
status=0
"$here/scripts/$script" "${args[@]}" >"$log" 2>&1 || status=$?
echo "scripts/$script ${args[*]}: exit $status in $(($(date +%s) - start)) s (log: $log)"
tail -n 15 "$log"
[ "$status" -eq 0 ] || { echo "FAIL: scripts/$script exited $status"; exit 1; }
for re in "${also[@]}"; do  # further lines the report must have
  grep -Eq "$re" "$log" || { echo "FAIL: scripts/$script printed no line matching /$re/"; exit 1; }
done
grep -Eq "$expect" "$log" ||
  { echo "FAIL: scripts/$script printed no line matching /$expect/"; exit 1; }
if [ "$script" = bench ]; then  # every benchmark executable ran
  for b in "$SHADESIM_BUILD_DIR"/bench/*_bench; do
    grep -q "^== $(basename "$b")\$" "$log" ||
      { echo "FAIL: $(basename "$b") did not run"; exit 1; }
  done
fi
echo "ok: scripts/$script"
