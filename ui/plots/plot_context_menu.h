#pragma once

#include <QObject>
#include <QPointer>
#include <QString>

class QCustomPlot;
class QMenu;
class QWidget;

namespace oscilab::ui {

/// A right-click menu with "Export plot…" on every QCustomPlot of the application: an
/// event filter on the application object sees the context-menu request of any plot, wherever
/// it sits (the review, the fit panel, dialogs, pages added later), unless the plot has a
/// context-menu policy of its own (anything but Qt::DefaultContextMenu). It also remembers the
/// plot the mouse was over last, for File ▸ Export ▸ Plot. One per application; the filter goes
/// with the object. UI thread only.
class PlotContextMenus : public QObject {
  Q_OBJECT

 public:
  explicit PlotContextMenus(QObject* parent = nullptr);
  ~PlotContextMenus() override;

  /// The plot the mouse entered last, while it still exists (visible or not).
  QCustomPlot* last_hovered() const;
  /// The menu shown for `plot` (deleted when closed): "Export plot…".
  static QMenu* make_menu(QCustomPlot* plot);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  QPointer<QWidget> last_hovered_;  // a QCustomPlot
};

/// Asks for a file name (PNG, SVG or PDF, by its extension) and exports `plot` there at its size
/// on screen (ui/plots/plot_export.h). A failure is shown in a message box, never thrown. Returns
/// the error message: empty when written or when the user cancelled.
QString export_plot_interactively(QCustomPlot& plot, QWidget* parent);

}  // namespace oscilab::ui
