# Test tiers: every ctest test carries exactly one of these labels, assigned here and
# nowhere else (docs/testing.md says what each tier holds and how long it takes).
#
#   quick    model, host, CLI and unit tests, source checks: no Verilator, Icarus or Yosys run,
#            no RTL build, <= 2 minutes on 2 cores from a built tree (scripts/test --quick)
#   rtl      RTL lint, Icarus, Yosys, RTL unit tests, co-simulation of named builds, and the CLI
#            cases that build RTL or synthesise on demand
#   regress  shadesim regress runs, explore --verify, Slurm, shards through GNU parallel
#   fuzz     the libFuzzer harnesses and their saved crashing inputs
#   slow     anything long that is none of the above
#
# ctest -L takes a regular expression: select a tier with -L '^quick$'.
#
# Two kinds of tests, two tables:
#  - tests made by add_test get their tier from SHADESIM_TIER_RULES (first matching name wins),
#    applied at configure time by shadesim_assign_test_tiers() at the end of each directory that
#    adds tests. A tier label a file sets itself (cmake/rtl.cmake's LABELS rtl) must agree with
#    the rule, or the configure fails.
#  - GoogleTest cases, discovered at build time (gtest_discover_tests), get the tier of their
#    executable (SHADESIM_GTEST_TIERS) unless a case rule (SHADESIM_GTEST_CASE_TIERS, first match
#    wins) names them;
#    shadesim_gtest_test_tiers() writes a ctest script that applies both when ctest loads the
#    discovered cases.
# A test no rule names has no tier: the quick test test_tiers_check fails and names it.

set(SHADESIM_TIERS quick rtl regress fuzz slow)

#   NAME REGEX                                                     TIER
set(SHADESIM_TIER_RULES
  # the tier check itself, source checks and the scripts' own tests: seconds, no tools
  "^test_tiers_check(_self_test)?$"                                 quick
  "^(doc_paths|quantization_home|include_layers)(_self_test)?$"     quick
  "^(plot_colours|cpp_format|rtl_line_length)$"                     quick
  "^python_lint(_self_test)?$"                                     quick
  "^clang_tidy_self_test$"                                          quick
  "^architecture_folders(_self_test)?$"                             quick
  "^tool_script_literals(_self_test)?$"                             quick
  "^mutate_rtl_self_test$"                                          quick
  "^check_commits_self_test$"                                      quick
  "^ci_schedule_self_test$"                                         quick
  # random scenes on their own unit (scripts/random-scenes): 50 small ones, the kept regressions
  "^random_scenes_(quick|self_test)$"                               quick
  # the bench scripts once at a tiny size (tests/bench_scripts_check.sh): throughput-table needs
  # only the CLI; bench-cosim-ab builds a baseline in a git worktree; the rest build RTL or
  # synthesise
  "^bench_script_throughput_table$"                                 quick
  # docs/area.md's silicon table on the sphere (Yosys and OpenSTA, cached after the first run)
  "^silicon_table_sphere$"                                          rtl
  # shadesim layout on a small unit: qflow, magic, netgen, OpenSTA (cached after one run)
  "^layout_small_unit$"                                               rtl
  "^bench_script_bench_cosim_ab$"                                   regress
  "^bench_script_"                                                  rtl
  # shadesim report's page in headless Chromium, from hand-written inputs (no RTL, no Yosys)
  "^report_page$"                                                   quick
  # the scoreboard's lane checks: plain C++ against synthetic beats (no Verilator)
  "^rtl_scoreboard_lanes_test$"                                     quick
  # shadesim regress, explore --verify, Slurm
  "^regress_"                                                       regress
  "^explore_verify_"                                                regress
  # the libFuzzer harnesses (built by their own clang project) and their regression inputs
  "^fuzz_"                                                          fuzz
  # formal checks (cmake/formal.cmake, docs/formal.md): Yosys and ABC, <= 3 minutes on 2 cores
  "^rtl_formal_"                                                    rtl
  # Verilator lint and co-simulation, Icarus, Yosys, the RTL unit tests, on-demand builds
  "^rtl_"                                                           rtl
  "^icarus_"                                                        rtl
  # what an opt-out left out (cmake/required_tools.cmake) sits in the tier it stands for
  "^left_out_(rtl|tool_[0-9]+|formal)$"                             rtl
  "^left_out_fuzz$"                                                 fuzz
  "^left_out_assimp_testmodels$"                                    quick)

# GoogleTest executables (tests/*_test.cpp): the tier of their cases.
#   EXECUTABLE                TIER
set(SHADESIM_GTEST_TIERS
  accuracy_test             quick
  area_estimate_test        quick
  area_test                 quick
  cli_test                  quick
  config_clock_test         quick
  command_stream_test       quick
  coverage_test             quick
  cycle_estimate_test       quick
  cycle_model_test          quick
  derivation_cache_test     quick
  derivation_test           quick
  digit_grouping_test       quick
  edge_stimulus_test        quick
  encode_test               quick
  explore_test              quick
  exponent_lut_test         quick
  fault_site_test           quick
  fixed_point_test          quick
  fuzz_regressions_test     quick
  golden_model_test         quick
  hard_scene_test           quick
  host_setup_test           quick
  image_test                quick
  junit_test                quick
  lanes_test                quick
  layout_test               quick
  liberty_flow_test         quick
  lockstep_test             quick
  miss_causes_test          quick
  mutation_test             quick
  phong_blinn_fit_test      quick
  pixel_combine_test        quick
  power_test                quick
  prepared_scene_test       quick
  raster_test               quick
  reference_test            quick
  render_test               quick
  rtl_config_test           quick
  rtl_parameters_test       quick
  scaleout_test             quick
  scene_config_test         quick
  scene_test                quick
  schlick_divider_test      quick
  scoreboard_test           quick
  series_test               quick
  setup_test                quick
  spec_error_test           quick
  sta_constraints_test      quick
  specular_units_test       quick
  taylor_test               quick
  throughput_choice_test    quick
  unit_config_file_test     quick
  wpow_unit_test            quick)

# Cases that leave their executable's tier: they build RTL, run Yosys or regress.
#   EXECUTABLE     CASE REGEX (ctest name: Suite.Case)                              TIER
set(SHADESIM_GTEST_CASE_TIERS
  # regress of grey_s428w on the Verilated RTL
  cli_test       "^Cli\\.CyclesEstimateEqualsTheRtlOnTheSameSceneAndStimulus$"      rtl
  cli_test       "^Cli\\.ARunThatShadesNothingIsNotAPass$"                          rtl
  cli_test       "^Cli\\.CosimRefusesAFaultOnARowWithNoPixels$"                     rtl
  # shadesim regress and cosim fail on a deliberate fault; their replay lines are run
  cli_test       "^Cli\\.ReplayLinesRunWhenPastedAndReproduceTheFailure$"           regress
  # regress of every shipped scene's own unit against cycles and the README's table
  cli_test       "^Cli\\.CyclesRegressAndTheReadmeAgreeOnEveryShippedScene$"         regress
  # regress of sphere's own unit on the Verilated RTL, its unit line
  derivation_cache_test "^DerivationCache\\.RegressSaysItsOwnUnitWasReused$"       rtl
  # Yosys: a direct run against shadesim area's cell count
  area_test      "^Area\\.CellCountEqualsADirectYosysRunAndTheCacheIsReused$"      rtl
  # Yosys on tiny modules (GE's closed forms) and a small LUT unit (its table RAM bits)
  area_test      "^Area\\.GateEquivalentsFollowTheClosedFormOnTinyModules$"         rtl
  area_test      "^Area\\.TableRamBitsAreApartFromGateEquivalents$"                 rtl
  # power: Verilator on the hand-counted fixture, OpenSTA on its mapped netlist, a traced
  # co-simulation of sphere's own unit
  power_test     "^Activity\\."                                                  rtl
  # sim/engines/unit_power.cpp end to end: sphere's osu018 netlist, its traced co-simulation, OpenSTA
  power_test     "^AreaPower\\."                                                 rtl
  power_test     "^Power\\.(TheAnnotation|SwitchingPower|AShiftRegister|Unmatched)" rtl
  # Yosys and OpenSTA on a tiny adder with osu018 (the liberty flow end to end)
  liberty_flow_test "^LibertyFlow\\.ATinyAdderMatchesYosysAreaAndItsOwnTiming$"    rtl
  # explore's CLI synthesises the area estimate's anchor with Yosys (once per build tree)
  explore_test   "^ExploreCli\\."                                                rtl
  scaleout_test  "^Explore\\.EmitsTheRunsOfItsVerificationAsRegressJobLines$"       rtl
  # shards through GNU parallel, a killed shard resumed, the watchdog, timeouts: regress on RTL
  scaleout_test  "^Scaleout\\."                                                     regress)

# The tier SHADESIM_TIER_RULES gives `name` (empty when none does) into `out`.
function(shadesim_test_tier name out)
  set(rules ${SHADESIM_TIER_RULES})
  list(LENGTH rules n)
  math(EXPR last "${n} / 2 - 1")
  foreach(i RANGE ${last})
    math(EXPR at "${i} * 2")
    math(EXPR at1 "${at} + 1")
    list(GET rules ${at} regex)
    list(GET rules ${at1} tier)
    if(name MATCHES "${regex}")
      set(${out} ${tier} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

# Call at the end of a directory's CMakeLists (after its last add_test, and after the includes
# that add tests): labels each of the directory's add_test tests with its tier, keeping its other
# labels (coverage, ...).
function(shadesim_assign_test_tiers)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(t ${tests})
    shadesim_test_tier(${t} tier)
    get_test_property(${t} LABELS labels)
    if(NOT labels)
      set(labels "")
    endif()
    set(kept "")
    foreach(l ${labels})
      if(l IN_LIST SHADESIM_TIERS)
        if(tier AND NOT l STREQUAL tier)
          message(FATAL_ERROR "test ${t}: labelled '${l}' where it is added, but "
                              "cmake/test_tiers.cmake puts it in '${tier}'; its tier belongs there")
        endif()
        if(NOT tier)
          message(WARNING "test ${t}: labelled '${l}' where it is added but no rule in "
                          "cmake/test_tiers.cmake names it")
        endif()
      else()
        list(APPEND kept ${l})
      endif()
    endforeach()
    if(tier)
      list(APPEND kept ${tier})
    else()
      message(WARNING "test ${t} has no tier: add a rule to SHADESIM_TIER_RULES in "
                      "cmake/test_tiers.cmake (test_tiers_check fails until then)")
    endif()
    set_tests_properties(${t} PROPERTIES LABELS "${kept}")
  endforeach()
endfunction()

# Call in the directory of the gtest_discover_tests calls, after the last one: a ctest script,
# included after the discovered cases (TEST_INCLUDE_FILES keeps the order), labels every case,
# or the executable's <name>_NOT_BUILT stand-in when it is not built yet.
function(shadesim_gtest_test_tiers)
  # ARGN: the executables given to gtest_discover_tests; each must be listed.
  foreach(exe ${ARGN})
    if(NOT exe IN_LIST SHADESIM_GTEST_TIERS)
      message(WARNING "GoogleTest executable ${exe} has no tier: add it to SHADESIM_GTEST_TIERS "
                      "in cmake/test_tiers.cmake (test_tiers_check fails until then)")
    endif()
  endforeach()
  set(exes ${SHADESIM_GTEST_TIERS})
  set(cases ${SHADESIM_GTEST_CASE_TIERS})
  list(LENGTH cases ncases)
  set(script "# Generated by cmake/test_tiers.cmake: the tier of each discovered GoogleTest case.\n")
  list(LENGTH exes n)
  math(EXPR last "${n} / 2 - 1")
  set(listed "")
  foreach(i RANGE ${last})
    math(EXPR at "${i} * 2")
    math(EXPR at1 "${at} + 1")
    list(GET exes ${at} exe)
    list(GET exes ${at1} tier)
    list(APPEND listed ${exe})
    if(NOT TARGET ${exe})
      continue()
    endif()
    string(APPEND script "if(DEFINED ${exe}_TESTS)\n  foreach(t IN LISTS ${exe}_TESTS)\n"
                         "    set(tier ${tier})\n")
    # The first case rule that matches wins.
    set(keyword "if")
    if(ncases GREATER 0)
      math(EXPR clast "${ncases} / 3 - 1")
      foreach(j RANGE ${clast})
        math(EXPR c0 "${j} * 3")
        math(EXPR c1 "${c0} + 1")
        math(EXPR c2 "${c0} + 2")
        list(GET cases ${c0} cexe)
        if(cexe STREQUAL exe)
          list(GET cases ${c1} cregex)
          list(GET cases ${c2} ctier)
          string(APPEND script "    ${keyword}(t MATCHES [==[${cregex}]==])\n      set(tier ${ctier})\n")
          set(keyword "elseif")
        endif()
      endforeach()
    endif()
    if(keyword STREQUAL "elseif")
      string(APPEND script "    endif()\n")
    endif()
    string(APPEND script "    set_tests_properties(\"\${t}\" PROPERTIES LABELS \${tier})\n  endforeach()\n"
                         "else()\n  set_tests_properties(${exe}_NOT_BUILT PROPERTIES LABELS ${tier})\nendif()\n")
  endforeach()
  # Every case rule names a listed executable (a typo would silently leave cases in quick).
  if(ncases GREATER 0)
    math(EXPR clast "${ncases} / 3 - 1")
    foreach(j RANGE ${clast})
      math(EXPR c0 "${j} * 3")
      list(GET cases ${c0} cexe)
      if(NOT cexe IN_LIST listed)
        message(FATAL_ERROR "cmake/test_tiers.cmake: a case rule names ${cexe}, which "
                            "SHADESIM_GTEST_TIERS does not list")
      endif()
    endforeach()
  endif()
  set(file ${CMAKE_CURRENT_BINARY_DIR}/test_tiers_gtest.cmake)
  file(WRITE ${file}.new "${script}")
  configure_file(${file}.new ${file} COPYONLY)
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${file})
endfunction()
