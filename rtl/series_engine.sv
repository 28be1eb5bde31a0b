// series_engine: the per-pixel forward-difference step of one series (model/series_engine.h,
// class SeriesEngine): v += d; d += d2, both additions reading the old d. The adders follow
// the series overflow rule: wrap (a plain SERIES_WL-bit adder) or saturate.
module series_engine #(
  parameter int SERIES_WL       = 32,
  parameter int SERIES_OVERFLOW = 1  // 0 saturate, 1 wrap
) (
  input  logic                 clk_i,
  input  logic                 load_i,  // take v, d, d2 from span setup (wins over step)
  input  logic                 step_i,  // advance one pixel
  input  logic [SERIES_WL-1:0] v_i,
  input  logic [SERIES_WL-1:0] d_i,
  input  logic [SERIES_WL-1:0] d2_i,
  output logic [SERIES_WL-1:0] v_o
);
  logic [SERIES_WL-1:0] v_q, d_q, d2_q;
  logic [SERIES_WL-1:0] v_next, d_next;
  logic signed [SERIES_WL:0] v_sum, d_sum;

  assign v_sum = {v_q[SERIES_WL-1], v_q} + {d_q[SERIES_WL-1], d_q};
  assign d_sum = {d_q[SERIES_WL-1], d_q} + {d2_q[SERIES_WL-1], d2_q};

  fixed_sat #(.IN_W(SERIES_WL + 1), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_fit_v (.in_i(v_sum), .out_o(v_next));
  fixed_sat #(.IN_W(SERIES_WL + 1), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
    u_fit_d (.in_i(d_sum), .out_o(d_next));

  always_ff @(posedge clk_i) begin
    if (load_i) begin
      v_q  <= v_i;
      d_q  <= d_i;
      d2_q <= d2_i;
    end else if (step_i) begin
      v_q <= v_next;
      d_q <= d_next;
    end
  end

  assign v_o = v_q;
endmodule
