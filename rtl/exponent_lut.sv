// exponent_lut: t^n from a table (model/exponent_lut.h, class ExponentLut; Bishop & Weimer).
//
// SPEC_PARAMS's slots (decoded below) mirror LutConfig: ADDR_BITS (A, 2^A entries), ENTRY_BITS
// (B, entry e means e / 2^B), INTERP_BITS (F, 0 = no interpolation), INDEX (LutIndex: 0
// truncate, 1 nearest). The other parameters are the unit's formats: SERIES_WL/IWL (the series
// format, fs = SERIES_WL - SERIES_IWL >= 1 fraction bits); OUT_WL/IWL/QUANT/OVERFLOW (the
// specular out format, unsigned). Shared vs per-exponent addressing is the host's business: the
// hardware is the same.
//
// Stages (each a register clocked by en_i, in the model's order):
//   1. ADDRESS  a = quantize(series << shift, unsigned A.F, INDEX rule, saturate)
//               (series << shift is exact; the rounding/saturation is fixed_round + fixed_sat)
//   2. READ     e0 = table[a >> F]; with F > 0 also e1 = table[min(idx + 1, 2^A - 1)] and frac
//   3. INTERP   (F > 0 only) v = e0 * 2^F + frac * (e1 - e0), exact
//   4. OUTPUT   quantize(v) into the out format: combinational after the last register
// Timing: a pipeline of LATENCY = 2 (+1 with F > 0) registers, all enabled by en_i (advance):
// spec_o shows the result of the series_i sampled at the LATENCY-th most recent en_i edge.
// One pixel per cycle (busy never).
//
// Configuration (the specular slot's cfg port; words in stream order):
//   MATERIAL (cfg_table_i = 0): cfg_addr_i 0 = exponent word (resets shift to 0: empty
//            unit_params mean shift 0), 1 = unit_params[0] = shift (0..fs, low bits taken).
//   TABLE    (cfg_table_i = 1): cfg_addr_i = entry address (base + i), cfg_data_i[B-1:0] = entry;
//            addresses >= 2^A are ignored (the model rejects them).
// Material banks (BANKS = 2, shade_unit's MATERIAL_BUFFERS): the shift register and the table
// are doubled. MATERIAL words write bank cfg_bank_i; TABLE entries write bank cfg_bank_i, or
// every bank with cfg_all_banks_i (a TABLE that is not per-material). ADDRESS reads the shift
// of the pixel's bank bank_i, and the bank travels with the address to READ.
// TABLE_FILE: optional $readmemh file written by ExponentLut::write_hex (absolute path), loaded at
// time 0; a missing file is a $fatal error, not $readmemh's warning.
module exponent_lut #(
  // The unit's fields, packed (shade_pkg::SpecSlots slots; decoded below). The default is
  // the model's default LutConfig: A 10, B 8, F 0, truncate.
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS =
      {{(shade_pkg::SpecSlots - 4){32'd0}}, 32'd0, 32'd0, 32'd8, 32'd10},
  parameter int SERIES_WL    = 32,
  parameter int SERIES_IWL   = 4,
  parameter int OUT_WL       = 17,
  parameter int OUT_IWL      = 1,
  parameter int OUT_QUANT    = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int OUT_OVERFLOW = 0,  // Overflow: 0 saturate, 1 wrap
  parameter int CFG_ADDR_W   = 16,
  parameter int BANKS        = 1,  // material banks, 1 or 2
  parameter     TABLE_FILE   = ""
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  en_i,
  input  logic [SERIES_WL-1:0]  series_i,
  input  logic                  bank_i,      // material bank of the pixel on series_i
  input  logic                  cfg_valid_i,
  input  logic                  cfg_bank_i,  // material bank the MATERIAL / TABLE words write
  input  logic                  cfg_all_banks_i,  // TABLE: write the entry into every bank
  input  logic                  cfg_table_i,
  input  logic [CFG_ADDR_W-1:0] cfg_addr_i,
  // verilator lint_off UNUSEDSIGNAL
  input  logic [63:0]           cfg_data_i,  // only the low B (entry) / shift bits are used
  // verilator lint_on UNUSEDSIGNAL
  output logic [OUT_WL-1:0]     spec_o
);
  // LutConfig from SPEC_PARAMS: the slots of the "lut" row of model/specular_units.cpp. The
  // names are the parameters' they replace, so the body reads as before.
  localparam int ADDR_BITS   = shade_pkg::spec_slot(SPEC_PARAMS, 0);  // lut.addr_bits
  localparam int ENTRY_BITS  = shade_pkg::spec_slot(SPEC_PARAMS, 1);  // lut.entry_bits
  localparam int INTERP_BITS = shade_pkg::spec_slot(SPEC_PARAMS, 2);  // lut.interp_bits
  localparam int INDEX       = shade_pkg::spec_slot(SPEC_PARAMS, 3);  // lut.index: LutIndex code
`ifndef SYNTHESIS
  // The ranges of the row (SpecularField lo / hi) this RTL needs; the model checks all of them.
  initial begin
    if (ADDR_BITS < 1 || ADDR_BITS > CFG_ADDR_W)
      $fatal(1, "exponent_lut: ADDR_BITS %0d is not 1..%0d: cfg_addr_i cannot reach every entry",
             ADDR_BITS, CFG_ADDR_W);
    if (ENTRY_BITS < 1) $fatal(1, "exponent_lut: ENTRY_BITS %0d is not >= 1", ENTRY_BITS);
    if (INDEX != 0 && INDEX != 1) $fatal(1, "exponent_lut: INDEX %0d is not 0 or 1", INDEX);
  end
`endif
  localparam int Fs      = SERIES_WL - SERIES_IWL;
  localparam int ShiftW  = $clog2(Fs + 1);
  localparam int AW      = ADDR_BITS + INTERP_BITS;
  localparam int Entries = 1 << ADDR_BITS;
  localparam int XW      = SERIES_WL + Fs;           // series << shift for any shift 0..fs
  localparam int AdrDrop = Fs - ADDR_BITS - INTERP_BITS;
  localparam int AdrRndW = XW + 1 - AdrDrop;
  localparam int VW      = ENTRY_BITS + INTERP_BITS + 2;  // signed, holds e0*2^F + frac*(e1-e0)
  localparam int OutDrop = ENTRY_BITS + INTERP_BITS - (OUT_WL - OUT_IWL);
  localparam int OutRndW = VW + 1 - OutDrop;

  // ---- per-material parameter: the input shift, per bank ---------------------------------
  logic [ShiftW-1:0] shift_q [BANKS];
  logic              rd_bank, wr_bank;  // the banks read (ADDRESS) and written (cfg)
  logic              bank_q;            // the bank of the pixel whose address is in a_q
  logic              tbl_bank;          // the table READ reads
  if (BANKS > 1) begin : g_banks
    assign rd_bank  = bank_i;
    assign wr_bank  = cfg_bank_i;
    assign tbl_bank = bank_q;
  end else begin : g_one_bank
    // verilator lint_off UNUSEDSIGNAL
    logic unused_bank;  // one bank: the tags are always 0
    assign unused_bank = bank_i ^ cfg_bank_i ^ cfg_all_banks_i ^ bank_q;
    // verilator lint_on UNUSEDSIGNAL
    assign rd_bank  = 1'b0;
    assign wr_bank  = 1'b0;
    assign tbl_bank = 1'b0;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int b = 0; b < BANKS; b++) shift_q[b] <= '0;
    end else if (cfg_valid_i && !cfg_table_i) begin
      if (cfg_addr_i == CFG_ADDR_W'(0))      shift_q[wr_bank] <= '0;
      else if (cfg_addr_i == CFG_ADDR_W'(1)) shift_q[wr_bank] <= cfg_data_i[ShiftW-1:0];
    end
  end

  // ---- table RAM, one per bank: written by TABLE words, two registered read ports ----------
  // An entry address of 2^A or more writes nothing. One expression for every A, so the tests of
  // the usual A < CFG_ADDR_W also cover A = CFG_ADDR_W (every address an entry), which no named
  // build has: as a generate branch of its own it hid a mutant (scripts/mutate-rtl).
  logic                  tbl_we;
  logic [ADDR_BITS-1:0]  tbl_waddr;
  assign tbl_we    = cfg_valid_i && cfg_table_i && (cfg_addr_i >> ADDR_BITS) == '0;
  assign tbl_waddr = ADDR_BITS'(cfg_addr_i);
  logic [ADDR_BITS-1:0]          idx, idx1;  // READ's addresses (idx1 used with F > 0)
  logic [BANKS*ENTRY_BITS-1:0]   rd0, rd1;   // bank b's entries at idx, idx1: [b*B +: B]
  for (genvar b = 0; b < BANKS; b++) begin : g_table
    logic [ENTRY_BITS-1:0] mem_q [Entries];
    always_ff @(posedge clk_i) begin
      if (tbl_we && (cfg_all_banks_i || wr_bank == 1'(b)))
        mem_q[tbl_waddr] <= cfg_data_i[ENTRY_BITS-1:0];
    end
    assign rd0[b*ENTRY_BITS +: ENTRY_BITS] = mem_q[idx];
    assign rd1[b*ENTRY_BITS +: ENTRY_BITS] = mem_q[idx1];

    if (TABLE_FILE != "") begin : g_init
`ifndef SYNTHESIS
      initial begin
        int fd;
        fd = $fopen(TABLE_FILE, "r");
        if (fd == 0)
          $fatal(1, "exponent_lut: cannot open TABLE_FILE '%s' (%s)", TABLE_FILE,
                 "ExponentLut::write_hex output expected");
        $fclose(fd);
        $readmemh(TABLE_FILE, mem_q);
      end
`else
      initial $readmemh(TABLE_FILE, mem_q);
`endif
    end
  end

  // ---- 1. ADDRESS ------------------------------------------------------------------------------
  logic signed [XW-1:0]      shifted;
  logic signed [AdrRndW-1:0] a_rnd;
  logic [AW-1:0]             a_d, a_q;
  assign shifted = {{Fs{series_i[SERIES_WL-1]}}, series_i} << shift_q[rd_bank];
  fixed_round #(.IN_W(XW), .DROP(AdrDrop), .ROUND(INDEX))
    u_adr_round (.in_i(shifted), .out_o(a_rnd));
  fixed_sat #(.IN_W(AdrRndW), .OUT_W(AW), .OUT_SIGNED(0), .WRAP(0))
    u_adr_sat (.in_i(a_rnd), .out_o(a_d));
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      a_q    <= a_d;
      bank_q <= rd_bank;
    end
  end

  // ---- 2. READ, 3. INTERP --------------------------------------------------------------------
  logic [ENTRY_BITS-1:0] e0_q;
  logic signed [VW-1:0]  v;  // the value OUTPUT quantizes, ENTRY_BITS + INTERP_BITS fraction bits
  assign idx  = a_q[AW-1:INTERP_BITS];
  assign idx1 = idx == ADDR_BITS'(Entries - 1) ? idx : idx + ADDR_BITS'(1);
  always_ff @(posedge clk_i) begin
    if (en_i) e0_q <= rd0[32'(tbl_bank) * ENTRY_BITS +: ENTRY_BITS];
  end

  if (INTERP_BITS > 0) begin : g_interp
    logic [ENTRY_BITS-1:0]   e1_q;
    logic [INTERP_BITS-1:0]  frac_q;
    logic signed [VW-1:0]    v_d, v_q;
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        e1_q   <= rd1[32'(tbl_bank) * ENTRY_BITS +: ENTRY_BITS];
        frac_q <= a_q[INTERP_BITS-1:0];
      end
    end
    // (F+1) x (B+1) signed multiplier: frac * (e1 - e0)
    logic signed [ENTRY_BITS:0]  diff;
    logic signed [INTERP_BITS:0] frac_s;
    logic signed [VW-1:0]        prod;
    assign diff   = $signed({1'b0, e1_q}) - $signed({1'b0, e0_q});
    assign frac_s = $signed({1'b0, frac_q});
    assign prod   = frac_s * diff;
    assign v_d    = $signed(VW'({e0_q, {INTERP_BITS{1'b0}}})) + prod;
    always_ff @(posedge clk_i) begin
      if (en_i) v_q <= v_d;
    end
    assign v = v_q;
  end else begin : g_no_interp
    // verilator lint_off UNUSEDSIGNAL
    logic unused_rd1;  // no interpolation: the second read port is not used
    assign unused_rd1 = ^rd1;
    // verilator lint_on UNUSEDSIGNAL
    assign v = $signed(VW'(e0_q));
  end

  // ---- 4. OUTPUT -------------------------------------------------------------------------------
  logic signed [OutRndW-1:0] out_rnd;
  fixed_round #(.IN_W(VW), .DROP(OutDrop), .ROUND(OUT_QUANT))
    u_out_round (.in_i(v), .out_o(out_rnd));
  fixed_sat #(.IN_W(OutRndW), .OUT_W(OUT_WL), .OUT_SIGNED(0), .WRAP(OUT_OVERFLOW))
    u_out_sat (.in_i(out_rnd), .out_o(spec_o));

`ifndef SYNTHESIS
  initial begin
    if (Fs < 1) $fatal(1, "exponent_lut: the series format needs at least one fraction bit");
    if (BANKS != 1 && BANKS != 2) $fatal(1, "exponent_lut: BANKS %0d is not 1 or 2", BANKS);
  end
`endif
endmodule
