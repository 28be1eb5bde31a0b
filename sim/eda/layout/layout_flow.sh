#!/bin/bash
# shadesim layout's steps on a prepared qflow project folder (sim/eda/layout/qflow_layout.cpp
# prepares it: source/, import.ys in synthesis, project_vars.sh, magic_drc.tcl). By hand:
#   sim/eda/layout/layout_flow.sh WORK synthesize place pins route backanno migrate lvs drc
# Each step's log is in WORK/log/ (qflow's) or drc_magic.log in WORK/log.
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
    pins)
      # qflow's arrangepins writes each I/O pin as a 0.3 x 0.3 um square, under the 0.2 um^2
      # minimum area magic checks on metal2 / metal3 once a via lands on it (sphere: 14 errors).
      # Each pin becomes 0.4 um across its edge's track pitch and 0.6 um along its routes.
      def=layout/shade_unit_unroute.def
      [ -f "$def" ] || def=layout/shade_unit.def
      perl -pi -e 's/LAYER metal2 \( -15 -15 \) \( 15 15 \)/LAYER metal2 ( -20 -30 ) ( 20 30 )/;
        s/LAYER metal3 \( -15 -15 \) \( 15 15 \)/LAYER metal3 ( -30 -20 ) ( 30 20 )/' "$def"
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
