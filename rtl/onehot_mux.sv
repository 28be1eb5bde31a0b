// onehot_mux: the input a one-hot select names, as an AND-OR (no priority, no encoder): the
// command decoder's picks of the header word's results (cmd_decoder, cmd_payload) and the start
// bank's of its value words (start_bank). A select of 0 gives 0; more than one hot bit, the OR.
module onehot_mux #(
  parameter int N = 2,  // inputs
  parameter int W = 1   // bits per input
) (
  input  logic [N-1:0]   sel_i,
  input  logic [N*W-1:0] in_i,  // input j at [j*W +: W]
  output logic [W-1:0]   out_o
);
  // A function, not an always_comb loop ORing into its own result: that never settles in
  // Icarus 11.
  function automatic logic [W-1:0] pick(input logic [N-1:0] s, input logic [N*W-1:0] v);
    pick = '0;
    for (int j = 0; j < N; j++) if (s[j]) pick = pick | v[j*W +: W];
  endfunction
  assign out_o = pick(sel_i, in_i);

`ifndef SYNTHESIS
  initial begin
    if (N < 1 || W < 1) $fatal(1, "onehot_mux: N %0d and W %0d must be at least 1", N, W);
  end
`endif
endmodule
