// span_queue: the SPAN headers between shade_unit's command decoder and span setup, with the
// triangle queue's bank bookkeeping (which coefficient bank a TRIANGLE writes, which one each
// span reads, and how many queued spans read each).
//
// TRI_QUEUE > 1: a ring of 4 * TRI_QUEUE spans (CycleConfig::span_queue()), each with its
// triangle's bank and its material bank; a run of SPAN headers of one beat enters together,
// setup stage 1 takes the head whenever it is free. A TRIANGLE waits until no queued span reads
// the bank it would write. TRI_QUEUE = 1: no queue, one bank; a SPAN header goes straight into
// setup stage 1.
module span_queue #(
  parameter int PORT_WORDS = 1,
  parameter int XY_BITS    = 12,
  parameter int TRI_QUEUE  = 1
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,
  input  logic                                   span_fire_i,  // SPAN headers taken ...
  input  logic [$clog2(PORT_WORDS+1)-1:0]        span_n_i,     // ... this many
  input  logic [$clog2(PORT_WORDS+1)-1:0]        hdr_pos_i,    // ... from this beat word on
  input  logic [(PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1)-1:0] word_sel_i,  // decoder's word
  input  logic                                   tri_fire_i,   // a TRIANGLE header is taken
  input  logic                                   mat_wr_i,     // the latest MATERIAL's bank
  input  logic                                   s1_free_i,    // setup stage 1 takes a span
  output logic                                   full_o,
  output logic [15:0]                            room_o,       // free entries
  output logic                                   empty_o,
  output logic                                   s1_load_o,    // a span enters stage 1 ...
  output logic [3*XY_BITS+1:0]                   s1_span_o,    // ... this one: {y, x0, len, last}
  output logic [(TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1)-1:0] rd_bank_o,    // ... its bank
  output logic                                   s1_mat_o,     // ... its material bank
  output logic [(TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1)-1:0] wr_bank_o,    // latest TRIANGLE's
  output logic [(TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1)-1:0] next_bank_o,  // the next one's
  output logic                                   tri_bank_free_o  // no queued span reads it
);
  localparam int WordW  = shade_pkg::WordW;
  localparam int SpanW  = 3 * XY_BITS + 2;  // shade_unit's span_t (len: XY_BITS + 1 bits)
  localparam int BankW  = TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1;
  localparam bit Queued = TRI_QUEUE > 1;
  localparam int SpanQ  = Queued ? 4 * TRI_QUEUE : 1;  // = CycleConfig::span_queue()
  localparam int NW     = $clog2(PORT_WORDS + 1);  // a count of beat words, 0..PORT_WORDS
  localparam int PosW   = PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1;

  // Each beat word read as a SPAN header, span k at [k*SpanW +: SpanW]: {y, x0, len, last},
  // MSB first; len in XY_BITS + 1 bits, as a span is 1..2^XY_BITS pixels long (a longer one
  // does not fit the screen: CommandStream::validate rejects it). One flat vector: Yosys 0.23
  // leaves an element of an unpacked array of packed structs assigned in a generate loop
  // undriven, and Icarus 11 cannot elaborate a member select of one.
  logic [PORT_WORDS*SpanW-1:0] beat_span;
  for (genvar k = 0; k < PORT_WORDS; k++) begin : g_beat_span
    logic [WordW-1:0] w;
    assign w = cmd_data_i[k*WordW +: WordW];
    assign beat_span[k*SpanW +: SpanW] = {w[shade_pkg::HighLsb +: XY_BITS],
                                          w[shade_pkg::MidLsb +: XY_BITS],
                                          w[shade_pkg::CountLsb +: XY_BITS + 1],
                                          w[shade_pkg::SpanLastBit]};
  end

  // Beat word k's span: a multiplexer (Yosys makes an indexed part-select [k*SpanW +: SpanW] a
  // shifter by k*SpanW, several times the LUTs).
  function automatic logic [SpanW-1:0] beat_at(input logic [PORT_WORDS*SpanW-1:0] b,
                                               input logic [PosW-1:0] k);
    beat_at = b[SpanW-1:0];
    for (int i = 1; i < PORT_WORDS; i++) if (k == PosW'(i)) beat_at = b[i*SpanW +: SpanW];
  endfunction

  if (Queued) begin : g_span_queue
    localparam int PtrW = $clog2(SpanQ);
    localparam int CntW = $clog2(SpanQ + 1);
    // Each queued span (as span_t's bits: Yosys 0.23 misreads an unpacked array of packed
    // structs written through a computed index) and its triangle's bank.
    logic [SpanW-1:0] sq_span_q [SpanQ];
    logic [BankW-1:0] sq_bank_q [SpanQ];
    logic             sq_mat_q [SpanQ];   // each queued span's material bank
    logic [PtrW-1:0]  head_q, tail_q;
    logic [CntW-1:0]  count_q;  // (SpanQ >= PORT_WORDS: CntW >= NW)
    logic [CntW-1:0]  bank_spans_q [TRI_QUEUE];  // queued spans per bank
    logic [BankW-1:0] wr_bank_q;
    logic             sq_pop;
    assign full_o          = count_q == CntW'(SpanQ);
    assign room_o          = 16'(SpanQ) - 16'(count_q);
    assign empty_o         = count_q == '0;
    assign sq_pop          = !empty_o && s1_free_i;
    assign s1_load_o       = sq_pop;
    assign s1_span_o       = sq_span_q[head_q];
    assign rd_bank_o       = sq_bank_q[head_q];
    assign s1_mat_o        = sq_mat_q[head_q];
    assign wr_bank_o       = wr_bank_q;
    assign next_bank_o     = wr_bank_q == BankW'(TRI_QUEUE - 1) ? '0 : wr_bank_q + BankW'(1);
    assign tri_bank_free_o = bank_spans_q[next_bank_o] == '0;
    // The ring's index n entries after i (n <= PORT_WORDS <= SpanQ).
    function automatic logic [PtrW-1:0] ring_add(input logic [PtrW-1:0] i,
                                                 input logic [NW-1:0] n);
      logic [PtrW+NW-1:0] sum;
      sum = (PtrW + NW)'(i) + (PtrW + NW)'(n);
      ring_add = PtrW'(sum >= (PtrW + NW)'(SpanQ) ? sum - (PtrW + NW)'(SpanQ) : sum);
    endfunction
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        head_q    <= '0;
        tail_q    <= '0;
        count_q   <= '0;
        wr_bank_q <= '0;
        for (int b = 0; b < TRI_QUEUE; b++) bank_spans_q[b] <= '0;
      end else begin
        if (span_fire_i) tail_q <= ring_add(tail_q, span_n_i);
        if (sq_pop)      head_q <= head_q == PtrW'(SpanQ - 1) ? '0 : head_q + PtrW'(1);
        count_q <= count_q + (span_fire_i ? CntW'(span_n_i) : '0) - CntW'(sq_pop);
        for (int b = 0; b < TRI_QUEUE; b++) begin
          bank_spans_q[b] <= bank_spans_q[b]
                           + (span_fire_i && wr_bank_q == BankW'(b) ? CntW'(span_n_i) : '0)
                           - CntW'(sq_pop && rd_bank_o == BankW'(b));
        end
        if (tri_fire_i) wr_bank_q <= next_bank_o;
      end
    end
    // Entry e takes the span o = e - tail_q (mod SpanQ) places into the run, if o < span_n_i:
    // beat word hdr_pos_i + o. When PORT_WORDS divides SpanQ, that word depends on e only
    // through e mod PORT_WORDS, so entries PORT_WORDS apart share one select of the beat.
    logic [SpanQ-1:0]      sq_we;   // entry e is written ...
    logic [SpanQ*PosW-1:0] sq_sel;  // ... from this beat word, at [e*PosW +: PosW]
    for (genvar e = 0; e < SpanQ; e++) begin : g_entry
      logic [PtrW:0]   diff;  // e + SpanQ - tail_q: 1..2 SpanQ
      logic [PtrW-1:0] o;
      assign diff = (PtrW + 1)'(e + SpanQ) - (PtrW + 1)'(tail_q);
      assign o    = PtrW'(diff >= (PtrW + 1)'(SpanQ) ? diff - (PtrW + 1)'(SpanQ) : diff);
      assign sq_we[e] = span_fire_i && (PtrW + NW)'(o) < (PtrW + NW)'(span_n_i);
      if (PORT_WORDS == 1) begin : g_one
        assign sq_sel[e*PosW +: PosW] = '0;
      end else if (SpanQ % PORT_WORDS == 0) begin : g_shared
        assign sq_sel[e*PosW +: PosW] = PosW'(hdr_pos_i) + PosW'(e % PORT_WORDS) - PosW'(tail_q);
      end else begin : g_own
        assign sq_sel[e*PosW +: PosW] = PosW'(hdr_pos_i + NW'(o));
      end
    end
    always_ff @(posedge clk_i) begin
      for (int e = 0; e < SpanQ; e++) begin
        if (sq_we[e]) begin
          sq_span_q[e] <= beat_at(beat_span, sq_sel[e*PosW +: PosW]);
          sq_bank_q[e] <= wr_bank_q;
          sq_mat_q[e]  <= mat_wr_i;
        end
      end
    end
    // verilator lint_off UNUSEDSIGNAL
    logic unused_sel;  // reason: a queued span is written from hdr_pos_i on, not word_sel_i
    assign unused_sel = ^word_sel_i ^ (^hdr_pos_i);  // (and may read only hdr_pos_i's low bits)
    // verilator lint_on UNUSEDSIGNAL

`ifndef SYNTHESIS
`ifdef VERILATOR
    // The ring never overflows or underflows, and its count is what entered less what left.
    a_no_overflow: assert property (@(posedge clk_i) disable iff (!rst_ni)
      span_fire_i |-> 32'(count_q) + 32'(span_n_i) <= SpanQ);
    a_count_range: assert property (@(posedge clk_i) disable iff (!rst_ni)
      32'(count_q) <= SpanQ);
    a_pop_nonempty: assert property (@(posedge clk_i) disable iff (!rst_ni) sq_pop |-> !empty_o);
    a_ring_consistent: assert property (@(posedge clk_i) disable iff (!rst_ni)
      32'(tail_q) == (32'(head_q) + 32'(count_q)) % SpanQ);
    logic [31:0] bank_sum;
    always_comb begin
      bank_sum = '0;
      for (int b = 0; b < TRI_QUEUE; b++) bank_sum = bank_sum + 32'(bank_spans_q[b]);
    end
    a_banks_sum_to_count: assert property (@(posedge clk_i) disable iff (!rst_ni)
      bank_sum == 32'(count_q));
    // A TRIANGLE never overwrites a bank a queued span still reads.
    a_tri_bank_free: assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_fire_i |-> tri_bank_free_o);
`endif
`endif
  end else begin : g_no_span_queue
    // One bank, and SPAN headers go straight into setup stage 1.
    assign full_o          = 1'b0;
    assign room_o          = 16'd1;  // unused: SPAN headers go one at a time
    assign empty_o         = 1'b1;
    assign s1_load_o       = span_fire_i;
    assign s1_span_o       = beat_at(beat_span, word_sel_i);  // (one-word port: no select)
    assign rd_bank_o       = '0;
    assign s1_mat_o        = mat_wr_i;
    assign next_bank_o     = '0;
    assign wr_bank_o       = '0;
    assign tri_bank_free_o = 1'b1;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_in;  // reason: without a queue nothing is stored, so these are not read
    assign unused_in = clk_i ^ rst_ni ^ (^span_n_i) ^ (^hdr_pos_i) ^ tri_fire_i ^ s1_free_i;
    // verilator lint_on UNUSEDSIGNAL
  end

`ifndef SYNTHESIS
  initial begin
    // A span's length (1..2^XY_BITS) is kept in XY_BITS + 1 bits of its 16-bit header field.
    if (XY_BITS < 1 || XY_BITS + 1 > shade_pkg::FieldW)
      $fatal(1, "span_queue: XY_BITS %0d is not 1..%0d", XY_BITS, shade_pkg::FieldW - 1);
  end
`endif
endmodule
