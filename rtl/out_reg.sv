// out_reg: shade_unit's pix port register - a beat of up to LANES finished pixels, valid/ready.
// It takes a new beat whenever it is empty or its beat is taken (adv_o, which moves the whole
// pipeline: no skid buffer).
module out_reg #(
  parameter int XY_BITS  = 12,
  parameter int LANES    = 1,
  parameter int COLOUR_W = 8  // one beat's colours: LANES * CHANNELS * OUT_BITS
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                load_i,   // a beat arrives (only while adv_o) ...
  input  logic [XY_BITS-1:0]  x_i,      // ... lane 0's position
  input  logic [XY_BITS-1:0]  y_i,
  input  logic [COLOUR_W-1:0] colour_i,
  input  logic [LANES-1:0]    mask_i,
  input  logic                eor_i,
  output logic                adv_o,    // the register can take a beat this cycle
  output logic [XY_BITS-1:0]  pix_x_o,
  output logic [XY_BITS-1:0]  pix_y_o,
  output logic [COLOUR_W-1:0] pix_colour_o,
  output logic [LANES-1:0]    pix_mask_o,
  output logic                pix_eor_o,
  output logic                pix_valid_o,
  input  logic                pix_ready_i
);
  assign adv_o = !pix_valid_o || pix_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)    pix_valid_o <= 1'b0;
    else if (adv_o) pix_valid_o <= load_i;
  end

  always_ff @(posedge clk_i) begin
    if (load_i) begin
      pix_x_o      <= x_i;
      pix_y_o      <= y_i;
      pix_colour_o <= colour_i;
      pix_mask_o   <= mask_i;
      pix_eor_o    <= eor_i;
    end
  end

`ifndef SYNTHESIS
`ifdef VERILATOR
  // The pix port's handshake: a beat offered stays offered, unchanged, until it is taken, and
  // a beat arrives only when the register can take it.
  a_valid_held: assert property (@(posedge clk_i) disable iff (!rst_ni)
    pix_valid_o && !pix_ready_i |=> pix_valid_o);
  a_data_stable: assert property (@(posedge clk_i) disable iff (!rst_ni)
    pix_valid_o && !pix_ready_i |=> $stable(pix_x_o) && $stable(pix_y_o) &&
                                    $stable(pix_colour_o) && $stable(pix_mask_o) &&
                                    $stable(pix_eor_o));
  a_load_when_free: assert property (@(posedge clk_i) disable iff (!rst_ni) load_i |-> adv_o);
  a_lane0_valid: assert property (@(posedge clk_i) disable iff (!rst_ni)
    pix_valid_o |-> pix_mask_o[0]);
`endif
`endif
endmodule
