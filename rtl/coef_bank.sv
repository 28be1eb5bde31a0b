// coef_bank: shade_unit's triangle queue registers - TRI_QUEUE banks of a triangle's origin and
// its N_COEF Taylor coefficients, written from the command port's beat, read by span setup.
//
// A beat word k carries payload word coef_idx[k] of a TRIANGLE: the tail of the current one
// (words 0 .. tail_n_i - 1, bank wr_bank_i) or the words after a TRIANGLE header
// taken now (bank next_bank_i). Every coefficient such a word holds loads from its field
// (shade_pkg::coef_word / coef_lsb), sign-extended to COEF_WL. Which bank a span reads and
// when a bank is free is the span queue's (rtl/span_queue.sv).
module coef_bank #(
  parameter int PORT_WORDS = 1,
  parameter int TRI_QUEUE  = 1,   // banks
  parameter int N_COEF     = 6,   // coefficients per triangle (6 per series)
  parameter int COEF_WL    = 36,
  parameter int COEF_T0_WL = COEF_WL,  // each term's width in the payload (coefficient packing)
  parameter int COEF_T1_WL = COEF_WL,
  parameter int COEF_T2_WL = COEF_WL,
  parameter int COEF_T3_WL = COEF_WL,
  parameter int COEF_T4_WL = COEF_WL,
  parameter int COEF_T5_WL = COEF_WL,
  parameter int OFS_BITS   = 17   // span setup's offset width (the origin's, read)
) (
  input  logic                                   clk_i,
  input  logic                                   cmd_valid_i,
  input  logic                                   tri_fire_i,  // a TRIANGLE header is taken ...
  // verilator lint_off UNUSEDSIGNAL
  // reason: packed coefficient terms may leave the top bits of a payload word unused, and span
  // setup reads only OFS_BITS bits of the origin
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,
  input  logic signed [15:0]                     hdr_xo_i,    // ... its origin
  input  logic signed [15:0]                     hdr_yo_i,
  // verilator lint_on UNUSEDSIGNAL
  // Counts and positions of beat words, 0..PORT_WORDS: $clog2(PORT_WORDS + 1) bits.
  input  logic [$clog2(PORT_WORDS+1)-1:0]        tail_n_i,
  input  logic [15:0]                            pay_idx_i,
  input  logic [$clog2(PORT_WORDS+1)-1:0]        hdr_pos_i,
  input  logic [$clog2(PORT_WORDS+1)-1:0]        hdr_n_i,
  input  logic [(TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1)-1:0] wr_bank_i,    // latest TRIANGLE's
  input  logic [(TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1)-1:0] next_bank_i,  // the next one's
  input  logic [(TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1)-1:0] rd_bank_i,    // span setup's
  output logic [N_COEF*COEF_WL-1:0]              coef_o,  // bank rd_bank_i, j at j * COEF_WL
  output logic signed [OFS_BITS-1:0]             xo_o,  // bank rd_bank_i's origin, sign-
  output logic signed [OFS_BITS-1:0]             yo_o   // extended or cut to OFS_BITS
);
  localparam int WordW      = shade_pkg::WordW;
  localparam int BankW      = TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1;
  localparam int CoefAW     = $clog2(TRI_QUEUE * N_COEF);
  localparam int NCoefWords = shade_pkg::coef_word(N_COEF - 1, COEF_T0_WL, COEF_T1_WL,
                                                   COEF_T2_WL, COEF_T3_WL, COEF_T4_WL,
                                                   COEF_T5_WL) + 1;  // TRIANGLE payload

  localparam int NW         = $clog2(PORT_WORDS + 1);  // a count of beat words
  localparam int AW         = $clog2(NCoefWords + PORT_WORDS);  // a payload index + offset

  logic signed [OFS_BITS-1:0] xo_q [TRI_QUEUE];  // each bank's origin, as span setup reads it
  logic signed [OFS_BITS-1:0] yo_q [TRI_QUEUE];

  // Beat word k carries payload word coef_idx[k] of a TRIANGLE (coef_we[k]). A tail starts its
  // beat (cmd_decoder's a_tail_starts_beat: a header takes its payload to the beat's end), so a
  // tail word's index is pay_idx_i + k <= the payload's last: it never wraps in 16 bits and is
  // below NCoefWords only if pay_idx_i is. AW bits hold every index that is written.
  logic                  pay_in;  // pay_idx_i < NCoefWords
  logic [AW-1:0]         coef_idx [PORT_WORDS];
  logic [PORT_WORDS-1:0] coef_we, coef_tail;
  logic [BankW-1:0]      coef_bank [PORT_WORDS];
  assign pay_in = pay_idx_i < 16'(NCoefWords);
  always_comb begin
    for (int k = 0; k < PORT_WORDS; k++) begin
      coef_tail[k] = NW'(k) < tail_n_i;
      coef_idx[k]  = coef_tail[k] ? AW'(pay_idx_i) + AW'(k) : AW'(k) - AW'(hdr_pos_i) - AW'(1);
      coef_we[k]   = (cmd_valid_i && coef_tail[k] && pay_in ||
                      tri_fire_i && NW'(k) > hdr_pos_i &&
                      (NW + 1)'(k) < (NW + 1)'(hdr_pos_i) + (NW + 1)'(hdr_n_i)) &&
                     coef_idx[k] < AW'(NCoefWords);
      coef_bank[k] = coef_tail[k] ? wr_bank_i : next_bank_i;
    end
  end

  // Unpacked coefficients of one width (every term wider than half a word): payload word i is
  // coefficient i, so each beat word writes at most one coefficient, at its payload index. The
  // packed layout's per-coefficient selection below would be evaluated on every cycle for
  // nothing (a simulator's cost, not the hardware's: the same registers load the same values).
  localparam bit CoefEach = NCoefWords == N_COEF && COEF_T1_WL == COEF_T0_WL &&
                            COEF_T2_WL == COEF_T0_WL && COEF_T3_WL == COEF_T0_WL &&
                            COEF_T4_WL == COEF_T0_WL && COEF_T5_WL == COEF_T0_WL;
  if (CoefEach) begin : g_coef_each
    // An array, not one packed vector: a partial write of a 1000+-bit vector costs the
    // Verilated model a full copy every clock.
    logic [COEF_WL-1:0] coef_q [TRI_QUEUE*N_COEF];  // bank b at b * N_COEF
    logic [CoefAW-1:0]  rd_base;  // bank rd_bank_i's first coefficient
    assign rd_base = CoefAW'(rd_bank_i * N_COEF);
    always_ff @(posedge clk_i) begin
      for (int k = 0; k < PORT_WORDS; k++) begin
        if (coef_we[k]) begin
          coef_q[CoefAW'(coef_bank[k] * N_COEF + 32'(coef_idx[k]))] <=
              COEF_WL'($signed(cmd_data_i[k*WordW +: COEF_T0_WL]));
        end
      end
    end
    for (genvar j = 0; j < N_COEF; j++) begin : g_read
      assign coef_o[j*COEF_WL +: COEF_WL] = coef_q[rd_base + CoefAW'(j)];
    end
  end else begin : g_coef_packed
    // Coefficient j loads from the one beat word (if any) that carries its payload word, and is
    // kept in its term's width W (sign-extended to COEF_WL as span setup reads it). One process
    // per coefficient: Verilator unrolls a loop of delayed array writes only up to 64.
    for (genvar j = 0; j < N_COEF; j++) begin : g_coef_load
      localparam int Word = shade_pkg::coef_word(j, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL,
                                                 COEF_T3_WL, COEF_T4_WL, COEF_T5_WL);
      localparam int Lsb  = shade_pkg::coef_lsb(j, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL,
                                                COEF_T3_WL, COEF_T4_WL, COEF_T5_WL);
      localparam int W    = shade_pkg::coef_term_wl(j, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL,
                                                    COEF_T3_WL, COEF_T4_WL, COEF_T5_WL);
      logic               load;
      logic [BankW-1:0]   bank;
      logic [W-1:0]       value;
      logic [W-1:0]       q [TRI_QUEUE];  // each bank's coefficient j
      always_comb begin
        load  = 1'b0;
        bank  = '0;
        value = '0;
        for (int k = 0; k < PORT_WORDS; k++) begin
          if (coef_we[k] && coef_idx[k] == AW'(Word)) begin
            load  = 1'b1;
            bank  = coef_bank[k];
            value = cmd_data_i[k*WordW + Lsb +: W];
          end
        end
      end
      always_ff @(posedge clk_i) begin
        if (load) q[bank] <= value;
      end
      assign coef_o[j*COEF_WL +: COEF_WL] = COEF_WL'($signed(q[rd_bank_i]));
    end
  end

  always_ff @(posedge clk_i) begin
    if (tri_fire_i) begin
      xo_q[next_bank_i] <= OFS_BITS'(hdr_xo_i);
      yo_q[next_bank_i] <= OFS_BITS'(hdr_yo_i);
    end
  end
  assign xo_o = xo_q[rd_bank_i];
  assign yo_o = yo_q[rd_bank_i];

`ifndef SYNTHESIS
  initial begin
    if (TRI_QUEUE < 1 || TRI_QUEUE > 8)
      $fatal(1, "coef_bank: TRI_QUEUE %0d is not 1..8", TRI_QUEUE);
    for (int t = 0; t < 6; t++) begin
      if (shade_pkg::coef_term_wl(t, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL, COEF_T3_WL, COEF_T4_WL,
                                  COEF_T5_WL) > COEF_WL ||
          shade_pkg::coef_term_wl(t, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL, COEF_T3_WL, COEF_T4_WL,
                                  COEF_T5_WL) < 2)
        $fatal(1, "coef_bank: COEF_T%0d_WL must be 2..COEF_WL (%0d)", t, COEF_WL);
    end
  end
`endif
endmodule
