// span_setup: start value and differences of one series for one span (model/span_setup.h,
// class SpanSetup), three register stages in the model's order:
//   stage 1  exact products of the coefficients with the integer offsets dx, dy
//   stage 2  exact sums  v = T0 + T1 dy + T2 dx + T3 dy^2 + T4 dx dy + T5 dx^2
//                        d = T2 + T4 dy + T5 (2 dx + 1),   d2 = 2 T5
//   stage 3  each rounded once into the series format (fixed_round, then fixed_sat)
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
  input  logic signed [OFS_W-1:0]  dx_i,
  input  logic signed [OFS_W-1:0]  dy_i,
  output logic [SERIES_WL-1:0]     v_o,
  output logic [SERIES_WL-1:0]     d_o,
  output logic [SERIES_WL-1:0]     d2_o
);
  localparam int SqW   = 2 * OFS_W;          // dx*dy, dx^2, dy^2 and 2dx+1 (exact)
  localparam int ProdW = COEF_WL + SqW;      // coefficient times any offset term (exact)
  localparam int SumW  = ProdW + 3;          // six terms: never overflows
  localparam int Drop  = (COEF_WL - COEF_IWL) - (SERIES_WL - SERIES_IWL);

  // Every product operand is cast to the product's width (signed casts sign-extend), so the
  // multiplications are exact. Casts rather than functions: a Verilated function zeroes its
  // wide temporaries on every clock.
  logic [COEF_WL-1:0] t0, t1, t2, t3, t4, t5;
  assign {t5, t4, t3, t2, t1, t0} = coef_i;

  // ---- stage 1: products --------------------------------------------------------------
  logic signed [SqW-1:0] dx_w, dy_w, dxx, dxy, dyy, dx2p1;
  assign dx_w  = {{OFS_W{dx_i[OFS_W-1]}}, dx_i};
  assign dy_w  = {{OFS_W{dy_i[OFS_W-1]}}, dy_i};
  assign dxx   = dx_w * dx_w;
  assign dxy   = dx_w * dy_w;
  assign dyy   = dy_w * dy_w;
  assign dx2p1 = (dx_w <<< 1) + SqW'(1);

  logic signed [ProdW-1:0] p_t0_q, p_t1y_q, p_t2x_q, p_t3yy_q, p_t4xy_q, p_t5xx_q;
  logic signed [ProdW-1:0] p_t2_q, p_t4y_q, p_t5x_q, p_t5_q;
  always_ff @(posedge clk_i) begin
    if (s1_en_i) begin
      p_t0_q   <= ProdW'($signed(t0));
      p_t1y_q  <= ProdW'($signed(t1)) * ProdW'(dy_w);
      p_t2x_q  <= ProdW'($signed(t2)) * ProdW'(dx_w);
      p_t3yy_q <= ProdW'($signed(t3)) * ProdW'(dyy);
      p_t4xy_q <= ProdW'($signed(t4)) * ProdW'(dxy);
      p_t5xx_q <= ProdW'($signed(t5)) * ProdW'(dxx);
      p_t2_q   <= ProdW'($signed(t2));
      p_t4y_q  <= ProdW'($signed(t4)) * ProdW'(dy_w);
      p_t5x_q  <= ProdW'($signed(t5)) * ProdW'(dx2p1);
      p_t5_q   <= ProdW'($signed(t5));
    end
  end

  // ---- stage 2: exact sums --------------------------------------------------------------
  logic signed [SumW-1:0] v_sum_q, d_sum_q, d2_sum_q;
  always_ff @(posedge clk_i) begin
    if (s2_en_i) begin
      v_sum_q  <= SumW'(p_t0_q) + SumW'(p_t1y_q) + SumW'(p_t2x_q) + SumW'(p_t3yy_q)
                + SumW'(p_t4xy_q) + SumW'(p_t5xx_q);
      d_sum_q  <= SumW'(p_t2_q) + SumW'(p_t4y_q) + SumW'(p_t5x_q);
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
