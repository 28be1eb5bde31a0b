// engine_ctrl: the span run control of shade_unit's series engines - which span the engines
// run, its next pixel position and how many pixels are left, and when they step.
//
// The engines take the span waiting in setup stage 3 (span_valid_i) on the cycle the previous
// span's last beat leaves them (or when idle), step once per beat of LANES pixels when the pix
// register can take one (adv_i) and no iterative specular unit is busy (spec_busy_i), and hand
// each beat's position, lane mask and end flags to the slot metadata line.
module engine_ctrl #(
  parameter int XY_BITS = 12,
  parameter int LANES   = 1  // 1, 2 or 4 pixels per beat
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  span_valid_i,  // a span waits in setup stage 3 ...
  input  logic [3*XY_BITS+1:0]  span_i,        // ... {y, x0, len[XY_BITS:0], last}
  input  logic                  adv_i,         // the pix register can take a beat
  input  logic                  spec_busy_i,   // an iterative specular unit cannot start
  output logic                  load_o,        // ... and take it
  output logic                  emit_o,        // the engines hand a beat on and step
  output logic                  run_o,         // the engines hold a span
  output logic [XY_BITS-1:0]    x_o,           // the beat's lane 0 pixel
  output logic [XY_BITS-1:0]    y_o,
  output logic [LANES-1:0]      mask_o,        // valid lanes
  output logic                  span_end_o,    // the span's last beat
  output logic                  eor_o          // ... of a span flagged last_in_row
);
  typedef struct packed {
    logic [XY_BITS-1:0] y;
    logic [XY_BITS-1:0] x0;
    logic [XY_BITS:0]   len;  // 1..2^XY_BITS
    logic               last;
  } span_t;

  span_t              span;
  logic               run_q, run_d;
  logic [XY_BITS:0]   rem_q;
  logic [XY_BITS-1:0] x_q, y_q;
  logic               last_q, last_pix, last_pix_q, last_pix_d, emit;

  // 1 <= rem <= LANES on the last beat (LANES = 1: rem == 1).
  function automatic logic last_beat(input logic [XY_BITS:0] rem);
    last_beat = rem - 1'b1 < (XY_BITS + 1)'(LANES);
  endfunction

  assign span         = span_i;
  assign emit         = run_q && adv_i && !spec_busy_i;
  // last_beat(rem_q), held in a register beside rem_q: the compare is off the path from adv_i
  // through the engines' load and step enables, which fan out to every engine register.
  assign last_pix     = last_pix_q;
  logic take_ready;  // the engines can take a span this cycle
  assign take_ready = !run_q || (emit && last_pix);
  assign load_o     = span_valid_i && take_ready;

  always_comb begin
    run_d = run_q;
    if (load_o)                run_d = 1'b1;
    else if (emit && last_pix) run_d = 1'b0;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) run_q <= 1'b0;
    else         run_q <= run_d;
  end

  always_comb begin
    last_pix_d = last_pix_q;
    if (load_o)    last_pix_d = last_beat(span.len);
    else if (emit) last_pix_d = last_beat(rem_q - (XY_BITS + 1)'(LANES));
  end

  always_ff @(posedge clk_i) begin
    last_pix_q <= last_pix_d;
    if (load_o) begin
      rem_q  <= span.len;
      x_q    <= span.x0;
      y_q    <= span.y;
      last_q <= span.last;
    end else if (emit) begin
      rem_q <= rem_q - (XY_BITS + 1)'(LANES);
      x_q   <= x_q + XY_BITS'(LANES);
    end
  end

  for (genvar j = 0; j < LANES; j++) begin : g_mask
    assign mask_o[j] = (XY_BITS + 1)'(j) < rem_q;
  end
  assign emit_o     = emit;
  assign run_o      = run_q;
  assign x_o        = x_q;
  assign y_o        = y_q;
  assign span_end_o = last_pix;
  assign eor_o      = last_q && last_pix;

`ifndef SYNTHESIS
  initial begin
    if (XY_BITS < 4 || XY_BITS > 15)
      $fatal(1, "engine_ctrl: XY_BITS %0d is not 4..15", XY_BITS);
    if (LANES != 1 && LANES != 2 && LANES != 4)
      $fatal(1, "engine_ctrl: LANES %0d is not 1, 2 or 4", LANES);
  end
`ifdef VERILATOR
  // A running span has pixels left: the engines never step past its end.
  a_rem_nonzero: assert property (@(posedge clk_i) disable iff (!rst_ni) run_q |-> rem_q != '0);
  // The registered last-beat flag is the compare it replaces.
  a_last_pix: assert property (@(posedge clk_i) disable iff (!rst_ni)
                               run_q |-> last_pix_q == last_beat(rem_q));
`endif
`endif
endmodule
