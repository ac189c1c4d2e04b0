// A module for module_loader_test.cpp: it exports one entry point, and lacks every other.
extern "C" __attribute__((visibility("default"))) int oscilab_test_module_answer_v1() { return 42; }
