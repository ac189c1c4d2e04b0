#pragma once

#include <QObject>
#include <QString>

class QAction;
class QCustomPlot;
class QMenu;

namespace oscilab::ui {

class BackgroundJob;
class MainWindow;
class PlotContextMenus;

/// File ▸ Export of the main window: a plot as PNG, SVG or PDF (the plot under the
/// mouse, else the one the mouse was over last, else the first of the current tab), the level
/// table as CSV, the recording shown as MATLAB .mat or UFF 58, the EDC table of the analysis as
/// .mat; and "Export plot…" in the context menu of every plot (PlotContextMenus). The writing is
/// the libraries' (ui/plots/plot_export.h, daq/export); the recording and EDC files are written on
/// a worker thread. Nothing throws out of a slot: a failure is reported like the window's other
/// errors (status bar, error_reported, a message box when interactive) and by
/// export_finished. UI thread only.
class ExportMenu : public QObject {
  Q_OBJECT

 public:
  /// Adds the "Export" submenu to `file_menu` (at its end) and the plots' context menus.
  ExportMenu(MainWindow* window, QMenu* file_menu);
  ~ExportMenu() override;

  /// The plot "Plot as PNG/SVG/PDF…" exports, or null when no plot is visible.
  QCustomPlot* plot_to_export() const;

  /// The exports without a file dialog (the actions ask for the path, then call these). Each
  /// returns false when it could not start or failed at once; export_finished tells the end.
  bool export_plot(const QString& path);
  bool export_level_table(const QString& path);
  bool export_recording_mat(const QString& path);
  bool export_recording_uff(const QString& path);
  bool export_edc_mat(const QString& path);
  bool busy() const;

  QMenu* menu() const { return menu_; }
  QAction* plot_action() const { return plot_action_; }
  QAction* table_action() const { return table_action_; }
  QAction* mat_action() const { return mat_action_; }
  QAction* uff_action() const { return uff_action_; }
  QAction* edc_mat_action() const { return edc_mat_action_; }

 Q_SIGNALS:
  /// An export ended: `ok`, or the reason in `message` (naming the file).
  void export_finished(const QString& message, bool ok);

 private:
  enum class FileKind { RecordingMat, RecordingUff, EdcMat };
  bool write_file(FileKind kind, const QString& path);
  void succeed(const QString& path);
  bool fail(const QString& message);
  QString ask_path(const QString& title, const QString& name, const QString& filter);

  MainWindow* window_ = nullptr;
  PlotContextMenus* context_menus_ = nullptr;
  BackgroundJob* job_ = nullptr;
  QMenu* menu_ = nullptr;
  QAction* plot_action_ = nullptr;
  QAction* table_action_ = nullptr;
  QAction* mat_action_ = nullptr;
  QAction* uff_action_ = nullptr;
  QAction* edc_mat_action_ = nullptr;
};

}  // namespace oscilab::ui
