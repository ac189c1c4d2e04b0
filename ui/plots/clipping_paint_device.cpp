#include "ui/plots/clipping_paint_device.h"

#include <algorithm>

#include <QPaintEngine>
#include <QPainter>
#include <QPainterPath>
#include <QPainterPathStroker>

namespace oscilab::ui {

// Reads the drawing painter's state at each draw (pen, brush, transform, clip) and draws on the
// target in device coordinates.
class ClippingPaintEngine : public QPaintEngine {
 public:
  explicit ClippingPaintEngine(QPainter& target)
      : QPaintEngine(QPaintEngine::AllFeatures), target_(target) {}

  bool begin(QPaintDevice*) override { return true; }
  bool end() override { return true; }
  Type type() const override { return QPaintEngine::User; }
  void updateState(const QPaintEngineState&) override {}

  void drawPath(const QPainterPath& path) override { draw(path, true); }

  void drawPolygon(const QPointF* points, int count, PolygonDrawMode mode) override {
    QPainterPath path;
    if (count <= 0) return;
    path.moveTo(points[0]);
    for (int i = 1; i < count; ++i) path.lineTo(points[i]);
    if (mode == PolylineMode) {
      draw(path, false);
      return;
    }
    path.closeSubpath();
    path.setFillRule(mode == WindingMode ? Qt::WindingFill : Qt::OddEvenFill);
    draw(path, true);
  }

  void drawPixmap(const QRectF& rect, const QPixmap& pixmap, const QRectF& source) override {
    prepare_target();
    target_.drawPixmap(rect, pixmap, source);
  }
  void drawImage(const QRectF& rect, const QImage& image, const QRectF& source,
                 Qt::ImageConversionFlags flags) override {
    prepare_target();
    target_.drawImage(rect, image, source, flags);
  }
  void drawTextItem(const QPointF& position, const QTextItem& item) override {
    prepare_target();
    target_.setFont(painter()->font());
    target_.setPen(painter()->pen());
    target_.drawTextItem(position, item);
  }

 private:
  // The target drawing in the drawing painter's coordinates (for what passes unchanged).
  void prepare_target() {
    target_.setTransform(painter()->combinedTransform());
    target_.setOpacity(painter()->opacity());
    target_.setRenderHints(painter()->renderHints());
  }

  void draw(const QPainterPath& path, bool fill) {
    const QPainter& source = *painter();
    const QTransform transform = source.combinedTransform();
    const QPen pen = source.pen();
    const QBrush brush = fill ? source.brush() : QBrush();
    QPainterPath clip;
    if (source.hasClipping()) clip = transform.map(source.clipPath());
    const QPainterPath on_device = transform.map(path);
    // The path's own geometry inside the clip's bounding box (half a pixel of slack for a point
    // on the frame): drawn as it is, a stroke along the frame reaching half its pen past it. The
    // clips QCustomPlot sets are rectangles, so their bounding box is the clip.
    const QRectF reach = on_device.boundingRect();
    const bool inside = clip.boundingRect().adjusted(-0.5, -0.5, 0.5, 0.5).contains(reach);
    prepare_target();
    if (!source.hasClipping() || inside) {
      target_.setPen(pen);
      target_.setBrush(brush);
      target_.drawPath(path);
      return;
    }
    target_.setTransform(QTransform());
    if (brush.style() != Qt::NoBrush) target_.fillPath(on_device.intersected(clip), brush);
    if (pen.style() == Qt::NoPen) return;
    QPainterPathStroker stroker(pen);
    QPainterPath outline;
    if (pen.isCosmetic()) {
      stroker.setWidth(std::max(1.0, pen.widthF()));
      outline = stroker.createStroke(on_device);
    } else {
      outline = transform.map(stroker.createStroke(path));
    }
    outline.setFillRule(Qt::WindingFill);
    target_.fillPath(outline.intersected(clip), pen.brush());
  }

  QPainter& target_;
};

ClippingPaintDevice::ClippingPaintDevice(QPainter& target, QSize size)
    : engine_(std::make_unique<ClippingPaintEngine>(target)), target_(target), size_(size) {}

ClippingPaintDevice::~ClippingPaintDevice() = default;

QPaintEngine* ClippingPaintDevice::paintEngine() const { return engine_.get(); }

int ClippingPaintDevice::metric(PaintDeviceMetric metric) const {
  const QPaintDevice* device = target_.device();
  switch (metric) {
    case PdmWidth:
      return size_.width();
    case PdmHeight:
      return size_.height();
    case PdmWidthMM:
      return qRound(size_.width() * 25.4 / device->logicalDpiX());
    case PdmHeightMM:
      return qRound(size_.height() * 25.4 / device->logicalDpiY());
    case PdmDpiX:
    case PdmPhysicalDpiX:
      return device->logicalDpiX();
    case PdmDpiY:
    case PdmPhysicalDpiY:
      return device->logicalDpiY();
    case PdmDevicePixelRatio:
      return 1;
    case PdmDevicePixelRatioScaled:
      return qRound(devicePixelRatioFScale());
    case PdmDepth:
      return 32;
    case PdmNumColors:
      return 0x7fffffff;
    default:
      return QPaintDevice::metric(metric);
  }
}

}  // namespace oscilab::ui
