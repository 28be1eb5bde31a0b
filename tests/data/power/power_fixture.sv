/* verilator lint_off DECLFILENAME */
// The fixture of tests/power_test.cpp: registers whose toggles can be counted by hand.
//   count_q          a 4-bit binary counter: bit i toggles once every 2^i cycles
//   shift_q          a 4-stage shift register: stage k repeats d_i k + 1 cycles later
//   g_div[i]         two instances of one module in a generate loop: a flip-flop that toggles
//                    when count_q[i:0] is all ones (every 2nd and every 4th cycle)
//   g_blk.blk_q      a register declared in a generate block: two more stages after shift_q
// power_fixture_osu018.v is this module mapped onto osu018 (the command is in its header).
module power_fixture_toggle (
    input  logic clk_i,
    input  logic rst_ni,
    input  logic en_i,
    output logic q_o
);
  logic q_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) q_q <= 1'b0;
    else if (en_i) q_q <= !q_q;
  end
  assign q_o = q_q;
endmodule

module power_fixture (
    input  logic       clk_i,
    input  logic       rst_ni,
    input  logic       d_i,
    output logic [3:0] count_o,
    output logic       shift_o,
    output logic [1:0] slow_o,
    output logic       blk_o
);
  logic [3:0] count_q;
  logic [3:0] shift_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) count_q <= '0;
    else count_q <= count_q + 4'd1;
  end

  always_ff @(posedge clk_i) shift_q <= {shift_q[2:0], d_i};

  for (genvar i = 0; i < 2; i++) begin : g_div
    power_fixture_toggle u_toggle (
        .clk_i,
        .rst_ni,
        .en_i(&count_q[i:0]),
        .q_o (slow_o[i])
    );
  end

  if (1) begin : g_blk
    logic [1:0] blk_q;
    always_ff @(posedge clk_i) blk_q <= {blk_q[0], shift_q[3]};
    assign blk_o = blk_q[1];
  end

  assign count_o = count_q;
  assign shift_o = shift_q[3];
endmodule
