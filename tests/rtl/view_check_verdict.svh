// The verdict a synthesis-view testbench ends with (included into its module): the count, then
// "<view>: PASS", or "<view>: FAIL, N wrong" through $fatal. tests/rtl/synthesis_view_check.cmake
// reads those two words.
task automatic view_check_verdict(input string view, input int checked, input string what,
                                  input int errors);
  $display("%s: %0d %s", view, checked, what);
  if (errors != 0) $fatal(1, "%s: FAIL, %0d wrong", view, errors);
  $display("%s: PASS", view);
  $finish;
endtask
