// span_source: where the engines' next span and its start values come from - shade_unit's span
// intake. Unit span setup (SetupUnit): SPAN headers into a span queue, TRIANGLE coefficients
// into coefficient banks, and three setup stages (setup_ctrl) that the series path computes the
// start values in. Host span setup (SetupHost): each SPAN carries its start values into a start
// bank. Either way the engines see a span at stage 3 (s3_valid_o, s3_span_o).
module span_source #(
  parameter bit HOST_SETUP  = 1'b0,  // SetupHost: a start bank; else queue, banks and setup
  parameter int PORT_WORDS  = 1,
  parameter int XY_BITS     = 12,
  parameter int TRI_QUEUE   = 1,     // coefficient banks (unit setup)
  parameter int N_COEF      = 6,     // coefficient words per triangle (unit setup)
  parameter int COEF_WL     = 36,
  parameter int COEF_T0_WL  = COEF_WL,
  parameter int COEF_T1_WL  = COEF_WL,
  parameter int COEF_T2_WL  = COEF_WL,
  parameter int COEF_T3_WL  = COEF_WL,
  parameter int COEF_T4_WL  = COEF_WL,
  parameter int COEF_T5_WL  = COEF_WL,
  parameter int OFS_BITS    = 17,
  parameter int N_SER       = 1,     // series (host setup: start values per span)
  parameter int SERIES_WL   = 32,
  parameter int START_DEPTH = 1      // start bank entries (host setup)
) (
  /* verilator coverage_off */  // reason: wiring; these nets are counted in shade_unit and children
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,
  input  logic                                  cmd_valid_i,
  // The decoder's item of this cycle (cmd_decoder's outputs of the same names).
  // verilator lint_off UNUSEDSIGNAL
  input  logic [shade_pkg::WordW-1:0]           word_i,  // reason: unit setup reads xo, yo only
  // verilator lint_on UNUSEDSIGNAL
  input  logic [(PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1)-1:0] word_sel_i,
  input  logic [$clog2(PORT_WORDS+1)-1:0]       hdr_pos_i, hdr_n_i, tail_n_i,
  input  logic [15:0]                           pay_idx_i,
  input  logic                                  span_fire_i, tri_fire_i, span_pay_i,
  input  logic                                  mat_wr_i,   // the material bank being written
  input  logic                                  eng_load_i, // the engines take the s3 span
  // What the decoder waits on.
  output logic                                  sq_full_o, sq_empty_o, tri_bank_free_o,
  output logic [15:0]                           sq_room_o,
  output logic                                  s1_free_o, start_free_o,
  // Setup stages (unit setup) and the series path's inputs.
  output logic                                  s1_load_o, s1_move_o, s2_move_o,
  output logic [3*XY_BITS+1:0]                  s1_span_o,  // {y, x0, len, last}
  output logic                                  s1_mat_o,   // its material bank
  output logic [N_COEF*COEF_WL-1:0]             coef_o,     // its triangle's coefficients
  output logic signed [OFS_BITS-1:0]            xo_o, yo_o, // ... and their origin
  output logic [N_SER*SERIES_WL-1:0]            bank_v_o, bank_d_o, bank_d2_o,  // host setup
  output logic                                  s3_valid_o,
  output logic [3*XY_BITS+1:0]                  s3_span_o,
  output logic                                  busy_o      // a span in setup or the bank
  /* verilator coverage_on */
);
  if (!HOST_SETUP) begin : g_unit_setup
    localparam int BankW = TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1;
    logic [BankW-1:0] wr_bank, next_bank, rd_bank;
    span_queue #(.PORT_WORDS(PORT_WORDS), .XY_BITS(XY_BITS), .TRI_QUEUE(TRI_QUEUE)) u_span_queue (
      .clk_i, .rst_ni, .cmd_data_i, .span_fire_i, .span_n_i(hdr_n_i), .hdr_pos_i, .word_sel_i,
      .tri_fire_i, .mat_wr_i, .s1_free_i(s1_free_o), .full_o(sq_full_o), .room_o(sq_room_o),
      .empty_o(sq_empty_o), .s1_load_o, .s1_span_o, .rd_bank_o(rd_bank), .s1_mat_o,
      .wr_bank_o(wr_bank), .next_bank_o(next_bank), .tri_bank_free_o
    );
    coef_bank #(
      .PORT_WORDS(PORT_WORDS), .TRI_QUEUE(TRI_QUEUE), .N_COEF(N_COEF), .COEF_WL(COEF_WL),
      .COEF_T0_WL(COEF_T0_WL), .COEF_T1_WL(COEF_T1_WL), .COEF_T2_WL(COEF_T2_WL),
      .COEF_T3_WL(COEF_T3_WL), .COEF_T4_WL(COEF_T4_WL), .COEF_T5_WL(COEF_T5_WL),
      .OFS_BITS(OFS_BITS)
    ) u_coef_bank (
      .clk_i, .cmd_data_i, .cmd_valid_i, .tri_fire_i,
      .hdr_xo_i(word_i[shade_pkg::HighLsb +: 16]), .hdr_yo_i(word_i[shade_pkg::MidLsb +: 16]),
      .tail_n_i, .pay_idx_i, .hdr_pos_i, .hdr_n_i, .wr_bank_i(wr_bank), .next_bank_i(next_bank),
      .rd_bank_i(rd_bank), .coef_o, .xo_o, .yo_o
    );
    setup_ctrl #(.XY_BITS(XY_BITS)) u_setup_ctrl (
      .clk_i, .rst_ni, .s1_load_i(s1_load_o), .s1_span_i(s1_span_o), .eng_load_i,
      .s1_free_o, .s1_move_o, .s2_move_o, .s3_valid_o, .s3_span_o, .busy_o
    );
    assign {start_free_o, bank_v_o, bank_d_o, bank_d2_o} = '0;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_host;  // reason: the start bank's payload state, for host setup only
    assign unused_host = span_pay_i;
    // verilator lint_on UNUSEDSIGNAL
  end else begin : g_host_setup
    logic start_empty;
    start_bank #(
      .PORT_WORDS(PORT_WORDS), .N_SER(N_SER), .SERIES_WL(SERIES_WL), .XY_BITS(XY_BITS),
      .DEPTH(START_DEPTH)
    ) u_start_bank (
      .clk_i, .rst_ni, .cmd_valid_i, .cmd_data_i, .hdr_i(word_i), .span_fire_i, .mat_i(mat_wr_i),
      .tail_n_i, .pay_idx_i, .hdr_pos_i, .hdr_n_i, .filling_i(span_pay_i),
      .load_i(eng_load_i), .free_o(start_free_o), .valid_o(s3_valid_o), .empty_o(start_empty),
      .span_o(s3_span_o), .mat_o(s1_mat_o), .v_o(bank_v_o), .d_o(bank_d_o), .d2_o(bank_d2_o)
    );
    // No span queue, coefficient banks or setup stages: their handshakes are idle.
    assign {sq_full_o, sq_room_o, sq_empty_o, tri_bank_free_o, s1_free_o} =
           {1'b0, 16'd0, 1'b1, 1'b1, 1'b0};
    assign {s1_load_o, s1_move_o, s2_move_o, s1_span_o, coef_o, xo_o, yo_o} = '0;
    assign busy_o = !start_empty;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_unit;  // reason: TRIANGLE headers and their words have nowhere to go
    assign unused_unit = tri_fire_i ^ (^word_sel_i);
    // verilator lint_on UNUSEDSIGNAL
  end

`ifndef SYNTHESIS
  initial begin
    if (HOST_SETUP && TRI_QUEUE != 1)
      $fatal(1, "span_source: TRI_QUEUE %0d with host span setup (no coefficient banks)",
             TRI_QUEUE);
  end
`endif
endmodule
