#include "ui/live_event_row.h"

#include <cmath>
#include <cstdio>

namespace oscilab::ui {
namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

}  // namespace

EventRow event_row(const daq::StreamEvent& event) {
  EventRow row;
  row.time = std::isfinite(event.t_s) ? format("%.3f s", event.t_s) : "\u2014";
  row.kind = event.kind;
  row.text = !event.text.empty()  ? event.text
             : event.data.empty() ? std::string()
                                  : event.data.dump();
  const std::string& k = event.kind;
  if (k == "gap" || k == "overflow" || k == "non-finite" || k == "saturated" || k == "alarm" ||
      k == "error" || k == "malformed-frame" || k == "layout-mismatch" || k == "late") {
    row.severity = Severity::Fault;
  } else if (k == "duplicate" || k == "reordered" || k == "discontinuity" || k == "disconnected") {
    row.severity = Severity::Warning;
  }
  return row;
}

}  // namespace oscilab::ui
