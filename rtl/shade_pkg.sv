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
      lsb = lsb + bits;
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

  // ---- span setup site (SpanSetupSite of model/unit_config.h; shade_unit's SPAN_SETUP) -------
  localparam int SetupUnit = 0;  // span setup in the unit, from TRIANGLE coefficients
  localparam int SetupHost = 1;  // start values on each SPAN (start_bank.sv)

  // ---- host span setup: a SPAN's start values (model/start_packing.h, StartLayout: the twin) --
  // Series by series, v, d, d2, each SERIES_WL bits, packed densely: value j is bits
  // [j*SERIES_WL +: SERIES_WL] of the payload words read as one bit string (word 0 lowest).
  function automatic int start_words(input int n_ser, input int series_wl);
    start_words = (3 * n_ser * series_wl + WordW - 1) / WordW;
  endfunction

  // ---- specular units (SpecularUnitKind, UnitTiming codes of model/rtl_parameters.cpp) --------
  localparam int SpecIdeal       = 0;
  localparam int SpecLut         = 1;
  localparam int SpecSchlick     = 2;
  localparam int SpecWpow        = 3;
  localparam int SpecNone        = 4;  // no specular term: shade_unit has no slot and no series
  localparam int TimingIterative = 1;  // 0: pipelined

  // A unit's own fields (LutConfig, SchlickConfig, WpowConfig) reach the RTL as ONE packed
  // parameter, SPEC_PARAMS, of SpecSlots slots of SpecSlotW bits: slot k is
  // SPEC_PARAMS[k*SpecSlotW +: SpecSlotW]. shade_unit and specular_unit only pass it on; each
  // unit module decodes its own slots at its top. Which field is in which slot is the field's
  // row in model/specular_units.cpp (SpecularField::slot); model/rtl_parameters.cpp packs them
  // (kSpecSlots, kSpecSlotBits are these two). A new field of a unit so touches that unit's
  // files and its row, not shade_unit, specular_unit or the testbench.
  localparam int SpecSlots  = 8;
  localparam int SpecSlotW  = 32;
  localparam int SpecParamW = SpecSlots * SpecSlotW;

  function automatic int spec_slot(input logic [SpecParamW-1:0] params, input int slot);
    spec_slot = params[slot*SpecSlotW +: SpecSlotW];
  endfunction

  // wpow's registers per squaring (slot 3): 2 splits each square over two cycles (pipelined
  // only), else 1.
  function automatic int wpow_square_stages(input logic [SpecParamW-1:0] params);
    wpow_square_stages = spec_slot(params, 3) == 2 ? 2 : 1;
  endfunction

  // Registers between the slot's series input and its specular output: ideal and none 0; lut 2 (+1
  // interpolated); schlick its quotient bits; wpow log2(max_m) squarings (times square_stages)
  // + the clamped base.
  // The slots read (model/specular_units.cpp): lut 2 interp_bits; schlick 0 quotient_bits,
  // 2 timing; wpow 0 max_m, 2 timing, 3 square_stages.
  function automatic int spec_latency(input int kind, input logic [SpecParamW-1:0] params);
    spec_latency = kind == SpecLut     ? (spec_slot(params, 2) > 0 ? 3 : 2) :
                   kind == SpecSchlick ? spec_slot(params, 0) :
                   kind == SpecWpow    ? $clog2(spec_slot(params, 0)) *
                                             wpow_square_stages(params) + 1 : 0;
  endfunction

  // Cycles per pixel: 1, except an iterative unit, which takes its whole latency per pixel.
  function automatic int spec_interval(input int kind, input logic [SpecParamW-1:0] params);
    spec_interval = (kind == SpecSchlick || kind == SpecWpow) &&
                    spec_slot(params, 2) == TimingIterative
                        ? spec_latency(kind, params)
                        : 1;
  endfunction

  // ---- series per pixel ----------------------------------------------------------------------
  // Each light's specular series: Schlick's numerator and denominator, one for the other units,
  // none without a specular term.
  function automatic int spec_series_per_light(input int kind);
    spec_series_per_light = kind == SpecSchlick ? 2 : kind == SpecNone ? 0 : 1;
  endfunction

  // One diffuse series per light and channel (per light when pixel_combine multiplies the diffuse
  // colour in), then each light's specular ones.
  function automatic int series_count(input int kind, input int lights, input int channels,
                                      input bit diffuse_multiply);
    series_count = (diffuse_multiply ? lights : lights * channels) +
                   lights * spec_series_per_light(kind);
  endfunction
  // verilator lint_on UNUSEDPARAM
endpackage
