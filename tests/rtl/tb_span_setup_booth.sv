// Exhaustive check of span_setup's radix-4 Booth product (mul_s, and mul_p through it): every
// 10-bit t against every d of OFS_W = 1..7 bits, against Verilog's own `*`, on two units each:
// a wrapping series (the product modulo 2^ProdW = 2^SumW = 2^10) and a saturating one (the
// exact product, ProdW = 10 + 2 OFS_W and SumW = ProdW + 3 bits). Prints "booth: N products
// checked" and "booth: PASS", or the first mismatches and "booth: FAIL" ($fatal).
// cmake/icarus.cmake runs it through tests/rtl/synthesis_view_check.cmake
// (icarus_span_setup_booth) and on a deliberately broken copy of rtl/span_setup.sv, which must
// fail.
module tb_span_setup_booth;
  localparam int TW = 10;  // t's bits: every value, read as signed
  localparam int ShownErrors = 5;  // a broken unit stops here: the rest would fail alike
  int errors = 0;
  int checked = 0;

  for (genvar w = 1; w <= 7; w++) begin : g_w
    // COEF_WL = SERIES_WL, same IWL: no bits dropped, so a wrapping series keeps 10 bits.
    span_setup #(.COEF_WL(TW), .COEF_IWL(2), .SERIES_WL(TW), .SERIES_IWL(2), .SERIES_QUANT(0),
                 .SERIES_OVERFLOW(1), .OFS_W(w)) u_wrap (
      .clk_i(1'b0), .s1_en_i(1'b0), .s2_en_i(1'b0), .s3_en_i(1'b0), .coef_i({6 * TW{1'b0}}),
      .x_i({w{1'b0}}), .y_i({w{1'b0}}), .xo_i({w{1'b0}}), .yo_i({w{1'b0}}), .v_o(), .d_o(),
      .d2_o());
    span_setup #(.COEF_WL(TW), .COEF_IWL(2), .SERIES_WL(TW), .SERIES_IWL(2), .SERIES_QUANT(0),
                 .SERIES_OVERFLOW(0), .OFS_W(w)) u_exact (
      .clk_i(1'b0), .s1_en_i(1'b0), .s2_en_i(1'b0), .s3_en_i(1'b0), .coef_i({6 * TW{1'b0}}),
      .x_i({w{1'b0}}), .y_i({w{1'b0}}), .xo_i({w{1'b0}}), .yo_i({w{1'b0}}), .v_o(), .d_o(),
      .d2_o());
    localparam int PW = TW + 2 * w;  // u_exact's ProdW; its SumW is PW + 3
    initial begin : check
      logic signed [TW-1:0] t;
      logic signed [w-1:0]  d;
      logic signed [63:0]   want;
      logic [TW-1:0]        got_wrap_s, got_wrap_p;
      logic [PW+2:0]        got_exact_s;
      logic [PW-1:0]        got_exact_p;
      #1;
      for (int ti = 0; ti < (1 << TW); ti++) begin
        for (int di = 0; di < (1 << w); di++) begin
          t    = TW'(ti);
          d    = w'(di);
          want = 64'(t) * 64'(d);
          got_wrap_s  = u_wrap.mul_s(t, d);
          got_wrap_p  = u_wrap.mul_p(t, d);
          got_exact_s = u_exact.mul_s((PW + 3)'(t), d);
          got_exact_p = u_exact.mul_p(PW'(t), d);
          checked = checked + 4;
          if (got_wrap_s != TW'(want) || got_wrap_p != TW'(want) ||
              got_exact_s != (PW + 3)'(want) || got_exact_p != PW'(want)) begin
            errors = errors + 1;
            $display({"booth: OFS_W=%0d t=%0d d=%0d: want %0d, wrap mul_s %0d mul_p %0d, ",
                      "exact mul_s %0d mul_p %0d"}, w, t, d, want, $signed(got_wrap_s),
                     $signed(got_wrap_p), $signed(got_exact_s), $signed(got_exact_p));
            if (errors == ShownErrors)
              view_check_verdict("booth", checked, "products checked up to that mismatch",
                                 errors);
          end
        end
      end
    end
  end

`include "view_check_verdict.svh"
  initial begin
    #2;
    view_check_verdict("booth", checked,
                       $sformatf("products checked (OFS_W 1..7, every %0d-bit t and every d)", TW),
                       errors);
  end
endmodule
