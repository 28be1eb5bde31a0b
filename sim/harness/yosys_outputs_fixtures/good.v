// yosys_outputs_check.py's own test: the pixel outputs of a flat netlist, each its own flip-flop
// (the form write_verilog -noattr gives a correct 2-lane, 2-bit-colour unit).
module shade_unit(clk_i, a, b, pix_x_o, pix_y_o, pix_colour_o);
  input clk_i;
  input [3:0] a;
  input [3:0] b;
  output [3:0] pix_colour_o;
  reg [3:0] pix_colour_o;
  output [1:0] pix_x_o;
  reg [1:0] pix_x_o;
  output [1:0] pix_y_o;
  reg [1:0] \pix_y_o_reg[0] ;
  reg [1:0] \pix_y_o_reg[1] ;
  always @(posedge clk_i)
    pix_colour_o[1:0] <= a[1:0];
  always @(posedge clk_i)
    pix_colour_o[2] <= a[2];
  always @(posedge clk_i)
    pix_colour_o[3] <= a[3];
  always @(posedge clk_i)
    pix_x_o <= b[1:0];
  always @(posedge clk_i)
    \pix_y_o_reg[0]  <= b[2];
  always @(posedge clk_i)
    \pix_y_o_reg[1]  <= b[3];
  assign pix_y_o[0] = \pix_y_o_reg[0] ;
  assign pix_y_o[1] = \pix_y_o_reg[1] ;
endmodule
