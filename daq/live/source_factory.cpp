#include "daq/live/source_factory.h"

#include <cctype>
#include <filesystem>

#include "analysis/common/input_error.h"
#include "analysis/model/model_json.h"
#include "daq/network/net_source.h"
#include "daq/network/tcp_socket.h"
#include "daq/sources/jack_source.h"
#include "daq/sources/replay_source.h"

namespace oscilab::daq {
namespace {

bool starts_with(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

// "a,b,c" → {"a", "b", "c"}, blanks around each name dropped.
std::vector<std::string> split_ports(const std::string& text) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    std::string item = text.substr(from, comma == std::string::npos ? comma : comma - from);
    const std::size_t first = item.find_first_not_of(" \t");
    const std::size_t last = item.find_last_not_of(" \t");
    out.push_back(first == std::string::npos ? "" : item.substr(first, last - first + 1));
    if (comma == std::string::npos) return out;
    from = comma + 1;
  }
}

// "usb" for "usb:3": the scheme a description names when it looks like SCHEME:REST (two or more
// letters, digits, '+', '-' or '.', starting with a letter), or "" when it does not.
std::string scheme_of(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos || colon < 2 ||
      !std::isalpha(static_cast<unsigned char>(spec[0]))) {
    return "";
  }
  for (std::size_t i = 0; i < colon; ++i) {
    const auto c = static_cast<unsigned char>(spec[i]);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return "";
  }
  return spec.substr(0, colon);
}

ReplaySource::Options replay_options(const SourceOptions& o) {
  ReplaySource::Options replay;
  replay.speed = o.replay.speed;
  replay.loop = o.replay.loop;
  return replay;
}

}  // namespace

SourceKind source_kind(const std::string& spec) {
  if (spec == "rig") return SourceKind::Rig;
  if (starts_with(spec, "net:")) return SourceKind::Network;
  if (starts_with(spec, "jack:")) return SourceKind::Jack;
  return SourceKind::Replay;
}

std::unique_ptr<SampleSource> make_source(const std::string& spec, const SourceOptions& o) {
  switch (source_kind(spec)) {
    case SourceKind::Rig: {
      if (o.rig.well != analysis::Well::Positive && o.rig.well != analysis::Well::Negative) {
        throw InputError(o.what +
                         " rig: the rig starts in the positive or the negative well, not \"" +
                         analysis::to_string(o.rig.well) + "\"");
      }
      RigSource::Options rig;
      rig.rig.positive_well = o.rig.well == analysis::Well::Positive;
      rig.rig.seed = o.rig.seed;
      rig.frequency_hz = o.rig.frequency_hz;
      rig.speed = o.rig.speed;
      rig.schedule = o.rig.schedule;
      rig.duration_s = o.rig.duration_s;
      return std::make_unique<RigSource>(
          o.rig.model_value ? *o.rig.model_value : analysis::model_from_spec(o.rig.model), rig);
    }
    case SourceKind::Network: {
      NetSource::Options net;
      const std::string address = spec.substr(4);
      if (address.size() > 2 && address.compare(address.size() - 2, 2, ":0") == 0) {
        net.host = address.substr(0, address.size() - 2);  // port 0: any free port
      } else {
        parse_host_port(address, o.what, net.host, net.port);
      }
      net.expected = o.network.expected;
      return std::make_unique<NetSource>(net);
    }
    case SourceKind::Jack: {
      JackSource::Options jack;
      jack.ports = split_ports(spec.substr(5));
      for (std::size_t i = 0; i < jack.ports.size(); ++i) {
        if (jack.ports[i].empty()) {
          throw InputError(o.what + " " + spec + ": port " + std::to_string(i + 1) +
                           " is empty (jack:PORT_BASE,PORT_MASS[,...])");
        }
      }
      if (!o.jack.calibration) {
        throw InputError(o.what + " " + spec +
                         ": a JACK source needs its calibration (a sidecar with one channel "
                         "per port)");
      }
      jack.server = o.jack.server;
      jack.client_name = o.jack.client;
      jack.calibration = *o.jack.calibration;
      jack.analysis_rate_hz = o.jack.analysis_rate_hz.value_or(o.jack.calibration->sample_rate_hz);
      return std::make_unique<JackSource>(jack);
    }
    case SourceKind::Replay:
      break;
  }
  // A description of an unknown kind ("usb:3") is not a missing file; a recording whose name
  // holds a colon still plays.
  if (const std::string scheme = scheme_of(spec);
      !scheme.empty() && scheme != "file" && !std::filesystem::exists(spec)) {
    throw InputError(o.what + " " + spec + ": unknown source kind \"" + scheme +
                     ":\" (rig, net:HOST:PORT, jack:PORT_BASE,PORT_MASS, file:REC or a "
                     "recording's path)");
  }
  const std::string path = starts_with(spec, "file:") ? spec.substr(5) : spec;
  if (path.empty()) throw InputError(o.what + " file: needs a recording path");
  return std::make_unique<ReplaySource>(path, replay_options(o));
}

std::unique_ptr<SampleSource> make_source(Recording recording, const SourceOptions& o) {
  return std::make_unique<ReplaySource>(std::move(recording), replay_options(o));
}

}  // namespace oscilab::daq
