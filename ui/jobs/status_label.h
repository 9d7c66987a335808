// A line of the status bar that never hides what it says (issue 25.7): at
// most `max_width` pixels wide (so that one long status cannot push the
// others off a 1920 px bar), elided in the middle when longer, the whole
// text in its tooltip. Used for the results and placement lines and the
// running job's message.
#pragma once

#include <QLabel>

namespace hull::ui {

class StatusLabel : public QLabel {
  Q_OBJECT

 public:
  explicit StatusLabel(int max_width, QWidget* parent = nullptr);

  void SetStatus(const QString& text);  // use this, not setText
  QString fullText() const { return full_; }
  bool elided() const { return text() != full_; }

 private:
  int max_width_;
  QString full_;
};

}  // namespace hull::ui
