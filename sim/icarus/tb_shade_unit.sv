// tb_shade_unit: Icarus Verilog (-g2012) testbench of rtl/shade_unit.sv, an independent
// simulator of the same RTL the Verilator harness runs. It replays a command stream's binary
// words and writes every output pixel with its exit cycle, so its pixels and cycles can be
// compared with the bit-accurate model's and the cycle model's (sim/icarus/stream_tool.cpp
// writes the files), and its cycle count with the harness's.
//
//   vvp tb.vvp +words=/abs/stream.hex [+gaps=/abs/gaps.hex +cycles=/abs/cycles.hex]
//              [+pixels=/abs/out.txt]
//
// Stimulus: the Verilator harness's, from the schedule files icarus_stream_tool export writes
// (the generator has one home, sim/harness/stimulus.h and sim/harness/idle_noise.h): +gaps= gives the
// idle cycles before each beat is offered (CommandDriver: valid stays high until the beat is
// taken), +cycles= per cycle pix_ready and the random words on cmd_data while cmd_valid is low.
// Both are read as the run goes, one entry per beat / per cycle. Without them: no gaps, pix_ready
// always high, zeros while valid is low (the harness's --gap-pct 0 --stall-pct 0). Either way
// the cycle count equals rtl_cosim_*'s `cycles=` for the same stream and stimulus. Cycle 0 is
// the first clock edge after reset, as in the harness; the count is the last pixel's cycle + 1.
// A run that outlasts the +cycles= schedule (the harness's bound) is late or hung: an error.
//
// PORT_WORDS > 1: the words go out PORT_WORDS to a beat, the last beat padded with zero words.
// LANES > 1: each pixel beat is written as its valid lanes' pixels in lane order (x + j), the
// end-of-row flag on the last of them; `pixels=` counts pixels, not beats.
// Parameters are shade_unit's, every one of them with its default (tb_params_check.cmake checks
// the two lists agree), set per configuration with iverilog -Ptb_shade_unit.NAME=VALUE.
module tb_shade_unit #(
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int XY_BITS          = 12,
  parameter int OFS_BITS         = 17,
  parameter int COEF_WL          = 36,
  parameter int COEF_IWL         = 4,
  parameter int COEF_T0_WL       = COEF_WL,
  parameter int COEF_T1_WL       = COEF_WL,
  parameter int COEF_T2_WL       = COEF_WL,
  parameter int COEF_T3_WL       = COEF_WL,
  parameter int COEF_T4_WL       = COEF_WL,
  parameter int COEF_T5_WL       = COEF_WL,
  parameter int SERIES_WL        = 32,
  parameter int SERIES_IWL       = 4,
  parameter int SERIES_QUANT     = 0,
  parameter int SERIES_OVERFLOW  = 1,
  parameter int SPEC_COLOUR_WL   = 13,
  parameter int SPEC_COLOUR_IWL  = 1,
  parameter int OUT_BITS         = 8,
  parameter int SPECULAR_KIND    = 0,
  parameter int SPECULAR_OUT_WL  = 17,
  parameter int SPECULAR_OUT_IWL = 1,
  parameter int PORT_WORDS       = 1,
  parameter int TRI_QUEUE        = 1,
  parameter int LANES            = 1,
  parameter int SPECULAR_OUT_QUANT    = 0,
  parameter int SPECULAR_OUT_OVERFLOW = 0,
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS = '0,
  parameter int MATERIAL_BUFFERS = 1,
  parameter int SPAN_SETUP       = 0,
  parameter int START_DEPTH      = 1,
  parameter int DIFFUSE_MULTIPLY = 0,
  parameter int COMBINE_STAGES   = 0,
  // The testbench's own: 1 instantiates the harness's deliberate-fault hooks beside the unit
  // (sim/harness/faults/; Icarus 11 has no bind), compiled with
  // -DSHADESIM_FAULT_DUT=tb_shade_unit.dut.
  parameter int FAULT_HOOKS      = 0,
  // Capacity of the word memory (Icarus allocates it all: ~45 bytes a word); a longer stream
  // is a hard error, never a silent truncation.
  parameter int MAX_WORDS        = 1 << 20,
  // After the last word is accepted, this many cycles with pix_valid low mean the unit is
  // drained (its pipeline is a few cycles deep; a pixel held by back-pressure keeps it high). Without any progress for HANG_CYCLES it is hung.
  parameter int DRAIN_CYCLES     = 64,
  parameter int HANG_CYCLES      = 100000
);
  localparam int ResetCycles = 4;  // sim/harness/cosim.h kResetCycles

  logic clk = 1'b0;
  logic rst_n = 1'b0;
  always #5 clk = ~clk;

  logic [PORT_WORDS*64-1:0]     cmd_data = '0;
  logic                         cmd_valid = 1'b0;
  logic                         cmd_ready;
  logic [XY_BITS-1:0]           pix_x, pix_y;
  logic [LANES*CHANNELS*OUT_BITS-1:0] pix_colour;
  logic [LANES-1:0]             pix_mask;
  logic                         pix_eor, pix_valid;
  logic                         pix_ready = 1'b0;  // low in reset, as the harness drives it

  shade_unit #(
    .CHANNELS(CHANNELS), .LIGHTS(LIGHTS), .XY_BITS(XY_BITS), .OFS_BITS(OFS_BITS),
    .COEF_WL(COEF_WL), .COEF_IWL(COEF_IWL),
    .COEF_T0_WL(COEF_T0_WL), .COEF_T1_WL(COEF_T1_WL), .COEF_T2_WL(COEF_T2_WL),
    .COEF_T3_WL(COEF_T3_WL), .COEF_T4_WL(COEF_T4_WL), .COEF_T5_WL(COEF_T5_WL),
    .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
    .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW),
    .SPEC_COLOUR_WL(SPEC_COLOUR_WL), .SPEC_COLOUR_IWL(SPEC_COLOUR_IWL), .OUT_BITS(OUT_BITS),
    .SPECULAR_KIND(SPECULAR_KIND),
    .SPECULAR_OUT_WL(SPECULAR_OUT_WL), .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL),
    .PORT_WORDS(PORT_WORDS), .TRI_QUEUE(TRI_QUEUE), .LANES(LANES),
    .SPECULAR_OUT_QUANT(SPECULAR_OUT_QUANT), .SPECULAR_OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW),
    .SPEC_PARAMS(SPEC_PARAMS),
    .MATERIAL_BUFFERS(MATERIAL_BUFFERS),
    .SPAN_SETUP(SPAN_SETUP), .START_DEPTH(START_DEPTH), .DIFFUSE_MULTIPLY(DIFFUSE_MULTIPLY),
    .COMBINE_STAGES(COMBINE_STAGES)
  ) dut (
    .clk_i(clk), .rst_ni(rst_n),
    .cmd_data_i(cmd_data), .cmd_valid_i(cmd_valid), .cmd_ready_o(cmd_ready),
    .pix_x_o(pix_x), .pix_y_o(pix_y), .pix_colour_o(pix_colour),
    .pix_mask_o(pix_mask), .pix_eor_o(pix_eor),
    .pix_valid_o(pix_valid), .pix_ready_i(pix_ready)
  );
  if (FAULT_HOOKS != 0) begin : g_faults
    fault_hooks #(
      .XY_BITS(XY_BITS), .LANES(LANES), .CHANNELS(CHANNELS), .LIGHTS(LIGHTS),
      .OUT_BITS(OUT_BITS), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .SPECULAR_KIND(SPECULAR_KIND), .SPECULAR_OUT_WL(SPECULAR_OUT_WL),
      .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL), .DIFFUSE_MULTIPLY(DIFFUSE_MULTIPLY)
    ) u_fault_hooks ();
  end

  logic [63:0] words [0:MAX_WORDS-1];  // unloaded entries stay X
  int n_words = 0;
  int next_word = 0;
  longint cycle = 0;
  longint last_pixel_cycle = -1;
  longint last_progress = 0;
  longint pixels = 0;
  int idle = 0;
  bit running = 1'b0;
  int pix_fd = 0;
  int gaps_fd = 0, cycles_fd = 0;
  int gaps_read = 0;
  longint schedule_cycles = 0;  // entries of +cycles=
  int wait_cycles = 0;  // idle cycles left before the next beat is offered (CommandDriver)
  string words_path, pixels_path, gaps_path, cycles_path;

  function automatic bit loaded(int i);
    return (^words[i]) !== 1'bx;
  endfunction

  // The beat starting at stream word `first`: PORT_WORDS words, zero (NOP) past the end
  // (model/command_stream.h).
  function automatic logic [PORT_WORDS*64-1:0] beat_at(int first);
    logic [PORT_WORDS*64-1:0] b = '0;
    for (int k = 0; k < PORT_WORDS; k++) begin
      if (first + k < n_words) b[k*64 +: 64] = words[first + k];
    end
    return b;
  endfunction

  // Opens a schedule file and checks its first line, "// shadesim-KIND N ...".
  // (A task: Icarus 11 allows only input ports on functions.)
  task automatic open_schedule(input string path, input string kind, output int fd,
                               output longint n);
    reg [8*512-1:0] header;
    string got;
    fd = $fopen(path, "r");
    if (fd == 0) $fatal(1, "tb_shade_unit: +%0s=%0s: cannot open the file", kind, path);
    if ($fgets(header, fd) == 0 || $sscanf(header, "// shadesim-%s %d", got, n) != 2 ||
        got != kind) begin
      $fatal(1, "tb_shade_unit: %0s: line 1: expected \"// shadesim-%0s N ...\" (icarus_stream_tool export --%0s writes it)",
             path, kind, kind);
    end
  endtask

  // Idle cycles before beat `gaps_read` (0 without +gaps=).
  function automatic int next_gap();
    int g;
    if (gaps_fd == 0) return 0;
    if ($fscanf(gaps_fd, "%h", g) != 1) begin
      $fatal(1, "tb_shade_unit: %0s: line %0d: expected the hex gap before beat %0d", gaps_path,
             gaps_read + 2, gaps_read);
    end
    gaps_read = gaps_read + 1;
    return g;
  endfunction

  // Drives the inputs of cycle `c` (nonblocking, as a register would): the next beat when the
  // driver offers one, else the schedule's idle noise; pix_ready from the schedule.
  task automatic drive(longint c);
    logic [PORT_WORDS*64-1:0] noise;
    logic                     ready;
    logic                     valid;
    noise = '0;
    ready = 1'b1;
    if (cycles_fd != 0) begin
      if (c >= schedule_cycles || $fscanf(cycles_fd, "%h %h", ready, noise) != 2) begin
        $fatal(1, {"tb_shade_unit: cycle %0d is past the %0d cycles of %0s (the harness's bound: ",
                   "the cycle model's count + 1000): the unit is late or hung (word %0d of %0d, ",
                   "%0d pixels out)"}, c, schedule_cycles, cycles_path, next_word, n_words, pixels);
      end
    end
    valid = next_word < n_words && wait_cycles == 0;
    cmd_valid <= valid;
    cmd_data  <= valid ? beat_at(next_word) : noise;
    pix_ready <= ready;
  endtask

  initial begin
    int fd;
    reg [8*512-1:0] header;  // Icarus 11: $fgets wants a reg, not a string
    if (!$value$plusargs("words=%s", words_path)) begin
      $fatal(1, "tb_shade_unit: missing +words=FILE (the command stream as $readmemh hex words)");
    end
    // $readmemh only warns about a missing file and leaves the memory X: check first. The
    // first line (a comment to $readmemh) gives the word count.
    fd = $fopen(words_path, "r");
    if (fd == 0) $fatal(1, "tb_shade_unit: +words=%0s: cannot open the file", words_path);
    if ($fgets(header, fd) == 0 || $sscanf(header, "// shadesim-words %d", n_words) != 1 || n_words < 1) begin
      $fatal(1, "tb_shade_unit: %0s: line 1: expected \"// shadesim-words N ...\" with N >= 1 (icarus_stream_tool export writes it)",
             words_path);
    end
    $fclose(fd);
    if (n_words > MAX_WORDS) begin
      $fatal(1, "tb_shade_unit: %0s: %0d words, more than MAX_WORDS=%0d; compile with a larger -Ptb_shade_unit.MAX_WORDS",
             words_path, n_words, MAX_WORDS);
    end
    $readmemh(words_path, words, 0, n_words - 1);
    if (!loaded(n_words - 1)) begin
      $fatal(1, "tb_shade_unit: %0s: fewer hex words than the %0d the first line promises", words_path, n_words);
    end
    if ($value$plusargs("gaps=%s", gaps_path)) begin
      longint n_gaps;
      open_schedule(gaps_path, "gaps", gaps_fd, n_gaps);
      if (n_gaps != (n_words + PORT_WORDS - 1) / PORT_WORDS) begin
        $fatal(1, "tb_shade_unit: %0s: %0d gaps, but the %0d words make %0d beats of PORT_WORDS=%0d",
               gaps_path, n_gaps, n_words, (n_words + PORT_WORDS - 1) / PORT_WORDS, PORT_WORDS);
      end
    end
    if ($value$plusargs("cycles=%s", cycles_path)) begin
      open_schedule(cycles_path, "cycles", cycles_fd, schedule_cycles);
    end
    if ($value$plusargs("pixels=%s", pixels_path)) begin
      pix_fd = $fopen(pixels_path, "w");
      if (pix_fd == 0) $fatal(1, "tb_shade_unit: +pixels=%0s: cannot open for writing", pixels_path);
    end
    repeat (ResetCycles) @(posedge clk);
    rst_n     <= 1'b1;
    wait_cycles = next_gap();
    drive(0);
    running   <= 1'b1;
  end

  // Everything sampled here is what the RTL saw before this edge; the inputs for the next
  // cycle are driven with nonblocking assignments, as a register would.
  always @(posedge clk) begin
    if (running) begin
      // CommandDriver::clock: the gap before the next beat starts when this one is taken.
      if (cmd_valid && cmd_ready) begin
        next_word = next_word + PORT_WORDS;
        last_progress = cycle;
        wait_cycles = next_word < n_words ? next_gap() : 0;
      end else if (wait_cycles > 0) begin
        wait_cycles = wait_cycles - 1;
      end
      if (pix_valid && pix_ready) begin
        last_pixel_cycle = cycle;
        last_progress = cycle;
        for (int j = 0; j < LANES; j++) begin
          if (pix_mask[j]) begin
            pixels = pixels + 1;
            if (pix_fd != 0) begin
              $fwrite(pix_fd, "%0d %0d", pix_x + XY_BITS'(j), pix_y);
              for (int c = 0; c < CHANNELS; c++) begin
                $fwrite(pix_fd, " %0d", pix_colour[(j*CHANNELS + c)*OUT_BITS +: OUT_BITS]);
              end
              $fwrite(pix_fd, " %0d %0d\n", pix_eor && (j == LANES - 1 || !pix_mask[j+1]), cycle);
            end
          end
        end
      end
      if (pix_valid || next_word < n_words) begin
        idle = 0;
      end else begin
        idle = idle + 1;
      end
      if (next_word >= n_words && idle >= DRAIN_CYCLES) begin
        if (pix_fd != 0) $fclose(pix_fd);
        $display("tb_shade_unit: words=%0d pixels=%0d cycles=%0d", n_words, pixels, last_pixel_cycle + 1);
        $finish;
      end
      if (cycle - last_progress > HANG_CYCLES) begin
        $fatal(1, "tb_shade_unit: hung: no word accepted and no pixel for %0d cycles at cycle %0d (word %0d of %0d, %0d pixels out)",
               HANG_CYCLES, cycle, next_word, n_words, pixels);
      end
      cycle = cycle + 1;
      drive(cycle);
    end
  end
endmodule
