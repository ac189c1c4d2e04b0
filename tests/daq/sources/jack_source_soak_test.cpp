// The JACK source freewheeling an hour of signal: no drift of the sample clock, no drop, memory
// flat (label `slow`; the unit suite runs the same soak for 5 minutes of signal).
#include <gtest/gtest.h>

#include "tests/daq/sources/jack_test_helpers.h"

namespace oscilab::daq {
namespace {

TEST(JackSourceSoak, FreewheelsAnHourOfSignalLosslesslyOnItsClock) { testing::soak(3600.0); }

}  // namespace
}  // namespace oscilab::daq
