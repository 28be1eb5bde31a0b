// wpow_split_square: one squaring of wpow_unit (b -> b^2 >> B, truncated) over two cycles, for
// SQUARE_STAGES 2 (one squaring in a cycle is the osu018 unit's critical path otherwise).
// The register between the two halves is this module's; wpow_unit registers the sum.
//
// b = h 2^H + l (H = BW / 2), so b^2 = h^2 2^2H + l^2 + h l 2^(H+1), and the squaring keeps
// b^2 >> B (2H is B or B + 1). Split at 2^B: h^2 lies wholly above it; l^2 and h l 2^(H+1) are
// each a high part (l^2 >> B, h l >> (B - H - 1)) and a low one, and the low parts' sum carries
// at most 1 into bit B. The middle register holds h^2, the two high parts and that carry (30
// bits for B = 16, not the 51 of h^2, l^2 and h l); b_o adds them:
// h^2 2^(2H-B) + (l^2 >> B) + (h l >> (B-H-1)) + carry = b^2 >> B exactly. Where the stage
// passes b through (square_i low), the middle holds b as h^2 2^(2H-B) + (l^2 >> B).
// No model class of its own: WpowUnit squares in one step and counts the extra cycle in its
// latency (WpowConfig::square_stages); the halves are checked against the model's square for
// every base of B = 16 (WpowUnitRtl tests).
module wpow_split_square #(
  parameter int B  = 16,    // fraction bits of b and of its square
  parameter int BW = B + 1  // b's width: unsigned 1.B, b <= 1.0
) (
  input  logic          clk_i,
  input  logic          en_i,      // the pipeline's advance
  input  logic [BW-1:0] b_i,
  input  logic          square_i,  // square b_i; else pass it through
  output logic [BW-1:0] b_o        // b_i^2 >> B (or b_i) of the latest en_i edge
);
  localparam int H     = BW / 2;            // l = b[H-1:0], h = b[BW-1:H]
  localparam int HW    = BW - H;
  localparam int HhW   = 2 * HW;            // h^2
  localparam int LlHi  = 2 * H - B;         // l^2 >> B: 0 or 1 bit (kept as 1 bit, maybe 0)
  localparam int CrLo  = B - H - 1;         // h l's bits below 2^B once shifted by H + 1
  localparam int CrHiW = BW - CrLo;         // h l >> CrLo
  localparam int MidW  = HhW + 1 + CrHiW + 1;  // {h^2, l^2 >> B, h l >> CrLo, carry}

  // x^2 of an HW-bit x (l is given zero-extended). Synthesis sums it as a square, as
  // wpow_unit's square() does; simulators multiply.
  function automatic logic [HhW-1:0] sq(input logic [HW-1:0] x);
`ifdef SYNTHESIS
    logic [HW-1:0] row;  // x_i & x_j for j > i, from bit i + j + 1 on
    sq = '0;
    for (int i = 0; i < HW; i++) begin
      row = {HW{x[i]}} & (x >> (i + 1));
      sq = sq + (HhW'(x[i]) << (2 * i)) + (HhW'(row) << (2 * i + 2));
    end
`else
    sq = HhW'(x) * HhW'(x);
`endif
  endfunction

  // ---- 1. the parts of b's square (or of b), registered ---------------------------------------
  logic [HW-1:0]  h;
  logic [HhW-1:0] ll;     // l^2, 2H bits used
  logic [BW-1:0]  hl;     // h l: HW + H = BW bits
  logic [B-1:0]   hl_lo;  // h l's low CrLo bits, shifted by H + 1: below 2^B
  // verilator lint_off UNUSEDSIGNAL
  logic [B:0]     low;    // the low parts' sum: only its carry into bit B is kept
  // verilator lint_on UNUSEDSIGNAL
  logic           ll_hi;
  logic [MidW-1:0] square_parts, pass_parts, mid_q;
  assign h            = b_i[BW-1:H];
  assign ll           = sq(HW'(b_i[H-1:0]));
  assign hl           = BW'(h) * BW'(b_i[H-1:0]);
  assign ll_hi        = LlHi > 0 ? ll[B] : 1'b0;
  assign hl_lo        = B'(hl << (H + 1));
  assign low          = (B+1)'(ll[B-1:0]) + (B+1)'(hl_lo);
  assign square_parts = {sq(h), ll_hi, CrHiW'(hl >> CrLo), low[B]};
  assign pass_parts   = {HhW'(b_i) >> LlHi, LlHi > 0 ? b_i[0] : 1'b0, CrHiW'(0), 1'b0};
  always_ff @(posedge clk_i) begin
    if (en_i) mid_q <= square_i ? square_parts : pass_parts;
  end

  // ---- 2. their sum ----------------------------------------------------------------------------
  // verilator lint_off UNUSEDSIGNAL
  logic [HhW:0] sum;  // b^2 >> B <= 2^B: the bits above BW stay 0
  // verilator lint_on UNUSEDSIGNAL
  assign sum = ((HhW+1)'(mid_q[MidW-1 -: HhW]) << LlHi) + (HhW+1)'(mid_q[CrHiW + 1]) +
               (HhW+1)'(mid_q[1 +: CrHiW]) + (HhW+1)'(mid_q[0]);
  assign b_o = sum[BW-1:0];

`ifndef SYNTHESIS
  initial begin
    if (B < 2 || BW != B + 1)
      $fatal(1, "wpow_split_square: needs B >= 2 and BW = B + 1, got B %0d BW %0d", B, BW);
  end
`endif
endmodule
