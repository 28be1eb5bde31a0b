// lane_fanout: lane LANE's engine start of one series for a unit with LANES pixel lanes
// (model/lane_fanout.h, class LaneFanout), from span_setup's (v, d, d2) at the span's first
// pixel. Lane j shades pixels x0 + j, x0 + j + K, ... (K = LANES) of p(i) = v + i d + i(i-1)/2 d2:
//   v_o  = p(j)                        = v + j d + j(j-1)/2 d2
//   d_o  = p(j + K) - p(j)             = K d + (K j + K(K-1)/2) d2
//   d2_o = p(j + 2K) - 2 p(j + K) + p(j) = K^2 d2
// Each formed exactly (constant multipliers: shifts and adds) and fitted once by the series
// overflow rule (fixed_sat): wrap is exact modulo 2^SERIES_WL, so the lanes' values equal the
// one-lane engine's bit for bit. Combinational: shade_unit's engines load it on load_eng, in the
// cycle they would load span_setup's output, so lanes cost no pipeline stage.
module lane_fanout #(
  parameter int SERIES_WL       = 32,
  parameter int SERIES_OVERFLOW = 1,  // 0 saturate, 1 wrap
  parameter int LANES           = 1,  // K
  parameter int LANE            = 0   // j, 0 <= j < K
) (
  input  logic [SERIES_WL-1:0] v_i,
  input  logic [SERIES_WL-1:0] d_i,
  input  logic [SERIES_WL-1:0] d2_i,
  output logic [SERIES_WL-1:0] v_o,
  output logic [SERIES_WL-1:0] d_o,
  output logic [SERIES_WL-1:0] d2_o
);
  // |each sum| <= (1 + 3 + 3) or (4 + 18) or 16 times 2^(SERIES_WL-1) for K <= 4: below
  // 2^(SERIES_WL+4), so six more bits hold every sum exactly.
  localparam int ExtW = SERIES_WL + 6;
  localparam int Tri    = LANE * (LANE - 1) / 2;                 // j(j-1)/2
  localparam int Stride = LANES * LANE + LANES * (LANES - 1) / 2;  // K j + K(K-1)/2
  localparam logic signed [ExtW-1:0] MulVd  = ExtW'(LANE);
  localparam logic signed [ExtW-1:0] MulVd2 = ExtW'(Tri);
  localparam logic signed [ExtW-1:0] MulDd  = ExtW'(LANES);
  localparam logic signed [ExtW-1:0] MulDd2 = ExtW'(Stride);
  localparam logic signed [ExtW-1:0] MulD2  = ExtW'(LANES * LANES);

  logic signed [ExtW-1:0] v, d, d2, v_sum, d_sum, d2_sum;
  assign v  = ExtW'($signed(v_i));
  assign d  = ExtW'($signed(d_i));
  assign d2 = ExtW'($signed(d2_i));
  assign v_sum  = v + MulVd * d + MulVd2 * d2;
  assign d_sum  = MulDd * d + MulDd2 * d2;
  assign d2_sum = MulD2 * d2;

  fixed_sat #(.IN_W(ExtW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_fit_v (.in_i(v_sum), .out_o(v_o));
  fixed_sat #(.IN_W(ExtW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_fit_d (.in_i(d_sum), .out_o(d_o));
  fixed_sat #(.IN_W(ExtW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_fit_d2 (.in_i(d2_sum), .out_o(d2_o));
endmodule
