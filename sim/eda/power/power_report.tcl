# The end of the scene's power run (after power_procs.tcl and the annotations): the power, and
# how many annotated pins and ports OpenSTA did not find (sim/eda/power/power.cpp requires 0).
# No fields.
# The power cache key does not hash this file: bump kPowerRecipe (sim/engines/unit_power.cpp)
# when a command changes.
report_power -digits 6
puts "shadesim: missing $shadesim_missing"
