# The conditions every OpenSTA run of a unit is timed under. sim/eda/sta/sta_constraints.h
# holds the values and fills in the @NAME@ fields; docs/area.md argues them. To run it by hand,
# replace the fields and source it after read_liberty, read_verilog and link_design.
#
# The clock: ideal edges (no clock tree pre-route) but an uncertainty that stands for the skew
# and jitter a tree and a PLL would add; "meets" must then also clear the guard band, which is
# the caller's comparison, not a constraint here.
create_clock -name clk -period @PERIOD@ [get_ports @CLOCK@]
set_clock_uncertainty -setup @UNCERTAINTY@ [get_clocks clk]
# Inputs: launched by a register of the surrounding block (its clock-to-Q) through a small
# buffer of the library, so their slew and the buffer's delay into our load are timed.
set data_inputs [delete_from_list [all_inputs] [get_ports @CLOCK@]]
set_input_delay @INPUT_DELAY@ -clock clk $data_inputs
set_driving_cell -lib_cell @DRIVING_CELL@ -pin @DRIVING_PIN@ $data_inputs
# Outputs: captured by registers of the surrounding block (their setup), each output loaded
# with the input pins of several of the library's flip-flops.
set_output_delay @OUTPUT_DELAY@ -clock clk [all_outputs]
set_load -pin_load @OUTPUT_LOAD@ [all_outputs]
