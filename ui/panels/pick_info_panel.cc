#include "ui/panels/pick_info_panel.h"

#include <QHeaderView>
#include <QLabel>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace hull::ui {

PickInfoPanel::PickInfoPanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("pickInfoPanel"));
  auto* layout = new QVBoxLayout(this);
  title_ = new QLabel(this);
  title_->setObjectName(QStringLiteral("pickTitle"));
  title_->setWordWrap(true);
  QFont bold = title_->font();
  bold.setBold(true);
  title_->setFont(bold);
  layout->addWidget(title_);
  rows_ = new QTreeWidget(this);
  rows_->setColumnCount(2);
  rows_->setHeaderLabels({QStringLiteral("Property"), QStringLiteral("Value")});
  rows_->setRootIsDecorated(false);
  rows_->setSelectionMode(QAbstractItemView::NoSelection);
  rows_->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  layout->addWidget(rows_, 1);
  layout->addStretch(0);  // keeps the title at the top while there are no rows
  Clear();
}

void PickInfoPanel::Show(const PickInfo& info) {
  if (info.kind == PickKind::kNone) {
    Clear();
    return;
  }
  info_ = info;
  title_->setText(info.title);
  rows_->clear();
  for (const auto& row : info.rows) rows_->addTopLevelItem(new QTreeWidgetItem({row.first, row.second}));
  rows_->setVisible(true);
}

void PickInfoPanel::Clear() {
  Clear(QStringLiteral(
      "Click a landmark, a keyframe on the trajectory, an object outline or a surface in the 3-D view."));
}

void PickInfoPanel::Clear(const QString& why) {
  info_ = PickInfo();
  title_->setText(why);
  rows_->clear();
  rows_->setVisible(false);
}

QString PickInfoPanel::title() const { return title_->text(); }

QStringList PickInfoPanel::rowsText() const {
  QStringList out;
  for (int i = 0; i < rows_->topLevelItemCount(); ++i) {
    out << rows_->topLevelItem(i)->text(0) + QStringLiteral(": ") + rows_->topLevelItem(i)->text(1);
  }
  return out;
}

}  // namespace hull::ui
