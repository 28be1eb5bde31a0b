// shade_unit: the whole shading unit (model/shade_unit.h, class ShadeUnit).
//
// cmd port: the command stream's binary words (model/command_stream.h; layout in rtl/shade_pkg.sv),
// PORT_WORDS per handshake (a beat; word k in cmd_data_i[64k +: 64]). The decoder takes a beat
// apart one item per cycle - a TRIANGLE header with the coefficient words after it in the beat,
// or the rest of a triangle's coefficient words in the beat, or one other header or payload
// word, or a NOP (0x00: the rest of the beat is padding) - and accepts the beat with its last.
// pix port: a beat of up to LANES pixels of one span per handshake, in stream order: lane j is
// pixel pix_x_o + j, its colour pix_colour_o[j*CHANNELS*OUT_BITS +: CHANNELS*OUT_BITS], valid
// when pix_mask_o[j] (lanes 0 .. n-1; lane 0 whenever pix_valid_o). A span of length len leaves
// in ceil(len / LANES) beats; pix_eor_o marks the beat holding the last pixel of a span flagged
// last_in_row (its last valid lane). LANES = 1: one pixel per beat, pix_mask_o = 1. Both ports
// are valid/ready; cmd_ready_o and the pipeline's advance depend combinationally on
// pix_ready_i (no skid buffers).
//
// Pipeline (the README's "RTL and co-simulation" has the latency / interval table):
//   decoder      header + payload words; TRIANGLE payload -> coefficient registers,
//                MATERIAL payload -> ambient / spec_colour registers and the specular slots,
//                TABLE payload -> specular slots. MATERIAL waits until the datapath is empty;
//                with MATERIAL_BUFFERS = 2 only until no span of the bank it switches to is in
//                flight (each span carries its material bank down to the pix register), and a
//                per-material TABLE until no span of the latest MATERIAL's bank is.
//   span_setup   3 stages (products, sums, rounding) per series; a SPAN header enters stage 1
//                whenever stage 1 is free, so setup overlaps the previous span's pixels.
//   engines      series_engine per series and lane; loaded from stage 3 through lane_fanout
//                (combinational: lane j's start and K-pixel differences) on the cycle the
//                previous span's last beat leaves the engines (back-to-back spans have no
//                bubble). A beat holds up to LANES pixels of one span.
//   slot         specular_unit per light and lane (LATENCY / INTERVAL below; all lanes in
//                lockstep). SPECULAR_KIND 4 (none): no slot and no specular series (no span_setup,
//                engines or coefficient registers for them); pixel_combine adds no specular
//                term. Pipelined units
//                (INTERVAL 1): a LATENCY-deep metadata line (valid, x, y, eor, diffuse values)
//                moves with the slot on the global advance. Iterative units (INTERVAL > 1): one
//                pixel in flight in a pending register; the engines step only when the unit
//                can start, which is also when the pending pixel is handed over.
//   output       pixel_combine per lane into the pix register.
module shade_unit #(
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int XY_BITS          = 12,
  // Signed width of span setup's offsets dx = x0 - xo, dy = y - yo (UnitConfig::offset_bits):
  // 17 holds any origin in the image; a scene's own unit takes what its triangles need.
  parameter int OFS_BITS         = 17,
  parameter int COEF_WL          = 36,
  parameter int COEF_IWL         = 4,
  // Coefficient packing: the width of each term T0..T5 in the TRIANGLE payload (COEF_WL's
  // fraction bits, fewer integer bits; sign-extended to COEF_WL on load). shade_pkg::coef_word
  // and coef_lsb place them in the payload words.
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
  // Triangle queue: coefficient banks. With more than one, SPAN headers go into a span queue
  // of 4 * TRI_QUEUE entries (each with its triangle's bank) and span setup takes them from
  // there, so the port runs ahead of the pixels by up to TRI_QUEUE triangles.
  parameter int TRI_QUEUE        = 1,
  // Pixel lanes: 1, 2 or 4 pixels of a span per beat (lane_fanout, model/lane_fanout.h).
  parameter int LANES            = 1,
  // Material buffers, 1 or 2 (UnitConfig::material_buffers): with 2 the per-material registers
  // (ambient, spec_colour, the specular unit's parameters) have two banks; a MATERIAL writes the
  // one no span in flight reads. The LUT has a table per bank: a per-material TABLE (header
  // bit TableMatBit, a per-exponent reload) writes the latest MATERIAL's bank and waits only
  // until no span of that bank is in flight; any other TABLE writes both and drains.
  parameter int MATERIAL_BUFFERS = 1,
  // The specular unit's output rounding and its own fields, packed: SPEC_PARAMS is passed to
  // specular_unit untouched (shade_pkg::SpecSlots; the selected unit's module decodes its
  // slots, model/specular_units.cpp gives each field its slot).
  parameter int SPECULAR_OUT_QUANT    = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int SPECULAR_OUT_OVERFLOW = 0,  // Overflow: 0 saturate, 1 wrap
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS = '0,
  // 1: the deliberate faults of the harness's own tests can be injected, one at a time, chosen
  // at run time (fault_select; the sites are shade_pkg::Fault*). 0 (every unit): none.
  parameter int FAULT_HOOKS      = 0
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
  localparam int SeriesPerLight = SPECULAR_KIND == shade_pkg::SpecSchlick ? 2 :
                                  Specular ? 1 : 0;
  localparam int NDiff          = LIGHTS * CHANNELS;
  localparam int NSer           = NDiff + LIGHTS * SeriesPerLight;
  localparam int NCoef          = 6 * NSer;
  localparam int NCoefWords     = shade_pkg::coef_word(NCoef - 1, COEF_T0_WL, COEF_T1_WL,
                                                       COEF_T2_WL, COEF_T3_WL, COEF_T4_WL,
                                                       COEF_T5_WL) + 1;  // TRIANGLE payload
  localparam int NMatFixed      = CHANNELS + LIGHTS * CHANNELS;  // ambient + spec_colour words
  localparam int OfsW           = OFS_BITS;
  // The slot's timing (shade_pkg, the one definition; specular_unit's contract).
  localparam int SpecLatency    = shade_pkg::spec_latency(SPECULAR_KIND, SPEC_PARAMS);
  localparam int SpecInterval   = shade_pkg::spec_interval(SPECULAR_KIND, SPEC_PARAMS);
  localparam bit Iterative      = SpecInterval > 1;
  localparam int LaneSerW       = NSer * SERIES_WL;  // one lane's series values
  localparam int LaneDiffW      = NDiff * SERIES_WL;  // ... of them the diffuse ones
  localparam int LaneColW       = CHANNELS * OUT_BITS;

`ifndef SYNTHESIS
  // The ranges UnitConfig::validate enforces (model/unit_config.cpp): a parameter outside them
  // would elaborate some other unit silently.
  initial begin
    if (CHANNELS != 1 && CHANNELS != 3)
      $fatal(1, "shade_unit: CHANNELS %0d is not 1 or 3", CHANNELS);
    if (LIGHTS < 1 || LIGHTS > 8)
      $fatal(1, "shade_unit: LIGHTS %0d is not 1..8", LIGHTS);
    if (XY_BITS < 4 || XY_BITS > 15)
      $fatal(1, "shade_unit: XY_BITS %0d is not 4..15", XY_BITS);
    if (OFS_BITS < 2 || OFS_BITS > 17)
      $fatal(1, "shade_unit: OFS_BITS %0d is not 2..17", OFS_BITS);
    if (SPECULAR_KIND < shade_pkg::SpecIdeal || SPECULAR_KIND > shade_pkg::SpecNone)
      $fatal(1, "shade_unit: SPECULAR_KIND %0d is not a unit (0 ideal .. 3 wpow, 4 none)",
             SPECULAR_KIND);
    if (SERIES_QUANT != 0 && SERIES_QUANT != 1)
      $fatal(1, "shade_unit: SERIES_QUANT %0d is not 0 (truncate) or 1 (round)", SERIES_QUANT);
    if (SERIES_OVERFLOW != 0 && SERIES_OVERFLOW != 1)
      $fatal(1, "shade_unit: SERIES_OVERFLOW %0d is not 0 (saturate) or 1 (wrap)",
             SERIES_OVERFLOW);
    if (LANES != 1 && LANES != 2 && LANES != 4)
      $fatal(1, "shade_unit: LANES %0d is not 1, 2 or 4", LANES);
  end
`endif

  typedef enum logic [1:0] {PaySkip, PayMaterial, PayTriangle, PayTable} pay_e;

  // ---- handshakes and pipeline movement ------------------------------------------------
  logic adv;       // the pix register can take a new value this cycle
  logic emit;      // the engines hand a pixel to the pix register
  logic last_pix;  // ... and it is the last beat of their span
  logic load_eng;  // the engines take the span waiting in setup stage 3
  logic stall_fault;
  logic hang_fault;

  // ---- deliberate faults (FAULT_HOOKS builds only) -------------------------------------------
  logic [shade_pkg::FaultSiteW-1:0] fault_site;
  logic [XY_BITS-1:0]               fault_row;
  if (FAULT_HOOKS != 0) begin : g_fault_select
    fault_select #(.XY_BITS(XY_BITS)) u_fault_select (.site_o(fault_site), .row_o(fault_row));
  end else begin : g_no_fault_select
    assign fault_site = shade_pkg::FaultNone;
    assign fault_row  = '0;
  end
  logic s1_v_q, s2_v_q, s3_v_q, run_q;
  logic s1_move, s2_move, s1_free, s3_free;
  logic datapath_empty, slot_empty;
  logic spec_busy;  // an iterative specular unit cannot start (all lights run in lockstep)
  logic out_adv;    // the pix register takes the slot's output pixel
  logic beat_done, hdr_fire, pay_fire, span_fire;

  // ---- triangle queue: banks, and the span queue between the decoder and span setup ----------
  localparam bit Queued = TRI_QUEUE > 1;
  localparam int SpanQ  = Queued ? 4 * TRI_QUEUE : 1;  // = CycleConfig::span_queue()
  localparam int BankW  = TRI_QUEUE > 1 ? $clog2(TRI_QUEUE) : 1;
  logic [BankW-1:0] wr_bank_q;      // bank of the latest TRIANGLE
  logic [BankW-1:0] next_bank;      // bank the next TRIANGLE loads
  logic [BankW-1:0] rd_bank;        // bank of the span entering setup stage 1
  logic             tri_bank_free;  // no queued span reads next_bank
  logic             sq_full, sq_empty, s1_load;

  // ---- material buffers: the bank the latest MATERIAL writes, and the bank of each span in
  // flight (span queue, setup stages, engines, slot metadata); spans in flight per bank --------
  localparam bit MatBanked = MATERIAL_BUFFERS == 2;
  logic mat_wr;             // bank the latest MATERIAL writes (0 with one buffer)
  logic mat_hdr_bank;       // bank a MATERIAL header taken now switches to
  assign mat_hdr_bank = MATERIAL_BUFFERS > 1 ? !mat_wr : 1'b0;
  logic mat_other_free;     // no span in flight reads the other bank
  logic mat_cur_free;       // no span in flight reads bank mat_wr
  logic s1_src_mat;         // bank of the span entering setup stage 1
  logic mat_q;              // bank of the engines' span
  logic mat_leave;          // a span's last beat leaves the slot for the pix register ...
  logic mat_leave_bank;     // ... of this bank

  // ---- decoder state ----------------------------------------------------------------------
  logic        in_payload_q;
  pay_e        pay_op_q;
  logic [15:0] pay_idx_q, pay_last_q, tbl_base_q;
  logic        tbl_mat_q;  // the TABLE being loaded is per-material (writes bank mat_wr only)
  logic [7:0]  hdr_op;
  logic [15:0] hdr_count;
  logic        hdr_ready;

  // The beat on the port and the item the decoder takes from it this cycle: the triangle
  // coefficient words due in the beat (tail), then at most one header (with a TRIANGLE's
  // coefficient words after it in the beat), or one MATERIAL / TABLE payload word.
  localparam int WordW = shade_pkg::WordW;
  localparam int PosW  = PORT_WORDS > 1 ? $clog2(PORT_WORDS) : 1;
  logic [PosW-1:0]  pos_q;        // next word of the beat still to be taken
  logic [WordW-1:0] cmd_word;     // the header looked at, else the payload word at pos_q
  logic [15:0]      beat_left;    // words of the beat from pos_q on
  logic [15:0]      pay_rem;      // payload words still to come
  logic             tri_payload;  // TRIANGLE coefficient words are due
  logic [15:0]      tail_n;       // ... this many of them in this beat
  logic [15:0]      hdr_pos;      // where a header would be
  logic             hdr_here;     // a header is looked at this cycle
  logic [15:0]      hdr_n;        // words the header takes (with its coefficient words)
  logic             take_hdr;
  logic [15:0]      item_n;       // words the item of this cycle takes (0: none)
  assign beat_left   = 16'(PORT_WORDS) - 16'(pos_q);
  assign pay_rem     = pay_last_q - pay_idx_q + 16'd1;
  assign tri_payload = in_payload_q && pay_op_q == PayTriangle;
  assign tail_n      = !tri_payload ? 16'd0 : pay_rem < beat_left ? pay_rem : beat_left;
  assign hdr_pos     = 16'(pos_q) + tail_n;
  assign hdr_here    = (!in_payload_q || (tri_payload && pay_rem <= beat_left)) &&
                       hdr_pos < 16'(PORT_WORDS);
  logic [PosW-1:0]  word_sel;
  assign word_sel    = hdr_here ? PosW'(hdr_pos) : pos_q;
  assign cmd_word    = cmd_data_i[word_sel * WordW +: WordW];

  assign hdr_op    = cmd_word[shade_pkg::OpcodeLsb +: 8];
  assign hdr_count = cmd_word[shade_pkg::CountLsb +: shade_pkg::FieldW];

  // With a span queue, a run of SPAN headers goes into it together, as many as it has room for.
  logic [PORT_WORDS-1:0] word_is_span;
  logic [15:0]           span_run;  // SPAN headers from hdr_pos on, back to back in the beat
  logic [15:0]           sq_room;   // free span queue entries
  // SPAN headers back to back in the beat from word `from` on. (A function in a continuous
  // assignment: an always_comb loop with a local flag never settles in Icarus 11.)
  function automatic logic [15:0] run_length(input logic [PORT_WORDS-1:0] is_span,
                                             input logic [15:0] from);
    logic going;
    going      = 1'b1;
    run_length = 16'd0;
    for (int k = 0; k < PORT_WORDS; k++) begin
      if (16'(k) >= from) begin
        if (going && is_span[k]) run_length = run_length + 16'd1;
        else going = 1'b0;
      end
    end
  endfunction
  for (genvar k = 0; k < PORT_WORDS; k++) begin : g_word_is_span
    assign word_is_span[k] = cmd_data_i[k*WordW + shade_pkg::OpcodeLsb +: 8] == shade_pkg::OpSpan;
  end
  assign span_run = run_length(word_is_span, hdr_pos);

  if (PORT_WORDS > 1) begin : g_hdr_n
    always_comb begin
      hdr_n = 16'd1;
      if (hdr_op == shade_pkg::OpNop) begin
        hdr_n = 16'(PORT_WORDS) - hdr_pos;
      end else if (hdr_op == shade_pkg::OpTriangle) begin
        hdr_n = 16'd1 + (hdr_count < 16'(PORT_WORDS) - hdr_pos - 16'd1
                         ? hdr_count : 16'(PORT_WORDS) - hdr_pos - 16'd1);
      end else if (Queued && hdr_op == shade_pkg::OpSpan && hdr_here) begin
        hdr_n = span_run < sq_room ? span_run : sq_room;
        if (hdr_n == 16'd0) hdr_n = 16'd1;  // a full queue: hdr_ready holds the header
      end
    end
  end else begin : g_hdr_one
    // A one-word port: a header taken is the whole beat (a NOP pads nothing, a TRIANGLE's words
    // follow in later beats, a SPAN run is one header), so the rules above all give 1 whenever
    // a header is taken, which is the only time hdr_n is read. Not evaluated on every cycle.
    assign hdr_n = 16'd1;
    logic unused_hdr_n;
    assign unused_hdr_n = ^span_run ^ (^sq_room);
  end

  assign datapath_empty = sq_empty && !s1_v_q && !s2_v_q && !s3_v_q && !run_q && slot_empty;

  // MATERIAL (ambient, spec_colour, exponent and unit parameters) and TABLE (LUT entries) must
  // not change what in-flight pixels read: both wait for an empty datapath, as the model
  // applies them in stream order. With two material buffers a MATERIAL writes the other bank
  // and waits only until no span in flight reads that one.
  always_comb begin
    unique case (hdr_op)
      shade_pkg::OpMaterial: hdr_ready = MatBanked ? mat_other_free : datapath_empty;
      shade_pkg::OpTable:    hdr_ready = MatBanked && cmd_word[shade_pkg::TableMatBit]
                                         ? mat_cur_free : datapath_empty;
      // Without a span queue a SPAN's setup reads the coefficient registers as it is taken:
      // not on the edge that writes its triangle's last words.
      shade_pkg::OpSpan:     hdr_ready = Queued ? !sq_full : s1_free && tail_n == 16'd0;
      shade_pkg::OpTriangle: hdr_ready = tri_bank_free;
      default:    hdr_ready = 1'b1;
    endcase
  end

  assign take_hdr    = hdr_here && hdr_ready;
  assign item_n      = tail_n + (take_hdr ? hdr_n : 16'd0) +
                       (in_payload_q && !tri_payload ? 16'd1 : 16'd0);
  assign beat_done   = item_n == beat_left;
  assign cmd_ready_o = item_n != 16'd0 && beat_done;
  assign hdr_fire    = cmd_valid_i && take_hdr;
  assign pay_fire    = cmd_valid_i && in_payload_q;
  assign span_fire   = hdr_fire && hdr_op == shade_pkg::OpSpan;

  // The next word of the beat: after the item of this cycle, or word 0 of the next beat.
  if (PORT_WORDS > 1) begin : g_beat_pos
    logic item_fire;
    assign item_fire = cmd_valid_i && item_n != 16'd0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        pos_q <= '0;
      end else if (item_fire) begin
        pos_q <= beat_done ? '0 : PosW'(16'(pos_q) + item_n);
      end
    end
  end else begin : g_one_word_beat
    // A one-word port: every item takes the whole beat (hdr_n above, one payload word or one
    // coefficient word), so the next word is always word 0.
    assign pos_q = '0;
  end

  logic [15:0] pay_take;  // payload words taken: the tail, or one MATERIAL / TABLE word
  assign pay_take = tri_payload ? tail_n : 16'd1;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      in_payload_q <= 1'b0;
      pay_op_q     <= PaySkip;
      pay_idx_q    <= 16'd0;
      pay_last_q   <= 16'd0;
      tbl_base_q   <= 16'd0;
      tbl_mat_q    <= 1'b0;
    end else begin
      if (hdr_fire) begin
        pay_idx_q  <= 16'd0;
        pay_last_q <= hdr_count - 16'd1;
        tbl_base_q <= cmd_word[shade_pkg::MidLsb +: shade_pkg::FieldW];
        tbl_mat_q  <= cmd_word[shade_pkg::TableMatBit];
        unique case (hdr_op)
          shade_pkg::OpMaterial: begin
            pay_op_q     <= PayMaterial;
            in_payload_q <= hdr_count != 16'd0;
          end
          // The coefficient words that came with the header are already taken.
          shade_pkg::OpTriangle: begin
            pay_op_q     <= PayTriangle;
            pay_idx_q    <= hdr_n - 16'd1;
            in_payload_q <= hdr_count > hdr_n - 16'd1;
          end
          shade_pkg::OpTable: begin
            pay_op_q     <= PayTable;
            in_payload_q <= hdr_count != 16'd0;
          end
          // END_FRAME and unknown opcodes carry no payload.
          shade_pkg::OpEndFrame: begin pay_op_q <= PaySkip; in_payload_q <= 1'b0; end
          default:               begin pay_op_q <= PaySkip; in_payload_q <= 1'b0; end
        endcase
      end else if (pay_fire) begin
        pay_idx_q <= pay_idx_q + pay_take;
        if (pay_idx_q + pay_take - 16'd1 == pay_last_q) in_payload_q <= 1'b0;
      end
    end
  end

  // Triangle origin and coefficients; material registers.
  logic signed [15:0]             xo_q [TRI_QUEUE];
  logic signed [15:0]             yo_q [TRI_QUEUE];
  // An array, not one packed vector: a partial write of a 1000+-bit vector costs the Verilated
  // model a full copy every clock.
  logic [COEF_WL-1:0]             coef_q [TRI_QUEUE*NCoef];  // bank b at b * NCoef
  logic [CHANNELS*SERIES_WL-1:0]  ambient_q [MATERIAL_BUFFERS];      // per material bank
  logic [NDiff*SPEC_COLOUR_WL-1:0] spec_colour_q [MATERIAL_BUFFERS];
  logic [LIGHTS-1:0]              gate_only_q [MATERIAL_BUFFERS];  // diffuse series gate only

  // Payload words of this cycle's item, per beat word k: the tail (words pos_q ..
  // pos_q + tail_n - 1, the current triangle's, bank wr_bank_q) or a new TRIANGLE's (the words
  // after its header, bank next_bank). coef_idx[k] is the payload word index; every
  // coefficient that word holds loads from its field.
  localparam int CoefAW = $clog2(TRI_QUEUE * NCoef);
  logic                  head_take;  // a TRIANGLE header is taken with its words
  logic [CoefAW-1:0]     rd_base;    // bank rd_bank's first coefficient
  logic [15:0]           coef_idx [PORT_WORDS];
  logic [PORT_WORDS-1:0] coef_we, coef_tail;
  logic [BankW-1:0]      coef_bank [PORT_WORDS];
  assign head_take = hdr_fire && hdr_op == shade_pkg::OpTriangle;
  assign rd_base   = CoefAW'(rd_bank * NCoef);
  always_comb begin
    for (int k = 0; k < PORT_WORDS; k++) begin
      coef_tail[k] = 16'(k) - 16'(pos_q) < tail_n;  // pos_q <= k < hdr_pos
      coef_idx[k]  = coef_tail[k] ? pay_idx_q + 16'(k) - 16'(pos_q) : 16'(k) - hdr_pos - 16'd1;
      coef_we[k]   = (cmd_valid_i && coef_tail[k] ||
                      head_take && 16'(k) > hdr_pos && 16'(k) < hdr_pos + hdr_n) &&
                     coef_idx[k] < 16'(NCoefWords);
      coef_bank[k] = coef_tail[k] ? wr_bank_q : next_bank;
    end
  end

  // Unpacked coefficients of one width (every term wider than half a word): payload word i is
  // coefficient i, so each beat word writes at most one coefficient, at its payload index. The
  // packed layout's per-coefficient selection below would be evaluated on every cycle for
  // nothing (a simulator's cost, not the hardware's: the same registers load the same values).
  localparam bit CoefEach = NCoefWords == NCoef && COEF_T1_WL == COEF_T0_WL &&
                            COEF_T2_WL == COEF_T0_WL && COEF_T3_WL == COEF_T0_WL &&
                            COEF_T4_WL == COEF_T0_WL && COEF_T5_WL == COEF_T0_WL;
  if (CoefEach) begin : g_coef_each
    always_ff @(posedge clk_i) begin
      for (int k = 0; k < PORT_WORDS; k++) begin
        if (coef_we[k]) begin
          coef_q[CoefAW'(coef_bank[k] * NCoef + 32'(coef_idx[k]))] <=
              COEF_WL'($signed(cmd_data_i[k*WordW +: COEF_T0_WL]));
        end
      end
    end
  end else begin : g_coef_packed
    logic [15:0] coef_word_of [NCoef];  // payload word of coefficient j (constant)
    for (genvar j = 0; j < NCoef; j++) begin : g_coef_word
      localparam int Word = shade_pkg::coef_word(j, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL,
                                                 COEF_T3_WL, COEF_T4_WL, COEF_T5_WL);
      assign coef_word_of[j] = 16'(Word);
    end

    // Coefficient j's field in beat word k, sign-extended.
    logic [COEF_WL-1:0] coef_field [PORT_WORDS][NCoef];
    for (genvar k = 0; k < PORT_WORDS; k++) begin : g_beat_word
      for (genvar j = 0; j < NCoef; j++) begin : g_coef
        localparam int Lsb = shade_pkg::coef_lsb(j, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL,
                                                  COEF_T3_WL, COEF_T4_WL, COEF_T5_WL);
        localparam int W   = shade_pkg::coef_term_wl(j, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL,
                                                      COEF_T3_WL, COEF_T4_WL, COEF_T5_WL);
        logic [W-1:0] field;
        assign field            = cmd_data_i[k*WordW + Lsb +: W];
        assign coef_field[k][j] = COEF_WL'($signed(field));
      end
    end

    // Coefficient j loads from the one beat word (if any) that carries its payload word. One
    // process per coefficient: Verilator unrolls a loop of delayed array writes only up to 64.
    for (genvar j = 0; j < NCoef; j++) begin : g_coef_load
      logic               load;
      logic [BankW-1:0]   bank;
      logic [COEF_WL-1:0] value;
      always_comb begin
        load  = 1'b0;
        bank  = '0;
        value = '0;
        for (int k = 0; k < PORT_WORDS; k++) begin
          if (coef_we[k] && coef_idx[k] == coef_word_of[j]) begin
            load  = 1'b1;
            bank  = coef_bank[k];
            value = coef_field[k][j];
          end
        end
      end
      always_ff @(posedge clk_i) begin
        if (load) coef_q[CoefAW'(bank * NCoef + j)] <= value;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (hdr_fire && hdr_op == shade_pkg::OpTriangle) begin
      xo_q[next_bank] <= cmd_word[shade_pkg::HighLsb +: shade_pkg::FieldW];
      yo_q[next_bank] <= cmd_word[shade_pkg::MidLsb +: shade_pkg::FieldW];
    end
    // Loaded with the MATERIAL header into the bank its payload writes (the other one with two
    // buffers: mat_wr switches on this edge), which no in-flight pixel reads.
    if (hdr_fire && hdr_op == shade_pkg::OpMaterial) begin
      gate_only_q[mat_hdr_bank] <= cmd_word[shade_pkg::GateOnlyLsb +: LIGHTS];
    end
    if (pay_fire && pay_op_q == PayMaterial) begin
      for (int i = 0; i < CHANNELS; i++) begin
        if (pay_idx_q == 16'(i)) begin
          ambient_q[mat_wr][i*SERIES_WL +: SERIES_WL] <= cmd_word[SERIES_WL-1:0];
        end
      end
      for (int i = 0; i < NDiff; i++) begin
        if (pay_idx_q == 16'(CHANNELS + i)) begin
          spec_colour_q[mat_wr][i*SPEC_COLOUR_WL +: SPEC_COLOUR_WL] <=
              cmd_word[SPEC_COLOUR_WL-1:0];
        end
      end
    end
  end

  // Configuration words for the specular slots: MATERIAL exponent (index 0) and unit
  // parameters (1..), TABLE entries at base + index.
  logic        cfg_valid, cfg_table, cfg_all_banks;
  logic [15:0] cfg_addr;
  assign cfg_table     = pay_op_q == PayTable;
  assign cfg_all_banks = cfg_table && !tbl_mat_q;  // a TABLE not per-material: every bank
  assign cfg_valid = pay_fire && (cfg_table ||
                     (pay_op_q == PayMaterial && pay_idx_q >= 16'(NMatFixed)));
  assign cfg_addr  = cfg_table ? tbl_base_q + pay_idx_q : pay_idx_q - 16'(NMatFixed);

  // ---- span setup: three stages, valid bits and span descriptors here --------------------
  typedef struct packed {
    logic [XY_BITS-1:0] y;
    logic [XY_BITS-1:0] x0;
    logic [15:0]        len;
    logic               last;
  } span_t;

  localparam int SpanW = 2 * XY_BITS + 16 + 1;  // $bits(span_t)

  span_t s1_src, s1_q, s2_q, s3_q;
  // Each beat word read as a SPAN header, span_t k at [k*SpanW +: SpanW]: {y, x0, len, last},
  // MSB first. One flat vector: Yosys 0.23 leaves an element of an unpacked array of packed
  // structs assigned in a generate loop undriven, and Icarus 11 cannot elaborate a member
  // select of one.
  logic [PORT_WORDS*SpanW-1:0] beat_span;
  for (genvar k = 0; k < PORT_WORDS; k++) begin : g_beat_span
    logic [WordW-1:0] w;
    assign w = cmd_data_i[k*WordW +: WordW];
    assign beat_span[k*SpanW +: SpanW] = {w[shade_pkg::HighLsb +: XY_BITS],
                                          w[shade_pkg::MidLsb +: XY_BITS],
                                          w[shade_pkg::CountLsb +: shade_pkg::FieldW],
                                          w[shade_pkg::SpanLastBit]};
  end

  if (Queued) begin : g_span_queue
    localparam int PtrW = $clog2(SpanQ);
    localparam int CntW = $clog2(SpanQ + 1);
    // Each queued span (as span_t's bits: Yosys 0.23 misreads an unpacked array of packed
    // structs written through a computed index) and its triangle's bank.
    logic [SpanW-1:0] sq_span_q [SpanQ];
    logic [BankW-1:0] sq_bank_q [SpanQ];
    logic             sq_mat_q [SpanQ];   // each queued span's material bank
    logic [PtrW-1:0] head_q, tail_q;
    logic [CntW-1:0] count_q;
    logic [CntW-1:0] bank_spans_q [TRI_QUEUE];  // queued spans per bank
    logic            sq_pop;
    assign sq_full       = count_q == CntW'(SpanQ);
    assign sq_room       = 16'(SpanQ) - 16'(count_q);
    assign sq_empty      = count_q == '0;
    assign sq_pop        = !sq_empty && s1_free;
    assign s1_load       = sq_pop;
    assign s1_src        = sq_span_q[head_q];
    assign rd_bank       = sq_bank_q[head_q];
    assign s1_src_mat    = sq_mat_q[head_q];
    assign next_bank     = wr_bank_q == BankW'(TRI_QUEUE - 1) ? '0 : wr_bank_q + BankW'(1);
    assign tri_bank_free = bank_spans_q[next_bank] == '0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        head_q    <= '0;
        tail_q    <= '0;
        count_q   <= '0;
        wr_bank_q <= '0;
        for (int b = 0; b < TRI_QUEUE; b++) bank_spans_q[b] <= '0;
      end else begin
        if (span_fire) tail_q <= PtrW'(ring_add(tail_q, hdr_n));
        if (sq_pop)    head_q <= head_q == PtrW'(SpanQ - 1) ? '0 : head_q + PtrW'(1);
        count_q <= count_q + (span_fire ? CntW'(hdr_n) : '0) - CntW'(sq_pop);
        for (int b = 0; b < TRI_QUEUE; b++) begin
          bank_spans_q[b] <= bank_spans_q[b]
                           + (span_fire && wr_bank_q == BankW'(b) ? CntW'(hdr_n) : '0)
                           - CntW'(sq_pop && rd_bank == BankW'(b));
        end
        if (hdr_fire && hdr_op == shade_pkg::OpTriangle) wr_bank_q <= next_bank;
      end
    end
    // The ring's index n entries after i (n <= PORT_WORDS <= SpanQ).
    function automatic logic [15:0] ring_add(input logic [PtrW-1:0] i, input logic [15:0] n);
      logic [15:0] sum;
      sum = 16'(i) + n;
      ring_add = sum >= 16'(SpanQ) ? sum - 16'(SpanQ) : sum;
    endfunction
    always_ff @(posedge clk_i) begin
      if (span_fire) begin
        for (int k = 0; k < PORT_WORDS; k++) begin
          if (16'(k) >= hdr_pos && 16'(k) < hdr_pos + hdr_n) begin
            sq_span_q[PtrW'(ring_add(tail_q, 16'(k) - hdr_pos))] <= beat_span[k*SpanW +: SpanW];
            sq_bank_q[PtrW'(ring_add(tail_q, 16'(k) - hdr_pos))] <= wr_bank_q;
            sq_mat_q[PtrW'(ring_add(tail_q, 16'(k) - hdr_pos))]  <= mat_wr;
          end
        end
      end
    end
  end else begin : g_no_span_queue
    // One bank, and SPAN headers go straight into setup stage 1.
    assign sq_full       = 1'b0;
    assign sq_room       = 16'd1;  // unused: SPAN headers go one at a time
    assign sq_empty      = 1'b1;
    assign s1_load       = span_fire;
    // (A one-word port has one place for the header: no select to evaluate on every cycle.)
    assign s1_src        = PORT_WORDS == 1 ? beat_span[SpanW-1:0]
                                           : beat_span[word_sel*SpanW +: SpanW];
    assign rd_bank       = '0;
    assign s1_src_mat    = mat_wr;
    assign next_bank     = '0;
    assign wr_bank_q     = '0;
    assign tri_bank_free = 1'b1;
  end

  // Span setup takes the offsets dx = x0 - xo, dy = y - yo of the span entering stage 1, modulo
  // 2^OfsW (x0 and y zero-extended or cut, the origin sign-extended or cut): exact for every
  // stream CommandStream::validate accepts, whose offsets fit OFS_BITS signed bits.
  logic signed [OfsW-1:0] s1_x, s1_y, s1_xo, s1_yo;
  assign s1_x  = OfsW'(s1_src.x0);
  assign s1_y  = OfsW'(s1_src.y);
  assign s1_xo = OfsW'(xo_q[rd_bank]);
  assign s1_yo = OfsW'(yo_q[rd_bank]);

  assign s3_free = !s3_v_q || load_eng;
  assign s2_move = s2_v_q && s3_free;
  assign s1_move = s1_v_q && (!s2_v_q || s2_move);
  assign s1_free = !s1_v_q || s1_move;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_v_q <= 1'b0;
      s2_v_q <= 1'b0;
      s3_v_q <= 1'b0;
    end else begin
      if (s1_load)      s1_v_q <= 1'b1;
      else if (s1_move) s1_v_q <= 1'b0;
      if (s1_move)      s2_v_q <= 1'b1;
      else if (s2_move) s2_v_q <= 1'b0;
      if (s2_move)       s3_v_q <= 1'b1;
      else if (load_eng) s3_v_q <= 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (s1_load)   s1_q <= s1_src;
    if (s1_move)   s2_q <= s1_q;
    if (s2_move)   s3_q <= s2_q;
  end

  // The material bank moves with the span (constant 0 with one buffer).
  if (MatBanked) begin : g_mat_banks
    localparam int MatCntW = $clog2(SpanQ + SpecLatency + 8);  // spans in flight, with margin
    logic                mat_wr_q;
    logic                s1_mat_q, s2_mat_q, s3_mat_q;  // bank of each setup stage's span
    logic [MatCntW-1:0]  mat_spans_q [2];  // per bank: spans taken, last beat not out of the slot
    assign mat_wr         = mat_wr_q;
    assign mat_other_free = mat_spans_q[!mat_wr_q] == '0;
    assign mat_cur_free   = mat_spans_q[mat_wr_q] == '0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        mat_wr_q       <= 1'b0;
        mat_spans_q[0] <= '0;
        mat_spans_q[1] <= '0;
      end else begin
        if (hdr_fire && hdr_op == shade_pkg::OpMaterial) mat_wr_q <= !mat_wr_q;
        for (int b = 0; b < 2; b++) begin
          mat_spans_q[b] <= mat_spans_q[b]
                          + (span_fire && mat_wr_q == 1'(b) ? MatCntW'(hdr_n) : '0)
                          - MatCntW'(mat_leave && mat_leave_bank == 1'(b));
        end
      end
    end
    always_ff @(posedge clk_i) begin
      if (s1_load)  s1_mat_q <= s1_src_mat;
      if (s1_move)  s2_mat_q <= s1_mat_q;
      if (s2_move)  s3_mat_q <= s2_mat_q;
      if (load_eng) mat_q    <= s3_mat_q;
    end
  end else begin : g_one_mat
    // verilator lint_off UNUSEDSIGNAL
    logic unused_mat;  // one buffer: every span reads bank 0
    assign unused_mat = s1_src_mat ^ mat_leave ^ mat_leave_bank;
    // verilator lint_on UNUSEDSIGNAL
    assign mat_wr         = 1'b0;
    assign mat_other_free = 1'b1;
    assign mat_cur_free   = 1'b1;
    assign mat_q          = 1'b0;
  end

  logic [NSer*SERIES_WL-1:0] setup_v, start_v, start_d, start_d2;

  // FaultSpanSetup: series 0's start value (light 0's diffuse, channel 0) one output LSB high
  // on the fault row, as a wrong setup product would make it.
  localparam int SetupFaultShift = SERIES_WL - SERIES_IWL > OUT_BITS ?
                                   SERIES_WL - SERIES_IWL - OUT_BITS : 0;
  /* verilator coverage_off */  // deliberate-fault hook: taken only by a fault test
  always_comb begin
    start_v = setup_v;
    if (fault_site == shade_pkg::FaultSpanSetup && s3_q.y == fault_row)
      start_v[SERIES_WL-1:0] = setup_v[SERIES_WL-1:0] + (SERIES_WL'(1) << SetupFaultShift);
  end
  /* verilator coverage_on */
  logic [LANES*LaneSerW-1:0] eng_v;  // lane j's series at j * LaneSerW

  for (genvar i = 0; i < NSer; i++) begin : g_series
    span_setup #(
      .COEF_WL(COEF_WL), .COEF_IWL(COEF_IWL), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW), .OFS_W(OfsW)
    ) u_setup (
      .clk_i, .s1_en_i(s1_load), .s2_en_i(s1_move), .s3_en_i(s2_move),
      .coef_i({coef_q[rd_base + CoefAW'(6*i+5)], coef_q[rd_base + CoefAW'(6*i+4)],
               coef_q[rd_base + CoefAW'(6*i+3)], coef_q[rd_base + CoefAW'(6*i+2)],
               coef_q[rd_base + CoefAW'(6*i+1)], coef_q[rd_base + CoefAW'(6*i)]}),
      .x_i(s1_x), .y_i(s1_y), .xo_i(s1_xo), .yo_i(s1_yo),
      .v_o(setup_v[i*SERIES_WL +: SERIES_WL]), .d_o(start_d[i*SERIES_WL +: SERIES_WL]),
      .d2_o(start_d2[i*SERIES_WL +: SERIES_WL])
    );
    if (LANES == 1) begin : g_one_lane
      series_engine #(.SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW)) u_engine (
        .clk_i, .load_i(load_eng), .step_i(emit),
        .v_i(start_v[i*SERIES_WL +: SERIES_WL]), .d_i(start_d[i*SERIES_WL +: SERIES_WL]),
        .d2_i(start_d2[i*SERIES_WL +: SERIES_WL]), .v_o(eng_v[i*SERIES_WL +: SERIES_WL])
      );
    end else begin : g_lanes
      for (genvar j = 0; j < LANES; j++) begin : g_lane
        logic [SERIES_WL-1:0] lane_v, lane_d, lane_d2;
        lane_fanout #(
          .SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW), .LANES(LANES), .LANE(j)
        ) u_fanout (
          .v_i(start_v[i*SERIES_WL +: SERIES_WL]), .d_i(start_d[i*SERIES_WL +: SERIES_WL]),
          .d2_i(start_d2[i*SERIES_WL +: SERIES_WL]), .v_o(lane_v), .d_o(lane_d), .d2_o(lane_d2)
        );
        series_engine #(.SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW)) u_engine (
          .clk_i, .load_i(load_eng), .step_i(emit), .v_i(lane_v), .d_i(lane_d), .d2_i(lane_d2),
          .v_o(eng_v[j*LaneSerW + i*SERIES_WL +: SERIES_WL])
        );
      end
    end
  end

  // ---- engines: span run control --------------------------------------------------------
  logic [15:0]        rem_q;
  logic [XY_BITS-1:0] x_q, y_q;
  logic               last_q, fault_done_q;

  assign adv      = !pix_valid_o || pix_ready_i;
  assign emit     = run_q && adv && !spec_busy;
  // 1 <= rem_q <= LANES (LANES = 1: rem_q == 1).
  assign last_pix = rem_q - 16'd1 < 16'(LANES);

  assign stall_fault = fault_site == shade_pkg::FaultStall && !fault_done_q && s3_q.last &&
                       s3_q.y == fault_row;
  assign hang_fault  = fault_site == shade_pkg::FaultHang && s3_q.y == fault_row;
  assign load_eng = s3_v_q && (!run_q || (emit && last_pix)) && !stall_fault && !hang_fault;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      run_q        <= 1'b0;
      fault_done_q <= 1'b0;
    end else begin
      if (load_eng)                   run_q <= 1'b1;
      else if (emit && last_pix)      run_q <= 1'b0;
      if (s3_v_q && stall_fault && (!run_q || (emit && last_pix))) fault_done_q <= 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin
    if (load_eng) begin
      rem_q  <= s3_q.len;
      x_q    <= s3_q.x0;
      y_q    <= s3_q.y;
      last_q <= s3_q.last;
    end else if (emit) begin
      rem_q <= rem_q - 16'(LANES);
      x_q   <= x_q + XY_BITS'(LANES);
    end
  end

  // ---- specular slots and the metadata that travels with them ------------------------------
  typedef struct packed {
    logic [XY_BITS-1:0]         x, y;  // lane 0's pixel
    logic                       eor;
    logic                       span_end;  // the span's last beat
    logic                       mat;       // the span's material bank
    logic [LANES-1:0]           mask;  // valid lanes
    logic [LANES*LaneDiffW-1:0] diffuse;  // lane j at j * LaneDiffW
  } meta_t;

  meta_t meta_in, meta_out;  // from the engines; at the slot's output
  logic  meta_out_valid;
  logic [LANES-1:0]           lane_mask;
  logic [LANES*LaneDiffW-1:0] lane_diffuse;
  for (genvar j = 0; j < LANES; j++) begin : g_lane_meta
    assign lane_mask[j] = 16'(j) < rem_q;
    assign lane_diffuse[j*LaneDiffW +: LaneDiffW] = eng_v[j*LaneSerW +: LaneDiffW];
  end
  assign meta_in.x       = x_q;
  assign meta_in.y       = y_q;
  assign meta_in.eor     = last_q && last_pix;
  assign meta_in.span_end = last_pix;
  assign meta_in.mat      = mat_q;
  assign meta_in.mask    = lane_mask;
  assign meta_in.diffuse = lane_diffuse;

  // Lane j, light l: spec and busy at j * LIGHTS + l. All lanes' slots start together.
  logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] slot_spec, spec;
  logic [LANES*LIGHTS-1:0]                 busy;
  logic                                    slot_en;
  assign slot_en   = Iterative ? emit : adv;
  assign spec_busy = |busy;
  if (Specular) begin : g_slots
    for (genvar g = 0; g < LANES * LIGHTS; g++) begin : g_spec
      localparam int L = g % LIGHTS;
      localparam int J = g / LIGHTS;
      specular_unit #(
        .SPECULAR_KIND(SPECULAR_KIND), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
        .SERIES_PER_LIGHT(SeriesPerLight), .SPECULAR_OUT_WL(SPECULAR_OUT_WL),
        .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL), .SPECULAR_OUT_QUANT(SPECULAR_OUT_QUANT),
        .SPECULAR_OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW), .MATERIAL_BUFFERS(MATERIAL_BUFFERS),
        .SPEC_PARAMS(SPEC_PARAMS)
      ) u_slot (
        .clk_i, .rst_ni, .en_i(slot_en),
        .series_i(eng_v[J*LaneSerW + (NDiff + L*SeriesPerLight)*SERIES_WL +:
                        SeriesPerLight*SERIES_WL]), .bank_i(mat_q),
        .cfg_valid_i(cfg_valid), .cfg_bank_i(mat_wr), .cfg_all_banks_i(cfg_all_banks),
        .cfg_table_i(cfg_table), .cfg_addr_i(cfg_addr),
        .cfg_data_i(cmd_word), .spec_o(slot_spec[g*SPECULAR_OUT_WL +: SPECULAR_OUT_WL]),
        .busy_o(busy[g])
      );
    end
  end else begin : g_no_slots
    // No specular term: no unit, so nothing is configured (the MATERIAL's exponent word and
    // TABLE entries are taken and dropped) and pixel_combine reads no specular value.
    assign slot_spec = '0;
    assign busy      = '0;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_cfg;
    assign unused_cfg = cfg_valid ^ cfg_table ^ cfg_all_banks ^ (^cfg_addr) ^ slot_en;
    // verilator lint_on UNUSEDSIGNAL
  end

  if (Iterative) begin : g_pending
    // One pixel in flight: captured when the unit starts it, handed to the pix register when
    // the unit is done - on the same edge as the next start (en_i = emit).
    logic  pend_v_q;
    meta_t pend_q;
    assign out_adv        = adv && !spec_busy;
    assign meta_out       = pend_q;
    assign meta_out_valid = pend_v_q;
    assign slot_empty     = !pend_v_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) pend_v_q <= 1'b0;
      else if (out_adv) pend_v_q <= run_q;
    end
    always_ff @(posedge clk_i) begin
      if (out_adv) pend_q <= meta_in;
    end
  end else if (SpecLatency > 0) begin : g_delay
    // SpecLatency stages moving with the slot's pipeline on the global advance (en_i = adv).
    logic [SpecLatency-1:0] line_v_q;
    // One flat vector, stage i at [i*MetaW +: MetaW]. Not an unpacked array of packed structs:
    // Icarus 11 left it X here (and with it every pixel's x, y and mask on the LUT builds).
    // Not a packed array of them either: Yosys 0.23 sizes `meta_t [N-1:0] line_q` as one meta_t
    // and reads line_q[i] as its bit i, so its netlist kept one bit of the metadata (lane 0's
    // diffuse LSB): x, y and mask constant, the other lanes' colours merged, most series gone.
    localparam int MetaW = 2 * XY_BITS + 3 + LANES + LANES * LaneDiffW;  // $bits(meta_t)
    logic [SpecLatency*MetaW-1:0] line_q;
    assign out_adv        = adv;
    assign meta_out       = line_q[(SpecLatency-1)*MetaW +: MetaW];
    assign meta_out_valid = line_v_q[SpecLatency-1];
    assign slot_empty     = line_v_q == '0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        line_v_q <= '0;
      end else if (adv) begin
        line_v_q[0] <= run_q;
        for (int i = 1; i < SpecLatency; i++) line_v_q[i] <= line_v_q[i-1];
      end
    end
    always_ff @(posedge clk_i) begin
      if (adv) begin
        line_q[0 +: MetaW] <= meta_in;
        for (int i = 1; i < SpecLatency; i++) begin
          line_q[i*MetaW +: MetaW] <= line_q[(i-1)*MetaW +: MetaW];
        end
      end
    end
  end else begin : g_direct
    assign out_adv        = adv;
    assign meta_out       = meta_in;
    assign meta_out_valid = run_q;
    assign slot_empty     = 1'b1;
  end

  // ---- pixel combine ----------------------------------------------------------------------------
  // FaultSpecular: light 0's specular result of every lane, its top fraction bit flipped (half
  // the unit's full scale) on the fault row, as a wrong unit would give it.
  /* verilator coverage_off */  // deliberate-fault hook: taken only by a fault test
  always_comb begin
    spec = slot_spec;
    if (fault_site == shade_pkg::FaultSpecular && meta_out.y == fault_row) begin
      for (int j = 0; j < LANES; j++)
        spec[j*LIGHTS*SPECULAR_OUT_WL + SPECULAR_OUT_WL - SPECULAR_OUT_IWL - 1] =
            !slot_spec[j*LIGHTS*SPECULAR_OUT_WL + SPECULAR_OUT_WL - SPECULAR_OUT_IWL - 1];
    end
  end
  /* verilator coverage_on */
  logic fault_trunc;  // FaultRounding: the fault row's output truncated
  assign fault_trunc = fault_site == shade_pkg::FaultRounding && meta_out.y == fault_row;

  logic [LANES*LaneColW-1:0] colour, colour_out;  // lane j at j * LaneColW
  for (genvar j = 0; j < LANES; j++) begin : g_combine
    pixel_combine #(
      .CHANNELS(CHANNELS), .LIGHTS(LIGHTS), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW),
      .SPEC_COLOUR_WL(SPEC_COLOUR_WL), .SPEC_COLOUR_IWL(SPEC_COLOUR_IWL),
      .SPECULAR_OUT_WL(SPECULAR_OUT_WL), .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL), .OUT_BITS(OUT_BITS),
      .SPECULAR(Specular)
    ) u_combine (
      .diffuse_i(meta_out.diffuse[j*LaneDiffW +: LaneDiffW]),
      .spec_i(spec[j*LIGHTS*SPECULAR_OUT_WL +: LIGHTS*SPECULAR_OUT_WL]),
      .ambient_i(ambient_q[meta_out.mat]), .spec_colour_i(spec_colour_q[meta_out.mat]),
      .gate_only_i(gate_only_q[meta_out.mat]), .trunc_i(fault_trunc),
      .colour_o(colour[j*LaneColW +: LaneColW])
    );
  end

  // FaultLsb, FaultChannel2: channel 0 or 2 of every lane's pixel on the fault row + 1 LSB.
  localparam int FaultChannel = CHANNELS > 2 ? 2 : 0;
  /* verilator coverage_off */  // deliberate-fault hook: taken only by a fault test
  always_comb begin
    colour_out = colour;
    if (meta_out.y == fault_row) begin
      for (int j = 0; j < LANES; j++) begin
        if (fault_site == shade_pkg::FaultLsb)
          colour_out[j*LaneColW +: OUT_BITS] = colour[j*LaneColW +: OUT_BITS] + OUT_BITS'(1);
        if (fault_site == shade_pkg::FaultChannel2 && CHANNELS > 2)
          colour_out[j*LaneColW + FaultChannel*OUT_BITS +: OUT_BITS] =
              colour[j*LaneColW + FaultChannel*OUT_BITS +: OUT_BITS] + OUT_BITS'(1);
      end
    end
  end
  /* verilator coverage_on */

  // A span's last beat leaves the slot: no pixel of it reads its bank any more (the pix register
  // holds finished colours).
  assign mat_leave      = out_adv && meta_out_valid && meta_out.span_end;
  assign mat_leave_bank = meta_out.mat;

  // ---- output register ------------------------------------------------------------------------
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pix_valid_o <= 1'b0;
    end else if (adv) begin
      pix_valid_o <= out_adv && meta_out_valid;
    end
  end

  always_ff @(posedge clk_i) begin
    if (out_adv && meta_out_valid) begin
      // FaultX, FaultY, FaultEor: the fault row's position or end-of-row flag wrong.
      pix_x_o      <= meta_out.x + XY_BITS'(fault_site == shade_pkg::FaultX &&
                                             meta_out.y == fault_row);
      pix_y_o      <= meta_out.y ^ XY_BITS'(fault_site == shade_pkg::FaultY &&
                                             meta_out.y == fault_row);
      pix_colour_o <= colour_out;
      pix_mask_o   <= meta_out.mask;
      pix_eor_o    <= meta_out.eor ^ (fault_site == shade_pkg::FaultEor &&
                                      meta_out.y == fault_row);
    end
  end
`ifndef SYNTHESIS
  initial begin
    if (PORT_WORDS != 1 && PORT_WORDS != 2 && PORT_WORDS != 4 && PORT_WORDS != 8)
      $fatal(1, "shade_unit: PORT_WORDS %0d is not 1, 2, 4 or 8", PORT_WORDS);
    if (TRI_QUEUE < 1 || TRI_QUEUE > 8)
      $fatal(1, "shade_unit: TRI_QUEUE %0d is not 1..8", TRI_QUEUE);
    if ($bits(meta_t) != 2 * XY_BITS + 3 + LANES + LANES * LaneDiffW)
      $fatal(1, "shade_unit: the metadata line's width (MetaW) is not $bits(meta_t)");
    if (FAULT_HOOKS != 0 && FAULT_HOOKS != 1)
      $fatal(1, "shade_unit: FAULT_HOOKS %0d is not 0 or 1", FAULT_HOOKS);
    if (MATERIAL_BUFFERS != 1 && MATERIAL_BUFFERS != 2)
      $fatal(1, "shade_unit: MATERIAL_BUFFERS %0d is not 1 or 2", MATERIAL_BUFFERS);
    for (int t = 0; t < 6; t++) begin
      if (shade_pkg::coef_term_wl(t, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL, COEF_T3_WL, COEF_T4_WL,
                                  COEF_T5_WL) > COEF_WL ||
          shade_pkg::coef_term_wl(t, COEF_T0_WL, COEF_T1_WL, COEF_T2_WL, COEF_T3_WL, COEF_T4_WL,
                                  COEF_T5_WL) < 2)
        $fatal(1, "shade_unit: COEF_T%0d_WL must be 2..COEF_WL (%0d)", t, COEF_WL);
    end
  end
`endif
endmodule
