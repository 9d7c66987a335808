#include "ui/jobs/error_text.h"

#include <QDir>

#include "base/error.h"

namespace hull::ui {

namespace {

QString DescribeInputError(const InputError& e) {
  const SourceLocation& where = e.where();
  QString text =
      where.file.empty() ? QStringLiteral("input") : QDir::toNativeSeparators(QString::fromStdString(where.file));
  if (where.line > 0) {
    text += QStringLiteral(", line %1").arg(where.line);
    if (where.column > 0) text += QStringLiteral(", column %1").arg(where.column);
  }
  if (!where.field.empty()) text += QStringLiteral(" (field \"%1\")").arg(QString::fromStdString(where.field));
  return text + QStringLiteral(":\n") + QString::fromStdString(e.detail());
}

}  // namespace

QString DescribeException(const std::exception_ptr& error) {
  if (!error) return QStringLiteral("no error");
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    return DescribeInputError(e);
  } catch (const OptionError& e) {
    return QString::fromStdString(e.what());
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  } catch (...) {
    return QStringLiteral("an unknown error (not a std::exception)");
  }
}

}  // namespace hull::ui
