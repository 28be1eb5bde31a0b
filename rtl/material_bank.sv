// material_bank: shade_unit's per-material registers - ambient, specular colours (and diffuse
// colours with DIFFUSE_MULTIPLY) and the gate-only light mask - in MATERIAL_BUFFERS banks, and
// the bookkeeping that keeps a MATERIAL from changing what an in-flight pixel reads.
//
// MATERIAL_BUFFERS = 2: a MATERIAL header switches the write bank (wr_bank_o); each span carries
// the bank current when its SPAN header was taken down the setup stages to the engines
// (eng_bank_o) and on through the slot metadata to the pix register; per bank, the spans taken
// whose last beat has not left the slot are counted. MATERIAL_BUFFERS = 1: one bank, bank 0.
module material_bank #(
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int SERIES_WL        = 32,
  parameter int SPEC_COLOUR_WL   = 13,
  parameter int MATERIAL_BUFFERS = 1,
  parameter int SPAN_Q           = 1,  // span queue entries (1: none)
  parameter int SPEC_LATENCY     = 0,  // the specular slot's latency
  parameter bit HOST_SETUP       = 1'b0,  // no setup stages: spans wait in the start bank
  parameter bit DIFFUSE_MULTIPLY = 1'b0   // kd_lc words follow spec_colour's in the payload
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  input  logic [shade_pkg::WordW-1:0]           word_i,      // the decoder's header / payload
  input  logic                                  mat_fire_i,  // a MATERIAL header is taken
  input  logic                                  pay_mat_i,   // a MATERIAL payload word ...
  input  logic [15:0]                           pay_idx_i,   // ... its index
  input  logic                                  span_fire_i,  // SPAN headers are taken ...
  input  logic [15:0]                           span_n_i,     // ... this many
  // The bank moving with a span: into setup stage 1, along the stages, into the engines. With
  // host setup the start bank holds each span's bank: s1_bank_i is the bank of the span the
  // engines load (eng_load_i), and the stage enables are unused.
  input  logic                                  s1_load_i,
  input  logic                                  s1_bank_i,
  input  logic                                  s1_move_i,
  input  logic                                  s2_move_i,
  input  logic                                  eng_load_i,
  output logic                                  eng_bank_o,  // the engines' span's bank
  input  logic                                  leave_i,       // a span's last beat leaves
  input  logic                                  leave_bank_i,  // ... of this bank
  output logic                                  wr_bank_o,     // the latest MATERIAL's bank
  output logic                                  other_free_o,  // no span in flight reads the
                                                               // other bank
  output logic                                  cur_free_o,    // ... reads bank wr_bank_o
  input  logic                                  rd_bank_i,     // the bank read below
  output logic [CHANNELS*SERIES_WL-1:0]         ambient_o,
  output logic [LIGHTS*CHANNELS*SPEC_COLOUR_WL-1:0] spec_colour_o,
  output logic [LIGHTS*CHANNELS*SPEC_COLOUR_WL-1:0] diffuse_colour_o,  // '0 without multiply
  output logic [LIGHTS-1:0]                     gate_only_o  // diffuse series gate only
);
  localparam int NColours = LIGHTS * CHANNELS;  // colour words of each kind
  // verilator lint_off UNUSEDSIGNAL
  logic unused_word;  // reason: each register takes the low bits of its word, not all 64
  assign unused_word = ^word_i;
  // verilator lint_on UNUSEDSIGNAL

  logic [CHANNELS*SERIES_WL-1:0]    ambient_q [MATERIAL_BUFFERS];
  logic [NColours*SPEC_COLOUR_WL-1:0] spec_colour_q [MATERIAL_BUFFERS];
  logic [LIGHTS-1:0]                gate_only_q [MATERIAL_BUFFERS];
  logic                             hdr_bank;  // bank a MATERIAL header taken now writes
  logic                             mat_wr;

  always_ff @(posedge clk_i) begin
    // Loaded with the MATERIAL header into the bank its payload writes (the other one with two
    // buffers: the write bank switches on this edge), which no in-flight pixel reads.
    if (mat_fire_i) gate_only_q[hdr_bank] <= word_i[shade_pkg::GateOnlyLsb +: LIGHTS];
    if (pay_mat_i) begin
      for (int i = 0; i < CHANNELS; i++) begin
        if (pay_idx_i == 16'(i)) begin
          ambient_q[mat_wr][i*SERIES_WL +: SERIES_WL] <= word_i[SERIES_WL-1:0];
        end
      end
      for (int i = 0; i < NColours; i++) begin
        if (pay_idx_i == 16'(CHANNELS + i)) begin
          spec_colour_q[mat_wr][i*SPEC_COLOUR_WL +: SPEC_COLOUR_WL] <=
              word_i[SPEC_COLOUR_WL-1:0];
        end
      end
    end
  end

  assign ambient_o     = ambient_q[rd_bank_i];
  assign spec_colour_o = spec_colour_q[rd_bank_i];

  if (DIFFUSE_MULTIPLY) begin : g_diffuse_colour
    logic [NColours*SPEC_COLOUR_WL-1:0] diffuse_colour_q [MATERIAL_BUFFERS];
    always_ff @(posedge clk_i) begin
      if (pay_mat_i) begin
        for (int i = 0; i < NColours; i++) begin
          if (pay_idx_i == 16'(CHANNELS + NColours + i)) begin
            diffuse_colour_q[mat_wr][i*SPEC_COLOUR_WL +: SPEC_COLOUR_WL] <=
                word_i[SPEC_COLOUR_WL-1:0];
          end
        end
      end
    end
    assign diffuse_colour_o = diffuse_colour_q[rd_bank_i];
  end else begin : g_no_diffuse_colour
    assign diffuse_colour_o = '0;
  end
  assign gate_only_o   = gate_only_q[rd_bank_i];
  assign wr_bank_o     = mat_wr;

  if (MATERIAL_BUFFERS == 2) begin : g_mat_banks
    localparam int MatCntW = $clog2(SPAN_Q + SPEC_LATENCY + 8);  // spans in flight, with margin
    logic               mat_wr_q;
    logic               s1_mat_q, s2_mat_q, s3_mat_q;  // bank of each setup stage's span
    logic               eng_mat_q;
    logic [MatCntW-1:0] mat_spans_q [2];  // per bank: spans taken, last beat not out of the slot
    assign mat_wr       = mat_wr_q;
    assign hdr_bank     = !mat_wr_q;
    assign other_free_o = mat_spans_q[!mat_wr_q] == '0;
    assign cur_free_o   = mat_spans_q[mat_wr_q] == '0;
    assign eng_bank_o   = eng_mat_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        mat_wr_q       <= 1'b0;
        mat_spans_q[0] <= '0;
        mat_spans_q[1] <= '0;
      end else begin
        if (mat_fire_i) mat_wr_q <= !mat_wr_q;
        for (int b = 0; b < 2; b++) begin
          mat_spans_q[b] <= mat_spans_q[b]
                          + (span_fire_i && mat_wr_q == 1'(b) ? MatCntW'(span_n_i) : '0)
                          - MatCntW'(leave_i && leave_bank_i == 1'(b));
        end
      end
    end
    always_ff @(posedge clk_i) begin
      if (s1_load_i)  s1_mat_q  <= s1_bank_i;
      if (s1_move_i)  s2_mat_q  <= s1_mat_q;
      if (s2_move_i)  s3_mat_q  <= s2_mat_q;
      if (eng_load_i) eng_mat_q <= HOST_SETUP ? s1_bank_i : s3_mat_q;
    end
`ifndef SYNTHESIS
`ifdef VERILATOR
    // A bank's count of spans in flight never wraps (under- or overflow).
    logic [1:0] wraps;
    always_comb begin
      for (int b = 0; b < 2; b++) begin
        wraps[b] = leave_i && leave_bank_i == 1'(b) && !(span_fire_i && mat_wr_q == 1'(b)) &&
                   mat_spans_q[b] == '0 ||
                   span_fire_i && mat_wr_q == 1'(b) &&
                   32'(mat_spans_q[b]) + 32'(span_n_i) >= (32'd1 << MatCntW);
      end
    end
    a_count_no_wrap: assert property (@(posedge clk_i) disable iff (!rst_ni) wraps == 2'b00);
`endif
`endif
  end else begin : g_one_mat
    assign mat_wr       = 1'b0;
    assign hdr_bank     = 1'b0;
    assign other_free_o = 1'b1;
    assign cur_free_o   = 1'b1;
    assign eng_bank_o   = 1'b0;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_mat;  // reason: one buffer - every span reads bank 0, nothing is counted
    assign unused_mat = rst_ni ^ span_fire_i ^ (^span_n_i) ^ s1_load_i ^ s1_bank_i ^
                        s1_move_i ^ s2_move_i ^ eng_load_i ^ leave_i ^ leave_bank_i;
    // verilator lint_on UNUSEDSIGNAL
  end

`ifndef SYNTHESIS
  initial begin
    if (CHANNELS != 1 && CHANNELS != 3)
      $fatal(1, "material_bank: CHANNELS %0d is not 1 or 3", CHANNELS);
    if (LIGHTS < 1 || LIGHTS > 8)
      $fatal(1, "material_bank: LIGHTS %0d is not 1..8", LIGHTS);
    if (MATERIAL_BUFFERS != 1 && MATERIAL_BUFFERS != 2)
      $fatal(1, "material_bank: MATERIAL_BUFFERS %0d is not 1 or 2", MATERIAL_BUFFERS);
  end
`endif
endmodule
