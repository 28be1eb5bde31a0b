// schlick_divider: Schlick's S = t / (n - n t + t) by a restoring radix-2 divider
// (model/schlick_divider.h, class SchlickDivider). No per-material parameters: the exponent lives
// in the two pre-scaled series (numerator t/n', denominator (n' - (n'-1) t)/n').
//
// SPEC_PARAMS's slots (decoded below) mirror SchlickConfig: QUOTIENT_BITS (Q, quotient fraction
// bits = iterations), OPERAND_BITS (D, operand fraction bits), TIMING (UnitTiming: 0 pipelined,
// 1 iterative); SERIES_WL/IWL; OUT_WL/IWL/QUANT/OVERFLOW (the specular out format, unsigned).
//
// Stages, in the model's order:
//   1. CLAMP/ALIGN  num <= 0 -> 0; den <= 0 -> 1; both quantized (truncate, saturate) to unsigned
//                   2.D operands; num_op == 0 -> 0; num_op >= den_op -> 1. Combinational, in
//                   front of the first quotient bit.
//   2. DIVIDE       Q restoring steps: r <- 2r; if r >= den_op { r -= den_op; bit 1 } else
//                   bit 0, from r = num_op < den_op: q = floor(num_op 2^Q / den_op). One
//                   register per step.
//   3. OUTPUT       quantize(q, Q fraction bits) into the out format (1 as 2^Q): combinational.
// The remainder stays below den_op < 2^(D+2), so a step is one (D+3)-bit subtract/compare.
//
// Timing, LATENCY = Q either way:
//   TIMING 0 (pipelined): Q stage registers, all enabled by en_i (advance): spec_o shows the result
//            of the operands sampled at the Q-th most recent en_i edge. One pixel per cycle;
//            busy_o = 0.
//   TIMING 1 (iterative): one step stage reused Q times. en_i while !busy_o starts a division
//            (operands sampled at that edge, cycle c); busy_o is high in cycles c+1 .. c+Q-1 (en_i
//            is ignored then), the result is on spec_o from cycle c+Q and stays there until the
//            edge that ends the next start cycle. A new start in cycle c+Q gives II = Q.
module schlick_divider #(
  // The unit's fields, packed (shade_pkg::SpecSlots slots; decoded below). The default is
  // the model's default SchlickConfig: Q 16, D 24, iterative.
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS =
      {{(shade_pkg::SpecSlots - 3){32'd0}}, 32'd1, 32'd24, 32'd16},
  parameter int SERIES_WL     = 32,
  parameter int SERIES_IWL    = 4,
  parameter int OUT_WL        = 17,
  parameter int OUT_IWL       = 1,
  parameter int OUT_QUANT     = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int OUT_OVERFLOW  = 0   // Overflow: 0 saturate, 1 wrap
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic [SERIES_WL-1:0] num_i,
  input  logic [SERIES_WL-1:0] den_i,
  output logic [OUT_WL-1:0]    spec_o,
  output logic                 busy_o
);
  // SchlickConfig from SPEC_PARAMS: the slots of the "schlick" row of model/specular_units.cpp
  // (slots 0 and 2 also set shade_pkg::spec_latency / spec_interval). The names are the
  // parameters' they replace, so the body reads as before.
  localparam int QUOTIENT_BITS = shade_pkg::spec_slot(SPEC_PARAMS, 0);  // schlick.quotient_bits
  localparam int OPERAND_BITS  = shade_pkg::spec_slot(SPEC_PARAMS, 1);  // schlick.operand_bits
  localparam int TIMING        = shade_pkg::spec_slot(SPEC_PARAMS, 2);  // schlick.timing code
`ifndef SYNTHESIS
  initial begin
    if (QUOTIENT_BITS < 1) $fatal(1, "schlick_divider: QUOTIENT_BITS %0d < 1", QUOTIENT_BITS);
    if (OPERAND_BITS < 2) $fatal(1, "schlick_divider: OPERAND_BITS %0d < 2", OPERAND_BITS);
    if (TIMING != 0 && TIMING != 1) $fatal(1, "schlick_divider: TIMING %0d is not 0 or 1", TIMING);
  end
`endif
  localparam int Q       = QUOTIENT_BITS;
  localparam int Fs      = SERIES_WL - SERIES_IWL;
  localparam int OpW     = OPERAND_BITS + 2;      // unsigned 2.D
  localparam int OpDrop  = Fs - OPERAND_BITS;
  localparam int OpRndW  = SERIES_WL + 1 - OpDrop;
  localparam int ResW    = Q + 2;                 // signed, holds 0 .. 2^Q
  localparam int OutDrop = Q - (OUT_WL - OUT_IWL);
  localparam int OutRndW = ResW + 1 - OutDrop;

  // Result class decided by CLAMP/ALIGN.
  typedef enum logic [1:0] {ClsDiv, ClsZero, ClsOne} cls_e;

  // One restoring step: r < den on entry and on exit.
  function automatic logic [OpW:0] divide_step(input logic [OpW-1:0] r, input logic [OpW-1:0] den);
    logic [OpW:0] r2, den_x;
    // diff's top bit is 0 whenever diff is used (ge): the remainder stays below den.
    // verilator lint_off UNUSEDSIGNAL
    logic [OpW:0] diff;
    // verilator lint_on UNUSEDSIGNAL
    logic         ge;
    r2    = {r, 1'b0};
    den_x = {1'b0, den};
    diff  = r2 - den_x;
    ge    = r2 >= den_x;
    // {next remainder, quotient bit}; the remainder is below den again, so OpW bits hold it
    divide_step = ge ? {diff[OpW-1:0], 1'b1} : {r2[OpW-1:0], 1'b0};
  endfunction

  // ---- 1. CLAMP/ALIGN --------------------------------------------------------------------------
  logic signed [OpRndW-1:0] num_rnd, den_rnd;
  logic [OpW-1:0]           num_op, den_op;
  cls_e                     cls_d;
  fixed_round #(.IN_W(SERIES_WL), .DROP(OpDrop), .ROUND(0))
    u_num_round (.in_i(num_i), .out_o(num_rnd));
  fixed_round #(.IN_W(SERIES_WL), .DROP(OpDrop), .ROUND(0))
    u_den_round (.in_i(den_i), .out_o(den_rnd));
  fixed_sat #(.IN_W(OpRndW), .OUT_W(OpW), .OUT_SIGNED(0), .WRAP(0))
    u_num_sat (.in_i(num_rnd), .out_o(num_op));
  fixed_sat #(.IN_W(OpRndW), .OUT_W(OpW), .OUT_SIGNED(0), .WRAP(0))
    u_den_sat (.in_i(den_rnd), .out_o(den_op));

  logic num_pos, den_pos;  // raw series value > 0
  assign num_pos = !num_i[SERIES_WL-1] && num_i != '0;
  assign den_pos = !den_i[SERIES_WL-1] && den_i != '0;
  assign cls_d = !num_pos            ? ClsZero :
                 !den_pos            ? ClsOne  :
                 num_op == '0        ? ClsZero :
                 num_op >= den_op    ? ClsOne  : ClsDiv;

  logic [OpW:0] first;  // the first step, straight from the aligned operands
  assign first = divide_step(num_op, den_op);

  // ---- 2. DIVIDE -------------------------------------------------------------------------------
  logic [Q-1:0] q_out;
  logic [1:0]   cls_out;  // a cls_e (no enum cast: Icarus 11 cannot elaborate one)

  if (TIMING == 0) begin : g_pipelined
    // Stage k holds the quotient's top k + 1 bits and its class; the remainder and divisor are
    // registered only into the stages that still divide (k < Q - 1).
    // q_q and cls_q as flat vectors, stage k at [k*Q +: Q] / [2k +: 2]: Icarus 11 left the last
    // stage of unpacked arrays X here (every quotient X), and Yosys 0.23 cannot parse a
    // multi-dimensional packed array.
    logic [Q*Q-1:0] q_q;
    logic [2*Q-1:0] cls_q;  // a cls_e per stage
    logic [OpW:0]        step  [Q];  // step[k]: what stage k computes ({remainder, bit})
    if (Q > 1) begin : g_carry
      logic [OpW-1:0] r_q   [Q-1];
      logic [OpW-1:0] den_q [Q-1];
      always_comb begin
        step[0] = first;
        for (int k = 1; k < Q; k++) step[k] = divide_step(r_q[k-1], den_q[k-1]);
      end
      always_ff @(posedge clk_i) begin
        if (en_i) begin
          r_q[0]   <= step[0][OpW:1];
          den_q[0] <= den_op;
          for (int k = 1; k < Q - 1; k++) begin
            r_q[k]   <= step[k][OpW:1];
            den_q[k] <= den_q[k-1];
          end
        end
      end
    end else begin : g_one_bit
      assign step[0] = first;
    end
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        q_q[0 +: Q]   <= Q'(step[0][0]);
        cls_q[0 +: 2] <= cls_d;
        for (int k = 1; k < Q; k++) begin
          q_q[k*Q +: Q]   <= (q_q[(k-1)*Q +: Q] << 1) | Q'(step[k][0]);
          cls_q[2*k +: 2] <= cls_q[2*(k-1) +: 2];
        end
      end
    end
    assign q_out   = q_q[(Q-1)*Q +: Q];
    assign cls_out = cls_q[2*(Q-1) +: 2];
    assign busy_o  = 1'b0;
    // The pipelined stages hold no state that needs a reset (every stage is overwritten on the
    // advance before its output is used); the last step's remainder is not a quotient bit.
    // verilator lint_off UNUSEDSIGNAL
    logic unused_pipe;
    assign unused_pipe = rst_ni ^ (^step[Q-1][OpW:1]);
    // verilator lint_on UNUSEDSIGNAL
  end else begin : g_iterative
    localparam int CntW = $clog2(Q + 1);
    logic [CntW-1:0] cnt_q;   // steps still to do
    logic [OpW-1:0]  r_q, den_q;
    logic [Q-1:0]    q_q;
    cls_e            cls_q;
    logic            start;
    logic [OpW:0]    step;
    assign busy_o = cnt_q != '0;
    assign start  = en_i && !busy_o;
    assign step   = divide_step(r_q, den_q);

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni)     cnt_q <= '0;
      else if (start)  cnt_q <= CntW'(Q - 1);
      else if (busy_o) cnt_q <= cnt_q - CntW'(1);
    end
    always_ff @(posedge clk_i) begin
      if (start) begin
        r_q   <= first[OpW:1];
        q_q   <= Q'(first[0]);
        den_q <= den_op;
        cls_q <= cls_d;
      end else if (busy_o) begin
        r_q <= step[OpW:1];
        q_q <= (q_q << 1) | Q'(step[0]);
      end
    end
    assign q_out   = q_q;
    assign cls_out = cls_q;
  end

  // ---- 3. OUTPUT -------------------------------------------------------------------------------
  logic signed [ResW-1:0]    res;
  logic signed [OutRndW-1:0] out_rnd;
  always_comb begin
    unique case (cls_out)
      ClsZero: res = '0;
      ClsOne:  res = ResW'(1) << Q;
      default: res = ResW'(q_out);
    endcase
  end
  fixed_round #(.IN_W(ResW), .DROP(OutDrop), .ROUND(OUT_QUANT))
    u_out_round (.in_i(res), .out_o(out_rnd));
  fixed_sat #(.IN_W(OutRndW), .OUT_W(OUT_WL), .OUT_SIGNED(0), .WRAP(OUT_OVERFLOW))
    u_out_sat (.in_i(out_rnd), .out_o(spec_o));
endmodule
