// The owner of the precompiled header the headless GoogleTest executables share (REUSE_FROM in
// tests/CMakeLists.txt): a target of its own, with the tests' flags and no definitions of any one
// suite, so that whichever suites a build leaves out the header stays valid for the rest. It
// holds no test and is never run.
