# shadesim area's liberty timing: the worst path, with each stage's load, slew and net, and the
# worst slack to check it against (sim/eda/sta/liberty_flow.cpp reads both). OpenSTA runs it
# after sta_read.tcl and constraints.tcl, filled in; their headers say how to run them by hand.
report_checks -path_delay max -fields {capacitance slew net} -digits 3
report_worst_slack -digits 3
