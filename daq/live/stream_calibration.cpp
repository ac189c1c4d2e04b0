#include "daq/live/stream_calibration.h"

#include <cmath>
#include <limits>

#include "analysis/model/excitation_force.h"

namespace oscilab::daq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kAcCouplingWarnFactor = 10.0;  // warn when f < this × the AC-coupling corner

analysis::MotionQuantity motion_quantity(Quantity quantity) {
  switch (quantity) {
    case Quantity::Velocity:
      return analysis::MotionQuantity::Velocity;
    case Quantity::Acceleration:
      return analysis::MotionQuantity::Acceleration;
    default:
      return analysis::MotionQuantity::Displacement;
  }
}

StreamCalibration::Channel calibration_of(const Sidecar& layout, int index) {
  StreamCalibration::Channel c;
  c.index = index;
  const ChannelInfo& channel = layout.channels[static_cast<std::size_t>(index)];
  c.scale = channel.scale;
  c.offset = channel.offset;
  c.factor = unit_to_si(channel.unit, channel.quantity, "stream channel \"" + channel.name + "\"");
  c.quantity = motion_quantity(channel.quantity);
  return c;
}

}  // namespace

StreamCalibration::StreamCalibration(const Sidecar& layout) {
  mass_kg_ = layout.mass_kg.value_or(1.0);
  const int channels = static_cast<int>(layout.channels.size());
  int base = -1, mass = -1, relative = -1;
  for (int i = 0; i < channels; ++i) {
    const ChannelRole role = layout.channels[static_cast<std::size_t>(i)].role;
    if (role == ChannelRole::Base && base < 0) base = i;
    if (role == ChannelRole::Mass && mass < 0) mass = i;
    if (role == ChannelRole::Relative && relative < 0) relative = i;
  }
  mass_relative_ = mass < 0;
  if (mass < 0) mass = relative;
  const bool motion_ok =
      base >= 0 && mass >= 0 &&
      layout.channels[static_cast<std::size_t>(base)].quantity != Quantity::Force &&
      layout.channels[static_cast<std::size_t>(mass)].quantity != Quantity::Force;
  if (!motion_ok) return;
  base_ = calibration_of(layout, base);
  mass_ = calibration_of(layout, mass);
  const double rate_hz = layout.sample_rate_hz;
  for (const auto& [cal, inverse] : {std::pair{&base_, &base_ac_}, std::pair{&mass_, &mass_ac_}}) {
    const ChannelInfo& channel = layout.channels[static_cast<std::size_t>(cal->index)];
    if (!channel.ac_coupling_hz) continue;
    inverse->emplace(*channel.ac_coupling_hz, rate_hz, "stream channel \"" + channel.name + "\"");
    ac_corners_.emplace_back(channel.name, *channel.ac_coupling_hz);
  }
}

std::vector<std::string> StreamCalibration::ac_coupling_warnings(double excitation_freq_hz) const {
  std::vector<std::string> warnings;
  for (const auto& [name, corner_hz] : ac_corners_) {
    // A first-order high-pass leads by atan(fc / f): 0.0997 rad at f = 10 fc. Corrected, a
    // corner known to ±10 % still leaves up to 0.01 rad there, a large error in the loop's
    // area, so an excitation within 10× of the corner is worth a warning (docs/live.md).
    if (excitation_freq_hz > 0 && excitation_freq_hz < kAcCouplingWarnFactor * corner_hz) {
      warnings.push_back("channel \"" + name + "\": the excitation " +
                         std::to_string(excitation_freq_hz) + " Hz is within " +
                         std::to_string(static_cast<int>(kAcCouplingWarnFactor)) +
                         "x of its AC-coupling corner " + std::to_string(corner_hz) +
                         " Hz; its phase is corrected, but the EDC now depends on how well the "
                         "corner is known: a DC-coupled input is better");
    }
  }
  return warnings;
}

StreamCalibration::Rows StreamCalibration::make_rows(int max_rows) const {
  Rows rows;
  for (auto* v :
       {&rows.base_si, &rows.mass_si, &rows.force_n, &rows.base_shown, &rows.mass_shown}) {
    v->assign(static_cast<std::size_t>(max_rows), kNaN);
  }
  return rows;
}

void StreamCalibration::calibrate(const RawBlock& block, Rows& rows) {
  const bool force_known = base_.quantity == analysis::MotionQuantity::Acceleration;
  for (int r = 0; r < block.rows; ++r) {
    const auto i = static_cast<std::size_t>(r);
    double b_si = base_.to_si(block.value(r, base_.index));
    double y_si = mass_.to_si(block.value(r, mass_.index));
    if (base_ac_) b_si = base_ac_->push(b_si);
    if (mass_ac_) y_si = mass_ac_->push(y_si);
    // Bad samples are excluded by the caller; zeros keep the filters and fits finite meanwhile,
    // and the display shows a hole.
    rows.base_shown[i] = std::isfinite(b_si) ? b_si : kNaN;
    rows.mass_shown[i] = std::isfinite(y_si) ? y_si : kNaN;
    rows.base_si[i] = std::isfinite(b_si) ? b_si : 0.0;
    rows.mass_si[i] = std::isfinite(y_si) ? y_si : 0.0;
    rows.force_n[i] =
        force_known ? analysis::excitation_force_n(mass_kg_, rows.base_shown[i]) : kNaN;
  }
}

}  // namespace oscilab::daq
