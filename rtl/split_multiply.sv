// split_multiply: unsigned p = a x b, combinational, or with STAGE over two cycles: the partial
// products a x b_hi and a x b_lo (b split at B_W / 2) registered on en_i (the pipeline's advance)
// and summed in the next, p = (a b_hi) 2^(B_W/2) + a b_lo, the same product. A clock period then
// holds half a multiplier, or an addition, not a whole multiplier (pixel_combine's colour
// products with COMBINE_STAGES 2).
module split_multiply #(
  parameter int A_W   = 17,
  parameter int B_W   = 13,
  parameter bit STAGE = 1'b0
) (
  input  logic               clk_i,
  input  logic               en_i,
  input  logic [A_W-1:0]     a_i,
  input  logic [B_W-1:0]     b_i,
  output logic [A_W+B_W-1:0] p_o
);
  localparam int LoW = B_W / 2;
  localparam int HiW = B_W - LoW;
  if (STAGE) begin : g_split
    logic [A_W+HiW-1:0] hi_d, hi_q;
    logic [A_W+LoW-1:0] lo_d, lo_q;
    assign hi_d = (A_W + HiW)'(a_i) * (A_W + HiW)'(b_i[B_W-1:LoW]);
    assign lo_d = (A_W + LoW)'(a_i) * (A_W + LoW)'(b_i[LoW-1:0]);
    always_ff @(posedge clk_i) begin
      if (en_i) {hi_q, lo_q} <= {hi_d, lo_d};
    end
    assign p_o = ((A_W + B_W)'(hi_q) << LoW) + (A_W + B_W)'(lo_q);
  end else begin : g_whole
    // One multiplier: synthesis maps a x b better whole than as two halves and a sum.
    // verilator lint_off UNUSEDSIGNAL
    logic unused_clock;  // reason: no register
    assign unused_clock = clk_i ^ en_i;
    // verilator lint_on UNUSEDSIGNAL
    assign p_o = (A_W + B_W)'(a_i) * (A_W + B_W)'(b_i);
  end
`ifndef SYNTHESIS
  initial begin
    if (B_W < 2) $fatal(1, "split_multiply: B_W %0d < 2 (nothing to split)", B_W);
  end
`endif
endmodule
