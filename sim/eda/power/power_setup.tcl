# The start of every OpenSTA power run (sim/eda/power/power.cpp): the library, the netlist, its
# top linked, and the clock with zero input and output delays (report_power needs a clock; the
# delays are not timed here). Fields: @LIBERTY@ the liberty file, @NETLIST@ the Verilog
# netlist, @TOP@ its top module, @PERIOD@ the clock period in ns, @CLOCK@ the clock port (in
# braces, brackets escaped). By hand: fill in (sed) this, then power_global.tcl (or
# power_procs.tcl, the annotations and power_report.tcl), and run `sta -no_splash -exit FILE`.
# The power cache key hashes this file's commands (power_scripts_commands in
# sim/eda/power/power.h, used by sim/engines/unit_power.cpp).
read_liberty {@LIBERTY@}
read_verilog {@NETLIST@}
link_design @TOP@
create_clock -name clk -period @PERIOD@ [get_ports @CLOCK@]
set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports @CLOCK@]]
set_output_delay 0 -clock clk [all_outputs]
