// pipe_reg: an optional pipeline register - W bits taken on en_i (the pipeline's advance) when
// PRESENT, a wire when not. The datapath modules' stage registers (pixel_combine), so a stage
// that UnitConfig leaves out costs nothing.
module pipe_reg #(
  parameter int W       = 1,
  parameter bit PRESENT = 1'b1
) (
  input  logic         clk_i,
  input  logic         en_i,
  input  logic [W-1:0] d_i,
  output logic [W-1:0] q_o
);
  if (PRESENT) begin : g_reg
    logic [W-1:0] q_q;
    always_ff @(posedge clk_i) begin
      if (en_i) q_q <= d_i;
    end
    assign q_o = q_q;
  end else begin : g_wire
    // verilator lint_off UNUSEDSIGNAL
    logic unused_clock;  // reason: a wire has no register
    assign unused_clock = clk_i ^ en_i;
    // verilator lint_on UNUSEDSIGNAL
    assign q_o = d_i;
  end
endmodule
