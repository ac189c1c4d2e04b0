// The owner of the precompiled header the Qt Test executables share (REUSE_FROM in
// tests/CMakeLists.txt): the Qt, Qt Test and QCustomPlot headers, with the tests' flags and no
// definitions of any one test. It tests nothing and is never run.
int main() { return 0; }
