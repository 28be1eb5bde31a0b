// libsystemc references sc_main; unit tests that use SystemC's data types (sc_fix as an oracle)
// run under gtest_main instead, so this definition only satisfies the linker and is never called.
extern "C" int sc_main(int, char**) { return 1; }
