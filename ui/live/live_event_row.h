#pragma once

#include <string>

#include "daq/sources/stream_event.h"
#include "ui/live/live_faults.h"

namespace oscilab::ui {

/// One row of the event log.
struct EventRow {
  std::string time;  // stream time "12.345 s", or "—" without one
  std::string kind;
  std::string text;  // the event's text, or a summary of its data
  Severity severity = Severity::Normal;
};
EventRow event_row(const daq::StreamEvent& event);

}  // namespace oscilab::ui
