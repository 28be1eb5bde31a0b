// Named user cover points for the edge bins, bound into the RTL in covered builds only:
// sim/eda/verilator/rtl_build.cpp adds this file and --coverage-user to a build that `shadesim regress
// --coverage` asks for. It is verification, not design: no rtl/ file names it, Icarus and Yosys
// never read it. `regress --coverage` reports each point as hit or not (verilator_coverage's
// "user" points).

// One file for the cover modules of every bound RTL module: they are one set of bins.
/* verilator lint_off DECLFILENAME */

// The unit's ports and its command decoder.
module shade_unit_cover #(
  parameter int XY_BITS  = 12,
  parameter int LANES    = 1,
  parameter int CHANNELS = 1,
  parameter int OUT_BITS = 8
) (
  input logic               clk_i,
  input logic               rst_ni,
  input logic               pix_valid_i,
  input logic               pix_ready_i,
  input logic [XY_BITS-1:0] pix_x_i,
  input logic [CHANNELS*OUT_BITS-1:0] pix_colour_i,  // lane 0
  input logic               hdr_fire_i,
  input logic [7:0]         hdr_op_i
);
  // A command header after an END_FRAME (not the NOP padding of its beat): decoding goes on
  // into the next frame.
  logic frame_ended_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) frame_ended_q <= 1'b0;
    else if (hdr_fire_i && hdr_op_i == shade_pkg::OpEndFrame) frame_ended_q <= 1'b1;
  end

  // A beat whose last lane reaches the last coordinate, 2^XY_BITS - 1 (the MSB of x set).
  cov_pix_x_at_edge: cover property (@(posedge clk_i)
    pix_valid_i && pix_ready_i && 32'(pix_x_i) + LANES >= (32'd1 << XY_BITS));
  cov_pix_x_msb: cover property (@(posedge clk_i) pix_valid_i && pix_ready_i && pix_x_i[XY_BITS-1]);
  cov_end_frame: cover property (@(posedge clk_i) hdr_fire_i && hdr_op_i == shade_pkg::OpEndFrame);
  cov_command_after_end_frame: cover property (@(posedge clk_i)
    frame_ended_q && hdr_fire_i && hdr_op_i != shade_pkg::OpEndFrame &&
    hdr_op_i != shade_pkg::OpNop);
  // Lane 0's output code of a channel at either end of its range: 0 (a total at or below 0,
  // clamped) and all ones (a total at or above 1, saturated).
  logic any_zero, any_full;
  always_comb begin
    any_zero = 1'b0;
    any_full = 1'b0;
    for (int c = 0; c < CHANNELS; c++) begin
      any_zero = any_zero | (pix_colour_i[c*OUT_BITS +: OUT_BITS] == '0);
      any_full = any_full | (pix_colour_i[c*OUT_BITS +: OUT_BITS] == '1);
    end
  end
  cov_colour_clamped_at_0: cover property (@(posedge clk_i) pix_valid_i && pix_ready_i && any_zero);
  cov_colour_saturated: cover property (@(posedge clk_i) pix_valid_i && pix_ready_i && any_full);
  cov_back_pressure: cover property (@(posedge clk_i) pix_valid_i && !pix_ready_i);
endmodule

// One series: a saturating adder that left the format (saturate builds only).
module series_engine_cover #(
  parameter int SERIES_WL       = 32,
  parameter int SERIES_OVERFLOW = 1
) (
  input logic                  clk_i,
  input logic                  step_i,
  input logic                  load_i,
  input logic [SERIES_WL:0]    v_sum_i,
  input logic [SERIES_WL:0]    d_sum_i
);
  if (SERIES_OVERFLOW == 0) begin : g_saturate
    cov_series_v_saturates: cover property (@(posedge clk_i)
      step_i && !load_i && v_sum_i[SERIES_WL] != v_sum_i[SERIES_WL-1]);
    cov_series_d_saturates: cover property (@(posedge clk_i)
      step_i && !load_i && d_sum_i[SERIES_WL] != d_sum_i[SERIES_WL-1]);
  end
endmodule

bind shade_unit shade_unit_cover
  #(.XY_BITS(XY_BITS), .LANES(LANES), .CHANNELS(CHANNELS), .OUT_BITS(OUT_BITS)) u_cover (
  .clk_i, .rst_ni, .pix_valid_i(pix_valid_o), .pix_ready_i, .pix_x_i(pix_x_o),
  .pix_colour_i(pix_colour_o[CHANNELS*OUT_BITS-1:0]),
  .hdr_fire_i(hdr_fire), .hdr_op_i(hdr_op));
bind series_engine series_engine_cover #(.SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW))
  u_cover (.clk_i, .step_i, .load_i, .v_sum_i(v_sum), .d_sum_i(d_sum));
