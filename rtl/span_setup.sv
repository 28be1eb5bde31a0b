// span_setup: start value and differences of one series for one span (model/span_setup.h,
// class SpanSetup), three register stages in the model's order, in Horner form:
//   stage 1  exact brackets  a = T1 + T3 dy + T4 dx,  b = T2 + T5 dx,
//                            d = T2 + T4 dy + T5 (2 dx + 1),  d2 = T5
//   stage 2  exact sums      v = T0 + a dy + b dx  (= T0 + T1 dy + T2 dx + T3 dy^2 + T4 dx dy
//                            + T5 dx^2),  d,  d2 = 2 T5
//   stage 3  each rounded once into the series format (fixed_round, then fixed_sat)
// Every multiplier has one OFS_W-bit offset operand: six of them, no squares, each summing the
// (OFS_W + 1) / 2 radix-4 Booth partial products of its offset (mul_p, mul_s).
// ("exact": with a wrapping series, exact modulo 2^KeepW, which decides every bit it keeps.)
// Each stage register loads when its enable is high; shade_unit owns the valid bits.
module span_setup #(
  parameter int COEF_WL         = 36,
  parameter int COEF_IWL        = 4,
  parameter int SERIES_WL       = 32,
  parameter int SERIES_IWL      = 4,
  parameter int SERIES_QUANT    = 0,  // 0 truncate, 1 round to nearest
  parameter int SERIES_OVERFLOW = 1,  // 0 saturate, 1 wrap
  parameter int OFS_W           = 17  // signed width of the offsets dx, dy
) (
  input  logic                     clk_i,
  input  logic                     s1_en_i,
  input  logic                     s2_en_i,
  input  logic                     s3_en_i,
  input  logic [6*COEF_WL-1:0]     coef_i,  // T0 in the low bits .. T5 in the high bits
  // The span's start and its triangle's origin: dx = x_i - xo_i, dy = y_i - yo_i (OFS_W bits).
  input  logic signed [OFS_W-1:0]  x_i,
  input  logic signed [OFS_W-1:0]  y_i,
  input  logic signed [OFS_W-1:0]  xo_i,
  input  logic signed [OFS_W-1:0]  yo_i,
  output logic [SERIES_WL-1:0]     v_o,
  output logic [SERIES_WL-1:0]     d_o,
  output logic [SERIES_WL-1:0]     d2_o
);
  localparam int SqW   = 2 * OFS_W;          // a dy and b dx reach COEF_WL + SqW bits (exact)
  localparam int Drop  = (COEF_WL - COEF_IWL) - (SERIES_WL - SERIES_IWL);
  // A wrapping series keeps only the low SERIES_WL bits of the rounded sum, which depend only
  // on the sum's low SERIES_WL + Drop bits (rounding adds below them, carries go up): the
  // products and sums are kept modulo 2^KeepW, which gives the same series bits as exact
  // arithmetic and is all the hardware needs (and a simulator computes it in a 64-bit word
  // instead of multi-word products). A saturating series needs every bit to see overflow.
  localparam int ExactW = COEF_WL + SqW + 3;  // v, d exact: never overflow
  localparam int KeepW  = SERIES_WL + Drop < 2 ? 2 : SERIES_WL + Drop;
  localparam bit Modular = SERIES_OVERFLOW != 0 && KeepW < ExactW;
  localparam int ProdW = Modular ? KeepW : COEF_WL + SqW;  // a bracket (|a| < 2^(COEF_WL+OFS_W))
  localparam int SumW  = Modular ? KeepW : ExactW;

  // Every product operand is cast to the product's width (signed casts sign-extend), so the
  // multiplications are exact (modulo 2^ProdW). Casts rather than functions: a Verilated
  // function zeroes its wide temporaries on every clock.
  logic [COEF_WL-1:0] t0, t1, t2, t3, t4, t5;
  assign {t5, t4, t3, t2, t1, t0} = coef_i;

  // ---- stage 1: the first-order products and the Horner brackets ------------------------
  // v = T0 + dy (T1 + T3 dy + T4 dx) + dx (T2 + T5 dx): every product has one offset operand,
  // none a square, so each multiplier is COEF_WL x OFS_W. Stage 1 forms the brackets
  //   a = T1 + T3 dy + T4 dx,   b = T2 + T5 dx,   d = T2 + T4 dy + T5 (2 dx + 1) = b + T4 dy +
  //   T5 dx + T5,   d2 = 2 T5
  // and stage 2 multiplies the brackets by dy and dx. The offsets are formed inside the
  // register process, so that a simulator computes them only on the edges that load stage 1
  // (the span's start changes with cmd_data_i on every cycle without a span queue). The
  // offsets are signed: each cast sign-extends them.
  function automatic logic signed [OFS_W-1:0] ofs(input logic signed [OFS_W-1:0] a,
                                                  input logic signed [OFS_W-1:0] b);
    ofs = a - b;
  endfunction
  // t x d for an OFS_W-bit signed offset d, modulo 2^SumW (mul_s): radix-4 Booth digits of d,
  // so (OFS_W + 1) / 2 partial products, each 0, +-t or +-2t, instead of OFS_W; a negative one
  // is its complement plus one, the one added with the sum. The same product, 16 % fewer GE for
  // span setup under Yosys (`shadesim area`: it maps `*` to an array of OFS_W rows); the model
  // multiplies (model/span_setup.h), and every co-simulation compares. mul_p is the same
  // product modulo 2^ProdW (SumW >= ProdW, so its low ProdW bits are mul_s's): one rule.
  function automatic logic [SumW-1:0] mul_s(input logic [SumW-1:0] t,
                                           input logic [OFS_W-1:0] d);
`ifdef SYNTHESIS
    logic [OFS_W+1:0] e;
    logic [SumW-1:0] acc, mag;
    logic            neg;
    e = {d[OFS_W-1], d, 1'b0};
    acc = '0;
    for (int k = 0; k < (OFS_W + 1) / 2; k++) begin
      unique case ({e[2*k+2], e[2*k+1], e[2*k]})
        3'b001, 3'b010, 3'b101, 3'b110: mag = t;
        3'b011, 3'b100:                 mag = t << 1;
        default:                        mag = '0;
      endcase
      neg = e[2*k+2] && !(e[2*k+1] && e[2*k]);
      acc = acc + ((neg ? ~mag : mag) << (2 * k)) + (SumW'(neg) << (2 * k));
    end
    mul_s = acc;
`else
    // Simulators multiply: the same product (icarus_span_setup_booth checks the Booth form
    // against `*` exhaustively; docs/rtl.md, "Synthesis and simulation views").
    mul_s = t * SumW'($signed(d));
`endif
  endfunction
  function automatic logic [ProdW-1:0] mul_p(input logic [ProdW-1:0] t,
                                            input logic [OFS_W-1:0] d);
    mul_p = ProdW'(mul_s(SumW'(t), d));
  endfunction
  logic signed [ProdW-1:0] p_t0_q, p_a_q, p_b_q, p_d_q, p_t5_q;
  logic signed [OFS_W-1:0] p_dx_q, p_dy_q;
  always_ff @(posedge clk_i) begin
    if (s1_en_i) begin
      p_t0_q <= ProdW'($signed(t0));
      p_a_q  <= ProdW'($signed(t1)) + mul_p(ProdW'($signed(t3)), ofs(y_i, yo_i))
              + mul_p(ProdW'($signed(t4)), ofs(x_i, xo_i));
      p_b_q  <= ProdW'($signed(t2)) + mul_p(ProdW'($signed(t5)), ofs(x_i, xo_i));
      p_d_q  <= ProdW'($signed(t2)) + mul_p(ProdW'($signed(t4)), ofs(y_i, yo_i))
              + (mul_p(ProdW'($signed(t5)), ofs(x_i, xo_i)) <<< 1) + ProdW'($signed(t5));
      p_t5_q <= ProdW'($signed(t5));
      p_dx_q <= ofs(x_i, xo_i);
      p_dy_q <= ofs(y_i, yo_i);
    end
  end

  // ---- stage 2: the brackets times the offsets, and the sums ----------------------------
  logic signed [SumW-1:0] v_sum_q, d_sum_q, d2_sum_q;
  always_ff @(posedge clk_i) begin
    if (s2_en_i) begin
      v_sum_q  <= SumW'(p_t0_q) + mul_s(SumW'(p_a_q), p_dy_q) + mul_s(SumW'(p_b_q), p_dx_q);
      d_sum_q  <= SumW'(p_d_q);
      d2_sum_q <= SumW'(p_t5_q) <<< 1;
    end
  end

  // ---- stage 3: one rounding into the series format --------------------------------------
  localparam int RndW = SumW + 1 - Drop;
  logic signed [RndW-1:0] v_rnd, d_rnd, d2_rnd;
  logic [SERIES_WL-1:0]   v_fit, d_fit, d2_fit;

  fixed_round #(.IN_W(SumW), .DROP(Drop), .ROUND(SERIES_QUANT))
    u_round_v (.in_i(v_sum_q), .out_o(v_rnd));
  fixed_round #(.IN_W(SumW), .DROP(Drop), .ROUND(SERIES_QUANT))
    u_round_d (.in_i(d_sum_q), .out_o(d_rnd));
  fixed_round #(.IN_W(SumW), .DROP(Drop), .ROUND(SERIES_QUANT))
    u_round_d2 (.in_i(d2_sum_q), .out_o(d2_rnd));
  fixed_sat #(.IN_W(RndW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_sat_v (.in_i(v_rnd), .out_o(v_fit));
  fixed_sat #(.IN_W(RndW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_sat_d (.in_i(d_rnd), .out_o(d_fit));
  fixed_sat #(.IN_W(RndW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_sat_d2 (.in_i(d2_rnd), .out_o(d2_fit));

  always_ff @(posedge clk_i) begin
    if (s3_en_i) begin
      v_o  <= v_fit;
      d_o  <= d_fit;
      d2_o <= d2_fit;
    end
  end
endmodule
