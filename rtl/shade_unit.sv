// shade_unit: the whole shading unit (model/shade_unit.h, class ShadeUnit): the wiring of its
// control modules and datapath. docs/rtl.md describes each module, the ports and the timing.
module shade_unit #(
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int XY_BITS          = 12,
  parameter int OFS_BITS         = 17,  // signed offsets x0 - xo, y - yo (17: any origin)
  parameter int COEF_WL          = 36,
  parameter int COEF_IWL         = 4,
  // Coefficient packing: each term's width in the TRIANGLE payload (shade_pkg::coef_word).
  parameter int COEF_T0_WL       = COEF_WL,
  parameter int COEF_T1_WL       = COEF_WL,
  parameter int COEF_T2_WL       = COEF_WL,
  parameter int COEF_T3_WL       = COEF_WL,
  parameter int COEF_T4_WL       = COEF_WL,
  parameter int COEF_T5_WL       = COEF_WL,
  parameter int SERIES_WL        = 32,
  parameter int SERIES_IWL       = 4,
  parameter int SERIES_QUANT     = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int SERIES_OVERFLOW  = 1,  // Overflow: 0 saturate, 1 wrap
  parameter int SPEC_COLOUR_WL   = 13,
  parameter int SPEC_COLOUR_IWL  = 1,
  parameter int OUT_BITS         = 8,
  // SpecularUnitKind: 0 ideal, 1 lut, 2 schlick, 3 wpow, 4 none (no specular term)
  parameter int SPECULAR_KIND    = 0,
  parameter int SPECULAR_OUT_WL  = 17,
  parameter int SPECULAR_OUT_IWL = 1,
  parameter int PORT_WORDS       = 1,  // 64-bit words per cmd handshake: 1, 2, 4 or 8
  parameter int TRI_QUEUE        = 1,  // coefficient banks (> 1: a span queue, span_queue.sv)
  parameter int LANES            = 1,  // pixels of a span per beat: 1, 2 or 4
  parameter int MATERIAL_BUFFERS = 1,  // banks of the per-material registers: 1 or 2
  // The specular unit's output rounding and its own fields, packed by slot (shade_pkg::SpecSlots;
  // model/specular_units.cpp gives each field its slot), passed to specular_unit untouched.
  parameter int SPECULAR_OUT_QUANT    = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int SPECULAR_OUT_OVERFLOW = 0,  // Overflow: 0 saturate, 1 wrap
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS = '0,
  // Span setup: shade_pkg::SetupUnit (coefficient banks and span setup in the unit) or
  // SetupHost (each SPAN carries its start values into start_bank; TRI_QUEUE must be 1).
  parameter int SPAN_SETUP       = 0,
  parameter int START_DEPTH      = 1,  // host setup: start bank entries, 1 or 2
  // DiffuseColour: 0 rolled into the series (a series per light and channel), 1 multiplied in
  // pixel_combine (one N.L series per light; the MATERIAL carries kd_c L_c).
  parameter int DIFFUSE_MULTIPLY = 0,
  // Pipelining (UnitConfig::combine_stages): register stages in pixel_combine, 0, 1 (its terms)
  // or 2 (its raw products too); the beat's metadata waits beside them in a line as deep.
  parameter int COMBINE_STAGES   = 0
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic [PORT_WORDS*shade_pkg::WordW-1:0] cmd_data_i,
  input  logic                         cmd_valid_i,
  output logic                         cmd_ready_o,
  output logic [XY_BITS-1:0]           pix_x_o,
  output logic [XY_BITS-1:0]           pix_y_o,
  output logic [LANES*CHANNELS*OUT_BITS-1:0] pix_colour_o,  // lane j at j*CHANNELS*OUT_BITS
  output logic [LANES-1:0]             pix_mask_o,
  output logic                         pix_eor_o,
  output logic                         pix_valid_o,
  input  logic                         pix_ready_i
);
  localparam bit Specular       = SPECULAR_KIND != shade_pkg::SpecNone;  // a specular term
  localparam int SeriesPerLight = shade_pkg::spec_series_per_light(SPECULAR_KIND);
  localparam int NColours       = LIGHTS * CHANNELS;  // colour words per MATERIAL and kind
  localparam bit Multiply       = DIFFUSE_MULTIPLY != 0;
  localparam int NDiff          = Multiply ? LIGHTS : NColours;  // diffuse series
  localparam int NSer           = shade_pkg::series_count(SPECULAR_KIND, LIGHTS, CHANNELS,
                                                         Multiply);
  localparam int NCoef          = 6 * NSer;
  // ambient + spec_colour (+ diffuse_colour) words
  localparam int NMatFixed      = CHANNELS + (Multiply ? 2 : 1) * NColours;
  // The slot's timing (shade_pkg, the one definition; specular_unit's contract).
  localparam int SpecLatency    = shade_pkg::spec_latency(SPECULAR_KIND, SPEC_PARAMS);
  localparam bit Iterative      = shade_pkg::spec_interval(SPECULAR_KIND, SPEC_PARAMS) > 1;
  localparam int LaneSerW       = NSer * SERIES_WL;  // one lane's series values
  localparam int LaneDiffW      = NDiff * SERIES_WL;  // ... of them the diffuse ones
  localparam int LaneColW       = CHANNELS * OUT_BITS;
  localparam bit Host           = SPAN_SETUP == shade_pkg::SetupHost;
  localparam int StartWords     = shade_pkg::start_words(NSer, SERIES_WL);  // per SPAN (host)
  localparam bit Queued         = TRI_QUEUE > 1;
  localparam int SpanQ          = Queued ? 4 * TRI_QUEUE : 1;  // = CycleConfig::span_queue()
  localparam int PosW           = PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1;
  localparam int SpanW          = 3 * XY_BITS + 2;  // $bits(span_t)
  typedef struct packed {
    logic [XY_BITS-1:0] y;
    logic [XY_BITS-1:0] x0;
    logic [XY_BITS:0]   len;  // 1..2^XY_BITS (CommandStream::validate)
    logic               last;
  } span_t;
  typedef struct packed {
    logic [XY_BITS-1:0]         x, y;      // lane 0's pixel
    logic                       eor;
    logic                       span_end;  // the span's last beat
    logic                       mat;       // the span's material bank
    logic [LANES-1:0]           mask;      // valid lanes
    logic [LANES*LaneDiffW-1:0] diffuse;   // lane j at j * LaneDiffW
  } meta_t;
  localparam int MetaW = 2 * XY_BITS + 3 + LANES + LANES * LaneDiffW;  // $bits(meta_t)
  logic [shade_pkg::WordW-1:0] cmd_word;
  // verilator lint_off UNUSEDSIGNAL
  logic [7:0]       hdr_op;  // reason: with hdr_fire, read by sim/harness/shade_cover.sv's bind
  logic             hdr_fire;
  // verilator lint_on UNUSEDSIGNAL
  logic [15:0]      pay_idx, sq_room, cfg_addr;  logic [PosW-1:0] word_sel;
  logic [$clog2(PORT_WORDS+1)-1:0] hdr_pos, hdr_n, tail_n;  // counts of beat words
  logic span_fire, tri_fire, mat_fire, pay_mat, cfg_valid, cfg_table, cfg_all_banks, s1_free;
  logic datapath_empty, mat_other_free, mat_cur_free, sq_full, sq_empty, tri_bank_free;
  logic start_free, span_pay;  // host setup: a start bank entry free; its payload words due
  cmd_decoder #(
    .PORT_WORDS(PORT_WORDS), .QUEUED(Queued), .MAT_BANKED(MATERIAL_BUFFERS == 2),
    .N_MAT_FIXED(NMatFixed), .HOST_SETUP(Host), .START_WORDS(StartWords)
  ) u_decoder (
    .clk_i, .rst_ni, .cmd_data_i, .cmd_valid_i, .cmd_ready_o, .datapath_empty_i(datapath_empty),
    .mat_other_free_i(mat_other_free), .mat_cur_free_i(mat_cur_free), .sq_full_i(sq_full),
    .sq_room_i(sq_room), .s1_free_i(s1_free), .tri_bank_free_i(tri_bank_free),
    .start_free_i(start_free), .span_pay_o(span_pay),
    .word_o(cmd_word), .word_sel_o(word_sel), .hdr_op_o(hdr_op), .hdr_pos_o(hdr_pos),
    .hdr_n_o(hdr_n), .hdr_fire_o(hdr_fire), .span_fire_o(span_fire), .tri_fire_o(tri_fire),
    .mat_fire_o(mat_fire), .tail_n_o(tail_n), .pay_idx_o(pay_idx),
    .pay_mat_o(pay_mat), .cfg_valid_o(cfg_valid), .cfg_table_o(cfg_table),
    .cfg_all_banks_o(cfg_all_banks), .cfg_addr_o(cfg_addr)
  );
  logic             s1_load, s1_src_mat, mat_wr;
  // verilator lint_off UNUSEDSIGNAL
  span_t            s1_src;  // reason: the series path reads x0 and y (span_source the rest)
  // verilator lint_on UNUSEDSIGNAL
  logic [NCoef*COEF_WL-1:0] coef;  // s1_src's triangle's, coefficient j at j * COEF_WL; origin:
  logic signed [OFS_BITS-1:0] xo, yo;
  logic s1_move, s2_move, load_eng, mat_q, mat_leave;
  logic  s3_v, setup_busy;  span_t s3_span;  // the span the engines take next
  logic [NSer*SERIES_WL-1:0] bank_v, bank_d, bank_d2;  // ... its start values (host setup)
  span_source #(
    .HOST_SETUP(Host), .PORT_WORDS(PORT_WORDS), .XY_BITS(XY_BITS), .TRI_QUEUE(TRI_QUEUE),
    .N_COEF(NCoef), .COEF_WL(COEF_WL), .COEF_T0_WL(COEF_T0_WL), .COEF_T1_WL(COEF_T1_WL),
    .COEF_T2_WL(COEF_T2_WL), .COEF_T3_WL(COEF_T3_WL), .COEF_T4_WL(COEF_T4_WL),
    .COEF_T5_WL(COEF_T5_WL), .OFS_BITS(OFS_BITS), .N_SER(NSer), .SERIES_WL(SERIES_WL),
    .START_DEPTH(START_DEPTH)
  ) u_span_source (
    .clk_i, .rst_ni, .cmd_data_i, .cmd_valid_i, .word_i(cmd_word), .word_sel_i(word_sel),
    .hdr_pos_i(hdr_pos), .hdr_n_i(hdr_n), .tail_n_i(tail_n), .pay_idx_i(pay_idx),
    .span_fire_i(span_fire), .tri_fire_i(tri_fire), .span_pay_i(span_pay), .mat_wr_i(mat_wr),
    .eng_load_i(load_eng), .sq_full_o(sq_full), .sq_empty_o(sq_empty),
    .tri_bank_free_o(tri_bank_free), .sq_room_o(sq_room), .s1_free_o(s1_free),
    .start_free_o(start_free), .s1_load_o(s1_load), .s1_move_o(s1_move), .s2_move_o(s2_move),
    .s1_span_o(s1_src), .s1_mat_o(s1_src_mat), .coef_o(coef), .xo_o(xo), .yo_o(yo),
    .bank_v_o(bank_v), .bank_d_o(bank_d), .bank_d2_o(bank_d2), .s3_valid_o(s3_v),
    .s3_span_o(s3_span), .busy_o(setup_busy)
  );
  meta_t meta_in, meta_out;  // from the engines; at the slot's output
  logic [CHANNELS*SERIES_WL-1:0] ambient;
  logic [NColours*SPEC_COLOUR_WL-1:0] spec_colour, diffuse_colour;
  logic [LIGHTS-1:0]             gate_only;
  material_bank #(
    .CHANNELS(CHANNELS), .LIGHTS(LIGHTS), .SERIES_WL(SERIES_WL),
    .SPEC_COLOUR_WL(SPEC_COLOUR_WL), .MATERIAL_BUFFERS(MATERIAL_BUFFERS),
    .SPAN_Q(Host ? START_DEPTH : SpanQ), .SPEC_LATENCY(SpecLatency), .HOST_SETUP(Host),
    .DIFFUSE_MULTIPLY(Multiply)
  ) u_material_bank (
    .clk_i, .rst_ni, .word_i(cmd_word), .mat_fire_i(mat_fire), .pay_mat_i(pay_mat),
    .pay_idx_i(pay_idx), .span_fire_i(span_fire), .span_n_i(Host ? 16'd1 : 16'(hdr_n)),
    .s1_load_i(s1_load),
    .s1_bank_i(s1_src_mat), .s1_move_i(s1_move), .s2_move_i(s2_move), .eng_load_i(load_eng),
    .eng_bank_o(mat_q), .leave_i(mat_leave), .leave_bank_i(meta_out.mat), .wr_bank_o(mat_wr),
    .other_free_o(mat_other_free), .cur_free_o(mat_cur_free), .rd_bank_i(meta_out.mat),
    .ambient_o(ambient), .spec_colour_o(spec_colour), .diffuse_colour_o(diffuse_colour),
    .gate_only_o(gate_only)
  );
  logic [NSer*SERIES_WL-1:0] setup_v;
  // Nets of their own (wires, which a force overrides in every simulator) between the modules:
  // the harness forces its deliberate errors onto them (sim/harness/faults/, docs/cosim.md).
  wire  [NSer*SERIES_WL-1:0] start_v = setup_v;
  logic [LANES*LaneSerW-1:0] eng_v;  logic emit, adv, spec_busy;  // eng_v: lane j at j*LaneSerW
  series_path #(
    .N_SER(NSer), .LANES(LANES), .COEF_WL(COEF_WL), .COEF_IWL(COEF_IWL), .SERIES_WL(SERIES_WL),
    .SERIES_IWL(SERIES_IWL), .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW),
    .OFS_BITS(OFS_BITS), .HOST_SETUP(Host)
  ) u_series (
    .clk_i, .s1_en_i(s1_load), .s2_en_i(s1_move), .s3_en_i(s2_move), .coef_i(coef),
    .x_i(OFS_BITS'(s1_src.x0)), .y_i(OFS_BITS'(s1_src.y)), .xo_i(xo), .yo_i(yo),
    .bank_v_i(bank_v), .bank_d_i(bank_d), .bank_d2_i(bank_d2),
    .setup_v_o(setup_v), .start_v_i(start_v), .load_i(load_eng), .step_i(emit), .v_o(eng_v)
  );
  wire  eng_span_valid = s3_v;
  logic run, eng_span_end, eng_eor;
  logic [XY_BITS-1:0]         eng_x, eng_y;
  logic [LANES-1:0]           eng_mask;
  logic [LANES*LaneDiffW-1:0] eng_diffuse;  // lane j at j * LaneDiffW
  engine_ctrl #(.XY_BITS(XY_BITS), .LANES(LANES)) u_engine_ctrl (
    .clk_i, .rst_ni, .span_valid_i(eng_span_valid), .span_i(s3_span), .adv_i(adv),
    .spec_busy_i(spec_busy), .load_o(load_eng), .emit_o(emit),
    .run_o(run), .x_o(eng_x), .y_o(eng_y), .mask_o(eng_mask), .span_end_o(eng_span_end),
    .eor_o(eng_eor)
  );
  for (genvar j = 0; j < LANES; j++) begin : g_lane_meta
    assign eng_diffuse[j*LaneDiffW +: LaneDiffW] = eng_v[j*LaneSerW +: LaneDiffW];
  end
  // (One concatenation: Icarus 11 cannot assign a part of a struct member.)
  assign meta_in = {eng_x, eng_y, eng_eor, eng_span_end, mat_q, eng_mask, eng_diffuse};
  logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] slot_spec;  // lane j, light l: j * LIGHTS + l
  wire  [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] spec = slot_spec;
  logic                                    slot_en, out_adv, meta_out_valid, slot_empty;
  assign slot_en = Iterative ? emit : adv;
  spec_slots #(
    .SPECULAR_KIND(SPECULAR_KIND), .LIGHTS(LIGHTS), .LANES(LANES), .N_DIFF(NDiff),
    .SERIES_PER_LIGHT(SeriesPerLight), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
    .SPECULAR_OUT_WL(SPECULAR_OUT_WL), .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL),
    .SPECULAR_OUT_QUANT(SPECULAR_OUT_QUANT), .SPECULAR_OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW),
    .MATERIAL_BUFFERS(MATERIAL_BUFFERS), .SPEC_PARAMS(SPEC_PARAMS)
  ) u_slots (
    .clk_i, .rst_ni, .en_i(slot_en), .series_i(eng_v), .bank_i(mat_q), .cfg_valid_i(cfg_valid),
    .cfg_bank_i(mat_wr), .cfg_all_banks_i(cfg_all_banks), .cfg_table_i(cfg_table),
    .cfg_addr_i(cfg_addr), .cfg_data_i(cmd_word), .spec_o(slot_spec), .busy_o(spec_busy)
  );
  slot_meta #(.META_W(MetaW), .LATENCY(SpecLatency), .ITERATIVE(Iterative)) u_slot_meta (
    .clk_i, .rst_ni, .adv_i(adv), .spec_busy_i(spec_busy), .valid_i(run), .meta_i(meta_in),
    .out_adv_o(out_adv), .valid_o(meta_out_valid), .meta_o(meta_out), .empty_o(slot_empty)
  );
  assign datapath_empty = sq_empty && !setup_busy && !run && slot_empty;
  // A span's last beat leaves the slot: no pixel of it reads its bank any more.
  assign mat_leave = out_adv && meta_out_valid && meta_out.span_end;
  logic [LANES*LaneColW-1:0] colour;  // lane j at j * LaneColW
  wire  [LANES*LaneColW-1:0] colour_out = colour;
  // The combine's own stages: the beat leaves the slot (reading its material: the bank may
  // change after) and waits COMBINE_STAGES advances before the pix register takes it.
  logic  pix_meta_valid;
  // verilator lint_off UNUSEDSIGNAL
  meta_t pix_meta;  // reason: past the combine's terms only position, mask and eor are read
  logic  combine_out_adv, combine_empty;  // reason: a pipelined line's are adv and not needed
  // verilator lint_on UNUSEDSIGNAL
  slot_meta #(.META_W(MetaW), .LATENCY(COMBINE_STAGES), .ITERATIVE(1'b0)) u_combine_meta (
    .clk_i, .rst_ni, .adv_i(adv), .spec_busy_i(1'b0), .valid_i(out_adv && meta_out_valid),
    .meta_i(meta_out), .out_adv_o(combine_out_adv), .valid_o(pix_meta_valid), .meta_o(pix_meta),
    .empty_o(combine_empty)
  );
  combine_lanes #(
    .CHANNELS(CHANNELS), .LIGHTS(LIGHTS), .LANES(LANES), .SERIES_WL(SERIES_WL),
    .SERIES_IWL(SERIES_IWL), .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW),
    .SPEC_COLOUR_WL(SPEC_COLOUR_WL), .SPEC_COLOUR_IWL(SPEC_COLOUR_IWL),
    .SPECULAR_OUT_WL(SPECULAR_OUT_WL), .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL), .OUT_BITS(OUT_BITS),
    .SPECULAR(Specular), .DIFFUSE_MULTIPLY(Multiply), .STAGES(COMBINE_STAGES)
  ) u_combine_lanes (
    .clk_i, .en_i(adv),
    .diffuse_i(meta_out.diffuse), .spec_i(spec), .ambient_i(ambient),
    .spec_colour_i(spec_colour), .diffuse_colour_i(diffuse_colour), .gate_only_i(gate_only),
    .colour_o(colour)
  );
  wire  [XY_BITS-1:0] out_x = pix_meta.x, out_y = pix_meta.y;
  wire                out_eor = pix_meta.eor;
  // (No combine stage: the line is a wire, and its valid already implies adv.)
  wire                pix_load = adv && pix_meta_valid;
  out_reg #(.XY_BITS(XY_BITS), .LANES(LANES), .COLOUR_W(LANES * LaneColW)) u_out_reg (
    .clk_i, .rst_ni, .load_i(pix_load), .x_i(out_x), .y_i(out_y),
    .colour_i(colour_out), .mask_i(pix_meta.mask), .eor_i(out_eor), .adv_o(adv), .pix_x_o,
    .pix_y_o, .pix_colour_o, .pix_mask_o, .pix_eor_o, .pix_valid_o, .pix_ready_i
  );

`ifndef SYNTHESIS
  // UnitConfig::validate's ranges (model/unit_config.cpp): each module checks its own.
  initial begin
    if (SPAN_SETUP != shade_pkg::SetupUnit && SPAN_SETUP != shade_pkg::SetupHost)
      $fatal(1, "shade_unit: SPAN_SETUP %0d is not 0 (unit) or 1 (host)", SPAN_SETUP);
    if (COMBINE_STAGES < 0 || COMBINE_STAGES > 2)
      $fatal(1, "shade_unit: COMBINE_STAGES %0d is not 0, 1 or 2", COMBINE_STAGES);
    if (DIFFUSE_MULTIPLY != 0 && DIFFUSE_MULTIPLY != 1)
      $fatal(1, "shade_unit: DIFFUSE_MULTIPLY %0d is not 0 or 1", DIFFUSE_MULTIPLY);
    if ($bits(meta_t) != MetaW || $bits(span_t) != SpanW)
      $fatal(1, "shade_unit: MetaW or SpanW is not $bits of its struct");
  end
`endif
endmodule
