# A power run with one activity for every net (the usual guess, and 0 for the clock pins and
# leakage alone), after power_setup.tcl. Fields: @ACTIVITY@ toggles per cycle, @DUTY@ the
# fraction of time at 1.
# The power cache key hashes this file's commands (power_scripts_commands in
# sim/eda/power/power.h, used by sim/engines/unit_power.cpp).
set_power_activity -global -activity @ACTIVITY@ -duty @DUTY@
report_power -digits 6
