#include "ui/live/live_event_row.h"

#include <cmath>
#include <cstdio>

#include "ui/number_text.h"

namespace oscilab::ui {
EventRow event_row(const daq::StreamEvent& event) {
  EventRow row;
  row.time = std::isfinite(event.t_s) ? number_text("%.3f s", event.t_s) : "\u2014";
  row.kind = event.kind_name();
  row.text = !event.text.empty()  ? event.text
             : event.data.empty() ? std::string()
                                  : event.data.dump();
  using daq::EventKind;
  switch (event.kind) {
    case EventKind::Gap:
    case EventKind::Overflow:
    case EventKind::NonFinite:
    case EventKind::Saturated:
    case EventKind::Alarm:
    case EventKind::Error:
    case EventKind::MalformedFrame:
    case EventKind::LayoutMismatch:
    case EventKind::Late:
      row.severity = Severity::Fault;
      break;
    case EventKind::Duplicate:
    case EventKind::Reordered:
    case EventKind::Discontinuity:
    case EventKind::Disconnected:
      row.severity = Severity::Warning;
      break;
    default:
      break;
  }
  return row;
}

}  // namespace oscilab::ui
