// Every fixed_sat parameter combination of small widths (IN_W 2..7, OUT_W 2..6, signed and
// unsigned targets, wrap and saturate: both the g_fits and the g_narrow views) driven with every
// input value. Prints one line per instance and value; tests/rtl/fixed_sat_check.py compares
// them with the overflow rule's closed form.
module tb_fixed_sat;
  localparam int MaxIn = 7;
  logic [MaxIn-1:0] x;
  logic             tick;

  for (genvar iw = 2; iw <= MaxIn; iw++) begin : g_in
    for (genvar ow = 2; ow <= 6; ow++) begin : g_out
      for (genvar s = 0; s <= 1; s++) begin : g_signed
        for (genvar w = 0; w <= 1; w++) begin : g_wrap
          logic [ow-1:0] out;
          fixed_sat #(.IN_W(iw), .OUT_W(ow), .OUT_SIGNED(s), .WRAP(w)) u_sat (
            .in_i(x[iw-1:0]), .out_o(out)
          );
          always @(posedge tick) begin
            if (x < (1 << iw)) $display("sat %0d %0d %0d %0d %0d %0d", iw, ow, s, w, x, out);
          end
        end
      end
    end
  end

  initial begin
    tick = 1'b0;
    for (int v = 0; v < (1 << MaxIn); v++) begin
      x = MaxIn'(v);
      #1 tick = 1'b1;
      #1 tick = 1'b0;
    end
    $display("done");
    $finish;
  end
endmodule
