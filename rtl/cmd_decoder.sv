// cmd_decoder: shade_unit's command port - the beat decoder and its payload FSM. A beat of
// PORT_WORDS words (layout in shade_pkg) is taken apart one item per cycle - the TRIANGLE
// coefficient words due in it (the tail), then at most one header (with a TRIANGLE's words after
// it, or a run of SPAN headers into a span queue), or one MATERIAL / TABLE payload word, or a NOP
// (the rest is padding) - and accepted with its last item. A header waits while the part of the
// unit it changes is busy (the *_i conditions below). With host span setup (HOST_SETUP) a SPAN
// header brings START_WORDS payload words, taken like a TRIANGLE's (with the header, then a
// tail per beat) into the start bank. The payload FSM is a module of its own (cmd_payload.sv).
//
// Timing (docs/rtl.md): the header's word is selected from flops (pos_q, and the
// payload FSM's registered tail), every word of the beat is decoded as a header at once and the
// header's word's results picked one-hot, and the ready conditions come last; the 64-bit word
// multiplexer (word_o) feeds no counter.
module cmd_decoder #(
  parameter int PORT_WORDS  = 1,     // 64-bit words per beat: 1, 2, 4 or 8
  parameter bit QUEUED      = 1'b0,  // SPAN headers go into a span queue (TRI_QUEUE > 1)
  parameter bit MAT_BANKED  = 1'b0,  // two material buffers
  parameter int N_MAT_FIXED = 2,     // MATERIAL payload words before the slots' (ambient, colour)
  parameter bit HOST_SETUP  = 1'b0,  // SPAN headers carry start values (start_bank.sv)
  parameter int START_WORDS = 1      // ... in this many payload words
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,
  input  logic                                  cmd_valid_i,
  output logic                                  cmd_ready_o,
  // What the rest of the unit lets a header through on.
  input  logic                                  datapath_empty_i,  // no pixel in flight
  input  logic                                  mat_other_free_i,  // MATERIAL's next bank free
  input  logic                                  mat_cur_free_i,    // the latest MATERIAL's bank
  input  logic                                  sq_full_i,         // span queue full
  input  logic [15:0]                           sq_room_i,         // ... its free entries
  input  logic                                  s1_free_i,         // setup stage 1 free
  input  logic                                  tri_bank_free_i,   // next coefficient bank free
  input  logic                                  start_free_i,      // a start bank entry free
  // The item taken this cycle.
  output logic [shade_pkg::WordW-1:0]           word_o,       // header, else payload word
  output logic [(PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1)-1:0] word_sel_o,  // ... its word
  output logic [7:0]                            hdr_op_o,
  output logic [$clog2(PORT_WORDS+1)-1:0]       hdr_pos_o,    // where a header would be
  output logic [$clog2(PORT_WORDS+1)-1:0]       hdr_n_o,      // words the header takes (read
                                                                // only with span/tri_fire_o)
  output logic                                  hdr_fire_o,   // a header is taken
  output logic                                  span_fire_o,  // ... SPAN headers (hdr_n_o)
  output logic                                  tri_fire_o,   // ... a TRIANGLE header
  output logic                                  mat_fire_o,   // ... a MATERIAL header
  output logic [$clog2(PORT_WORDS+1)-1:0]       tail_n_o,     // TRIANGLE words due in beat
  output logic [15:0]                           pay_idx_o,    // of the next payload word
  output logic                                  span_pay_o,   // the tail is a SPAN's (host)
  output logic                                  pay_mat_o,    // a MATERIAL payload word taken
  // Configuration words for the specular slots: MATERIAL exponent (index 0) and unit
  // parameters (1..), TABLE entries at base + index.
  output logic                                  cfg_valid_o,
  output logic                                  cfg_table_o,
  output logic                                  cfg_all_banks_o,  // a TABLE not per-material
  output logic [15:0]                           cfg_addr_o
);
  localparam int WordW = shade_pkg::WordW;
  localparam int PosW  = PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1;
  localparam int NW    = $clog2(PORT_WORDS + 1);  // a count of beat words: 0..PORT_WORDS
  logic [PosW-1:0] pos_q;
  logic          in_payload, tri_payload;  // payload words are due; ... as a tail
  logic          tail_hdr;     // ... and a header after the tail in this beat
  logic          mat_word;     // a MATERIAL / TABLE payload word is due
  logic [NW-1:0] tail_n;       // TRIANGLE / SPAN words due in the beat (from word 0)
  logic [NW-1:0] beat_left;    // words of the beat from pos_q on
  logic [NW-1:0] hdr_pos;
  logic          hdr_here;     // a header is looked at this cycle
  logic [NW-1:0] hdr_n;
  logic          hdr_ready, take_hdr, hdr_fire;
  logic [NW-1:0] item_n;       // words the item of this cycle takes (0: none; <= beat_left)
  logic          beat_done;
  logic [PosW-1:0]       word_sel;
  logic [PORT_WORDS-1:0] sel;  // word_sel, one-hot
  logic [WordW-1:0]      cmd_word;
  // Where the header would be: after the tail (a tail starts its beat: a_tail_starts_beat), else
  // at pos_q. The payload FSM keeps tail_n and tail_hdr as registers, so the word's select comes
  // straight from flops.
  assign beat_left = NW'(PORT_WORDS) - NW'(pos_q);
  assign hdr_pos   = NW'(pos_q) + tail_n;
  assign mat_word  = in_payload && !tri_payload;
  assign hdr_here  = !in_payload || tail_hdr;
  assign word_sel  = tail_hdr ? PosW'(tail_n) : pos_q;
  always_comb begin
    for (int k = 0; k < PORT_WORDS; k++) sel[k] = word_sel == PosW'(k);
  end
  onehot_mux #(.N(PORT_WORDS), .W(WordW)) u_pick_word (
    .sel_i(sel), .in_i(cmd_data_i), .out_o(cmd_word)
  );

  // Every word of the beat is decoded as the header it would be, in parallel (g_word), and the
  // selected word's results are picked with one-hot AND-OR: the words a header takes (hdr_n_w),
  // whether it finishes the beat (done_w), where the next item starts (npos_w), what it waits for
  // (wait_*_w, is_*_w).
  logic [PORT_WORDS-1:0] is_span_w, is_tri_w, is_mat_w, done_w;
  logic [PORT_WORDS-1:0] wait_dp_w, wait_mat_w, wait_cur_w, wait_none_w;
  logic [PORT_WORDS*NW-1:0]   hdr_n_w;  // hdr_n of a header there (word k at k * NW)
  logic [PORT_WORDS*PosW-1:0] npos_w;   // pos_q after it (0: the beat is done)
  // SPAN headers back to back in the beat from word `from` on. (A function in a continuous
  // assignment: an always_comb loop with a local flag never settles in Icarus 11.)
  function automatic logic [NW-1:0] run_length(input logic [PORT_WORDS-1:0] is_span,
                                               input int from);
    logic going;
    going      = 1'b1;
    run_length = '0;
    for (int j = from; j < PORT_WORDS; j++) begin
      if (going && is_span[j]) run_length = run_length + 1'b1;
      else going = 1'b0;
    end
  endfunction
  for (genvar k = 0; k < PORT_WORDS; k++) begin : g_word
    localparam logic [NW-1:0] After = NW'(PORT_WORDS - 1 - k);  // beat words after word k
    localparam bit HostMore = START_WORDS > PORT_WORDS - 1 - k;  // a host SPAN's words: more
    logic [7:0]    op;
    logic [15:0]   count;
    logic          is_tab, tab_cur;  // a TABLE; ... of the latest MATERIAL's bank (two banks)
    logic          host_span;
    logic          more;      // payload words past the beat (count compared before the opcode
                              // picks it: a host SPAN's START_WORDS is a constant)
    logic          count_big; // count has a bit at or above NW: more than any After
    logic [NW-1:0] word_n;    // hdr_n of a header here
    logic [NW-1:0] span_run;  // SPAN headers back to back from here
    logic [NW-1:0] queue_n;   // ... into the span queue, as it has room for
    assign op           = cmd_data_i[k*WordW + shade_pkg::OpcodeLsb +: 8];
    assign count        = cmd_data_i[k*WordW + shade_pkg::CountLsb +: shade_pkg::FieldW];
    assign is_span_w[k] = op == shade_pkg::OpSpan;
    assign is_tri_w[k]  = op == shade_pkg::OpTriangle;
    assign is_mat_w[k]  = op == shade_pkg::OpMaterial;
    assign is_tab       = op == shade_pkg::OpTable;
    assign tab_cur      = MAT_BANKED && cmd_data_i[k*WordW + shade_pkg::TableMatBit];
    assign host_span    = HOST_SETUP && is_span_w[k];
    // count > After without a 16-bit compare (a carry chain at the head of the iCE40's critical
    // path): After < 2^NW, so only count's low NW bits need comparing.
    assign count_big    = |(count >> NW);
    assign more         = host_span ? HostMore : count_big || count[NW-1:0] > After;
    assign span_run     = run_length(is_span_w, k);
    assign queue_n      = 16'(span_run) < sq_room_i ? span_run : NW'(sq_room_i);
    always_comb begin
      word_n = NW'(1);
      if (op == shade_pkg::OpNop) word_n = NW'(PORT_WORDS - k);
      else if (is_tri_w[k] || host_span)  // 1 + min(payload words, After): count + 1 is
                                          // added beside the compare, not after it
        word_n = more ? NW'(PORT_WORDS - k) : host_span ? NW'(START_WORDS + 1)
                                                        : NW'(count) + NW'(1);
      else if (QUEUED && is_span_w[k]) word_n = queue_n == '0 ? NW'(1) : queue_n;
    end
    assign hdr_n_w[k*NW +: NW] = word_n;
    // A header's words run to the beat's end (PORT_WORDS: pos_q wraps to 0).
    assign done_w[k] = word_n == NW'(PORT_WORDS - k);
    assign npos_w[k*PosW +: PosW] = PosW'(NW'(k) + word_n);
    // What a header here waits for (hdr_ready below): one of these, or nothing.
    assign wait_dp_w[k]   = is_mat_w[k] && !MAT_BANKED || is_tab && !tab_cur;
    assign wait_mat_w[k]  = is_mat_w[k] && MAT_BANKED;
    assign wait_cur_w[k]  = is_tab && tab_cur;
    assign wait_none_w[k] = !(is_mat_w[k] || is_tab || is_span_w[k] || is_tri_w[k]);
  end
  logic          done;
  logic [PosW-1:0] npos;
  logic [NW-1:0] hdr_n_sel;
  logic          hdr_span, hdr_tri, hdr_mat, hdr_dp, hdr_mat_bank, hdr_cur, hdr_none;
  assign done      = |(sel & done_w);
  onehot_mux #(.N(PORT_WORDS), .W(PosW)) u_pick_pos (.sel_i(sel), .in_i(npos_w), .out_o(npos));
  onehot_mux #(.N(PORT_WORDS), .W(NW)) u_pick_n (.sel_i(sel), .in_i(hdr_n_w), .out_o(hdr_n_sel));
  assign {hdr_span, hdr_tri, hdr_mat} = {|(sel & is_span_w), |(sel & is_tri_w), |(sel & is_mat_w)};
  assign {hdr_dp, hdr_mat_bank, hdr_cur, hdr_none} =
         {|(sel & wait_dp_w), |(sel & wait_mat_w), |(sel & wait_cur_w), |(sel & wait_none_w)};
  // MATERIAL (ambient, spec_colour, exponent and unit parameters) and TABLE (LUT entries) must
  // not change what in-flight pixels read: both wait for an empty datapath, as the model
  // applies them in stream order. With two material buffers a MATERIAL writes the other bank
  // and waits only until no span in flight reads that one, a TABLE of the latest MATERIAL's
  // bank until none reads that. Without a span queue a SPAN's setup reads the coefficient
  // registers as it is taken: not on the edge that writes its triangle's last words (a tail in
  // this beat). With host setup a SPAN needs a start bank entry, and may follow the previous
  // one's tail. The conditions come last (start_free_i late in the cycle, after the engines'
  // load), each ANDed with whether the header is of its kind.
  logic span_ready;
  assign span_ready = HOST_SETUP ? start_free_i : QUEUED ? !sq_full_i : s1_free_i && tail_n == '0;
  assign hdr_ready  = hdr_none || hdr_dp && datapath_empty_i || hdr_mat_bank && mat_other_free_i ||
                      hdr_cur && mat_cur_free_i || hdr_span && span_ready ||
                      hdr_tri && tri_bank_free_i;
  // hdr_n: the selected word's. Read only when a header is taken (the item below, and its readers
  // under span_fire_o / tri_fire_o); in other cycles it is what that word would take.
  if (PORT_WORDS > 1) begin : g_hdr_n
    assign hdr_n = hdr_n_sel;
  end else begin : g_hdr_one
    // A one-word port: a header taken is the whole beat (a NOP pads nothing, a TRIANGLE's words
    // follow in later beats, a SPAN run is one header), so the rules above all give 1 whenever
    // a header is taken, which is the only time hdr_n is read. Not evaluated on every cycle.
    assign hdr_n = NW'(1);
    // verilator lint_off UNUSEDSIGNAL
    logic unused_hdr_n;  // reason: the per-word counts matter on wide ports only
    assign unused_hdr_n = ^hdr_n_sel;
    // verilator lint_on UNUSEDSIGNAL
  end
  assign take_hdr    = hdr_here && hdr_ready;
  assign hdr_fire    = cmd_valid_i && take_hdr;
  // The item: a header (after the tail, if any) to where done_w says; else the tail, which ends
  // the beat unless a header follows it; else a MATERIAL / TABLE word; else nothing.
  assign item_n      = tail_n + (take_hdr ? hdr_n : '0) + NW'(mat_word);
  assign beat_done   = item_n == beat_left;
  assign cmd_ready_o = hdr_here ? hdr_ready && done
                               : tri_payload || pos_q == PosW'(PORT_WORDS - 1);
  // The next word of the beat: after the item of this cycle, or word 0 of the next beat.
  if (PORT_WORDS > 1) begin : g_beat_pos
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        pos_q <= '0;
      end else if (hdr_fire) begin
        pos_q <= npos;
      end else if (cmd_valid_i && in_payload) begin
        pos_q <= tri_payload ? PosW'(tail_n) : pos_q + PosW'(1);
      end
    end
  end else begin : g_one_word_beat
    // A one-word port: every item takes the whole beat, so the next word is always word 0.
    assign pos_q = '0;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_npos;  // reason: likewise
    assign unused_npos = ^npos;
    // verilator lint_on UNUSEDSIGNAL
  end
  cmd_payload #(
    .PORT_WORDS(PORT_WORDS), .N_MAT_FIXED(N_MAT_FIXED), .HOST_SETUP(HOST_SETUP),
    .START_WORDS(START_WORDS)
  ) u_payload (
    .clk_i, .rst_ni, .cmd_valid_i, .cmd_data_i, .hdr_sel_i(sel), .hdr_fire_i(hdr_fire),
    .in_payload_o(in_payload), .tri_payload_o(tri_payload), .tail_n_o(tail_n),
    .tail_hdr_o(tail_hdr), .pay_idx_o, .pay_mat_o, .span_pay_o, .cfg_valid_o, .cfg_table_o,
    .cfg_all_banks_o, .cfg_addr_o
  );
  assign {word_o, word_sel_o, hdr_op_o, hdr_pos_o, hdr_n_o} =
         {cmd_word, word_sel, cmd_word[shade_pkg::OpcodeLsb +: 8], hdr_pos, hdr_n};
  assign {hdr_fire_o, tail_n_o} = {hdr_fire, tail_n};
  assign span_fire_o = cmd_valid_i && hdr_here && hdr_span && span_ready;
  assign tri_fire_o  = cmd_valid_i && hdr_here && hdr_tri && tri_bank_free_i;
  assign mat_fire_o  = cmd_valid_i && hdr_here && hdr_mat &&
                       (MAT_BANKED ? mat_other_free_i : datapath_empty_i);

`ifndef SYNTHESIS
  initial begin
    if (PORT_WORDS != 1 && PORT_WORDS != 2 && PORT_WORDS != 4 && PORT_WORDS != 8)
      $fatal(1, "cmd_decoder: PORT_WORDS %0d is not 1, 2, 4 or 8", PORT_WORDS);
  end
`ifdef VERILATOR
  // The command port's handshake (the sender's side): a beat offered stays, unchanged, till taken.
  a_cmd_valid_held: assert property (@(posedge clk_i) disable iff (!rst_ni)
    cmd_valid_i && !cmd_ready_o |=> cmd_valid_i);
  a_cmd_data_stable: assert property (@(posedge clk_i) disable iff (!rst_ni)
    cmd_valid_i && !cmd_ready_o |=> $stable(cmd_data_i));
  // (And the decoder never takes more words than the beat has left.)
  a_item_fits: assert property (@(posedge clk_i) disable iff (!rst_ni) item_n <= beat_left);
  // cmd_ready_o, worked out from the selected word's done_w, is the beat's last item.
  a_ready_is_beat_done: assert property (@(posedge clk_i) disable iff (!rst_ni)
    cmd_ready_o == (item_n != '0 && beat_done));
  // A TRIANGLE's or host SPAN's tail starts its beat: the header takes its payload words to the
  // beat's end, and a tail takes all it has in the beat. coef_bank and start_bank rely on it.
  a_tail_starts_beat: assert property (@(posedge clk_i) disable iff (!rst_ni)
    tail_n != '0 |-> pos_q == '0);
`endif
`endif
endmodule
