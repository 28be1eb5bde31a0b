// setup_ctrl: the three span setup stages' valid bits and span descriptors (rtl/span_setup.sv
// holds each series' arithmetic; these say which span is in which stage and when it moves).
//
// A span enters stage 1 whenever stage 1 is free (s1_load_i), moves on when the next stage is
// free, and leaves stage 3 when the engines take it (eng_load_i): setup overlaps the previous
// span's pixels, and back-to-back spans have no bubble.
module setup_ctrl #(
  parameter int XY_BITS = 12
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 s1_load_i,   // a span enters stage 1 ...
  input  logic [3*XY_BITS+1:0] s1_span_i,   // ... this one: {y, x0, len[XY_BITS:0], last}
  input  logic                 eng_load_i,  // the engines take stage 3's span
  output logic                 s1_free_o,   // stage 1 can take a span this cycle
  output logic                 s1_move_o,   // stage 1's span moves to stage 2
  output logic                 s2_move_o,   // stage 2's span moves to stage 3
  output logic                 s3_valid_o,  // stage 3 holds a span ...
  output logic [3*XY_BITS+1:0] s3_span_o,   // ... this one
  output logic                 busy_o       // some stage holds a span
);
  localparam int SpanW = 3 * XY_BITS + 2;

  logic             s1_v_q, s2_v_q, s3_v_q;
  logic [SpanW-1:0] s1_q, s2_q, s3_q;
  logic             s1_move, s2_move, s3_free;

  assign s3_free = !s3_v_q || eng_load_i;
  assign s2_move = s2_v_q && s3_free;
  assign s1_move = s1_v_q && (!s2_v_q || s2_move);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_v_q <= 1'b0;
      s2_v_q <= 1'b0;
      s3_v_q <= 1'b0;
    end else begin
      if (s1_load_i)       s1_v_q <= 1'b1;
      else if (s1_move)    s1_v_q <= 1'b0;
      if (s1_move)         s2_v_q <= 1'b1;
      else if (s2_move)    s2_v_q <= 1'b0;
      if (s2_move)         s3_v_q <= 1'b1;
      else if (eng_load_i) s3_v_q <= 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (s1_load_i) s1_q <= s1_span_i;
    if (s1_move)   s2_q <= s1_q;
    if (s2_move)   s3_q <= s2_q;
  end

  assign s1_free_o  = !s1_v_q || s1_move;
  assign s1_move_o  = s1_move;
  assign s2_move_o  = s2_move;
  assign s3_valid_o = s3_v_q;
  assign s3_span_o  = s3_q;
  assign busy_o     = s1_v_q || s2_v_q || s3_v_q;

`ifndef SYNTHESIS
`ifdef VERILATOR
  // A stage is loaded only when free, and the engines take only a span that is there.
  a_s1_load_free: assert property (@(posedge clk_i) disable iff (!rst_ni)
    s1_load_i |-> s1_free_o);
  a_eng_load_valid: assert property (@(posedge clk_i) disable iff (!rst_ni)
    eng_load_i |-> s3_v_q);
`endif
`endif
endmodule
