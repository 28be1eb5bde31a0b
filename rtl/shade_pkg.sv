// shade_pkg: the one RTL definition of what shade_unit's command port carries (the layout of a
// command word; model/command_word.h is its C++ twin) and of the specular slot's timing
// (model/cycle_model.cpp SlotTiming::of, from the model classes' latency / cycles_per_pixel).
//
// Referenced as shade_pkg::NAME (Yosys 0.23 reads neither `import` inside a module nor
// `return` in a function, hence the qualified names and the assignments to the function name).
package shade_pkg;
  // A package is a set of definitions and each module reads only the ones it needs (the unit
  // tests Verilate exponent_lut & co. as their own top, which read none of the command layout).
  // verilator lint_off UNUSEDPARAM
  // ---- command words (model/command_stream.h documents each command) ------------------------
  localparam int          WordW       = 64;
  localparam int          OpcodeLsb   = 56;     // header[63:56]
  localparam logic [7:0]  OpNop       = 8'h00;  // beat padding: it and the rest of the beat
  localparam logic [7:0]  OpMaterial  = 8'h01;
  localparam logic [7:0]  OpTriangle  = 8'h02;
  localparam logic [7:0]  OpSpan      = 8'h03;
  localparam logic [7:0]  OpTable     = 8'h04;
  localparam logic [7:0]  OpEndFrame  = 8'h0F;
  localparam int          FieldW      = 16;     // every header field below is 16 bits wide
  localparam int          CountLsb    = 0;      // [15:0]  payload words; SPAN: length
  localparam int          MidLsb      = 16;     // [31:16] TRIANGLE yo, SPAN x0, TABLE base
  localparam int          GateOnlyLsb = MidLsb; // MATERIAL [31:16]: gate-only light mask
  localparam int          HighLsb     = 32;     // [47:32] TRIANGLE xo, SPAN y
  localparam int          SpanLastBit = 55;     // SPAN: last span of its scanline
  localparam int          TableMatBit = 55;     // TABLE: the table of the latest MATERIAL

  // ---- coefficient packing (model/coef_packing.h, CoefLayout: the C++ twin) ------------------
  // A TRIANGLE's coefficients in stream order, coefficient j being term j % 6 of width w<term>;
  // each starts at the lowest free bit of the current payload word, or at bit 0 of the next
  // word when it does not fit in what is left; none straddles two words.
  function automatic int coef_term_wl(input int j, input int w0, input int w1, input int w2,
                                      input int w3, input int w4, input int w5);
    coef_term_wl = j % 6 == 0 ? w0 : j % 6 == 1 ? w1 : j % 6 == 2 ? w2 :
                   j % 6 == 3 ? w3 : j % 6 == 4 ? w4 : w5;
  endfunction

  // Payload word (0: the first after the header) and lowest bit of coefficient j.
  function automatic int coef_word(input int j, input int w0, input int w1, input int w2,
                                   input int w3, input int w4, input int w5);
    integer i, word, lsb, bits;
    word = 0;
    lsb  = 0;
    for (i = 0; i <= j; i = i + 1) begin
      bits = coef_term_wl(i, w0, w1, w2, w3, w4, w5);
      if (lsb + bits > WordW) begin
        word = word + 1;
        lsb  = 0;
      end
      if (i < j) lsb = lsb + bits;
    end
    coef_word = word;
  endfunction

  function automatic int coef_lsb(input int j, input int w0, input int w1, input int w2,
                                  input int w3, input int w4, input int w5);
    integer i, lsb, bits;
    lsb = 0;
    for (i = 0; i <= j; i = i + 1) begin
      bits = coef_term_wl(i, w0, w1, w2, w3, w4, w5);
      if (lsb + bits > WordW) lsb = 0;
      if (i < j) lsb = lsb + bits;
    end
    coef_lsb = lsb;
  endfunction

  // ---- specular units (SpecularUnitKind, UnitTiming codes of model/rtl_parameters.cpp) --------
  localparam int SpecIdeal       = 0;
  localparam int SpecLut         = 1;
  localparam int SpecSchlick     = 2;
  localparam int SpecWpow        = 3;
  localparam int TimingIterative = 1;  // 0: pipelined

  // Registers between the slot's series input and its specular output: ideal 0; lut 2 (+1
  // interpolated); schlick its quotient bits; wpow log2(max_m) squarings + the clamped base.
  function automatic int spec_latency(input int kind, input int lut_interp_bits,
                                      input int schlick_quotient_bits, input int wpow_max_m);
    spec_latency = kind == SpecLut     ? (lut_interp_bits > 0 ? 3 : 2) :
                   kind == SpecSchlick ? schlick_quotient_bits :
                   kind == SpecWpow    ? $clog2(wpow_max_m) + 1 : 0;
  endfunction

  // Cycles per pixel: 1, except an iterative unit, which takes its whole latency per pixel.
  function automatic int spec_interval(input int kind, input int lut_interp_bits,
                                       input int schlick_quotient_bits, input int schlick_timing,
                                       input int wpow_max_m, input int wpow_timing);
    spec_interval = (kind == SpecSchlick && schlick_timing == TimingIterative) ||
                    (kind == SpecWpow && wpow_timing == TimingIterative)
                        ? spec_latency(kind, lut_interp_bits, schlick_quotient_bits, wpow_max_m)
                        : 1;
  endfunction
  // verilator lint_on UNUSEDPARAM
endpackage
