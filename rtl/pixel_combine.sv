// pixel_combine: ambient + diffuse + specular per channel, clamp, round to the output code
// (model/pixel_combine.h, class PixelCombine). Combinational with STAGES = 0 (shade_unit's
// out_reg registers the result); STAGES = 1 registers stage 1's terms (each light's diffuse and
// specular term, the ambient) on en_i, the pipeline's advance, so the multiplies and the sum
// with its rounding are in separate cycles. STAGES = 2 also registers the raw products (and the
// gates, the clamped diffuse values, the ambient) before their rounding, and adds each light's
// two terms before the terms register, so stage 2 sums LIGHTS + 1 terms, not 2 LIGHTS + 1.
// The registers change when a value is ready, not the value (the sum is exact either way):
// shade_unit delays the beat's metadata by the same STAGES (UnitConfig::combine_stages).
//   stage 1  each diffuse value clamped below at 0; each specular intensity s_l times the
//            light's specular colour k_lc, brought to the series fraction bits by the series
//            rule (fixed_round + fixed_sat); the specular gate of light l,
//            g_l = (sum_c D_lc) > 0 (the model's header comment states the rule and why)
//   stage 2  exact sum per channel: ambient_c + sum_l max(0, D_lc) [light not gate-only]
//                                   + sum_l g_l s_l k_lc
//   stage 3  round to nearest into u0.OUT_BITS, saturating
// SPECULAR = 0 (specular kind none): no specular term - no gates, products or specular sums;
// spec_i and spec_colour_i are not read.
// DIFFUSE_MULTIPLY = 1 (UnitConfig::diffuse_colour multiply): one diffuse series per light,
// N_l = N.L itself; stage 1 forms max(0, N_l) x kd_lc per channel by the series rule, like the
// specular product, and the gate is N_l > 0; the multiplier takes N_l truncated to the colour's
// fraction bits (the model says why). diffuse_colour_i is read only then, gate_only_i never.
module pixel_combine #(
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int SERIES_WL        = 32,
  parameter int SERIES_IWL       = 4,
  parameter int SERIES_QUANT     = 0,
  parameter int SERIES_OVERFLOW  = 1,
  parameter int SPEC_COLOUR_WL   = 13,
  parameter int SPEC_COLOUR_IWL  = 1,
  parameter int SPECULAR_OUT_WL  = 17,
  parameter int SPECULAR_OUT_IWL = 1,
  parameter int OUT_BITS         = 8,
  parameter bit SPECULAR         = 1,  // 0: no specular term (SpecularUnitKind none)
  parameter bit DIFFUSE_MULTIPLY = 0,  // 1: one N.L series per light, times kd_lc
  parameter int STAGES           = 0   // 0, 1 (terms registered) or 2 (raw products too)
) (
  input  logic                                      clk_i,
  input  logic                                      en_i,  // the pipeline's advance
  // [l*CHANNELS + c], or [l] with DIFFUSE_MULTIPLY
  input  logic [(DIFFUSE_MULTIPLY ? LIGHTS : LIGHTS*CHANNELS)*SERIES_WL-1:0] diffuse_i,
  input  logic [LIGHTS*SPECULAR_OUT_WL-1:0]         spec_i,         // [l]
  input  logic [CHANNELS*SERIES_WL-1:0]             ambient_i,      // [c]
  input  logic [LIGHTS*CHANNELS*SPEC_COLOUR_WL-1:0] spec_colour_i,  // [l*CHANNELS + c]
  input  logic [LIGHTS*CHANNELS*SPEC_COLOUR_WL-1:0] diffuse_colour_i,  // [l*CHANNELS + c]: kd_lc
  input  logic [LIGHTS-1:0]                         gate_only_i,    // [l]: D_l0 gates only
  output logic [CHANNELS*OUT_BITS-1:0]              colour_o        // [c]
);
  localparam int SeriesFrac = SERIES_WL - SERIES_IWL;
  localparam int ProdW      = SPECULAR_OUT_WL + SPEC_COLOUR_WL + 1;  // unsigned product + sign
  localparam int ProdFrac   = (SPECULAR_OUT_WL - SPECULAR_OUT_IWL) +
                              (SPEC_COLOUR_WL - SPEC_COLOUR_IWL);
  localparam int ProdDrop   = ProdFrac - SeriesFrac;
  localparam int ProdRndW   = ProdW + 1 - ProdDrop;
  localparam int AccW       = SERIES_WL + $clog2(2 * LIGHTS + 1) + 1;
  localparam int OutDrop    = SeriesFrac - OUT_BITS;
  localparam int OutRndW    = AccW + 1 - OutDrop;

  localparam int GateW      = SERIES_WL + $clog2(CHANNELS + 1);  // sum of a light's channels
  // The diffuse product max(0, N_l) x kd_lc: N_l without its sign and its NlDrop lowest bits,
  // times the colour, then a sign bit.
  localparam int ColourFrac   = SPEC_COLOUR_WL - SPEC_COLOUR_IWL;
  localparam int NlDrop       = SeriesFrac > ColourFrac ? SeriesFrac - ColourFrac : 0;
  localparam int NlW          = SERIES_WL - 1 - NlDrop;
  localparam int DiffProdW    = NlW + SPEC_COLOUR_WL + 1;
  localparam int DiffDrop     = ColourFrac - NlDrop;
  localparam int DiffRndW     = DiffProdW + 1 - DiffDrop;
  localparam int GateChannels = DIFFUSE_MULTIPLY ? 1 : CHANNELS;  // series summed by a gate

  localparam bit RawReg   = STAGES >= 2;  // the raw products' register
  localparam bit TermsReg = STAGES >= 1;  // the terms' register
  // Stage 2's terms: the ambient and, per light, its diffuse and its specular term, or (STAGES 2)
  // their sum.
  localparam int Terms    = STAGES >= 2 ? LIGHTS + 1 : 2 * LIGHTS + 1;

  // The specular gate per light: the sum of its channels' diffuse values is > 0 (none without a
  // specular term); lit_r as stage 1's rounding reads it.
  logic [LIGHTS-1:0] lit, lit_r;
  if (!SPECULAR) begin : g_no_gate
    assign lit = '0;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_spec;  // reason: no specular term reads them
    assign unused_spec = (^spec_i) ^ (^spec_colour_i) ^ (^lit_r);
    // verilator lint_on UNUSEDSIGNAL
  end else begin : g_gates
    for (genvar l = 0; l < LIGHTS; l++) begin : g_gate
      // Running sum over the channels (continuous assignments: Icarus 11 does not settle an
      // always_comb that reads back what it writes).
      logic [(GateChannels + 1)*GateW-1:0] part /*verilator split_var*/;
      assign part[0 +: GateW] = '0;
      for (genvar c = 0; c < GateChannels; c++) begin : g_sum
        logic signed [SERIES_WL-1:0] d;
        assign d = $signed(diffuse_i[(l*GateChannels + c)*SERIES_WL +: SERIES_WL]);
        assign part[(c + 1)*GateW +: GateW] = part[c*GateW +: GateW] + GateW'(d);
      end
      logic signed [GateW-1:0] n_dot_l;
      assign n_dot_l = $signed(part[GateChannels*GateW +: GateW]);
      assign lit[l]  = !n_dot_l[GateW-1] && n_dot_l != '0;
    end
  end
  pipe_reg #(.W(LIGHTS), .PRESENT(RawReg)) u_lit_reg (.clk_i, .en_i, .d_i(lit), .q_o(lit_r));

  for (genvar c = 0; c < CHANNELS; c++) begin : g_chan
    // Stage 2's terms: [0] the ambient, then per light its diffuse and specular term ([2l+1],
    // [2l+2]) or their sum ([l+1], STAGES 2); terms_d as formed, terms as stage 2 reads them.
    localparam int TermsW = Terms * AccW;
    logic [TermsW-1:0] terms_d, terms;
    logic [AccW-1:0]   ambient;
    pipe_reg #(.W(AccW), .PRESENT(RawReg)) u_ambient_reg (
      .clk_i, .en_i, .d_i(AccW'($signed(ambient_i[c*SERIES_WL +: SERIES_WL]))), .q_o(ambient)
    );
    assign terms_d[0 +: AccW] = ambient;
    pipe_reg #(.W(TermsW), .PRESENT(TermsReg)) u_terms_reg (
      .clk_i, .en_i, .d_i(terms_d), .q_o(terms)
    );
    // Running sum over the terms: sums[0] = terms[0], sums[t] = sums[t-1] + terms[t].
    logic [Terms*AccW-1:0] sums /*verilator split_var*/;
    assign sums[0 +: AccW] = terms[0 +: AccW];
    for (genvar t = 1; t < Terms; t++) begin : g_term
      assign sums[t*AccW +: AccW] = $signed(sums[(t-1)*AccW +: AccW]) +
                                    $signed(terms[t*AccW +: AccW]);
    end

    for (genvar l = 0; l < LIGHTS; l++) begin : g_light
      logic signed [AccW-1:0]      diffuse_term, spec_term;

      if (SPECULAR) begin : g_spec
        logic [SPECULAR_OUT_WL-1:0]  spec;
        logic [SPEC_COLOUR_WL-1:0]   colour;
        logic [ProdW-2:0]            magnitude;
        logic signed [ProdW-1:0]     product_r;
        logic signed [ProdRndW-1:0]  product_rnd;
        logic [SERIES_WL-1:0]        product_fit;

        assign spec    = spec_i[l*SPECULAR_OUT_WL +: SPECULAR_OUT_WL];
        assign colour  = spec_colour_i[(l*CHANNELS + c)*SPEC_COLOUR_WL +: SPEC_COLOUR_WL];
        split_multiply #(.A_W(SPECULAR_OUT_WL), .B_W(SPEC_COLOUR_WL), .STAGE(RawReg)) u_mul (
          .clk_i, .en_i, .a_i(spec), .b_i(colour), .p_o(magnitude)
        );
        assign product_r = $signed({1'b0, magnitude});

        fixed_round #(.IN_W(ProdW), .DROP(ProdDrop), .ROUND(SERIES_QUANT))
          u_round (.in_i(product_r), .out_o(product_rnd));
        fixed_sat #(.IN_W(ProdRndW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
          u_sat (.in_i(product_rnd), .out_o(product_fit));

        assign spec_term = lit_r[l] ? AccW'($signed(product_fit)) : '0;
      end else begin : g_no_spec
        assign spec_term = '0;
      end

      if (DIFFUSE_MULTIPLY) begin : g_diff_mul
        logic signed [SERIES_WL-1:0] n_dot_l;
        logic [SPEC_COLOUR_WL-1:0]   colour;
        logic [DiffProdW-2:0]        magnitude;
        logic signed [DiffProdW-1:0] product_r;
        logic signed [DiffRndW-1:0]  product_rnd;
        logic [SERIES_WL-1:0]        product_fit;
        logic                        lit_diffuse, lit_diffuse_r;  // N_l > 0

        assign n_dot_l = $signed(diffuse_i[l*SERIES_WL +: SERIES_WL]);
        assign colour  = diffuse_colour_i[(l*CHANNELS + c)*SPEC_COLOUR_WL +: SPEC_COLOUR_WL];
        split_multiply #(.A_W(NlW), .B_W(SPEC_COLOUR_WL), .STAGE(RawReg)) u_mul (
          .clk_i, .en_i, .a_i(n_dot_l[SERIES_WL-2:NlDrop]), .b_i(colour), .p_o(magnitude)
        );
        assign product_r = $signed({1'b0, magnitude});
        assign lit_diffuse = !n_dot_l[SERIES_WL-1] && n_dot_l != '0;
        pipe_reg #(.W(1), .PRESENT(RawReg)) u_lit_reg (
          .clk_i, .en_i, .d_i(lit_diffuse), .q_o(lit_diffuse_r)
        );

        fixed_round #(.IN_W(DiffProdW), .DROP(DiffDrop), .ROUND(SERIES_QUANT))
          u_round (.in_i(product_r), .out_o(product_rnd));
        fixed_sat #(.IN_W(DiffRndW), .OUT_W(SERIES_WL), .OUT_SIGNED(1), .WRAP(SERIES_OVERFLOW))
          u_sat (.in_i(product_rnd), .out_o(product_fit));

        assign diffuse_term = lit_diffuse_r ? AccW'($signed(product_fit)) : '0;
      end else begin : g_diff_series
        logic signed [SERIES_WL-1:0] diffuse;
        logic signed [AccW-1:0]      clamped;
        assign diffuse = $signed(diffuse_i[(l*CHANNELS + c)*SERIES_WL +: SERIES_WL]);
        assign clamped = diffuse[SERIES_WL-1] || gate_only_i[l] ? '0 : AccW'(diffuse);
        pipe_reg #(.W(AccW), .PRESENT(RawReg)) u_diffuse_reg (
          .clk_i, .en_i, .d_i(clamped), .q_o(diffuse_term)
        );
      end
      if (STAGES >= 2) begin : g_light_sum
        assign terms_d[(l + 1)*AccW +: AccW] = diffuse_term + spec_term;
      end else begin : g_light_terms
        assign terms_d[(2*l + 1)*AccW +: AccW] = diffuse_term;
        assign terms_d[(2*l + 2)*AccW +: AccW] = spec_term;
      end
    end

    logic signed [AccW-1:0] acc;
    assign acc = $signed(sums[(Terms-1)*AccW +: AccW]);

    logic signed [OutRndW-1:0] out_rnd;
    fixed_round #(.IN_W(AccW), .DROP(OutDrop), .ROUND(1)) u_round_out (.in_i(acc), .out_o(out_rnd));
    fixed_sat #(.IN_W(OutRndW), .OUT_W(OUT_BITS), .OUT_SIGNED(0), .WRAP(0))
      u_sat_out (.in_i(out_rnd), .out_o(colour_o[c*OUT_BITS +: OUT_BITS]));
  end
`ifndef SYNTHESIS
  initial begin
    if (STAGES < 0 || STAGES > 2)
      $fatal(1, "pixel_combine: STAGES %0d is not 0, 1 or 2", STAGES);
  end
`endif
  if (DIFFUSE_MULTIPLY) begin : g_no_gate_only
    // verilator lint_off UNUSEDSIGNAL
    logic unused_gate_only;  // reason: every light's one series is N.L and gates itself
    assign unused_gate_only = ^gate_only_i;
    // verilator lint_on UNUSEDSIGNAL
  end else begin : g_no_diffuse_colour
    // verilator lint_off UNUSEDSIGNAL
    logic unused_diffuse_colour;  // reason: the colour is rolled into the series
    assign unused_diffuse_colour = ^diffuse_colour_i;
    // verilator lint_on UNUSEDSIGNAL
  end
endmodule
