// The report document as an A4 PDF (QPdfWriter): text and tables laid out by
// QTextDocument, figures painted by the same QPainter code that makes the
// PNGs (vector lines and text; the heatmaps' meshes as a raster at about
// 360 dpi). Page breaks: sections marked new_page start a page, headings
// keep with what follows, figures never split (they shrink to fit a page),
// long tables continue on the next page with their header repeated. Every
// page has a footer with the title and the page number.
#pragma once

#include <QString>
#include <functional>

#include "ui/report/figures.h"
#include "ui/report/report_document.h"

namespace hull::report {

// figure(ref) returns the figure to paint for a reference. Returns the
// number of pages. Throws std::runtime_error when the file cannot be written.
int WriteReportPdf(const ReportDocument& doc, const std::function<const Figure&(const FigureRef&)>& figure,
                   const QString& path);

}  // namespace hull::report
