// wpow_unit: W_m(t) = (zeta (t - 1) + 1)^m by repeated squaring (model/wpow_unit.h, class
// WpowUnit; Romanyuk et al.). zeta and the pre-scale live in the series (host setup).
//
// SPEC_PARAMS's slots (decoded below) mirror WpowConfig: MAX_M (m, a power of two 1..32;
// K = log2(m) squaring stages), BASE_BITS (B, fraction bits of the base and of every square),
// TIMING (UnitTiming: 0 pipelined, 1 iterative), SQUARE_STAGES (registers per squaring, 1 or
// 2); SERIES_WL/IWL (fs = SERIES_WL - SERIES_IWL >= 1); OUT_WL/IWL/QUANT/OVERFLOW (the specular
// out format, unsigned).
//
// Stages, in the model's order:
//   0. BASE      b = quantize(series << shift, unsigned 1.B, truncate, saturate); b = min(b, 1.0)
//                (the clamp is correctness: a negative base squared would come back large).
//   1..K SQUARE  b = quantize(b * b, 2B -> B fraction bits, truncate). Stages 1..K-s pass b
//                through (bypass), the last s square (s = squarings, per material).
//   K+1. OUTPUT  quantize(b, B fraction bits) into the out format: combinational.
// b <= 1.0 throughout, so a square never overflows u1.B (the model's saturation never fires).
//
// Timing, LATENCY = K * SQUARE_STAGES + 1 (shade_pkg::spec_latency):
//   TIMING 0 (pipelined): K * SQUARE_STAGES + 1 registers (base, one or two per squarer), all
//            enabled by en_i (advance): spec_o shows the result of the series sampled at the
//            LATENCY-th most recent en_i edge. One pixel per cycle; busy_o = 0. With
//            SQUARE_STAGES 2 each squaring takes two (wpow_split_square: its partial squares
//            registered, then their sum).
//   TIMING 1 (iterative): one working register and one squarer. en_i while !busy_o loads the
//            base (cycle c); cycles c+1 .. c+K run the K steps (bypass or square), busy_o high
//            then (en_i ignored); the result is on spec_o from cycle c+K+1 until the edge that
//            ends the next start cycle. II = K + 1 (1 when K = 0).
//
// Configuration (the specular slot's cfg port, MATERIAL words, cfg_table_i = 0):
//   cfg_addr_i 0 = exponent word: resets shift = 0, squarings = K (empty unit_params);
//   1 = unit_params[0] = shift (0..fs); 2 = unit_params[1] = squarings s (0..K).
// Out-of-range values are the model's error; the hardware takes the low bits.
// Material banks (BANKS = 2, shade_unit's MATERIAL_BUFFERS): shift and squarings are doubled;
// MATERIAL words write bank cfg_bank_i. The bank tag bank_i of the pixel on series_i travels
// with it through the unit's own stages, so each stage reads the bank of the pixel it holds.
module wpow_unit #(
  // The unit's fields, packed (shade_pkg::SpecSlots slots; decoded below). The default is
  // the model's default WpowConfig: m 16, B 16, pipelined.
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS =
      {{(shade_pkg::SpecSlots - 4){32'd0}}, 32'd1, 32'd0, 32'd16, 32'd16},
  parameter int SERIES_WL    = 32,
  parameter int SERIES_IWL   = 4,
  parameter int OUT_WL       = 17,
  parameter int OUT_IWL      = 1,
  parameter int OUT_QUANT    = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int OUT_OVERFLOW = 0,  // Overflow: 0 saturate, 1 wrap
  parameter int CFG_ADDR_W   = 16,
  parameter int BANKS        = 1   // material banks, 1 or 2
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  en_i,
  input  logic [SERIES_WL-1:0]  series_i,
  input  logic                  bank_i,      // material bank of the pixel on series_i
  input  logic                  cfg_valid_i,
  input  logic                  cfg_bank_i,  // material bank the MATERIAL words write
  input  logic                  cfg_table_i,
  input  logic [CFG_ADDR_W-1:0] cfg_addr_i,
  // verilator lint_off UNUSEDSIGNAL
  input  logic [63:0]           cfg_data_i,  // only the low shift / squarings bits are used
  // verilator lint_on UNUSEDSIGNAL
  output logic [OUT_WL-1:0]     spec_o,
  output logic                  busy_o
);
  // WpowConfig from SPEC_PARAMS: the slots of the "wpow" row of model/specular_units.cpp
  // (slots 0 and 2 also set shade_pkg::spec_latency / spec_interval). The names are the
  // parameters' they replace, so the body reads as before.
  localparam int MAX_M     = shade_pkg::spec_slot(SPEC_PARAMS, 0);  // wpow.max_m
  localparam int BASE_BITS = shade_pkg::spec_slot(SPEC_PARAMS, 1);  // wpow.base_bits
  localparam int TIMING    = shade_pkg::spec_slot(SPEC_PARAMS, 2);  // wpow.timing code
  localparam int SQUARE_STAGES = shade_pkg::spec_slot(SPEC_PARAMS, 3);  // wpow.square_stages
`ifndef SYNTHESIS
  initial begin
    if (BASE_BITS < 2) $fatal(1, "wpow_unit: BASE_BITS %0d < 2", BASE_BITS);
    if (TIMING != 0 && TIMING != 1) $fatal(1, "wpow_unit: TIMING %0d is not 0 or 1", TIMING);
    if (SQUARE_STAGES != 1 && SQUARE_STAGES != 2)
      $fatal(1, "wpow_unit: SQUARE_STAGES %0d is not 1 or 2", SQUARE_STAGES);
    if (SQUARE_STAGES != 1 && TIMING != 0)
      $fatal(1, "wpow_unit: SQUARE_STAGES 2 needs TIMING 0 (pipelined)");
  end
`endif
  localparam int K       = $clog2(MAX_M);
  localparam int B       = BASE_BITS;
  localparam int BW      = B + 1;                    // unsigned 1.B
  localparam int Fs      = SERIES_WL - SERIES_IWL;
  localparam int ShiftW  = $clog2(Fs + 1);
  localparam int SqW     = $clog2(K + 1) > 0 ? $clog2(K + 1) : 1;
  localparam int XW      = SERIES_WL + Fs;           // series << shift for any shift 0..fs
  localparam int BaseDrop = Fs - B;
  localparam int BaseRndW = XW + 1 - BaseDrop;
  localparam int OutDrop = B - (OUT_WL - OUT_IWL);
  localparam int OutRndW = BW + 2 - OutDrop;
  localparam logic [BW-1:0] One = BW'(1) << B;

  // ---- per-material parameters, per bank ----------------------------------------------------
  logic [ShiftW-1:0] shift_q [BANKS];
  logic [SqW-1:0]    sq_q [BANKS];
  logic              in_bank, wr_bank;  // the bank of the pixel on series_i; the bank written
  if (BANKS > 1) begin : g_banks
    assign in_bank = bank_i;
    assign wr_bank = cfg_bank_i;
  end else begin : g_one_bank
    // verilator lint_off UNUSEDSIGNAL
    logic unused_bank;  // one bank: the tags are always 0
    assign unused_bank = bank_i ^ cfg_bank_i;
    // verilator lint_on UNUSEDSIGNAL
    assign in_bank = 1'b0;
    assign wr_bank = 1'b0;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int b = 0; b < BANKS; b++) begin
        shift_q[b] <= '0;
        sq_q[b]    <= SqW'(K);
      end
    end else if (cfg_valid_i && !cfg_table_i) begin
      if (cfg_addr_i == CFG_ADDR_W'(0)) begin
        shift_q[wr_bank] <= '0;
        sq_q[wr_bank]    <= SqW'(K);
      end else if (cfg_addr_i == CFG_ADDR_W'(1)) begin
        shift_q[wr_bank] <= cfg_data_i[ShiftW-1:0];
      end else if (cfg_addr_i == CFG_ADDR_W'(2)) begin
        sq_q[wr_bank] <= cfg_data_i[SqW-1:0];
      end
    end
  end

  // (b * b) >> B, truncating; exact in 2B+1 bits because b <= 2^B. Synthesis sums it as a
  // square, not as a product: b_i b_j (i < j) is a partial product twice, so row i holds b_i at
  // 2i and b_i & b_j (j > i) once at i + j + 1. That is 153 partial-product bits for B = 16
  // against a multiplier's 289, 40 % fewer transistors under Yosys (`shadesim area`).
  // Simulators take the product, the same value in a fraction of their time (the loop is bit
  // level); the summed form is checked against it for every base of B = 16 by
  // WpowUnitRtl.M2Base16EverySquareEqualsTheModelsProduct (a build with SYNTHESIS defined), and
  // as synthesised by rtl_netlist_cosim (docs/rtl.md, "Synthesis and simulation views").
  function automatic logic [BW-1:0] square(input logic [BW-1:0] b);
    // verilator lint_off UNUSEDSIGNAL
    logic [2*BW-1:0] p;  // the low B bits are what truncation drops; the top bit stays 0
    // verilator lint_on UNUSEDSIGNAL
`ifdef SYNTHESIS
    logic [BW-1:0] row;  // b_i & b_j for j > i, from bit i + j + 1 on
    p = '0;
    for (int i = 0; i < BW; i++) begin
      row = {BW{b[i]}} & (b >> (i + 1));
      p = p + ((2*BW)'(b[i]) << (2 * i)) + ((2*BW)'(row) << (2 * i + 2));
    end
`else
    p = (2*BW)'(b) * (2*BW)'(b);
`endif
    square = p[2*B:B];
  endfunction

  // ---- 0. BASE ---------------------------------------------------------------------------------
  logic signed [XW-1:0]       shifted;
  logic signed [BaseRndW-1:0] base_rnd;
  logic [BW-1:0]              base_sat, base_d;
  assign shifted = {{Fs{series_i[SERIES_WL-1]}}, series_i} << shift_q[in_bank];
  fixed_round #(.IN_W(XW), .DROP(BaseDrop), .ROUND(0))
    u_base_round (.in_i(shifted), .out_o(base_rnd));
  fixed_sat #(.IN_W(BaseRndW), .OUT_W(BW), .OUT_SIGNED(0), .WRAP(0))
    u_base_sat (.in_i(base_rnd), .out_o(base_sat));
  assign base_d = base_sat > One ? One : base_sat;

  // ---- 1..K. SQUARE ----------------------------------------------------------------------------
  logic [BW-1:0] b_out;

  if (TIMING == 0 || K == 0) begin : g_pipelined
    // Flat vectors, stage k at [k*BW +: BW] / [k]: Icarus 11 left the last stage of unpacked
    // arrays X here (every pipelined W_m colour X), and Yosys 0.23 cannot parse a
    // multi-dimensional packed array.
    logic [(K+1)*BW-1:0] b_q;   // stage 0: base; stage k: after squaring step k
    logic [K:0]          bk_q;  // the bank of the pixel in stage k
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        b_q[0 +: BW] <= base_d;
        bk_q[0] <= in_bank;
      end
    end
    for (genvar k = 1; k <= K; k++) begin : g_stage
      logic squares;  // stage k squares iff k > K - s, i.e. s >= K - k + 1
      assign squares = sq_q[bk_q[k-1]] >= SqW'(K - k + 1);
      if (SQUARE_STAGES == 2) begin : g_split
        logic [BW-1:0] sum;
        logic          bm_q;  // the bank of the pixel in the squaring's middle register
        wpow_split_square #(.B(B), .BW(BW)) u_square (
          .clk_i, .en_i, .b_i(b_q[(k-1)*BW +: BW]), .square_i(squares), .b_o(sum)
        );
        always_ff @(posedge clk_i) begin
          if (en_i) begin
            bm_q            <= bk_q[k-1];
            b_q[k*BW +: BW] <= sum;
            bk_q[k]         <= bm_q;
          end
        end
      end else begin : g_whole
        always_ff @(posedge clk_i) begin
          if (en_i) begin
            b_q[k*BW +: BW] <= squares ? square(b_q[(k-1)*BW +: BW]) : b_q[(k-1)*BW +: BW];
            bk_q[k]         <= bk_q[k-1];
          end
        end
      end
    end
    // verilator lint_off UNUSEDSIGNAL
    logic unused_last_bank;  // the last stage's bank: nothing after it reads a parameter
    assign unused_last_bank = bk_q[K];
    if (K == 0) begin : g_no_stage
      logic unused_squarings;  // reason: m = 1 has no squaring stage to read them
      assign unused_squarings = ^sq_q[0] ^ ^sq_q[BANKS-1];
    end
    // verilator lint_on UNUSEDSIGNAL
    assign b_out  = b_q[K*BW +: BW];
    assign busy_o = 1'b0;
  end else begin : g_iterative
    localparam int CntW = $clog2(K + 1);
    logic [CntW-1:0] cnt_q;  // steps still to do; the step done with cnt_q = c squares iff c <= s
    logic [BW-1:0]   w_q;
    logic            wb_q;  // the bank of the pixel in w_q
    assign busy_o = cnt_q != '0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni)               cnt_q <= '0;
      else if (en_i && !busy_o)  cnt_q <= CntW'(K);
      else if (busy_o)           cnt_q <= cnt_q - CntW'(1);
    end
    always_ff @(posedge clk_i) begin
      if (en_i && !busy_o) begin
        w_q  <= base_d;
        wb_q <= in_bank;
      end else if (busy_o && cnt_q <= sq_q[wb_q]) begin
        w_q <= square(w_q);
      end
    end
    assign b_out = w_q;
  end

  // ---- K+1. OUTPUT ---------------------------------------------------------------------------
  logic signed [OutRndW-1:0] out_rnd;
  fixed_round #(.IN_W(BW + 1), .DROP(OutDrop), .ROUND(OUT_QUANT))
    u_out_round (.in_i($signed({1'b0, b_out})), .out_o(out_rnd));
  fixed_sat #(.IN_W(OutRndW), .OUT_W(OUT_WL), .OUT_SIGNED(0), .WRAP(OUT_OVERFLOW))
    u_out_sat (.in_i(out_rnd), .out_o(spec_o));

`ifndef SYNTHESIS
  initial begin
    if (Fs < 1) $fatal(1, "wpow_unit: the series format needs at least one fraction bit");
    if (MAX_M < 1 || (1 << K) != MAX_M)
      $fatal(1, "wpow_unit: MAX_M must be a power of two, got %0d", MAX_M);
    if (BANKS != 1 && BANKS != 2) $fatal(1, "wpow_unit: BANKS %0d is not 1 or 2", BANKS);
  end
`endif
endmodule
