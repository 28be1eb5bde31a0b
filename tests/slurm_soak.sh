#!/bin/sh
# Soak for tests/slurm_check.sh: runs it RUNS times in a row, optionally beside LOAD processes
# that burn a CPU each (shell busy loops, stopped by their ids at the end), and prints every
# run's result and wall time, then the pass count and the median time. Exits 0 only when every
# run passed. Not a ctest: it is the evidence that the check is deterministic on a loaded
# machine (docs/regression.md gives the command and the last result).
#
# Usage: slurm_soak.sh SHADESIM SOURCE_DIR CACHE [RUNS [LOAD]]     (defaults: 20 runs, 2 burners)
# A run's output is kept in $TMPDIR/slurm_soak.N.log (/tmp when TMPDIR is unset).
set -eu
shadesim=$1 source_dir=$2 cache=$3 runs=${4:-20} load=${5:-2}
here=$(cd "$(dirname "$0")" && pwd)
logs=${TMPDIR:-/tmp}

burners=""
stop_burners() {
  for p in $burners; do kill "$p" 2>/dev/null || true; done
  burners=""
}
trap stop_burners EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
i=0
while [ "$i" -lt "$load" ]; do
  sh -c 'while :; do :; done' &
  burners="$burners $!"
  i=$((i + 1))
done

passed=0 failed=0 times=""
i=1
while [ "$i" -le "$runs" ]; do
  log=$logs/slurm_soak.$i.log
  start=$(date +%s.%N)
  if sh "$here/slurm_check.sh" "$shadesim" "$source_dir" "$cache" >"$log" 2>&1; then
    result=pass passed=$((passed + 1))
  else
    result="FAIL (exit $?, log $log)" failed=$((failed + 1))
  fi
  secs=$(echo "$start $(date +%s.%N)" | awk '{printf "%.1f", $2 - $1}')
  times="$times $secs"
  echo "run $i/$runs: $result, $secs s"
  i=$((i + 1))
done
stop_burners
median=$(echo "$times" | tr ' ' '\n' | sed '/^$/d' | sort -n |
  awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else printf "%.1f\n", (a[NR / 2] + a[NR / 2 + 1]) / 2}')
echo "slurm_soak: $passed passed, $failed failed of $runs runs beside $load CPU burner(s); median $median s"
[ "$failed" = 0 ]
