# The start of every OpenSTA run on a unit's netlist (shadesim area's timing and flip-flop
# overhead, shadesim layout's post-route timing): the library, the netlist, its top linked.
# Fields: @LIBERTY@ the liberty file, @NETLIST@ the Verilog netlist. By hand: replace both (sed),
# append the rest of the run (e.g. constraints.tcl and liberty_report.tcl, filled in) and run
# `sta -no_splash -exit FILE`.
read_liberty {@LIBERTY@}
read_verilog {@NETLIST@}
link_design shade_unit
