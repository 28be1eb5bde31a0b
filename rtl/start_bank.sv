// start_bank: with host span setup (shade_unit SPAN_SETUP = shade_pkg::SetupHost) the start
// values of the next spans - DEPTH entries, each a SPAN's descriptor, its material bank and its
// START_WORDS payload words as they came (shade_pkg::start_words; model/start_packing.h) - written
// from the command port's beat, loaded by the engines (model/start_bank.h, class StartBank).
//
// A SPAN header taken (span_fire_i) takes the next entry with the payload words behind it in the
// beat; the decoder's tail words (filling_i) complete the newest entry. The oldest entry is
// valid once complete, and leaves when the engines load it (load_i), so the next span's payload
// streams in while the engines run the current span. Value j of an entry is bits
// [j*SERIES_WL +: SERIES_WL] of its payload words, series i's v, d, d2 being j = 3i, 3i+1, 3i+2.
module start_bank #(
  parameter int PORT_WORDS = 1,
  parameter int N_SER      = 1,
  parameter int SERIES_WL  = 32,
  parameter int XY_BITS    = 12,
  parameter int DEPTH      = 1   // entries: 1 or 2
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,
  input  logic                                   cmd_valid_i,
  // verilator lint_off UNUSEDSIGNAL
  // reason: the header's other fields, the last payload word's bits past the last value, and
  // the payload index's bits above a START_WORDS payload's
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,
  input  logic [shade_pkg::WordW-1:0]            hdr_i,        // the decoder's header word
  input  logic [15:0]                            pay_idx_i,    // the tail's first payload index
  // verilator lint_on UNUSEDSIGNAL
  input  logic                                   span_fire_i,  // a SPAN header is taken ...
  input  logic                                   mat_i,        // ... in this material bank
  // Counts and positions of beat words, 0..PORT_WORDS: $clog2(PORT_WORDS + 1) bits.
  input  logic [$clog2(PORT_WORDS+1)-1:0]        tail_n_i,     // payload words due in the beat
  // verilator lint_off UNUSEDSIGNAL
  // reason: with a one-word port no payload word follows its header in the beat
  input  logic [$clog2(PORT_WORDS+1)-1:0]        hdr_pos_i,
  input  logic [$clog2(PORT_WORDS+1)-1:0]        hdr_n_i,
  // verilator lint_on UNUSEDSIGNAL
  input  logic                                   filling_i,  // the tail is the newest entry's
  input  logic                                   load_i,     // the engines take the oldest
  output logic                                   free_o,     // a SPAN header may be taken
  output logic                                   valid_o,    // the oldest entry is complete
  output logic                                   empty_o,
  output logic [3*XY_BITS+1:0]                   span_o,     // its {y, x0, len, last}
  output logic                                   mat_o,      // its material bank
  output logic [N_SER*SERIES_WL-1:0]             v_o,        // its series i at i * SERIES_WL
  output logic [N_SER*SERIES_WL-1:0]             d_o,
  output logic [N_SER*SERIES_WL-1:0]             d2_o
);
  localparam int WordW  = shade_pkg::WordW;
  localparam int NWords = shade_pkg::start_words(N_SER, SERIES_WL);
  localparam int Bits   = 3 * N_SER * SERIES_WL;  // of the NWords * WordW payload bits
  localparam int SpanW  = 3 * XY_BITS + 2;
  localparam int PtrW   = DEPTH > 1 ? $clog2(DEPTH) : 1;
  localparam int CntW   = $clog2(DEPTH + 1);
  localparam int NW     = $clog2(PORT_WORDS + 1);  // a count of beat words
  localparam int AW     = $clog2(NWords + PORT_WORDS);  // a payload index + offset

  logic [CntW-1:0] count_q;
  logic [PtrW-1:0] rd_q, wr_q, newest;  // oldest entry, next to take, latest taken
  assign newest  = DEPTH > 1 ? wr_q - 1'b1 : '0;
  assign valid_o = 32'(count_q) > (filling_i ? 32'd1 : 32'd0);
  assign free_o  = 32'(count_q) < DEPTH || load_i;
  assign empty_o = count_q == '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      count_q <= '0;
      rd_q    <= '0;
      wr_q    <= '0;
    end else begin
      count_q <= count_q + CntW'(span_fire_i) - CntW'(load_i);
      if (DEPTH > 1 && load_i) rd_q <= rd_q + 1'b1;
      if (DEPTH > 1 && span_fire_i) wr_q <= wr_q + 1'b1;
    end
  end

  // Beat word k carries payload word idx: a tail word of the newest entry (words 0 ..
  // tail_n_i - 1: a tail starts its beat, cmd_decoder's a_tail_starts_beat) at idx = pay_idx_i +
  // k, or one after the SPAN header taken now (entry wr_q) at idx = k - hdr_pos_i - 1 (AW bits).
  // Timing (docs/rtl.md): for each payload word w and beat word k, whether k is w's (hit_t, hit_h),
  // as compares of pay_idx_i and hdr_pos_i (from the decoder's flops) with constants, instead of
  // working out idx for every k and comparing it with every w.
  // verilator lint_off UNUSEDSIGNAL
  // reason: the bits past the last value are zero and unread
  logic [NWords*WordW-1:0] head;  // the oldest entry's payload words
  // verilator lint_on UNUSEDSIGNAL
  logic                    tail_we;  // the tail's words are written
  assign tail_we = cmd_valid_i && filling_i;
  // Payload word w of every entry, only as wide as the values reach; one process per word.
  // A cycle may write the same word of two entries: a tail word of the newest entry and, from
  // the SPAN header taken with it, a word of the next entry (a short payload: its indices
  // overlap). Two write ports per word, then; with DEPTH 2 the two entries differ.
  for (genvar w = 0; w < NWords; w++) begin : g_word
    localparam int WW = Bits - w * WordW < WordW ? Bits - w * WordW : WordW;
    logic [PORT_WORDS-1:0] hit_t, hit_h;    // beat word k is w, from the tail, after the header
    logic                  load_t, load_h;  // from the tail (entry newest), from the header (wr_q)
    logic [WW-1:0]         value_t, value_h;
    logic [PORT_WORDS*WW-1:0] low;          // each beat word's low WW bits
    logic [WW-1:0]         q [DEPTH];
    for (genvar k = 0; k < PORT_WORDS; k++) begin : g_beat_word
      assign low[k*WW +: WW] = cmd_data_i[k*WordW +: WW];
      assign hit_t[k] = NW'(k) < tail_n_i && AW'(pay_idx_i) == AW'(w - k);
      if (k < w + 1) begin : g_before  // no header before it with w after that
        assign hit_h[k] = 1'b0;
      end else begin : g_after  // k = hdr_pos_i + 1 + w, within the header's hdr_n_i words
        assign hit_h[k] = hdr_pos_i == NW'(k - 1 - w) && hdr_n_i > NW'(w + 1);
      end
    end
    // The enables last: span_fire_i comes late (after the engines' load, through free_o).
    assign load_t  = tail_we && |hit_t;
    assign load_h  = span_fire_i && |hit_h;
    onehot_mux #(.N(PORT_WORDS), .W(WW)) u_pick_t (.sel_i(hit_t), .in_i(low), .out_o(value_t));
    onehot_mux #(.N(PORT_WORDS), .W(WW)) u_pick_h (.sel_i(hit_h), .in_i(low), .out_o(value_h));
    always_ff @(posedge clk_i) begin
      if (load_t) q[newest] <= value_t;
      if (load_h) q[wr_q] <= value_h;
    end
    assign head[w*WordW +: WordW] = WordW'(q[rd_q]);
  end

  logic [SpanW-1:0] span_q [DEPTH];
  logic             mat_q [DEPTH];
  always_ff @(posedge clk_i) begin
    if (span_fire_i) begin
      span_q[wr_q] <= {hdr_i[shade_pkg::HighLsb +: XY_BITS], hdr_i[shade_pkg::MidLsb +: XY_BITS],
                       hdr_i[shade_pkg::CountLsb +: XY_BITS + 1], hdr_i[shade_pkg::SpanLastBit]};
      mat_q[wr_q]  <= mat_i;
    end
  end
  assign span_o = span_q[rd_q];
  assign mat_o  = mat_q[rd_q];

  for (genvar i = 0; i < N_SER; i++) begin : g_values
    assign v_o[i*SERIES_WL +: SERIES_WL]  = head[(3*i)*SERIES_WL +: SERIES_WL];
    assign d_o[i*SERIES_WL +: SERIES_WL]  = head[(3*i+1)*SERIES_WL +: SERIES_WL];
    assign d2_o[i*SERIES_WL +: SERIES_WL] = head[(3*i+2)*SERIES_WL +: SERIES_WL];
  end

`ifndef SYNTHESIS
  initial begin
    if (DEPTH != 1 && DEPTH != 2)
      $fatal(1, "start_bank: DEPTH %0d is not 1 or 2", DEPTH);
    // The model's range (UnitConfig: series iwl >= 2, fraction >= out_bits >= 1, wl <= 62).
    if (N_SER < 1 || SERIES_WL < 3 || SERIES_WL > 62)
      $fatal(1, "start_bank: N_SER %0d or SERIES_WL %0d out of range (1.., 3..62)", N_SER,
             SERIES_WL);
  end
`ifdef VERILATOR
  // An entry is taken only when free and loaded only when complete; the count never wraps.
  a_take_free: assert property (@(posedge clk_i) disable iff (!rst_ni) span_fire_i |-> free_o);
  a_load_valid: assert property (@(posedge clk_i) disable iff (!rst_ni) load_i |-> valid_o);
  a_count_max: assert property (@(posedge clk_i) disable iff (!rst_ni) 32'(count_q) <= DEPTH);
`endif
`endif
endmodule
