// slot_meta: the metadata line beside shade_unit's specular slots - each beat's position,
// lane mask, end flags, material bank and diffuse series values (META_W bits, shade_unit's
// meta_t) - so they reach the pixel combine together with the slots' specular results.
//
// Pipelined slots (INTERVAL 1, LATENCY > 0): a LATENCY-deep line moving with the slots on the
// global advance (adv_i). Iterative slots (INTERVAL > 1): one beat in flight in a pending
// register, captured when the slots start it and handed over when they are done - on the same
// edge as the next start. No slot latency (ideal, none): the engines' beat goes straight on.
module slot_meta #(
  parameter int META_W    = 8,
  parameter int LATENCY   = 0,  // the slot's registers between series and result
  parameter bit ITERATIVE = 1'b0  // the slot takes more than one cycle per pixel
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              adv_i,        // the pix register can take a beat
  input  logic              spec_busy_i,  // an iterative slot cannot start
  input  logic              valid_i,      // the engines hold a span: meta_i is a beat
  input  logic [META_W-1:0] meta_i,
  output logic              out_adv_o,    // the pix register takes the line's output beat
  output logic              valid_o,      // the line's output is a beat ...
  output logic [META_W-1:0] meta_o,       // ... this one
  output logic              empty_o       // no beat in the line
);
  if (ITERATIVE) begin : g_pending
    logic              pend_v_q;
    logic [META_W-1:0] pend_q;
    assign out_adv_o = adv_i && !spec_busy_i;
    assign meta_o    = pend_q;
    assign valid_o   = pend_v_q;
    assign empty_o   = !pend_v_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni)        pend_v_q <= 1'b0;
      else if (out_adv_o) pend_v_q <= valid_i;
    end
    always_ff @(posedge clk_i) begin
      if (out_adv_o) pend_q <= meta_i;
    end
  end else if (LATENCY > 0) begin : g_delay
    // One flat vector, stage i at [i*META_W +: META_W]. Not an unpacked array of packed
    // structs: Icarus 11 left it X (and with it every pixel's x, y and mask on the LUT builds).
    // Not a packed array of them either: Yosys 0.23 sizes `meta_t [N-1:0] line_q` as one meta_t
    // and reads line_q[i] as its bit i, so its netlist kept one bit of the metadata.
    logic [LATENCY-1:0]        line_v_q;
    logic [LATENCY*META_W-1:0] line_q;
    assign out_adv_o = adv_i;
    assign meta_o    = line_q[(LATENCY-1)*META_W +: META_W];
    assign valid_o   = line_v_q[LATENCY-1];
    assign empty_o   = line_v_q == '0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        line_v_q <= '0;
      end else if (adv_i) begin
        line_v_q[0] <= valid_i;
        for (int i = 1; i < LATENCY; i++) line_v_q[i] <= line_v_q[i-1];
      end
    end
    always_ff @(posedge clk_i) begin
      if (adv_i) begin
        line_q[0 +: META_W] <= meta_i;
        for (int i = 1; i < LATENCY; i++) begin
          line_q[i*META_W +: META_W] <= line_q[(i-1)*META_W +: META_W];
        end
      end
    end
    // verilator lint_off UNUSEDSIGNAL
    logic unused_busy;  // reason: a pipelined slot is never busy
    assign unused_busy = spec_busy_i;
    // verilator lint_on UNUSEDSIGNAL
  end else begin : g_direct
    assign out_adv_o = adv_i;
    assign meta_o    = meta_i;
    assign valid_o   = valid_i;
    assign empty_o   = 1'b1;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_in;  // reason: no line, no registers; such a slot is never busy
    assign unused_in = clk_i ^ rst_ni ^ spec_busy_i;
    // verilator lint_on UNUSEDSIGNAL
  end
endmodule
