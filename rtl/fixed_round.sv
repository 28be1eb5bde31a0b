// fixed_round: the quantization half of FixedFormat::quantize (model/fixed_point.cpp).
// Drops DROP low bits of a signed value: truncation is floor toward -inf (arithmetic shift),
// round-to-nearest adds half an LSB first (ties toward +inf), exactly as the model does.
// A negative DROP shifts left (the target has more fraction bits); nothing is lost then.
// The result is one bit wider than needed so the rounding increment can never overflow;
// fixed_sat applies the overflow rule afterwards.
module fixed_round #(
  parameter int IN_W  = 32,
  parameter int DROP  = 0,
  parameter int ROUND = 0,  // Quantization: 0 = kTruncate, 1 = kRoundNearest
  parameter int OUT_W = IN_W + 1 - DROP
) (
  input  logic signed [IN_W-1:0]  in_i,
  output logic signed [OUT_W-1:0] out_o
);
  if (DROP > 0) begin : g_drop
    logic signed [IN_W:0] ext;
    logic signed [IN_W:0] biased;
    assign ext = {in_i[IN_W-1], in_i};
    if (ROUND != 0) begin : g_rnd
      localparam logic signed [IN_W:0] Half = (IN_W + 1)'(1) <<< (DROP - 1);
      assign biased = ext + Half;
    end else begin : g_trn
      assign biased = ext;
    end
    // The top DROP bits of the shift are sign copies, never part of the (narrower) result.
    // verilator lint_off UNUSED
    logic signed [IN_W:0] shifted;
    // verilator lint_on UNUSED
    assign shifted = biased >>> DROP;
    assign out_o = shifted[OUT_W-1:0];
  end else if (DROP == 0) begin : g_same
    assign out_o = {in_i[IN_W-1], in_i};
  end else begin : g_widen
    assign out_o = {in_i[IN_W-1], in_i, {(-DROP){1'b0}}};
  end
endmodule
