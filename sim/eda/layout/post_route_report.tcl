# shadesim layout's post-route timing: the worst path with input pins too, so each wire's delay
# (driver pin to load pin) shows, and the worst slack. sim/eda/layout/qflow_layout.cpp runs it
# after sim/eda/sta/sta_read.tcl, sim/eda/sta/constraints.tcl and `read_spef` of the routed
# SPEF, all filled in; their headers say how to run them by hand.
report_checks -path_delay max -fields {capacitance slew net input_pins} -digits 3
report_worst_slack -digits 3
