// Check of wpow_unit's squarer as synthesis sees it (`square`, summed as a square: b_i at 2i,
// b_i & b_j once at i + j + 1) against Verilog's own `*`: (b * b) >> B for every base b of
// 0 .. 2^B (u1.B, b <= 1.0) at B = 2 .. 12 and 16, and at B = 30 (the model's widest) on its
// edges and 20,000 bases of a fixed pseudo-random sequence. Prints "square: N squares checked"
// and "square: PASS", or the first mismatches and "square: FAIL" ($fatal).
// cmake/icarus.cmake runs it through tests/rtl/synthesis_view_check.cmake
// (icarus_wpow_square) and on a deliberately broken copy of rtl/wpow_unit.sv, which must fail;
// scripts/mutate-rtl runs it first on every mutant of wpow_unit.sv.
module tb_wpow_square;
  localparam int Widest = 30;
  localparam int Samples = 20000;
  localparam int ShownErrors = 5;  // a broken unit stops here: the rest would fail alike
  int errors = 0;
  int checked = 0;

  // One unit of B fraction bits: m 16, pipelined (slots 0..2 of SPEC_PARAMS); a series wide
  // enough for every B here (fs = 36) and a 2-bit output fraction (OutDrop = B - 2 >= 0).
  function automatic logic [shade_pkg::SpecParamW-1:0] params(input int b);
    return {{(shade_pkg::SpecSlots - 3){32'd0}}, 32'd0, 32'(b), 32'd16};
  endfunction

  for (genvar g = 0; g < 13; g++) begin : g_b
    localparam int B = g < 11 ? g + 2 : (g == 11 ? 16 : Widest);
    localparam int BW = B + 1;
    wpow_unit #(.SPEC_PARAMS(params(B)), .SERIES_WL(40), .SERIES_IWL(4), .OUT_WL(3),
                .OUT_IWL(1)) u_unit (
      .clk_i(1'b0), .rst_ni(1'b1), .en_i(1'b0), .series_i(40'd0), .bank_i(1'b0),
      .cfg_valid_i(1'b0), .cfg_bank_i(1'b0), .cfg_table_i(1'b0), .cfg_addr_i(16'd0),
      .cfg_data_i(64'd0), .spec_o(), .busy_o());

    task automatic check(input logic [63:0] b);
      logic [63:0]   want;
      logic [BW-1:0] got;
      want = (b * b) >> B;
      got  = u_unit.square(BW'(b));
      checked = checked + 1;
      if (64'(got) != want) begin
        errors = errors + 1;
        $display("square: B=%0d b=%0d: want %0d, got %0d", B, b, want, got);
        if (errors == ShownErrors)
          view_check_verdict("square", checked, "squares checked up to that mismatch", errors);
      end
    endtask

    initial begin : sweep
      logic [63:0] x;
      #1;
      if (B <= 16) begin
        for (longint b = 0; b <= (64'd1 << B); b++) check(64'(b));
      end else begin
        check(64'd0);
        check(64'd1);
        check((64'd1 << B) - 64'd1);
        check(64'd1 << B);
        x = 64'd1;
        for (int k = 0; k < Samples; k++) begin
          x = x * 64'd6364136223846793005 + 64'd1442695040888963407;  // Knuth's MMIX LCG
          check((x >> 20) % ((64'd1 << B) + 64'd1));
        end
      end
    end
  end

`include "view_check_verdict.svh"
  initial begin
    #2;
    view_check_verdict("square", checked,
                       $sformatf("squares checked (B 2..12 and 16 every base, B %0d %0d bases)",
                                 Widest, Samples + 4), errors);
  end
endmodule
