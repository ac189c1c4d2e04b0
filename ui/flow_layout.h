#pragma once

#include <vector>

#include <QLayout>

namespace oscilab::ui {

/// Lays its items out left to right at their size hints and wraps to a new row when the next one
/// would not fit, like words in a paragraph: a strip of figures stays readable from a narrow
/// laptop window to a wide screen instead of overprinting or forcing the window wider. Its height
/// follows its width (heightForWidth).
class FlowLayout : public QLayout {
 public:
  explicit FlowLayout(QWidget* parent = nullptr, int horizontal_spacing = 6,
                      int vertical_spacing = 2);
  ~FlowLayout() override;

  void addItem(QLayoutItem* item) override;
  int count() const override;
  QLayoutItem* itemAt(int index) const override;
  QLayoutItem* takeAt(int index) override;
  Qt::Orientations expandingDirections() const override;
  bool hasHeightForWidth() const override;
  int heightForWidth(int width) const override;
  QSize minimumSize() const override;
  QSize sizeHint() const override;
  void setGeometry(const QRect& rect) override;

 private:
  // Places the items in `rect` (or only measures, when `apply` is false); returns the height used.
  int arrange(const QRect& rect, bool apply) const;

  std::vector<QLayoutItem*> items_;
  int horizontal_spacing_;
  int vertical_spacing_;
};

}  // namespace oscilab::ui
