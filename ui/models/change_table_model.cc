#include "ui/models/change_table_model.h"

#include <QColor>
#include <QStringList>

#include "ui/models/objects_table_model.h"

namespace hull::ui {

namespace {

enum Column { kKind, kIdA, kIdB, kHeightA, kHeightB, kChange, kColumns };

QString Millimetres(double m) { return QString::number(m * 1000.0, 'f', 1); }

}  // namespace

std::array<int, 5> CountChanges(const SurveyComparison& comparison) {
  std::array<int, 5> n{};
  for (const ObjectChange& c : comparison.objects) ++n[static_cast<std::size_t>(c.kind)];
  return n;
}

QString ChangeCountsText(const SurveyComparison& comparison) {
  const std::array<int, 5> n = CountChanges(comparison);
  return QStringLiteral("%1 new, %2 grown, %3 shrunk, %4 removed, %5 unchanged")
      .arg(n[static_cast<std::size_t>(ObjectChangeKind::kNew)])
      .arg(n[static_cast<std::size_t>(ObjectChangeKind::kGrown)])
      .arg(n[static_cast<std::size_t>(ObjectChangeKind::kShrunk)])
      .arg(n[static_cast<std::size_t>(ObjectChangeKind::kRemoved)])
      .arg(n[static_cast<std::size_t>(ObjectChangeKind::kUnchanged)]);
}

ChangeTableModel::ChangeTableModel(QObject* parent) : QAbstractTableModel(parent) {}

void ChangeTableModel::SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison) {
  beginResetModel();
  comparison_ = std::move(comparison);
  endResetModel();
}

int ChangeTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() || !comparison_ ? 0 : static_cast<int>(comparison_->comparison.objects.size());
}

int ChangeTableModel::columnCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : kColumns; }

QVariant ChangeTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
  static const QStringList headers = {QStringLiteral("Change"),        QStringLiteral("Survey A"),
                                      QStringLiteral("Survey B"),      QStringLiteral("Height A (mm)"),
                                      QStringLiteral("Height B (mm)"), QStringLiteral("Height change (mm)")};
  return headers.value(section);
}

QVariant ChangeTableModel::data(const QModelIndex& index, int role) const {
  if (!comparison_ || !index.isValid()) return {};
  const ObjectChange& c = comparison_->comparison.objects[static_cast<std::size_t>(index.row())];
  if (role == kIndexRole) return index.row();
  if (role == Qt::TextAlignmentRole) {
    return index.column() <= kIdB ? int(Qt::AlignLeft | Qt::AlignVCenter) : int(Qt::AlignRight | Qt::AlignVCenter);
  }
  if (role == Qt::ForegroundRole && index.column() == kKind) {
    switch (c.kind) {
      case ObjectChangeKind::kNew:
      case ObjectChangeKind::kGrown:
        return QColor(180, 30, 40);
      case ObjectChangeKind::kRemoved:
      case ObjectChangeKind::kShrunk:
        return QColor(40, 70, 190);
      case ObjectChangeKind::kUnchanged:
        return {};
    }
  }
  if (role != Qt::DisplayRole && role != kSortRole) return {};
  const bool sort = role == kSortRole;
  const bool has_a = !c.id_a.empty(), has_b = !c.id_b.empty();
  // A height read from a map without an object there (below its detection)
  // is shown too; only new / removed have none.
  const bool height_a = c.kind != ObjectChangeKind::kNew, height_b = c.kind != ObjectChangeKind::kRemoved;
  switch (index.column()) {
    case kKind:
      return sort ? QVariant(static_cast<int>(c.kind)) : QVariant(QString::fromLatin1(ObjectChangeKindName(c.kind)));
    case kIdA:
      return has_a ? QString::fromStdString(c.id_a) : QStringLiteral("–");
    case kIdB:
      return has_b ? QString::fromStdString(c.id_b) : QStringLiteral("–");
    case kHeightA:
      if (sort) return c.height_a;
      return height_a ? Millimetres(c.height_a) : QStringLiteral("–");
    case kHeightB:
      if (sort) return c.height_b;
      return height_b ? Millimetres(c.height_b) : QStringLiteral("–");
    case kChange:
      return sort ? QVariant(c.change)
                  : QVariant((c.change >= 0 ? QStringLiteral("+") : QString()) + Millimetres(c.change));
  }
  return {};
}

}  // namespace hull::ui
