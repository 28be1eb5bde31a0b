// cmd_payload: cmd_decoder's payload FSM - which header's payload words are being taken, and how
// far. A TRIANGLE's (or, with host span setup, a SPAN's) words arrive as the tail of each beat,
// several per cycle; a MATERIAL's or TABLE's one word per cycle. MATERIAL and TABLE words leave
// as configuration writes for the specular slots (MATERIAL exponent at index 0, unit parameters
// from 1, TABLE entries at base + index).
module cmd_payload #(
  parameter int PORT_WORDS  = 1,  // 64-bit words per beat: 1, 2, 4 or 8
  parameter int N_MAT_FIXED = 2   // MATERIAL payload words before the slots' (ambient, colour)
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic                            cmd_valid_i,
  input  logic                            hdr_fire_i,   // a header is taken ...
  input  logic [shade_pkg::WordW-1:0]     hdr_i,        // ... this one
  input  logic                            host_span_i,  // ... a SPAN with start values
  input  logic [15:0]                     pay_count_i,  // ... with this many payload words
  input  logic [$clog2(PORT_WORDS+1)-1:0] hdr_n_i,      // ... of which it took this many - 1
  input  logic [$clog2(PORT_WORDS+1)-1:0] tail_n_i,     // TRIANGLE / SPAN words in this beat
  output logic                            in_payload_o,  // payload words are due
  output logic                            tri_payload_o, // ... as a tail (TRIANGLE or SPAN)
  output logic [15:0]                     pay_idx_o,     // index of the next payload word
  output logic [15:0]                     pay_rem_o,     // payload words still to come
  output logic                            pay_mat_o,     // a MATERIAL payload word taken
  output logic                            span_pay_o,    // the tail is a SPAN's (host setup)
  output logic                            cfg_valid_o,
  output logic                            cfg_table_o,
  output logic                            cfg_all_banks_o,  // a TABLE not per-material
  output logic [15:0]                     cfg_addr_o
);
  typedef enum logic [2:0] {PaySkip, PayMaterial, PayTriangle, PayTable, PaySpan} pay_e;
  logic        in_payload_q, in_payload_d;
  pay_e        pay_op_q, pay_op_d;
  logic [15:0] pay_idx_q, pay_idx_d, pay_rem_q, pay_rem_d, tbl_base_q, tbl_base_d;
  logic        tbl_mat_q, tbl_mat_d;  // the TABLE being loaded is per-material
  logic [7:0]  hdr_op;
  logic [15:0] hdr_count;
  logic        pay_fire;
  logic [15:0] pay_take;  // payload words taken: the tail, or one MATERIAL / TABLE word
  assign hdr_op        = hdr_i[shade_pkg::OpcodeLsb +: 8];
  assign hdr_count     = hdr_i[shade_pkg::CountLsb +: shade_pkg::FieldW];
  assign tri_payload_o = in_payload_q && (pay_op_q == PayTriangle || pay_op_q == PaySpan);
  assign pay_fire      = cmd_valid_i && in_payload_q;
  assign pay_take      = tri_payload_o ? 16'(tail_n_i) : 16'd1;
  always_comb begin
    in_payload_d = in_payload_q;
    pay_op_d     = pay_op_q;
    pay_idx_d    = pay_idx_q;
    pay_rem_d    = pay_rem_q;
    tbl_base_d   = tbl_base_q;
    tbl_mat_d    = tbl_mat_q;
    if (hdr_fire_i) begin
      pay_idx_d  = 16'd0;
      pay_rem_d  = hdr_count;
      tbl_base_d = hdr_i[shade_pkg::MidLsb +: shade_pkg::FieldW];
      tbl_mat_d  = hdr_i[shade_pkg::TableMatBit];
      unique case (hdr_op)
        shade_pkg::OpMaterial: begin
          pay_op_d     = PayMaterial;
          in_payload_d = hdr_count != 16'd0;
        end
        // The coefficient words that came with the header are already taken.
        shade_pkg::OpTriangle: begin
          pay_op_d     = PayTriangle;
          pay_idx_d    = 16'(hdr_n_i) - 16'd1;
          pay_rem_d    = hdr_count - 16'(hdr_n_i) + 16'd1;
          in_payload_d = hdr_count > 16'(hdr_n_i) - 16'd1;
        end
        shade_pkg::OpTable: begin
          pay_op_d     = PayTable;
          in_payload_d = hdr_count != 16'd0;
        end
        // Host setup: the start values that came with the header are already taken.
        shade_pkg::OpSpan: begin
          if (host_span_i) begin
            pay_op_d     = PaySpan;
            pay_idx_d    = 16'(hdr_n_i) - 16'd1;
            pay_rem_d    = pay_count_i - 16'(hdr_n_i) + 16'd1;
            in_payload_d = pay_count_i > 16'(hdr_n_i) - 16'd1;
          end else begin
            pay_op_d     = PaySkip;
            in_payload_d = 1'b0;
          end
        end
        // END_FRAME and unknown opcodes carry no payload.
        default: begin
          pay_op_d     = PaySkip;
          in_payload_d = 1'b0;
        end
      endcase
    end else if (pay_fire) begin  // the tail, or one MATERIAL / TABLE word
      pay_idx_d = pay_idx_q + pay_take;
      pay_rem_d = pay_rem_q - pay_take;
      if (pay_take == pay_rem_q) in_payload_d = 1'b0;  // the payload's last word
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      in_payload_q <= 1'b0;
      pay_op_q     <= PaySkip;
      pay_idx_q    <= 16'd0;
      pay_rem_q    <= 16'd1;
      tbl_base_q   <= 16'd0;
      tbl_mat_q    <= 1'b0;
    end else begin
      in_payload_q <= in_payload_d;
      pay_op_q     <= pay_op_d;
      pay_idx_q    <= pay_idx_d;
      pay_rem_q    <= pay_rem_d;
      tbl_base_q   <= tbl_base_d;
      tbl_mat_q    <= tbl_mat_d;
    end
  end
  assign {in_payload_o, pay_idx_o, pay_rem_o} = {in_payload_q, pay_idx_q, pay_rem_q};
  assign cfg_table_o     = pay_op_q == PayTable;
  assign cfg_all_banks_o = cfg_table_o && !tbl_mat_q;
  assign cfg_valid_o     = pay_fire && (cfg_table_o ||
                           (pay_op_q == PayMaterial && pay_idx_q >= 16'(N_MAT_FIXED)));
  assign cfg_addr_o      = cfg_table_o ? tbl_base_q + pay_idx_q : pay_idx_q - 16'(N_MAT_FIXED);
  assign pay_mat_o       = pay_fire && pay_op_q == PayMaterial;
  assign span_pay_o      = in_payload_q && pay_op_q == PaySpan;
endmodule
