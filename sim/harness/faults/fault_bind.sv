// fault_bind: puts the deliberate-fault hooks (fault_hooks.sv) into every shade_unit, with the
// unit's own parameters, in the Verilated builds with fault hooks (builds.json "fault_hooks").
// Test apparatus: no other build, and no synthesis, reads this file.
bind shade_unit fault_hooks #(
  .XY_BITS(XY_BITS), .LANES(LANES), .CHANNELS(CHANNELS), .LIGHTS(LIGHTS), .OUT_BITS(OUT_BITS),
  .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL), .SPECULAR_KIND(SPECULAR_KIND),
  .SPECULAR_OUT_WL(SPECULAR_OUT_WL), .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL),
  .DIFFUSE_MULTIPLY(DIFFUSE_MULTIPLY)
) u_fault_hooks ();
