# The scene's power run, after power_setup.tcl: procedures that set a pin's or an input port's
# activity and count what they could not find (a pin or port the netlist reader saw must exist
# in OpenSTA's view of the same netlist). sim/eda/power/power.cpp follows them with one
# `shadesim_pin NAME ACTIVITY DUTY` or `shadesim_port ...` line per annotated pin and port, then
# power_report.tcl. No fields.
# The power cache key hashes this file's commands (power_scripts_commands in
# sim/eda/power/power.h, used by sim/engines/unit_power.cpp).
set shadesim_missing 0
proc shadesim_pin {name activity duty} {
  set p [get_pins -quiet $name]
  if {[llength $p] == 1} { sta::set_power_pin_activity $p $activity $duty } else {
    incr ::shadesim_missing; puts "shadesim: no pin $name" }
}
proc shadesim_port {name activity duty} {
  set p [get_ports -quiet $name]
  if {[llength $p] == 1} { sta::set_power_input_port_activity $p $activity $duty } else {
    incr ::shadesim_missing; puts "shadesim: no port $name" }
}
