// fault_pkg: the harness's deliberate faults, by site (sim/harness/fault_site.h is the C++ twin;
// tests/fault_site_test.cpp reads both). Test apparatus: a build with fault hooks binds
// fault_hooks into shade_unit (fault_bind.sv), which injects the one chosen at run time
// (fault_select) on one row; every other build, and synthesis, has none.
package fault_pkg;
  // verilator lint_off UNUSEDPARAM
  // reason: a site list; each hook reads the ones it injects
  localparam int          FaultSiteW     = 4;
  localparam logic [3:0]  FaultNone      = 4'd0;
  localparam logic [3:0]  FaultLsb       = 4'd1;   // channel 0 of every pixel of the row + 1 LSB
  localparam logic [3:0]  FaultStall     = 4'd2;   // one extra engine stall before the row's
                                                   // last_in_row span (first occurrence)
  localparam logic [3:0]  FaultHang      = 4'd3;   // the engines never take a span of the row
  localparam logic [3:0]  FaultChannel2  = 4'd4;   // channel 2 of every pixel of the row + 1 LSB
  localparam logic [3:0]  FaultX         = 4'd5;   // pix_x_o + 1 on the row
  localparam logic [3:0]  FaultY         = 4'd6;   // pix_y_o bit 0 flipped on the row
  localparam logic [3:0]  FaultEor       = 4'd7;   // pix_eor_o inverted on the row
  localparam logic [3:0]  FaultSpanSetup = 4'd8;   // series 0's start value + 1 output LSB
  localparam logic [3:0]  FaultRounding  = 4'd9;   // the output truncated, not rounded
  localparam logic [3:0]  FaultSpecular  = 4'd10;  // light 0's specular result: top fraction
                                                   // bit flipped
  // verilator lint_on UNUSEDPARAM
endpackage
