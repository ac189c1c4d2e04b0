// GUI test of the Live tab's "JACK (sound card)" source under the offscreen platform, against a
// real jackd (dummy backend) with a test client playing two sines: the port choice lists the
// server's capture ports, the source starts from the controls, the level meters show each
// channel's peak in % of full scale, errors are shown and never thrown, and the settings keep
// the JACK fields in the session.
#include <filesystem>

#include <unistd.h>

#include <QComboBox>
#include <QProgressBar>
#include <QTest>

#include "analysis/common/input_error.h"
#include "daq/sources/jack_source.h"
#include "tests/daq/sources/jack_test_helpers.h"
#include "ui/live/live_monitor.h"
#include "ui/live/live_source_controls.h"

using oscilab::ui::LiveMonitor;
using oscilab::ui::LiveSettings;
using oscilab::ui::LiveSourceKind;
namespace jt = oscilab::daq::testing;

class LiveJackTest : public QObject {
  Q_OBJECT

 private Q_SLOTS:
  void listsPortsStartsAndMetersThePeaks() {
    jt::JackTestServer server;
    jt::JackTestPlayer player(server.name(), 2);
    player.play_sines({{0.5, 9.0, 0.0}, {0.25, 9.0, 1.0}});  // peaks: 50 % and 25 %
    const std::filesystem::path calibration =
        std::filesystem::temp_directory_path() /
        ("oscilab_live_jack_" + std::to_string(::getpid()) + ".json");
    oscilab::daq::write_sidecar(jt::calibration(), calibration.string());

    LiveMonitor monitor;
    monitor.resize(1400, 900);
    monitor.show();
    LiveSettings s;
    s.source = LiveSourceKind::Jack;
    s.jack_server = server.name();
    s.jack_calibration = calibration.string();
    monitor.set_settings(s);
    QVERIFY(monitor.list_jack_ports());
    QComboBox* base = monitor.source_controls()->jack_port_box(0);
    QVERIFY(base->findText("system:capture_1") >= 0);
    QVERIFY(base->findText(QString::fromStdString(player.port(0))) >= 0);
    base->setCurrentText(QString::fromStdString(player.port(0)));
    monitor.source_controls()->jack_port_box(1)->setCurrentText(
        QString::fromStdString(player.port(1)));
    QVERIFY2(monitor.start(), qPrintable(monitor.message()));
    QVERIFY(monitor.jack() != nullptr);
    // The guards (a minute) only turn a hang into a failure; a loaded machine is slow, no error.
    QVERIFY2(
        QTest::qWaitFor([&] { return monitor.jack()->counters().samples_delivered > 512; }, 60000),
        "the JACK source never delivered 512 samples");
    // The peak of a sine of 0.5 of full scale is 50 %; ±2 % for a period's sampling of the peak.
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(monitor.source_controls()->jack_meter(0)->value() - 50) <= 2,
                             60000);
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(monitor.source_controls()->jack_meter(1)->value() - 25) <= 2,
                             60000);
    monitor.stop();
    QVERIFY(!monitor.running());

    // The settings keep the JACK fields.
    const LiveSettings back = LiveSettings::from_json(monitor.settings().to_json());
    QCOMPARE(back.source, LiveSourceKind::Jack);
    QCOMPARE(back.jack_server, server.name());
    QCOMPARE(back.jack_base_port, player.port(0));
    QCOMPARE(back.jack_mass_port, player.port(1));
    QCOMPARE(back.jack_calibration, calibration.string());
    std::filesystem::remove(calibration);
  }

  void showsErrorsInsteadOfThrowing() {
    LiveMonitor monitor;
    LiveSettings s;
    s.source = LiveSourceKind::Jack;
    s.jack_server = "oscilab-no-such-server";
    monitor.set_settings(s);
    QVERIFY(!monitor.list_jack_ports());
    QVERIFY(monitor.message().contains("\"oscilab-no-such-server\" is not running"));
    QVERIFY(!monitor.start());  // no calibration chosen
    QVERIFY(monitor.message().contains("calibration"));
    s.jack_calibration = "/nonexistent/cal.json";
    monitor.set_settings(s);
    QVERIFY(!monitor.start());
    QVERIFY(monitor.message().contains("/nonexistent/cal.json"));
    bool threw = false;
    try {
      LiveSettings::from_json({{"source", "jack"}, {"jack", {{"server", 3}}}});
    } catch (const oscilab::InputError& error) {
      threw = std::string(error.what()) == "live.jack.server: expected a string, got 3";
    }
    QVERIFY(threw);
  }
};

QTEST_MAIN(LiveJackTest)
#include "live_jack_test.moc"
