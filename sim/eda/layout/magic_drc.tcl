# shadesim layout: magic's DRC of the routed layout, and its GDS. Run from the project's layout/
# folder after `qflow migrate` (which writes shade_unit.mag):
#   magic -dnull -noconsole -rcfile @TECHDIR@/osu018.magicrc magic_drc.tcl
# Filled in by sim/eda/layout/qflow_layout.cpp. The cells are their LEF abstracts (Debian's
# qflow-tech-osu018 ships no cell layouts), so the DRC checks the routing, the pins and the
# cells' abstracts, as qflow's own drc step does; the GDS holds the same.
lef read @LEF@
load shade_unit
drc on
select top cell
expand
drc check
drc catchup
puts stdout "drc = [drc list count total]"
foreach {why boxes} [drc listall why] {
  puts stdout "drc why: $why ([llength $boxes])"
}
gds write @GDS@
quit -noprompt
