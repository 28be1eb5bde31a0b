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
  localparam int          HighLsb     = 32;     // [47:32] TRIANGLE xo, SPAN y
  localparam int          SpanLastBit = 55;     // SPAN: last span of its scanline

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
