# shadesim layout: qflow's settings for the unit (qflow reads this file from the project folder;
# filled in by sim/eda/layout/qflow_layout.cpp).
#
# synthesis: no new synthesis - import.ys reads shadesim area's mapped, buffered netlist.
# nofanout: that netlist is already fanout-buffered (at most 8 cell inputs a net, the clock
#   excepted: the analysis clock is ideal, as in shadesim area).
# initial_density: the cells' share of the core rows (the rest is FILL), which sets the die.
set yosys_options="-s @WORK@/synthesis/import.ys"
set nofanout
set initial_density=@DENSITY@
