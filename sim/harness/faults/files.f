// The deliberate-fault hooks (test apparatus, sim/harness/faults/fault_hooks.sv says how they
// work), compiled after rtl/files.f by a simulation build with fault hooks, in this order.
// fault_bind.sv, which binds them into shade_unit, is not listed: Verilator builds add it, and
// Icarus 11 (no bind) instantiates fault_hooks in its testbench instead.
fault_pkg.sv
fault_select.sv
fault_hooks.sv
