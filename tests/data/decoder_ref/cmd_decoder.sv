// cmd_decoder: shade_unit's command port - the beat decoder and its payload FSM. A beat of
// PORT_WORDS words (layout in shade_pkg) is taken apart one item per cycle - the TRIANGLE
// coefficient words due in it (the tail), then at most one header (with a TRIANGLE's words after
// it, or a run of SPAN headers into a span queue), or one MATERIAL / TABLE payload word, or a NOP
// (the rest is padding) - and accepted with its last item. A header waits while the part of the
// unit it changes is busy (the *_i conditions below). With host span setup (HOST_SETUP) a SPAN
// header brings START_WORDS payload words, taken like a TRIANGLE's (with the header, then a
// tail per beat) into the start bank. The payload FSM is a module of its own (cmd_payload.sv).
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
  output logic [$clog2(PORT_WORDS+1)-1:0]       hdr_n_o,      // words the header takes
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
  logic [7:0]  hdr_op;
  logic [15:0] hdr_count;
  logic        host_span;  // a SPAN header with start values (HOST_SETUP)
  logic [15:0] pay_count;  // payload words of the header: its count, a host SPAN's START_WORDS
  logic        hdr_ready, hdr_fire;
  logic        in_payload, tri_payload;  // payload words are due; ... as a tail
  logic [15:0] pay_rem;                  // ... this many still to come
  logic [NW-1:0] beat_left;  // words of the beat from pos_q on
  logic [NW-1:0] tail_n;
  logic [NW-1:0] hdr_pos;
  logic          hdr_here;     // a header is looked at this cycle
  logic [NW-1:0] hdr_n;
  logic          take_hdr;
  logic [NW-1:0] item_n;       // words the item of this cycle takes (0: none; <= beat_left)
  logic        beat_done;
  logic [PosW-1:0]  word_sel;
  logic [WordW-1:0] cmd_word;
  assign beat_left   = NW'(PORT_WORDS) - NW'(pos_q);
  assign tail_n      = !tri_payload ? '0 : pay_rem < 16'(beat_left) ? NW'(pay_rem) : beat_left;
  assign hdr_pos     = NW'(pos_q) + tail_n;
  assign hdr_here    = (!in_payload || (tri_payload && pay_rem <= 16'(beat_left))) &&
                       hdr_pos < NW'(PORT_WORDS);
  assign word_sel    = hdr_here ? PosW'(hdr_pos) : pos_q;
  assign cmd_word    = cmd_data_i[word_sel * WordW +: WordW];
  assign hdr_op      = cmd_word[shade_pkg::OpcodeLsb +: 8];
  assign hdr_count   = cmd_word[shade_pkg::CountLsb +: shade_pkg::FieldW];
  assign host_span   = HOST_SETUP && hdr_op == shade_pkg::OpSpan;
  assign pay_count   = host_span ? 16'(START_WORDS) : hdr_count;
  // With a span queue, a run of SPAN headers goes into it together, as many as it has room for.
  logic [PORT_WORDS-1:0] word_is_span;
  logic [NW-1:0]         span_run;  // SPAN headers from hdr_pos on, back to back in the beat
  // SPAN headers back to back in the beat from word `from` on. (A function in a continuous
  // assignment: an always_comb loop with a local flag never settles in Icarus 11.)
  function automatic logic [NW-1:0] run_length(input logic [PORT_WORDS-1:0] is_span,
                                               input logic [NW-1:0] from);
    logic going;
    going      = 1'b1;
    run_length = '0;
    for (int k = 0; k < PORT_WORDS; k++) begin
      if (NW'(k) >= from) begin
        if (going && is_span[k]) run_length = run_length + 1'b1;
        else going = 1'b0;
      end
    end
  endfunction
  for (genvar k = 0; k < PORT_WORDS; k++) begin : g_word_is_span
    assign word_is_span[k] = cmd_data_i[k*WordW + shade_pkg::OpcodeLsb +: 8] == shade_pkg::OpSpan;
  end
  assign span_run = run_length(word_is_span, hdr_pos);
  if (PORT_WORDS > 1) begin : g_hdr_n
    wire [NW-1:0] after = NW'(PORT_WORDS) - hdr_pos - NW'(1);  // beat words after the header
    always_comb begin
      hdr_n = NW'(1);  // (read only when a header is taken: hdr_pos < PORT_WORDS, no wrap)
      if (hdr_op == shade_pkg::OpNop) begin
        hdr_n = NW'(PORT_WORDS) - hdr_pos;
      end else if (hdr_op == shade_pkg::OpTriangle || host_span) begin
        hdr_n = NW'(1) + (pay_count < 16'(after) ? NW'(pay_count) : after);
      end else if (QUEUED && hdr_op == shade_pkg::OpSpan && hdr_here) begin
        hdr_n = 16'(span_run) < sq_room_i ? span_run : NW'(sq_room_i);
        if (hdr_n == '0) hdr_n = NW'(1);  // a full queue: hdr_ready holds the header
      end
    end
  end else begin : g_hdr_one
    // A one-word port: a header taken is the whole beat (a NOP pads nothing, a TRIANGLE's words
    // follow in later beats, a SPAN run is one header), so the rules above all give 1 whenever
    // a header is taken, which is the only time hdr_n is read. Not evaluated on every cycle.
    assign hdr_n = NW'(1);
    // verilator lint_off UNUSEDSIGNAL
    logic unused_hdr_n;  // reason: the run length and the queue's room matter on wide ports only
    assign unused_hdr_n = ^span_run ^ (^sq_room_i);
    // verilator lint_on UNUSEDSIGNAL
  end
  // MATERIAL (ambient, spec_colour, exponent and unit parameters) and TABLE (LUT entries) must
  // not change what in-flight pixels read: both wait for an empty datapath, as the model
  // applies them in stream order. With two material buffers a MATERIAL writes the other bank
  // and waits only until no span in flight reads that one.
  always_comb begin
    unique case (hdr_op)
      shade_pkg::OpMaterial: hdr_ready = MAT_BANKED ? mat_other_free_i : datapath_empty_i;
      shade_pkg::OpTable:    hdr_ready = MAT_BANKED && cmd_word[shade_pkg::TableMatBit]
                                         ? mat_cur_free_i : datapath_empty_i;
      // Without a span queue a SPAN's setup reads the coefficient registers as it is taken:
      // not on the edge that writes its triangle's last words.
      // With host setup a SPAN needs a start bank entry, and may follow the previous one's tail.
      shade_pkg::OpSpan:     hdr_ready = HOST_SETUP ? start_free_i :
                                         QUEUED ? !sq_full_i : s1_free_i && tail_n == '0;
      shade_pkg::OpTriangle: hdr_ready = tri_bank_free_i;
      default:               hdr_ready = 1'b1;
    endcase
  end
  assign take_hdr    = hdr_here && hdr_ready;
  assign item_n      = tail_n + (take_hdr ? hdr_n : '0) + NW'(in_payload && !tri_payload);
  assign beat_done   = item_n == beat_left;
  assign cmd_ready_o = item_n != '0 && beat_done;
  assign hdr_fire    = cmd_valid_i && take_hdr;
  // The next word of the beat: after the item of this cycle, or word 0 of the next beat.
  if (PORT_WORDS > 1) begin : g_beat_pos
    logic item_fire;
    assign item_fire = cmd_valid_i && item_n != '0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        pos_q <= '0;
      end else if (item_fire) begin
        pos_q <= beat_done ? '0 : PosW'(NW'(pos_q) + item_n);
      end
    end
  end else begin : g_one_word_beat
    // A one-word port: every item takes the whole beat, so the next word is always word 0.
    assign pos_q = '0;
  end
  cmd_payload #(.PORT_WORDS(PORT_WORDS), .N_MAT_FIXED(N_MAT_FIXED)) u_payload (
    .clk_i, .rst_ni, .cmd_valid_i, .hdr_fire_i(hdr_fire), .hdr_i(cmd_word), .host_span_i(host_span),
    .pay_count_i(pay_count), .hdr_n_i(hdr_n), .tail_n_i(tail_n), .in_payload_o(in_payload),
    .tri_payload_o(tri_payload), .pay_idx_o, .pay_rem_o(pay_rem), .pay_mat_o, .span_pay_o,
    .cfg_valid_o, .cfg_table_o, .cfg_all_banks_o, .cfg_addr_o
  );
  assign {word_o, word_sel_o, hdr_op_o, hdr_pos_o, hdr_n_o} =
         {cmd_word, word_sel, hdr_op, hdr_pos, hdr_n};
  assign {hdr_fire_o, tail_n_o} = {hdr_fire, tail_n};
  assign span_fire_o = hdr_fire && hdr_op == shade_pkg::OpSpan;
  assign tri_fire_o  = hdr_fire && hdr_op == shade_pkg::OpTriangle;
  assign mat_fire_o  = hdr_fire && hdr_op == shade_pkg::OpMaterial;

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
  // A TRIANGLE's or host SPAN's tail starts its beat: the header takes its payload words to the
  // beat's end, and a tail takes all it has in the beat. coef_bank and start_bank rely on it.
  a_tail_starts_beat: assert property (@(posedge clk_i) disable iff (!rst_ni)
    tail_n != '0 |-> pos_q == '0);
`endif
`endif
endmodule
