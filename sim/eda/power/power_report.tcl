# The end of the scene's power run (after power_procs.tcl and the annotations): the power, and
# how many annotated pins and ports OpenSTA did not find (sim/eda/power/power.cpp requires 0).
# No fields.
report_power -digits 6
puts "shadesim: missing $shadesim_missing"
