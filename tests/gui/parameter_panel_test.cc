// The parameter panel: built from the descriptor table, validated on every
// edit with inline errors, undo/redo of valid changes, and binding to
// another table and validator (as the core options structs will be bound).
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QSignalSpy>
#include <QSpinBox>
#include <QUndoStack>

#include "base/error.h"
#include "gui_test_support.h"
#include "ui/panels/parameter_panel.h"

using namespace hull::ui;

namespace {

QDoubleSpinBox* Real(ParameterPanel& panel, const char* key) {
  return qobject_cast<QDoubleSpinBox*>(panel.editor(QString::fromLatin1(key)));
}

}  // namespace

class ParameterPanelTest : public QObject {
  Q_OBJECT

 private slots:
  void aFieldPerDescriptorShowingTheDefaults() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    for (const ParameterDescriptor& d : DefaultParameterTable()) {
      QWidget* editor = panel.editor(d.key);
      QVERIFY2(editor, qPrintable(d.key));
      QCOMPARE(editor->toolTip(), d.tooltip);
    }
    QCOMPARE(Real(panel, "sigma0")->value(), 1.0);
    QCOMPARE(Real(panel, "sigma1")->value(), 0.02);
    QCOMPARE(Real(panel, "alpha")->value(), 0.12);
    QCOMPARE(qobject_cast<QSpinBox*>(panel.editor(QStringLiteral("dbscan_min_points")))->value(), 3);
    QCOMPARE(qobject_cast<QComboBox*>(panel.editor(QStringLiteral("model")))->currentData().toString(),
             QStringLiteral("max-mixture"));
    QCOMPARE(panel.values(), DefaultValues(DefaultParameterTable()));
    QVERIFY(CheckDefaultParameters(panel.values()).empty());
  }

  void aValidEditIsAppliedAndUndoable() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    QSignalSpy changed(&panel, &ParameterPanel::parametersChanged);
    Real(panel, "tau")->setValue(0.06);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(panel.values().value(QStringLiteral("tau")).toDouble(), 0.06);
    QCOMPARE(changed.last().at(0).value<ParameterValues>().value(QStringLiteral("tau")).toDouble(), 0.06);
    QCOMPARE(panel.undoStack()->count(), 1);

    panel.undoStack()->undo();
    QCOMPARE(panel.values().value(QStringLiteral("tau")).toDouble(), 0.0);
    QCOMPARE(Real(panel, "tau")->value(), 0.0);
    QCOMPARE(changed.count(), 2);
    panel.undoStack()->redo();
    QCOMPARE(panel.values().value(QStringLiteral("tau")).toDouble(), 0.06);
    QCOMPARE(Real(panel, "tau")->value(), 0.06);
  }

  void editsOfOneFieldMergeIntoOneStep() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    Real(panel, "alpha")->setValue(0.13);
    Real(panel, "alpha")->setValue(0.14);
    Real(panel, "alpha")->setValue(0.15);
    QCOMPARE(panel.undoStack()->count(), 1);
    Real(panel, "tau")->setValue(0.02);
    QCOMPARE(panel.undoStack()->count(), 2);
    panel.undoStack()->undo();
    panel.undoStack()->undo();
    QCOMPARE(panel.values().value(QStringLiteral("alpha")).toDouble(), 0.12);
  }

  void anInvalidEditShowsAnInlineErrorAndChangesNothing() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    panel.show();
    QSignalSpy changed(&panel, &ParameterPanel::parametersChanged);
    Real(panel, "sigma1")->setValue(1.0);  // the on-surface sigma not below sigma0 = 1 m
    QVERIFY2(panel.errorText(QStringLiteral("sigma1")).contains(QStringLiteral("smaller than σ₀")),
             qPrintable(panel.errorText(QStringLiteral("sigma1"))));
    QVERIFY(panel.findChild<QLabel*>(QStringLiteral("sigma1_error"))->isVisible());
    QCOMPARE(changed.count(), 0);
    QCOMPARE(panel.undoStack()->count(), 0);
    QCOMPARE(panel.values().value(QStringLiteral("sigma1")).toDouble(), 0.02);
    QVERIFY(panel.errorText(QStringLiteral("sigma0")).isEmpty());

    // Fixing it through the other field applies both as one step.
    Real(panel, "sigma0")->setValue(5.0);
    QVERIFY(panel.errorText(QStringLiteral("sigma1")).isEmpty());
    QCOMPARE(changed.count(), 1);
    QCOMPARE(panel.values().value(QStringLiteral("sigma0")).toDouble(), 5.0);
    QCOMPARE(panel.values().value(QStringLiteral("sigma1")).toDouble(), 1.0);
    QCOMPARE(panel.undoStack()->count(), 1);
    panel.undoStack()->undo();
    QCOMPARE(panel.values(), DefaultValues(DefaultParameterTable()));
    QCOMPARE(Real(panel, "sigma1")->value(), 0.02);
  }

  void aRefusedKeystrokeSaysWhy() {
    // Typing σ₁ = 2 (its editor goes to 1 m): Qt's spin box drops the key;
    // the panel says why, in full, and that σ₁ keeps its value.
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    panel.resize(320, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QSignalSpy changed(&panel, &ParameterPanel::parametersChanged);
    QDoubleSpinBox* sigma1 = Real(panel, "sigma1");
    sigma1->setFocus();
    sigma1->selectAll();
    QTest::keyClicks(sigma1, QStringLiteral("2"));
    const QString error = panel.errorText(QStringLiteral("sigma1"));
    QVERIFY2(error.contains(QStringLiteral("2 is outside [0.001, 1] m")), qPrintable(error));
    QVERIFY2(error.contains(QStringLiteral("σ₁ (on surface) stays 0.02 m")), qPrintable(error));
    QLabel* label = panel.findChild<QLabel*>(QStringLiteral("sigma1_error"));
    QVERIFY(label->isVisible());
    // The whole message fits the dock's width: wrapped, not cut.
    QVERIFY(label->wordWrap());
    QVERIFY(label->mapTo(&panel, QPoint(label->width(), 0)).x() <= panel.width());
    QCOMPARE(changed.count(), 0);
    QCOMPARE(panel.values().value(QStringLiteral("sigma1")).toDouble(), 0.02);
    QVERIFY(panel.grab().save(hull::ui::testing::OutputDir() + QStringLiteral("/parameter_refused.png")));
    // Not a number in an integer field.
    QSpinBox* points = qobject_cast<QSpinBox*>(panel.editor(QStringLiteral("dbscan_min_points")));
    points->setFocus();
    points->selectAll();
    QTest::keyClicks(points, QStringLiteral("x"));
    const QString points_error = panel.errorText(QStringLiteral("dbscan_min_points"));
    QVERIFY2(points_error.contains(QStringLiteral("is not a whole number")), qPrintable(points_error));
    // A valid edit clears the message.
    sigma1->setValue(0.03);
    QVERIFY(panel.errorText(QStringLiteral("sigma1")).isEmpty());
    QCOMPARE(changed.count(), 1);
  }

  void restoreDefaultsIsOneUndoableStep() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    Real(panel, "tau")->setValue(0.1);
    qobject_cast<QComboBox*>(panel.editor(QStringLiteral("model")))->setCurrentIndex(0);
    QCOMPARE(panel.values().value(QStringLiteral("model")).toString(), QStringLiteral("naive"));
    panel.RestoreDefaults();
    QCOMPARE(panel.values(), DefaultValues(DefaultParameterTable()));
    panel.undoStack()->undo();
    QCOMPARE(panel.values().value(QStringLiteral("model")).toString(), QStringLiteral("naive"));
    QCOMPARE(panel.values().value(QStringLiteral("tau")).toDouble(), 0.1);
  }

  void resetValuesClearsTheHistory() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    Real(panel, "tau")->setValue(0.1);
    ParameterValues v = DefaultValues(DefaultParameterTable());
    v.insert(QStringLiteral("alpha"), 0.3);
    panel.ResetValues(v);
    QCOMPARE(panel.undoStack()->count(), 0);
    QCOMPARE(Real(panel, "alpha")->value(), 0.3);
    QCOMPARE(Real(panel, "tau")->value(), 0.0);
  }

  void bindsToAnotherTableThroughItsValidator() {
    // How the core options will be bound: a table of their fields and a
    // validator that runs Check() and maps OptionError(field) to the field.
    ParameterDescriptor eps;
    eps.key = QStringLiteral("epsilon");
    eps.group = QStringLiteral("Clustering");
    eps.label = QStringLiteral("ε");
    eps.minimum = 0.0;
    eps.maximum = 1.0;
    eps.default_value = 0.1;
    ParameterValidator validator = [](const ParameterValues& v) -> std::vector<ParameterError> {
      try {
        if (v.value(QStringLiteral("epsilon")).toDouble() > 0.5) throw hull::OptionError("epsilon", "too coarse");
        if (v.value(QStringLiteral("epsilon")).toDouble() == 0.0) throw hull::OptionError("solver", "would not stop");
      } catch (const hull::OptionError& e) {
        return {{QString::fromStdString(e.field()), QString::fromStdString(e.what())}};
      }
      return {};
    };
    ParameterPanel panel({eps}, validator);
    Real(panel, "epsilon")->setValue(0.7);
    QCOMPARE(panel.errorText(QStringLiteral("epsilon")), QStringLiteral("option epsilon: too coarse"));
    QCOMPARE(panel.values().value(QStringLiteral("epsilon")).toDouble(), 0.1);
    Real(panel, "epsilon")->setValue(0.0);  // an error about a field the panel does not show
    QVERIFY(panel.errorText(QStringLiteral("epsilon")).isEmpty());
    QVERIFY(panel.errorText(QString()).startsWith(QStringLiteral("solver:")));
    Real(panel, "epsilon")->setValue(0.2);
    QVERIFY(panel.errorText(QString()).isEmpty());
    QCOMPARE(panel.values().value(QStringLiteral("epsilon")).toDouble(), 0.2);
  }

  void tableChecksCatchWrongTypesAndRanges() {
    ParameterValues v = DefaultValues(DefaultParameterTable());
    v.insert(QStringLiteral("model"), QStringLiteral("magic"));
    v.insert(QStringLiteral("dbscan_min_points"), 2.5);
    v.insert(QStringLiteral("alpha"), 7.0);
    v.remove(QStringLiteral("tau"));
    const auto errors = CheckDefaultParameters(v);
    QStringList keys;
    for (const auto& e : errors) keys << e.key;
    keys.sort();
    QCOMPARE(keys, (QStringList{QStringLiteral("alpha"), QStringLiteral("dbscan_min_points"), QStringLiteral("model"),
                                QStringLiteral("tau")}));
  }
};

HI_GUI_TEST_MAIN(ParameterPanelTest)
#include "parameter_panel_test.moc"
