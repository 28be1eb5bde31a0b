// cmd_payload: cmd_decoder's payload FSM - which header's payload words are being taken, and how
// far. A TRIANGLE's (or, with host span setup, a SPAN's) words arrive as the tail of each beat,
// several per cycle; a MATERIAL's or TABLE's one word per cycle. MATERIAL and TABLE words leave
// as configuration writes for the specular slots (MATERIAL exponent at index 0, unit parameters
// from 1, TABLE entries at base + index).
//
// Timing (docs/rtl.md): what a header starts is worked out for every word of the beat at once, from
// that word alone (g_start), and the header's word (hdr_sel_i, one-hot) picks one; the beat's
// first item does not wait for the header's word to be multiplexed and decoded. The tail's length
// and whether a header follows it in the beat are kept as registered copies of what pay_rem_q
// says (tri_q, tail_q, tail_hdr_q; a_*_copy below), so the decoder reads them straight from flops.
module cmd_payload #(
  parameter int PORT_WORDS  = 1,     // 64-bit words per beat: 1, 2, 4 or 8
  parameter int N_MAT_FIXED = 2,     // MATERIAL payload words before the slots' (ambient, colour)
  parameter bit HOST_SETUP  = 1'b0,  // a SPAN header brings START_WORDS payload words
  parameter int START_WORDS = 1
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,
  input  logic                                   cmd_valid_i,
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,   // the beat
  input  logic [PORT_WORDS-1:0]                  hdr_sel_i,    // the header's word (one-hot)
  input  logic                                   hdr_fire_i,   // the header is taken
  output logic                                   in_payload_o,  // payload words are due
  output logic                                   tri_payload_o, // ... as a tail (TRIANGLE or SPAN)
  output logic [$clog2(PORT_WORDS+1)-1:0]        tail_n_o,      // ... this many in the beat
  output logic                                   tail_hdr_o,    // ... and a header after them
  output logic [15:0]                            pay_idx_o,     // index of the next payload word
  output logic                                   pay_mat_o,     // a MATERIAL payload word taken
  output logic                                   span_pay_o,    // the tail is a SPAN's (host)
  output logic                                   cfg_valid_o,
  output logic                                   cfg_table_o,
  output logic                                   cfg_all_banks_o,  // a TABLE not per-material
  output logic [15:0]                            cfg_addr_o
);
  localparam int WordW = shade_pkg::WordW;
  localparam int NW    = $clog2(PORT_WORDS + 1);  // a count of beat words: 0..PORT_WORDS
  // Which payload is being taken (the model's CmdPayload::Payload). Codes, not an enum: the
  // header's is picked by AND-OR over the beat's words.
  localparam logic [2:0] PaySkip = 3'd0, PayMaterial = 3'd1, PayTriangle = 3'd2, PayTable = 3'd3,
                         PaySpan = 3'd4;
  logic          in_payload_q, in_payload_d;
  logic [2:0]    pay_op_q, pay_op_d;
  logic [15:0]   pay_idx_q, pay_idx_d, pay_rem_q, pay_rem_d;
  logic          tbl_mat_q, tbl_mat_d;  // the TABLE being loaded is per-material
  // cfg_addr_o = cfg_base_q + pay_idx_q: a TABLE's base, else -N_MAT_FIXED (set by the header,
  // so no select sits in front of the adder).
  logic [15:0]   cfg_base_q, cfg_base_d;
  // Registered copies of what the state above says (a_*_copy below; the model keeps none):
  logic          tri_q, tri_d;            // in_payload_q && a TRIANGLE's or SPAN's payload
  logic [NW-1:0] tail_q, tail_d;          // tri_q ? min(pay_rem_q, PORT_WORDS) : 0
  logic          tail_hdr_q, tail_hdr_d;  // tri_q && pay_rem_q < PORT_WORDS
  logic          pay_fire;
  logic [15:0]   pay_take;  // payload words taken: the tail, or one MATERIAL / TABLE word
  logic          pay_last;  // ... the payload's last
  logic          more_after;  // a tail that is not the payload's last: more in the next beat

  // The words a header takes with it (s_idx below) are at most max(After, START_WORDS) for any
  // word, so start_w carries them in IdxW bits, not pay_idx's 16: the rest would be constant 0.
  localparam int IdxMax = HOST_SETUP && START_WORDS > PORT_WORDS - 1 ? START_WORDS
                                                                      : PORT_WORDS - 1;
  localparam int IdxW   = IdxMax < 2 ? 1 : $clog2(IdxMax + 1);
  // The state fields a header starts, in this order, StW bits:
  // {in_payload, pay_op, pay_idx (IdxW bits), pay_rem, cfg_base, tbl_mat, tri, tail, tail_hdr}.
  localparam int StW = 1 + 3 + IdxW + 16 + 16 + 1 + 1 + NW + 1;
  // What a header in word k starts: its payload words follow it, as many as the beat holds
  // (After) come with it (cmd_decoder's hdr_n - 1), and a TRIANGLE's or host SPAN's rest comes
  // as a tail per beat. One per word (word k at k * StW), picked by hdr_sel_i below.
  logic [PORT_WORDS*StW-1:0] start_w;
  for (genvar k = 0; k < PORT_WORDS; k++) begin : g_start
    localparam int          Aft   = PORT_WORDS - 1 - k;
    localparam logic [15:0] After = 16'(Aft);
    // A host SPAN's START_WORDS are known: its rest and whether it has one are constants.
    localparam bit          HostMore  = START_WORDS > Aft;
    localparam bit          HostShort = START_WORDS < Aft + PORT_WORDS;
    localparam logic [15:0] HostRest  = 16'(START_WORDS - Aft);
    logic [7:0]    op;
    logic [15:0]   count, rest, w_base;
    logic          host_span, tail_kind, more, short_rest;
    logic          s_in, s_tri, s_tail_hdr;  // the state it starts: fields of start_w
    logic [2:0]    s_op;
    logic [IdxW-1:0] s_idx;
    logic [15:0]   s_rem, s_cfg_base;
    logic [NW-1:0] s_tail;
    assign op         = cmd_data_i[k*WordW + shade_pkg::OpcodeLsb +: 8];
    assign count      = cmd_data_i[k*WordW + shade_pkg::CountLsb +: shade_pkg::FieldW];
    assign w_base     = cmd_data_i[k*WordW + shade_pkg::MidLsb +: shade_pkg::FieldW];  // TABLE
    assign host_span  = HOST_SETUP && op == shade_pkg::OpSpan;
    assign tail_kind  = op == shade_pkg::OpTriangle || host_span;
    // Words left for the next beats (more), this many (rest), fewer than a beat (short_rest).
    assign more       = host_span ? HostMore : op == shade_pkg::OpTriangle && count > After;
    assign rest       = host_span ? HostRest : count - After;
    assign short_rest = host_span ? HostShort : count < 16'(Aft + PORT_WORDS);
    always_comb begin
      unique case (op)
        shade_pkg::OpMaterial: s_op = PayMaterial;
        shade_pkg::OpTriangle: s_op = PayTriangle;
        shade_pkg::OpTable:    s_op = PayTable;
        shade_pkg::OpSpan:     s_op = host_span ? PaySpan : PaySkip;
        default:               s_op = PaySkip;  // END_FRAME, unknown: no payload
      endcase
    end
    assign s_in       = tail_kind ? more : (op == shade_pkg::OpMaterial ||
                                            op == shade_pkg::OpTable) && count != 16'd0;
    // The words taken with the header, min(payload words, After).
    // (count here is a TRIANGLE's that ends in this beat: at most After.)
    assign s_idx      = !tail_kind ? '0 : more ? IdxW'(Aft) : host_span ? IdxW'(START_WORDS)
                                                             : IdxW'(count);
    assign s_rem      = !tail_kind ? count : more ? rest : 16'd0;
    assign s_cfg_base = op == shade_pkg::OpTable ? w_base : 16'd0 - 16'(N_MAT_FIXED);
    assign s_tri      = more;
    assign s_tail     = !more ? '0 : short_rest ? NW'(rest) : NW'(PORT_WORDS);
    assign s_tail_hdr = more && short_rest;
    // (Plain signals only in the concatenation: Yosys 0.23 sizes expressions in one wrongly.)
    assign start_w[k*StW +: StW] = {s_in, s_op, s_idx, s_rem, s_cfg_base,
                                    cmd_data_i[k*WordW + shade_pkg::TableMatBit], s_tri, s_tail,
                                    s_tail_hdr};
  end

  assign pay_fire   = cmd_valid_i && in_payload_q;
  assign pay_take   = tri_q ? 16'(tail_q) : 16'd1;
  assign pay_last   = pay_take == pay_rem_q;
  assign more_after = tri_q && !pay_last;  // then the tail was PORT_WORDS words
  // The next state: what the header starts, else (pay_fire) the tail or one MATERIAL / TABLE
  // word taken, else held. hdr_fire_i picks last: it comes late (a SPAN waits on the start bank,
  // after the engines' load), so nothing else waits on it.
  logic             hdr_in;  // what the header starts, pay_idx in IdxW bits
  logic [2:0]       hdr_op;
  logic [IdxW-1:0]  hdr_idx;
  logic [StW-IdxW-5:0] hdr_rest;  // pay_rem onwards
  logic [StW-IdxW+15:0] pay_next;
  logic [StW-1:0]   hdr_start;  // the header's word's start_w
  onehot_mux #(.N(PORT_WORDS), .W(StW)) u_pick_start (
    .sel_i(hdr_sel_i), .in_i(start_w), .out_o(hdr_start)
  );
  assign {hdr_in, hdr_op, hdr_idx, hdr_rest} = hdr_start;
  // (Each field a signal of its own: Yosys 0.23 sizes expressions inside a concatenation wrongly.)
  logic [15:0]   pay_idx_p, pay_rem_p;  // after the payload words taken
  logic [NW-1:0] tail_p;
  logic          tail_hdr_p;
  assign pay_idx_p  = pay_idx_q + pay_take;
  assign pay_rem_p  = pay_rem_q - pay_take;
  // After a PORT_WORDS tail, pay_rem_q - PORT_WORDS words to come: the next tail.
  assign tail_hdr_p = more_after && pay_rem_q < 16'(2 * PORT_WORDS);
  assign tail_p     = !more_after ? '0 : tail_hdr_p ? NW'(pay_rem_q) - NW'(PORT_WORDS)
                                                    : NW'(PORT_WORDS);
  always_comb begin
    pay_next = {in_payload_q, pay_op_q, pay_idx_q, pay_rem_q, cfg_base_q, tbl_mat_q, tri_q,
                tail_q, tail_hdr_q};
    if (pay_fire) begin
      pay_next = {!pay_last, pay_op_q, pay_idx_p, pay_rem_p, cfg_base_q, tbl_mat_q, more_after,
                  tail_p, tail_hdr_p};
    end
  end
  always_comb begin
    if (hdr_fire_i) begin
      {in_payload_d, pay_op_d} = {hdr_in, hdr_op};
      pay_idx_d = 16'(hdr_idx);
      {pay_rem_d, cfg_base_d, tbl_mat_d, tri_d, tail_d, tail_hdr_d} = hdr_rest;
    end else begin
      {in_payload_d, pay_op_d, pay_idx_d, pay_rem_d, cfg_base_d, tbl_mat_d, tri_d, tail_d,
       tail_hdr_d} = pay_next;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      in_payload_q <= 1'b0;
      pay_op_q     <= PaySkip;
      pay_idx_q    <= 16'd0;
      pay_rem_q    <= 16'd1;
      cfg_base_q   <= 16'd0 - 16'(N_MAT_FIXED);
      tbl_mat_q    <= 1'b0;
      tri_q        <= 1'b0;
      tail_q       <= '0;
      tail_hdr_q   <= 1'b0;
    end else begin
      in_payload_q <= in_payload_d;
      pay_op_q     <= pay_op_d;
      pay_idx_q    <= pay_idx_d;
      pay_rem_q    <= pay_rem_d;
      cfg_base_q   <= cfg_base_d;
      tbl_mat_q    <= tbl_mat_d;
      tri_q        <= tri_d;
      tail_q       <= tail_d;
      tail_hdr_q   <= tail_hdr_d;
    end
  end
  assign {in_payload_o, tri_payload_o, tail_n_o, tail_hdr_o} =
         {in_payload_q, tri_q, tail_q, tail_hdr_q};
  assign pay_idx_o       = pay_idx_q;
  assign cfg_table_o     = pay_op_q == PayTable;
  assign cfg_all_banks_o = cfg_table_o && !tbl_mat_q;
  assign cfg_valid_o     = pay_fire && (cfg_table_o ||
                           (pay_op_q == PayMaterial && pay_idx_q >= 16'(N_MAT_FIXED)));
  assign cfg_addr_o      = cfg_base_q + pay_idx_q;
  assign pay_mat_o       = pay_fire && pay_op_q == PayMaterial;
  assign span_pay_o      = in_payload_q && pay_op_q == PaySpan;

`ifndef SYNTHESIS
`ifdef VERILATOR
  // The registered copies say what the payload state says.
  a_tri_copy: assert property (@(posedge clk_i) disable iff (!rst_ni)
    tri_q == (in_payload_q && (pay_op_q == PayTriangle || pay_op_q == PaySpan)));
  a_tail_copy: assert property (@(posedge clk_i) disable iff (!rst_ni)
    tail_q == (!tri_q ? NW'(0) : pay_rem_q < 16'(PORT_WORDS) ? NW'(pay_rem_q) : NW'(PORT_WORDS)));
  a_tail_hdr_copy: assert property (@(posedge clk_i) disable iff (!rst_ni)
    tail_hdr_q == (tri_q && pay_rem_q < 16'(PORT_WORDS)));
  // (A TABLE's base is kept only in cfg_base_q.)
  a_cfg_base: assert property (@(posedge clk_i) disable iff (!rst_ni)
    cfg_table_o || cfg_base_q == 16'd0 - 16'(N_MAT_FIXED));
`endif
`endif
endmodule
