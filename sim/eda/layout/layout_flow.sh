#!/bin/bash
# shadesim layout's steps on a prepared qflow project folder (sim/eda/layout/qflow_layout.cpp
# prepares it: source/, synthesis/import.ys, project_vars.sh, magic_drc.tcl). By hand:
#   sim/eda/layout/layout_flow.sh WORK synthesize place route backanno migrate lvs drc
# Each step's log is in WORK/log/ (qflow's) or WORK/log/drc_magic.log.
set -euo pipefail
work=$1
shift
cd "$work"
techdir=${QFLOW_TECHDIR:-/usr/share/qflow/tech/osu018}
for step in "$@"; do
  case $step in
    synthesize | place | route | backanno | migrate | lvs)
      # qflow writes its verdicts in log/; the driver reads them (and checks the files each step
      # must leave), so a failing LVS is reported, not an aborted run.
      qflow -T osu018 "$step" shade_unit
      ;;
    drc)
      (cd layout && magic -dnull -noconsole -rcfile "$techdir/osu018.magicrc" ../magic_drc.tcl) \
        >log/drc_magic.log 2>&1
      ;;
    *)
      echo "layout_flow.sh: unknown step '$step'" >&2
      exit 2
      ;;
  esac
done
