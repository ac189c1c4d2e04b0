// GUI tests of the record view and the main window, driving the real widgets with synthetic
// mouse events. Run under QT_QPA_PLATFORM=offscreen (set by ctest).
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QProgressDialog>
#include <QPushButton>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTest>
#include <QTimer>
#include <QWheelEvent>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "daq/recording/opened_recording.h"
#include "ui/main_window.h"
#include "ui/review/record_view.h"

using oscilab::daq::ChannelRole;
using oscilab::daq::Quantity;
using oscilab::daq::Recording;
using oscilab::ui::MainWindow;
using oscilab::ui::RecordView;

namespace {

constexpr double kRateHz = 512.0;    // the rig's rate
constexpr double kDurationS = 10.0;  // 5120 samples
constexpr double kFreqHz = 9.0;      // excitation frequency of the paper's tests
constexpr double kAccAmp = 2.5;      // m/s²
constexpr double kDispAmp = 0.004;   // m: shown in mm
constexpr double kDispPhase = std::numbers::pi / 6;

double base_acc(double t_s) { return kAccAmp * std::sin(2 * std::numbers::pi * kFreqHz * t_s); }
double mass_disp(double t_s) {
  return kDispAmp * std::sin(2 * std::numbers::pi * kFreqHz * t_s + kDispPhase);
}

// Strings are moved in rather than assigned from literals: GCC 12 at -O3 warns falsely
// (-Wrestrict, GCC bug 105651) on short literal assignments to std::string.
oscilab::daq::ChannelInfo channel(std::string name, ChannelRole role, Quantity quantity,
                                  std::string unit, std::string sensor) {
  oscilab::daq::ChannelInfo info;
  info.name = std::move(name);
  info.role = role;
  info.quantity = quantity;
  info.unit = std::move(unit);
  info.sensor = std::move(sensor);
  return info;
}

// Two channels as the rig records them: base acceleration (m/s²) and mass displacement (m).
std::shared_ptr<Recording> sine_recording(double duration_s = kDurationS) {
  auto recording = std::make_shared<Recording>();
  recording->sidecar.sample_rate_hz = kRateHz;
  recording->sidecar.channels = {
      channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2", "accelerometer"),
      channel("y", ChannelRole::Mass, Quantity::Displacement, "m", "laser vibrometer")};
  const auto samples = Eigen::Index(std::lround(duration_s * kRateHz));
  recording->samples_si.resize(samples, 2);
  for (Eigen::Index i = 0; i < samples; ++i) {
    const double t_s = double(i) / kRateHz;
    recording->samples_si(i, 0) = base_acc(t_s);
    recording->samples_si(i, 1) = mass_disp(t_s);
  }
  return recording;
}

// A recording made in memory, held as the window holds what it opens.
std::shared_ptr<const oscilab::daq::OpenedRecording> held(const std::shared_ptr<Recording>& r) {
  return std::make_shared<const oscilab::daq::OpenedRecording>(oscilab::daq::hold_recording(*r));
}

QCPRange time_range(RecordView& view, int channel) {
  return view.channel_rect(channel)->axis(QCPAxis::atBottom)->range();
}

void send_mouse(QWidget* widget, QEvent::Type type, QPointF pos, Qt::MouseButtons buttons,
                Qt::MouseButton button = Qt::NoButton) {
  QMouseEvent event(type, pos, widget->mapToGlobal(pos), button, buttons, Qt::NoModifier);
  QApplication::sendEvent(widget, &event);
}

// A loader that takes `steps` × 50 ms, reporting its progress and polling its token at each
// step as the file loader does at each window of samples.
MainWindow::Loader slow_loader(const Recording& recording, int steps) {
  return [recording, steps](const std::string& path, const oscilab::daq::OpeningControl& control) {
    for (int step = 0; step < steps; ++step) {
      if (control.cancel.cancelled()) throw oscilab::daq::OpeningCancelled();
      control.progress(double(step) / steps);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    Recording read = recording;
    read.source_path = path;
    return oscilab::daq::hold_recording(std::move(read));
  };
}

}  // namespace

class RecordViewTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void init() {
    window_ = std::make_unique<MainWindow>();
    window_->set_interactive_errors(false);
    window_->resize(1000, 700);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    recording_ = sine_recording();
    window_->show_recording(held(recording_));
    QApplication::processEvents();
  }
  void cleanup() { window_.reset(); }

  void plots_one_axis_rect_per_channel_over_a_shared_time_axis() {
    RecordView& view = *window_->record_view();
    QCustomPlot* plot = view.plot();
    QCOMPARE(plot->axisRectCount(), 2);
    QCOMPARE(plot->graphCount(), 2);
    const int samples = int(recording_->sample_count());
    const double last_s = (samples - 1) / kRateHz;
    for (int c = 0; c < 2; ++c) {
      QCPGraph* graph = view.channel_graph(c);
      QVERIFY(graph != nullptr);
      QCOMPARE(graph->keyAxis(), view.channel_rect(c)->axis(QCPAxis::atBottom));
      QCOMPARE(graph->data()->size(), samples);
      QCOMPARE(graph->data()->constBegin()->key, 0.0);
      QCOMPARE((graph->data()->constEnd() - 1)->key, last_s);
      QVERIFY(graph->adaptiveSampling());
      // Fitted: the whole record on the time axis.
      QCOMPARE(time_range(view, c).lower, 0.0);
      QCOMPARE(time_range(view, c).upper, last_s);
    }
    // Only the bottom plot labels the shared time axis.
    QVERIFY(!view.channel_rect(0)->axis(QCPAxis::atBottom)->tickLabels());
    QVERIFY(view.channel_rect(1)->axis(QCPAxis::atBottom)->tickLabels());
    QCOMPARE(view.channel_rect(1)->axis(QCPAxis::atBottom)->label(), QString("time [s]"));
  }

  void shows_values_in_si_prefixed_display_units() {
    RecordView& view = *window_->record_view();
    QCOMPARE(view.channel_rect(0)->axis(QCPAxis::atLeft)->label(), QString("base_acc [m/s²]"));
    QCOMPARE(view.channel_rect(1)->axis(QCPAxis::atLeft)->label(), QString("y [mm]"));
    QVERIFY(view.channel_graph(0)->name().contains("accelerometer"));
    QVERIFY(view.channel_graph(1)->name().contains("laser vibrometer"));
    // Each plot is titled with its channel and sensor.
    auto* title = qobject_cast<QCPTextElement*>(view.plot()->plotLayout()->element(2, 0));
    QVERIFY(title != nullptr);
    QCOMPARE(title->text(), QString("y \u2014 laser vibrometer (mass)"));
    // Every point: acceleration as it is, displacement ×1000 (m → mm), against the closed form.
    auto acc = view.channel_graph(0)->data()->constBegin();
    auto disp = view.channel_graph(1)->data()->constBegin();
    double max_disp_mm = 0.0;
    for (int i = 0; i < int(recording_->sample_count()); ++i, ++acc, ++disp) {
      const double t_s = i / kRateHz;
      QVERIFY(std::abs(acc->value - base_acc(t_s)) < 1e-12);
      QVERIFY(std::abs(disp->value - 1e3 * mass_disp(t_s)) < 1e-12);
      max_disp_mm = std::max(max_disp_mm, std::abs(disp->value));
    }
    // 4 mm amplitude; 512 Hz samples a 9 Hz sine within 0.1 % of its peak.
    QVERIFY(std::abs(max_disp_mm - 4.0) < 4e-3);
    // Value axes fitted around the data.
    const QCPRange y_range = view.channel_rect(1)->axis(QCPAxis::atLeft)->range();
    QVERIFY(y_range.lower < -3.99 && y_range.lower > -4.5);
    QVERIFY(y_range.upper > 3.99 && y_range.upper < 4.5);
  }

  void wheel_zoom_and_drag_pan_move_all_time_axes_together() {
    RecordView& view = *window_->record_view();
    QCustomPlot* plot = view.plot();
    const QCPRange full = time_range(view, 0);
    const QPointF centre = view.channel_rect(0)->rect().center();

    QWheelEvent wheel(centre, plot->mapToGlobal(centre), QPoint(), QPoint(0, 120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(plot, &wheel);
    const QCPRange zoomed = time_range(view, 0);
    QVERIFY(zoomed.size() < 0.9 * full.size());  // one wheel step zooms by 0.85
    QCOMPARE(time_range(view, 1), zoomed);       // linked

    const QPointF from = view.channel_rect(1)->rect().center();
    const QPointF to = from - QPointF(100, 0);
    send_mouse(plot, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    send_mouse(plot, QEvent::MouseMove, to, Qt::LeftButton);
    send_mouse(plot, QEvent::MouseButtonRelease, to, Qt::NoButton, Qt::LeftButton);
    const QCPRange panned = time_range(view, 1);
    QVERIFY(panned.lower > zoomed.lower);  // dragging left shows later times
    QVERIFY(std::abs(panned.size() - zoomed.size()) < 1e-9 * full.size());
    QCOMPARE(time_range(view, 0), panned);

    // Zooming out far stops at the whole record.
    QWheelEvent out(centre, plot->mapToGlobal(centre), QPoint(), QPoint(0, -120 * 20), Qt::NoButton,
                    Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(plot, &out);
    QCOMPARE(time_range(view, 0), full);
    QCOMPARE(time_range(view, 1), full);
  }

  void double_click_and_fit_action_show_the_whole_record() {
    RecordView& view = *window_->record_view();
    const QCPRange full = time_range(view, 0);
    view.set_time_window(2.0, 3.0);
    QCOMPARE(time_range(view, 1), QCPRange(2.0, 3.0));
    const QPointF centre = view.channel_rect(0)->rect().center();
    send_mouse(view.plot(), QEvent::MouseButtonDblClick, centre, Qt::LeftButton, Qt::LeftButton);
    QCOMPARE(time_range(view, 0), full);
    QCOMPARE(time_range(view, 1), full);

    view.set_time_window(2.0, 3.0);
    window_->fit_action()->trigger();
    QCOMPARE(time_range(view, 1), full);
  }

  void value_axes_follow_the_data_in_the_time_window() {
    // base_acc at a tenth of its amplitude (0.25 m/s²) in the first half of the record.
    auto quiet_start = sine_recording();
    quiet_start->samples_si.topRows(quiet_start->sample_count() / 2).col(0) *= 0.1;
    window_->show_recording(held(quiet_start));
    RecordView& view = *window_->record_view();
    QCPAxis* acc_axis = view.channel_rect(0)->axis(QCPAxis::atLeft);
    // Whole record: ±2.5 m/s² and a 5 % margin.
    QVERIFY(std::abs(acc_axis->range().upper - 2.5 * 1.1) < 1e-2);
    view.set_time_window(1.0, 2.0);
    QVERIFY(std::abs(acc_axis->range().upper - 0.25 * 1.1) < 1e-3);
    QVERIFY(std::abs(acc_axis->range().lower + 0.25 * 1.1) < 1e-3);
    // Off: the whole record's range again, whatever the window.
    QVERIFY(window_->auto_value_range_action()->isChecked());
    window_->auto_value_range_action()->trigger();
    QVERIFY(!view.auto_value_range());
    QVERIFY(std::abs(acc_axis->range().upper - 2.5 * 1.1) < 1e-2);
    view.set_time_window(2.0, 3.0);
    QVERIFY(std::abs(acc_axis->range().upper - 2.5 * 1.1) < 1e-2);
  }

  void cursor_reads_every_channel_at_the_time_under_the_mouse() {
    RecordView& view = *window_->record_view();
    QSignalSpy readouts(&view, &RecordView::cursor_text_changed);
    // At t = 0.25 s: base_acc = 2.5 sin(4.5π) = 2.5 m/s², y = 4 sin(4.5π + π/6) = 2√3 mm.
    view.set_cursor_time(0.25 + 0.3 / kRateHz);  // snaps to the sample at 0.25 s
    const QString text = view.cursor_text();
    // Each value to 4 significant digits of its channel's largest value; spaces aside.
    QCOMPARE(text.simplified(), QString("t = 0.250 s base_acc = 2.500 m/s² y = 3.464 mm"));
    QCOMPARE(readouts.count(), 1);
    QCOMPARE(readouts.front().front().toString(), text);

    // The cursor line stands at that time on every plot.
    int lines = 0;
    for (int i = 0; i < view.plot()->itemCount(); ++i) {
      if (auto* line = qobject_cast<QCPItemStraightLine*>(view.plot()->item(i))) {
        QVERIFY(line->visible());
        QCOMPARE(line->point1->coords().x(), 0.25);
        ++lines;
      }
    }
    QCOMPARE(lines, 2);

    // The mouse does the same: zoom so that one pixel is far below a sample period.
    view.set_time_window(1.2, 1.3);
    QCPAxis* time_axis = view.channel_rect(1)->axis(QCPAxis::atBottom);
    const QPointF over(time_axis->coordToPixel(1.25), view.channel_rect(1)->rect().center().y());
    send_mouse(view.plot(), QEvent::MouseMove, over, Qt::NoButton);
    const QString moved = view.cursor_text().simplified();
    QVERIFY2(moved.startsWith("t = 1.250 s"), qPrintable(moved));
    QVERIFY2(moved.contains(QString("base_acc = %1 m/s²").arg(base_acc(1.25), 0, 'f', 3)),
             qPrintable(moved));
  }

  void replaces_the_plots_when_another_recording_is_shown() {
    auto three = sine_recording(1.0);
    three->sidecar.channels.push_back(channel("f", ChannelRole::Force, Quantity::Force, "N", ""));
    three->samples_si.conservativeResize(Eigen::NoChange, 3);
    three->samples_si.col(2).setConstant(0.2);  // N: shown in mN
    window_->show_recording(held(three));
    RecordView& view = *window_->record_view();
    QCOMPARE(view.plot()->axisRectCount(), 3);
    QCOMPARE(view.plot()->graphCount(), 3);
    QCOMPARE(view.channel_graph(2)->data()->size(), 512);
    QCOMPARE(view.channel_rect(2)->axis(QCPAxis::atLeft)->label(), QString("f [mN]"));
    QCOMPARE(view.channel_graph(2)->data()->constBegin()->value, 200.0);
  }

  void a_recording_without_channels_or_rate_shows_no_plot_and_does_not_crash() {
    auto empty = std::make_shared<Recording>();
    window_->show_recording(held(empty));
    RecordView& view = *window_->record_view();
    QCOMPARE(view.plot()->axisRectCount(), 0);
    view.set_cursor_time(1.0);
    view.fit();
    QVERIFY(view.cursor_text().isEmpty());
    auto no_rate = sine_recording(1.0);
    no_rate->sidecar.sample_rate_hz = 0.0;
    window_->show_recording(held(no_rate));
    QCOMPARE(view.plot()->axisRectCount(), 0);
  }

  void draws_a_record_of_up_to_kRawSamples_from_its_samples() {
    // 262 s at 512 Hz: the length of the paper's stepped-sine tests, 134 144 samples a channel.
    auto long_recording = sine_recording(262.0);
    window_->show_recording(held(long_recording));
    RecordView& view = *window_->record_view();
    QCOMPARE(view.channel_graph(0)->data()->size(), 134144);
    QCOMPARE(view.channel_graph(1)->data()->size(), 134144);
    QCOMPARE(time_range(view, 0).upper, 134143 / kRateHz);
    QCOMPARE(view.samples_per_point(), Eigen::Index(1));
  }

  void draws_a_longer_record_from_its_overview_and_its_samples_when_zoomed_in() {
    // 70 min: 2 150 400 samples a channel, eight times what is drawn from the samples.
    auto hour = sine_recording(4200.0);
    const Eigen::Index n = hour->sample_count();
    // The amplitude of base_acc grows with t, so that each stretch has its own extremes.
    for (Eigen::Index i = 0; i < n; ++i) hour->samples_si(i, 0) *= 1.0 + double(i) / double(n);
    window_->show_recording(held(hour));
    RecordView& view = *window_->record_view();
    const int width_px = std::max(view.channel_rect(0)->width(), 800);
    // Whole record: at most kBucketsPerPixel buckets a pixel over the window, the window on
    // either side clipped to the record; each pair of points the least and the greatest
    // sample of its bucket, the second method taking them one by one.
    const auto check_envelope = [&](Eigen::Index max_points) {
      const Eigen::Index size = view.samples_per_point();
      QVERIFY(size > 1);
      const auto* data = view.channel_graph(0)->data().data();
      QVERIFY(data->size() % 2 == 0);
      QVERIFY(data->size() <= max_points);
      for (auto it = data->constBegin(); it != data->constEnd(); it += 2) {
        const auto b0 = Eigen::Index(std::lround(it->key * kRateHz));
        QCOMPARE(b0 % size, Eigen::Index(0));
        const Eigen::Index count = std::min(size, n - b0);
        QCOMPARE(Eigen::Index(std::lround((it + 1)->key * kRateHz)), b0 + count - 1);
        const auto bucket = hour->samples_si.col(0).segment(b0, count);
        QCOMPARE(it->value, bucket.minCoeff());
        QCOMPARE((it + 1)->value, bucket.maxCoeff());
      }
    };
    check_envelope(2 * (RecordView::kBucketsPerPixel * width_px + 1));
    // 20 min (614 400 samples): a finer level, over the window and one on either side.
    view.set_time_window(1800.0, 3000.0);
    check_envelope(2 * (3 * RecordView::kBucketsPerPixel * width_px + 2));
    QVERIFY(view.samples_per_point() < 2 * 4096);
    // A jump to 100 s: the samples themselves, the window and one on either side.
    view.set_time_window(2000.0, 2100.0);
    QCOMPARE(view.samples_per_point(), Eigen::Index(1));
    const auto* data = view.channel_graph(0)->data().data();
    const Eigen::Index window_samples = Eigen::Index(100.0 * kRateHz) + 1;
    QCOMPARE(Eigen::Index(data->size()), 3 * window_samples);
    for (auto it = data->constBegin(); it != data->constEnd(); ++it) {
      const auto i = Eigen::Index(std::lround(it->key * kRateHz));
      QCOMPARE(it->value, hour->samples_si(i, 0));
    }
    // Value axes on the whole record's range while zoomed in: from the overview, exact here
    // (its buckets cover the whole record), with the 5 % margin.
    view.set_auto_value_range(false);
    const double lo = hour->samples_si.col(0).minCoeff(), hi = hour->samples_si.col(0).maxCoeff();
    const QCPRange axis = view.channel_rect(0)->axis(QCPAxis::atLeft)->range();
    QVERIFY(std::abs(axis.upper - (hi + 0.05 * (hi - lo))) < 1e-12 * hi);
    QVERIFY(std::abs(axis.lower - (lo - 0.05 * (hi - lo))) < 1e-12 * hi);
    view.set_auto_value_range(true);
    // A pan within what was read reads nothing again.
    const QCPGraphData* before = &*data->constBegin();
    view.set_time_window(2050.0, 2150.0);
    QCOMPARE(&*view.channel_graph(0)->data()->constBegin(), before);
    // A pan past it reads what a pan reaches: kRawSamples around the window.
    view.set_time_window(2150.0, 2250.0);
    QCOMPARE(Eigen::Index(view.channel_graph(0)->data()->size()), RecordView::kRawSamples - 1);
  }

  void opens_a_sound_file_with_its_samples_left_in_it() {
    // What File ▸ Open does: the samples stay in the file and the curves are the samples
    // read_recording gives.
    const QString path = QDir::temp().filePath("oscilab-record-view-open.flac");
    auto made = sine_recording(20.0);
    made->sidecar.channels[0].scale = 1e-6;  // 24-bit FLAC: µm/s² steps
    made->sidecar.channels[1].scale = 1e-9;
    oscilab::daq::write_recording(*made, path.toStdString());
    QVERIFY(window_->open_recording(path));
    const Recording whole = oscilab::daq::read_recording(path.toStdString());
    RecordView& view = *window_->record_view();
    QCOMPARE(view.samples_per_point(), Eigen::Index(1));
    const auto* data = view.channel_graph(1)->data().data();
    QCOMPARE(Eigen::Index(data->size()), whole.sample_count());
    Eigen::Index i = 0;
    for (auto it = data->constBegin(); it != data->constEnd(); ++it, ++i) {
      QVERIFY(std::abs(it->value - 1e3 * whole.samples_si(i, 1)) < 1e-12);  // shown in mm
    }
    QFile::remove(path);
    QFile::remove(QString::fromStdString(oscilab::daq::sidecar_path_for(path.toStdString())));
  }

  void a_missing_file_is_reported_and_the_window_stays_usable() {
    QSignalSpy errors(window_.get(), &MainWindow::error_reported);
    const QString title = window_->windowTitle();
    const QString missing = QDir::temp().filePath("oscilab-no-such-recording.wav");
    QVERIFY(!window_->open_recording(missing));
    QCOMPARE(errors.count(), 1);
    const QString message = errors.front().front().toString();
    QVERIFY2(message.contains("oscilab-no-such-recording"), qPrintable(message));
    QVERIFY(window_->statusBar()->currentMessage().contains(message));
    // The recording shown before is still there and still works.
    QCOMPARE(window_->windowTitle(), title);
    QCOMPARE(window_->record_view()->plot()->axisRectCount(), 2);
    window_->record_view()->set_cursor_time(0.25);
    QVERIFY(window_->record_view()->cursor_text().simplified().contains("base_acc = 2.500 m/s²"));
  }

  void any_loader_exception_is_reported_not_thrown() {
    MainWindow window(nullptr,
                      [](const std::string& path,
                         const oscilab::daq::OpeningControl&) -> oscilab::daq::OpenedRecording {
                        if (path == "bad.wav")
                          throw oscilab::InputError("bad.wav.json: channels[1].unit: unknown");
                        throw std::runtime_error("disk on fire");
                      });
    window.set_interactive_errors(false);
    QSignalSpy errors(&window, &MainWindow::error_reported);
    QVERIFY(!window.open_recording("bad.wav"));
    QVERIFY(!window.open_recording("other.wav"));
    QCOMPARE(errors.count(), 2);
    QCOMPARE(errors[0].front().toString(), QString("bad.wav.json: channels[1].unit: unknown"));
    QVERIFY(errors[1].front().toString().contains("other.wav"));
    QVERIFY(errors[1].front().toString().contains("disk on fire"));
  }

  void opening_a_file_shows_it_and_names_it_in_the_title() {
    const Recording recording = *sine_recording(1.0);
    MainWindow window(nullptr,
                      [recording](const std::string& path, const oscilab::daq::OpeningControl&) {
                        Recording read = recording;
                        read.source_path = path;
                        return oscilab::daq::hold_recording(std::move(read));
                      });
    QSignalSpy opened(&window, &MainWindow::recording_opened);
    QVERIFY(window.open_recording("/data/run1.wav"));
    QCOMPARE(opened.count(), 1);
    QVERIFY(window.windowTitle().startsWith("run1.wav"));
    QVERIFY(window.statusBar()->currentMessage().contains("2 channels, 512 Hz, 1.00 s"));
    QCOMPARE(window.record_view()->channel_graph(0)->data()->size(), 512);
  }

  void a_long_opening_keeps_the_window_alive_and_shows_its_progress() {
    MainWindow window(nullptr, slow_loader(*sine_recording(1.0), 24));  // 1.2 s
    // A timer every 20 ms: a UI thread blocked for the opening would fire it once after; one
    // that keeps its event loop running fires it about 60 times (a loaded machine fewer).
    int ticks = 0;
    QTimer ticker;
    QObject::connect(&ticker, &QTimer::timeout, [&ticks] { ++ticks; });
    ticker.start(20);
    // Past the 400 ms delay the progress dialog is up, part of the way.
    bool shown = false;
    int value = -1;
    QTimer::singleShot(900, &window, [&] {
      if (auto* dialog = window.findChild<QProgressDialog*>("opening_progress")) {
        shown = dialog->isVisible();
        value = dialog->value();
      }
    });
    QElapsedTimer clock;
    clock.start();
    QVERIFY(window.open_recording("/data/long.wav"));
    QVERIFY(clock.elapsed() >= 1200);
    QVERIFY2(ticks >= 10, qPrintable(QString::number(ticks)));
    QVERIFY(shown);
    QVERIFY2(value > 0 && value < 1000, qPrintable(QString::number(value)));
    QCOMPARE(window.opened_paths().size(), 1);
    QVERIFY(window.findChild<QProgressDialog*>("opening_progress") == nullptr);
  }

  void a_cancelled_opening_opens_nothing_and_says_so() {
    MainWindow window(nullptr, slow_loader(*sine_recording(1.0), 400));  // 20 s unless cancelled
    window.set_interactive_errors(false);
    QSignalSpy errors(&window, &MainWindow::error_reported);
    QSignalSpy opened(&window, &MainWindow::recording_opened);
    bool clicked = false;
    QTimer::singleShot(700, &window, [&] {
      auto* dialog = window.findChild<QProgressDialog*>("opening_progress");
      auto* cancel = dialog ? dialog->findChild<QPushButton*>() : nullptr;
      if (cancel) {
        cancel->click();  // as the person at the laptop would
        clicked = true;
      }
    });
    QElapsedTimer clock;
    clock.start();
    QVERIFY(!window.open_recording("/data/long.wav"));
    QVERIFY(clicked);
    QVERIFY2(clock.elapsed() < 5000, qPrintable(QString::number(clock.elapsed())));
    QCOMPARE(errors.count(), 0);  // a cancel is not an error: no message box
    QCOMPARE(opened.count(), 0);
    QVERIFY(window.opened_paths().isEmpty());
    QCOMPARE(window.statusBar()->currentMessage(), QString("/data/long.wav: opening cancelled"));
  }

  void file_menu_has_open_and_quit() {
    QCOMPARE(window_->open_action()->shortcut(), QKeySequence(QKeySequence::Open));
    QCOMPARE(window_->quit_action()->shortcut(), QKeySequence(QKeySequence::Quit));
    window_->quit_action()->trigger();
    QVERIFY(!window_->isVisible());
  }

 private:
  std::unique_ptr<MainWindow> window_;
  std::shared_ptr<Recording> recording_;
};

QTEST_MAIN(RecordViewTest)
#include "record_view_test.moc"
