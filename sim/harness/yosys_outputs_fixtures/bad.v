// yosys_outputs_check.py's own test: what Yosys 0.23 made of a four-lane unit whose metadata line
// was a packed array of packed structs (lanes 1..3 one merged register, x and y constant 0).
module shade_unit(clk_i, a, pix_x_o, pix_y_o, pix_colour_o);
  input clk_i;
  input [15:0] a;
  output [15:0] pix_colour_o;
  reg [15:0] pix_colour_o;
  output [3:0] pix_x_o;
  output [3:0] pix_y_o;
  always @(posedge clk_i)
    pix_colour_o[3:0] <= a[3:0];
  always @(posedge clk_i)
    pix_colour_o[14:11] <= a[14:11];
  assign { pix_colour_o[15], pix_colour_o[10:4] } = { pix_colour_o[11], pix_colour_o[14:11], pix_colour_o[14:12] };
  assign pix_x_o = 4'h0;
  assign pix_y_o = 4'h0;
endmodule
