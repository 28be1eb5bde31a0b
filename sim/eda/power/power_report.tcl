# The end of the scene's power run (after power_procs.tcl and the annotations): the power, and
# how many annotated pins and ports OpenSTA did not find (sim/eda/power/power.cpp requires 0).
# No fields.
# The power cache key hashes this file's commands (power_scripts_commands in
# sim/eda/power/power.h, used by sim/engines/unit_power.cpp).
report_power -digits 6
puts "shadesim: missing $shadesim_missing"
