// The report document as HTML: a self-contained page (CSS inline, figures as
// PNG data URIs) and the block fragments the PDF writer lays out with
// QTextDocument (which reads a subset of HTML 4: tables by attributes, simple
// CSS), so both formats show the same tables.
#pragma once

#include <QByteArray>
#include <QString>
#include <functional>
#include <string>

#include "ui/report/report_document.h"

namespace hull::report {

QString HtmlEscape(const std::string& text);

// One block (not a figure) as an HTML fragment.
QString BlockHtml(const Block& block);
// A table fragment with only rows [begin, end) (the header is repeated).
QString TableHtml(const Table& table, std::size_t begin, std::size_t end);

// "1. Survey and vessel"
QString SectionHeading(const ReportDocument& doc, std::size_t section);

// The numbered figure caption: "Figure 3. Title. Caption".
QString FigureCaption(int number, const FigureRef& figure);

// The whole page. png(id) returns a figure's PNG bytes (embedded as a data URI).
QString ReportHtml(const ReportDocument& doc, const std::function<QByteArray(const FigureRef&)>& png);

}  // namespace hull::report
