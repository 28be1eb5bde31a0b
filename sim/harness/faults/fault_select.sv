// fault_select: which deliberate fault a build with fault hooks injects (fault_hooks), and on which
// row, chosen at run time so one Verilated build serves every fault test: the plusargs
// +shadesim_fault=SITE (fault_pkg::Fault*) and +shadesim_fault_row=Y, which the harness passes
// (shadesim cosim --fault SITE@Y). No plusarg: no fault. Simulation only: under synthesis the
// site is FaultNone.
module fault_select #(
  parameter int XY_BITS = 12
) (
  output logic [fault_pkg::FaultSiteW-1:0] site_o,
  output logic [XY_BITS-1:0]               row_o
);
`ifndef SYNTHESIS
  logic [fault_pkg::FaultSiteW-1:0] site;
  logic [XY_BITS-1:0]               row;
  initial begin
    if (!$value$plusargs("shadesim_fault=%d", site)) site = fault_pkg::FaultNone;
    if (!$value$plusargs("shadesim_fault_row=%d", row)) row = '0;
  end
  assign site_o = site;
  assign row_o  = row;
`else
  assign site_o = fault_pkg::FaultNone;
  assign row_o  = '0;
`endif
endmodule
