// shade_formal: the formal-only wrapper around shade_unit (docs/formal.md). It assumes a legal
// environment on the ports and asserts the handshake, queue and conservation properties, as
// immediate assertions Yosys 0.23 reads (read_verilog -formal; no `|->`, no `disable iff`).
//
// The p_* wires are probes of shade_unit's internal signals. Yosys reads no hierarchical
// reference, so they are left undriven here and tests/formal/run.py connects each one to its
// signal after `flatten` (`connect -set`); a probe it does not connect fails the run.
//
// One-word command port only (PORT_WORDS = 1): the environment's own parser below splits the
// stream into headers and payload words one beat at a time.
module shade_formal #(
  parameter int SPECULAR_KIND    = 0,
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS = '0,
  parameter int LANES            = 1,
  parameter int TRI_QUEUE        = 1,
  parameter int MATERIAL_BUFFERS = 1,
  parameter int XY_BITS          = 4,
  parameter int MAX_LEN          = 4,   // longest span the environment sends (<= 2^XY_BITS)
  parameter int MAX_PAY          = 3,   // longest MATERIAL / TRIANGLE / TABLE payload
  parameter bit CONSERVE         = 1,   // the span-by-span scoreboard (a BMC check)
  parameter int DRAIN            = 48   // cycles END_FRAME may take to empty the unit
) (
  input logic        clk_i,
  input logic        rst_ni,
  input logic [63:0] cmd_data_i,
  input logic        cmd_valid_i,
  input logic        pix_ready_i,
  input logic        quiet_i  // the environment stops after an END_FRAME (drain check)
);
  localparam int OutBits = 2;
  localparam int SpanQ   = TRI_QUEUE > 1 ? 4 * TRI_QUEUE : 1;
  localparam int CntW    = $clog2(SpanQ + 1);
  localparam int PtrW    = SpanQ > 1 ? $clog2(SpanQ) : 1;
  localparam int LenW    = XY_BITS + 1;

  logic                         cmd_ready;
  logic [XY_BITS-1:0]           pix_x, pix_y;
  logic [LANES*OutBits-1:0]     pix_colour;
  logic [LANES-1:0]             pix_mask;
  logic                         pix_eor, pix_valid;
  // Narrow widths: the properties are about control, not arithmetic.
  shade_unit #(
    .XY_BITS(XY_BITS), .OFS_BITS(6), .COEF_WL(6), .COEF_IWL(2), .SERIES_WL(6),
    .SERIES_IWL(2), .SPEC_COLOUR_WL(3), .SPEC_COLOUR_IWL(1), .OUT_BITS(OutBits),
    .SPECULAR_KIND(SPECULAR_KIND), .SPECULAR_OUT_WL(4), .SPECULAR_OUT_IWL(1),
    .PORT_WORDS(1), .TRI_QUEUE(TRI_QUEUE), .LANES(LANES), .MATERIAL_BUFFERS(MATERIAL_BUFFERS),
    .SPEC_PARAMS(SPEC_PARAMS)
  ) u_dut (
    .clk_i, .rst_ni, .cmd_data_i, .cmd_valid_i, .cmd_ready_o(cmd_ready), .pix_x_o(pix_x),
    .pix_y_o(pix_y), .pix_colour_o(pix_colour), .pix_mask_o(pix_mask), .pix_eor_o(pix_eor),
    .pix_valid_o(pix_valid), .pix_ready_i
  );

  // ---- reset: low in the first cycle, high from then on -------------------------------------
  logic past_ok = 1'b0;  // a previous cycle exists and was out of reset
  initial assume (!rst_ni);
  always @(posedge clk_i) begin
    past_ok <= rst_ni;
    if (past_ok) assume (rst_ni);
  end

  // ---- the environment: a legal one-word command stream --------------------------------------
  logic [7:0]  op;
  logic [15:0] count;
  logic [15:0] env_rem;  // payload words still due (0: the next word is a header)
  logic        take, hdr, span_in, end_frame_in, quiet;
  assign op           = cmd_data_i[63:56];
  assign count        = cmd_data_i[15:0];
  assign take         = cmd_valid_i && cmd_ready;
  assign hdr          = env_rem == '0;
  assign span_in      = take && hdr && op == shade_pkg::OpSpan;
  assign end_frame_in = take && hdr && op == shade_pkg::OpEndFrame;
  always @(posedge clk_i) begin
    if (!rst_ni) env_rem <= '0;
    else if (take)
      env_rem <= !hdr ? env_rem - 16'd1 :
                 op == shade_pkg::OpMaterial || op == shade_pkg::OpTriangle ||
                 op == shade_pkg::OpTable ? count : '0;
  end
  logic [XY_BITS:0] len_in;
  logic [15:0]      x0_in, y_in;
  assign len_in = count[XY_BITS:0];
  assign x0_in  = cmd_data_i[31:16];
  assign y_in   = cmd_data_i[47:32];
  always @* begin
    if (rst_ni && cmd_valid_i && hdr) begin
      assume (op == shade_pkg::OpNop || op == shade_pkg::OpMaterial ||
              op == shade_pkg::OpTriangle || op == shade_pkg::OpSpan ||
              op == shade_pkg::OpTable || op == shade_pkg::OpEndFrame);
      if (op == shade_pkg::OpMaterial || op == shade_pkg::OpTriangle || op == shade_pkg::OpTable)
        assume (count <= 16'(MAX_PAY));
      // CommandStream::validate: 1 <= len, the span on the screen.
      if (op == shade_pkg::OpSpan) begin
        assume (count >= 16'd1 && count <= 16'(MAX_LEN));
        assume (x0_in < 16'(1 << XY_BITS) && y_in < 16'(1 << XY_BITS));
        assume (x0_in + count <= 16'(1 << XY_BITS));
      end
    end
  end
  // The sender holds a beat, unchanged, until it is taken (cmd_decoder's a_cmd_valid_held and
  // a_cmd_data_stable, the sender's side: assumed here).
  always @(posedge clk_i) begin
    if (past_ok && rst_ni && $past(cmd_valid_i && !cmd_ready)) begin
      assume (cmd_valid_i);
      assume (cmd_data_i == $past(cmd_data_i));
    end
  end
  // After an END_FRAME with quiet_i, nothing more arrives and the pix port always takes.
  always @(posedge clk_i) begin
    if (!rst_ni) quiet <= 1'b0;
    else if (end_frame_in && quiet_i) quiet <= 1'b1;
  end
  always @* if (quiet) assume (!cmd_valid_i && pix_ready_i);

  // ---- probes of internal signals (connected by run.py after flatten) -----------------------
  logic             p_hdr_fire, p_pay_fire, p_item_n, p_beat_left;  // (one-word port: 1 bit)
  logic             p_span_fire, p_tri_fire, p_tri_bank_free, p_s1_load, p_s1_free;
  logic             p_s1_v, p_s2_v, p_s3_v, p_eng_load, p_run;
  logic [XY_BITS:0] p_rem;
  logic             p_out_load, p_out_adv, p_datapath_empty;

  // ---- command port -----------------------------------------------------------------------
  always @* begin
    if (rst_ni) begin
      // Nothing is taken from a beat that is not offered, and (one-word port: a beat is one
      // item) nothing is taken while the unit is not ready.
      a_cmd_fire_valid: assert (!(p_hdr_fire || p_pay_fire) || cmd_valid_i);
      a_cmd_fire_ready: assert (!(p_hdr_fire || p_pay_fire) || cmd_ready);
      a_cmd_ready_fires: assert (!take || p_hdr_fire || p_pay_fire);
      a_item_fits: assert (p_item_n <= p_beat_left);
      // The decoder reads the stream as the environment does: header for header.
      a_decoder_in_step: assert (!take || p_hdr_fire == hdr);
    end
  end

  // ---- pix port ---------------------------------------------------------------------------
  always @(posedge clk_i) begin
    if (past_ok && rst_ni && $past(pix_valid && !pix_ready_i)) begin
      a_pix_valid_held: assert (pix_valid);
      a_pix_data_stable: assert (pix_x == $past(pix_x) && pix_y == $past(pix_y) &&
                                 pix_colour == $past(pix_colour) &&
                                 pix_mask == $past(pix_mask) && pix_eor == $past(pix_eor));
    end
  end
  always @* begin
    if (rst_ni) begin
      a_pix_load_when_free: assert (!p_out_load || p_out_adv);  // out_reg's a_load_when_free
      a_pix_lane0: assert (!pix_valid || pix_mask[0]);
    end
  end

  // ---- setup stages: a three-entry queue (push s1_load, pop the engines' load) --------------
  logic [1:0] setup_n;  // spans pushed less spans popped
  always @(posedge clk_i) begin
    if (!rst_ni) setup_n <= '0;
    else setup_n <= setup_n + 2'(p_s1_load) - 2'(p_eng_load);
  end
  always @* begin
    if (rst_ni) begin
      a_setup_no_overflow: assert (!p_s1_load || p_s1_free);
      a_setup_no_underflow: assert (!p_eng_load || p_s3_v);
      a_setup_count: assert (32'(setup_n) == 32'(p_s1_v) + 32'(p_s2_v) + 32'(p_s3_v));
      a_engine_rem: assert (!p_run || p_rem != '0);  // engine_ctrl's a_rem_nonzero
    end
  end

  // ---- pix register: a one-entry queue (push a beat loaded, pop a beat taken) ---------------
  logic out_n;
  always @(posedge clk_i) begin
    if (!rst_ni) out_n <= 1'b0;
    else out_n <= 1'(32'(out_n) + 32'(p_out_load && p_out_adv) - 32'(pix_valid && pix_ready_i));
  end
  always @* if (rst_ni) a_out_count: assert (out_n == pix_valid);

  // ---- span queue (TRI_QUEUE > 1): the ring and its per-bank counts -------------------------
  if (TRI_QUEUE > 1) begin : g_sq
    logic [CntW-1:0] p_count, p_bank0, p_bank1;
    logic [PtrW-1:0] p_head, p_tail;
    logic [CntW-1:0] sq_n;  // SPAN headers the environment sent less spans setup took
    always @(posedge clk_i) begin
      if (!rst_ni) sq_n <= '0;
      else sq_n <= sq_n + CntW'(span_in) - CntW'(p_s1_load);
    end
    always @* begin
      if (rst_ni) begin
        a_sq_no_overflow: assert (!p_span_fire || 32'(p_count) + 1 <= SpanQ);
        a_sq_count_range: assert (32'(p_count) <= SpanQ);
        a_sq_no_underflow: assert (!p_s1_load || p_count != '0);
        a_sq_count: assert (p_count == sq_n);
        // (No `%`: a 32-bit modulo becomes a divider in the model; head + count < 2 SpanQ.)
        a_sq_ring: assert (8'(p_tail) == (8'(p_head) + 8'(p_count) >= 8'(SpanQ)
                                          ? 8'(p_head) + 8'(p_count) - 8'(SpanQ)
                                          : 8'(p_head) + 8'(p_count)));
        a_sq_banks: assert (32'(p_bank0) + 32'(p_bank1) == 32'(p_count));
        a_sq_tri_bank_free: assert (!p_tri_fire || p_tri_bank_free);
      end
    end
  end

  // ---- material banks (MATERIAL_BUFFERS = 2): spans in flight per bank ---------------------
  if (MATERIAL_BUFFERS == 2) begin : g_mb
    localparam int MatCntW = $clog2(SpanQ + shade_pkg::spec_latency(SPECULAR_KIND, SPEC_PARAMS)
                                    + 8);  // material_bank's
    logic [MatCntW-1:0] p_spans0, p_spans1;  // its per-bank counts
    logic               p_leave, p_leave_bank;  // a span's last beat leaves the slots, its bank
    logic [7:0]         in_flight;  // SPAN headers sent less spans whose last beat left
    always @(posedge clk_i) begin
      if (!rst_ni) in_flight <= '0;
      else in_flight <= in_flight + 8'(span_in) - 8'(p_leave);
    end
    always @* begin
      if (rst_ni) begin
        a_mb_no_underflow: assert (!p_leave || (p_leave_bank ? p_spans1 : p_spans0) != '0);
        a_mb_count: assert (32'(p_spans0) + 32'(p_spans1) == 32'(in_flight));
      end
    end
  end

  // ---- conservation: every span's pixels leave exactly once, in order ------------------------
  if (CONSERVE) begin : g_conserve
    // Spans in flight the scoreboard holds: more than the unit can (queue, 3 setup stages, the
    // engines, the slots, the pix register).
    localparam int SD = TRI_QUEUE > 1 ? 32 : 16;
    logic [XY_BITS-1:0] sb_y [SD];
    logic [XY_BITS-1:0] sb_x0 [SD];
    logic [XY_BITS:0]   sb_len [SD];
    logic               sb_last [SD];
    logic [$clog2(SD)-1:0] sb_head, sb_tail;
    logic [5:0]         sb_n;
    logic [XY_BITS:0]   done;  // pixels of the head span already out
    logic [XY_BITS:0]   rem;
    logic               beat_out, last_beat;
    logic [LANES-1:0]   exp_mask;
    assign beat_out  = pix_valid && pix_ready_i;
    assign rem       = sb_len[sb_head] - done;
    assign last_beat = rem <= (XY_BITS + 1)'(LANES);
    for (genvar j = 0; j < LANES; j++) begin : g_mask
      assign exp_mask[j] = (XY_BITS + 1)'(j) < rem;
    end
    always @(posedge clk_i) begin
      if (!rst_ni) begin
        sb_head <= '0;
        sb_tail <= '0;
        sb_n    <= '0;
        done    <= '0;
      end else begin
        if (span_in) begin
          sb_y[sb_tail]    <= y_in[XY_BITS-1:0];
          sb_x0[sb_tail]   <= x0_in[XY_BITS-1:0];
          sb_len[sb_tail]  <= len_in;
          sb_last[sb_tail] <= cmd_data_i[shade_pkg::SpanLastBit];
          sb_tail          <= sb_tail + 1'b1;
        end
        if (beat_out) begin
          if (last_beat) begin
            sb_head <= sb_head + 1'b1;
            done    <= '0;
          end else begin
            done <= done + (XY_BITS + 1)'(LANES);
          end
        end
        sb_n <= sb_n + 6'(span_in) - 6'(beat_out && last_beat);
      end
    end
    always @* begin
      if (rst_ni) begin
        a_sb_room: assert (sb_n < 6'(SD));  // the scoreboard's own bound
        if (beat_out) begin
          a_no_extra_pixel: assert (sb_n != '0);
          a_pix_x: assert (pix_x == sb_x0[sb_head] + XY_BITS'(done));
          a_pix_y: assert (pix_y == sb_y[sb_head]);
          a_pix_mask: assert (pix_mask == exp_mask);
          a_pix_eor: assert (pix_eor == (sb_last[sb_head] && last_beat));
        end
      end
    end
    // END_FRAME leaves the unit empty: once every pixel of the spans sent before a quiet
    // END_FRAME has left, nothing is left inside (no stray beat, no span in a stage) ...
    always @* begin
      if (rst_ni && quiet && sb_n == '0) begin
        a_empty_after_last: assert (p_datapath_empty && !pix_valid);
      end
    end
    // ... and DRAIN cycles after it every span sent has left (a bound only a BMC depth beyond
    // the frame plus DRAIN reaches: docs/formal.md).
    logic [7:0] since;
    always @(posedge clk_i) begin
      if (!rst_ni || !quiet) since <= '0;
      else if (since != 8'hff) since <= since + 8'd1;
    end
    always @* begin
      if (rst_ni && quiet && since >= 8'(DRAIN)) begin
        a_drained: assert (sb_n == '0);
        a_empty: assert (p_datapath_empty && !pix_valid);
      end
    end
  end
endmodule
