#include "ui/panels/survey_summary_panel.h"

#include <QDir>
#include <QFileInfo>
#include <QHeaderView>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "ui/session/session.h"

namespace hull::ui {

namespace {

QTreeWidgetItem* Section(QTreeWidget* tree, const QString& title) {
  auto* item = new QTreeWidgetItem(tree, {title});
  QFont bold = item->font(0);
  bold.setBold(true);
  item->setFont(0, bold);
  item->setFirstColumnSpanned(true);
  item->setExpanded(true);
  return item;
}

void Row(QTreeWidgetItem* section, const QString& label, const QString& value) {
  auto* item = new QTreeWidgetItem(section, {label, value});
  item->setToolTip(1, value);
}

QString Count(std::size_t n) { return QString::number(static_cast<qulonglong>(n)); }

}  // namespace

SurveySummaryPanel::SurveySummaryPanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("surveySummaryPanel"));
  auto* layout = new QVBoxLayout(this);
  tree_ = new QTreeWidget(this);
  tree_->setColumnCount(2);
  tree_->setHeaderHidden(true);
  tree_->setSelectionMode(QAbstractItemView::NoSelection);
  tree_->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  layout->addWidget(tree_);
  Update(Session());
}

void SurveySummaryPanel::Update(const Session& session) {
  tree_->clear();
  QTreeWidgetItem* mesh = Section(tree_, QStringLiteral("Hull model"));
  if (const auto& m = session.mesh()) {
    Row(mesh, QStringLiteral("File"), QFileInfo(m->path).fileName());
    Row(mesh, QStringLiteral("Folder"), QDir::toNativeSeparators(QFileInfo(m->path).absolutePath()));
    Row(mesh, QStringLiteral("Triangles"), Count(m->mesh->num_faces()));
    Row(mesh, QStringLiteral("Vertices"), Count(m->mesh->num_vertices()));
    const Eigen::Vector3d size = m->mesh->Bounds().sizes();
    Row(mesh, QStringLiteral("Extent (M)"),
        QStringLiteral("%1 × %2 × %3 m").arg(size.x(), 0, 'f', 2).arg(size.y(), 0, 'f', 2).arg(size.z(), 0, 'f', 2));
  } else {
    Row(mesh, QStringLiteral("File"), QStringLiteral("none (File ▸ Open mesh…)"));
  }
  QTreeWidgetItem* survey = Section(tree_, QStringLiteral("Survey"));
  if (const auto& s = session.survey()) {
    const SurveyBundle& b = *s->bundle;
    Row(survey, QStringLiteral("Name"), QString::fromStdString(b.manifest.name));
    Row(survey, QStringLiteral("Folder"), QDir::toNativeSeparators(s->path));
    Row(survey, QStringLiteral("Vehicle"), QString::fromStdString(b.manifest.vehicle));
    Row(survey, QStringLiteral("Camera"),
        QStringLiteral("%1, %2 × %3 px")
            .arg(b.manifest.camera.stereo() ? QStringLiteral("stereo") : QStringLiteral("monocular"))
            .arg(b.manifest.camera.width)
            .arg(b.manifest.camera.height));
    Row(survey, QStringLiteral("Keyframes"), Count(b.nav.size()));
    if (!b.nav.empty()) {
      Row(survey, QStringLiteral("Duration"), QStringLiteral("%1 s").arg(b.nav.back().t - b.nav.front().t, 0, 'f', 1));
    }
    Row(survey, QStringLiteral("DVL returns"), Count(s->overlays->dvl_hits.size()));
    Row(survey, QStringLiteral("Feature observations"), Count(b.features.size()));
    Row(survey, QStringLiteral("Landmarks observed"), Count(b.CountLandmarks()));
    Row(survey, QStringLiteral("Landmarks shown"),
        QStringLiteral("%1 (%2)")
            .arg(Count(s->overlays->landmarks.size()))
            .arg(QString::fromLatin1(LandmarkSourceName(s->overlays->landmark_source))));
    Row(survey, QStringLiteral("Ground truth"),
        b.truth ? QStringLiteral("yes: %1 poses, %2 objects")
                      .arg(Count(b.truth->poses.size()))
                      .arg(Count(b.truth->objects.size()))
                : QStringLiteral("no"));
  } else {
    Row(survey, QStringLiteral("Folder"), QStringLiteral("none (File ▸ Open survey…)"));
  }
  QTreeWidgetItem* placement = Section(tree_, QStringLiteral("Model placement"));
  Row(placement, QStringLiteral("x_gM from"), QString::fromUtf8(ModelPlacementLabel(session.placement())));
  const Vector6d x = session.ModelPose().ToVector();
  Row(placement, QStringLiteral("Translation"),
      QStringLiteral("%1, %2, %3 m").arg(x[0], 0, 'f', 3).arg(x[1], 0, 'f', 3).arg(x[2], 0, 'f', 3));
  Row(placement, QStringLiteral("Roll, pitch, yaw"),
      QStringLiteral("%1°, %2°, %3°")
          .arg(x[3] * 180 / M_PI, 0, 'f', 2)
          .arg(x[4] * 180 / M_PI, 0, 'f', 2)
          .arg(x[5] * 180 / M_PI, 0, 'f', 2));
}

QStringList SurveySummaryPanel::rowsText() const {
  QStringList out;
  for (int i = 0; i < tree_->topLevelItemCount(); ++i) {
    const QTreeWidgetItem* section = tree_->topLevelItem(i);
    for (int k = 0; k < section->childCount(); ++k) {
      out << section->text(0) + QStringLiteral(" / ") + section->child(k)->text(0) + QStringLiteral(": ") +
                 section->child(k)->text(1);
    }
  }
  return out;
}

}  // namespace hull::ui
