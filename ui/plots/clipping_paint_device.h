#pragma once

#include <memory>

#include <QPaintDevice>
#include <QSize>

class QPainter;

namespace oscilab::ui {

class ClippingPaintEngine;

/// A paint device that passes everything drawn on it to another painter, doing the clipping
/// itself: what would cross the clip is cut geometrically (a fill intersected with the clip, a
/// stroke turned into its outline and intersected), what lies inside passes unchanged. For a
/// target whose engine ignores clipping: Qt's SVG generator (QSvgGenerator) draws a curve past
/// the axes otherwise. Text, images and pixmaps pass unclipped. The target painter stays active
/// for the device's life; one painter at a time. UI thread only.
class ClippingPaintDevice : public QPaintDevice {
 public:
  /// `target` is an active painter on the real device; `size` is the drawing's size in pixels.
  ClippingPaintDevice(QPainter& target, QSize size);
  ~ClippingPaintDevice() override;
  QPaintEngine* paintEngine() const override;

 protected:
  int metric(PaintDeviceMetric metric) const override;

 private:
  std::unique_ptr<ClippingPaintEngine> engine_;
  QPainter& target_;
  QSize size_;
};

}  // namespace oscilab::ui
