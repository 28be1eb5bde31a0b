// fixed_sat: the overflow half of FixedFormat::quantize (model/fixed_point.cpp).
// Fits a signed IN_W-bit value into OUT_W bits, signed or unsigned: wrap keeps the low OUT_W
// bits (two's complement, like a plain adder); saturate clamps to the representable range
// (an unsigned target clamps negatives to 0).
module fixed_sat #(
  parameter int IN_W       = 33,
  parameter int OUT_W      = 32,
  parameter int OUT_SIGNED = 1,
  parameter int WRAP       = 0   // Overflow: 0 = kSaturate, 1 = kWrap
) (
  input  logic signed [IN_W-1:0] in_i,
  output logic [OUT_W-1:0]       out_o
);
  // Bits above the target's sign (signed) or above its MSB (unsigned) decide overflow.
  localparam int TopLo = OUT_SIGNED != 0 ? OUT_W - 1 : OUT_W;

  if (IN_W <= TopLo) begin : g_fits
    // Every input value is representable (except negatives for an unsigned target).
    logic [OUT_W-1:0] ext;
    assign ext = OUT_W'({{(OUT_W + 1 - IN_W){in_i[IN_W-1]}}, in_i[IN_W-2:0]});
    if (OUT_SIGNED == 0 && WRAP == 0) begin : g_clamp_neg
      assign out_o = in_i[IN_W-1] ? '0 : ext;
    end else begin : g_pass
      assign out_o = ext;
    end
  end else begin : g_narrow
    logic [IN_W-1-TopLo:0] top;
    logic                  overflow;
    logic [OUT_W-1:0]      max_val;
    logic [OUT_W-1:0]      min_val;
    assign top = in_i[IN_W-1:TopLo];
    if (OUT_SIGNED != 0) begin : g_signed
      assign overflow = !((&top) || !(|top));
      assign max_val  = {1'b0, {(OUT_W - 1){1'b1}}};
      assign min_val  = {1'b1, {(OUT_W - 1){1'b0}}};
    end else begin : g_unsigned
      assign overflow = |top;
      assign max_val  = {OUT_W{1'b1}};
      assign min_val  = '0;
    end
    if (WRAP != 0) begin : g_wrap
      // Wrapping keeps the low bits by definition: the overflow test and the clamp values
      // (which read the bits above) are not needed, and their inputs' top bits go unread.
      // verilator lint_off UNUSED
      logic unused_sat;
      assign unused_sat = overflow ^ (^max_val) ^ (^min_val);
      // verilator lint_on UNUSED
      assign out_o = in_i[OUT_W-1:0];
    end else begin : g_sat
      assign out_o = !overflow ? in_i[OUT_W-1:0] : (in_i[IN_W-1] ? min_val : max_val);
    end
  end
endmodule
