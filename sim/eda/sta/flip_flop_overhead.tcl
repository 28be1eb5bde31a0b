# The clock-to-Q and setup of the library's plain flip-flop, timed by OpenSTA under an ideal
# clock: sim/eda/sta/liberty_flow.cpp writes a netlist of one flip-flop `a` whose Q drives the D
# pins of flip-flops b0, b1, ... (the most load a net keeps after buffering) and runs
# sta_read.tcl on it, then this. Fields: @PERIOD@ the clock period in ns, @D_PIN@ the
# flip-flop's data pin. By hand: keep the overhead.v and overhead.tcl of a failed run's work
# folder, or fill in sta_read.tcl and this (sed) and run `sta -no_splash -exit FILE`.
# The liberty cache key hashes this file's commands (sim/eda/sta/liberty_flow.cpp).
create_clock -name clk -period @PERIOD@ [get_ports clk_i]
report_checks -to b0/@D_PIN@ -path_delay max -fields {capacitance slew net} -digits 3
