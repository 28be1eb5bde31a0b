// shade_unit's RTL sources in dependency order, leaves first: the one list every tool reads
// (cmake/rtl.cmake, cmake/rtl_units.cmake, cmake/icarus.cmake, sim/eda/verilator/rtl_build.cpp, sim/eda/yosys/area.cpp).
// One file name per line, relative to this folder; lines starting with // are comments.
shade_pkg.sv
fixed_round.sv
fixed_sat.sv
pipe_reg.sv
split_multiply.sv
span_setup.sv
series_engine.sv
lane_fanout.sv
pixel_combine.sv
exponent_lut.sv
schlick_divider.sv
wpow_split_square.sv
wpow_unit.sv
specular_unit.sv
onehot_mux.sv
cmd_payload.sv
cmd_decoder.sv
coef_bank.sv
start_bank.sv
span_queue.sv
material_bank.sv
setup_ctrl.sv
span_source.sv
engine_ctrl.sv
slot_meta.sv
out_reg.sv
combine_lanes.sv
series_path.sv
spec_slots.sv
shade_unit.sv
