#include "ui/report/report_pdf.h"

#include <QAbstractTextDocumentLayout>
#include <QFile>
#include <QPageLayout>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QTextDocument>
#include <memory>
#include <stdexcept>
#include <vector>

#include "ui/report/report_html.h"

namespace hull::report {
namespace {

constexpr int kDpi = 300;
constexpr double kMarginMm = 18;
constexpr double kFooterMm = 9;
constexpr double kBlockGapMm = 2.6;

double Mm(double mm) { return mm / 25.4 * kDpi; }

const char* const kTextStyle = R"(
p { margin-top: 0; margin-bottom: 0; }
h3 { font-size: 10.5pt; margin-top: 4px; margin-bottom: 0; }
ul { margin-top: 0; margin-bottom: 0; }
li { margin-bottom: 2px; }
th { font-weight: bold; }
)";

// Lays the document out page by page. Run twice: once without painting, to
// learn the page of each section and the page count for the contents and the
// footers, then again to paint.
class PdfLayout {
 public:
  PdfLayout(const ReportDocument& doc, const std::function<const Figure&(const FigureRef&)>& figure, QPdfWriter& writer,
            QPainter* painter)
      : doc_(doc), figure_(figure), writer_(writer), p_(painter) {
    width_ = writer.width();
    page_height_ = writer.height() - Mm(kFooterMm);
  }

  void Run(const std::vector<int>& section_pages, int total_pages) {
    section_pages_ = section_pages;
    total_pages_ = total_pages;
    pages_ = 1;
    y_ = 0;
    Title();
    int figure = 0;
    for (std::size_t i = 0; i < doc_.sections.size(); ++i) {
      const Section& s = doc_.sections[i];
      if (s.new_page && y_ > 0) NewPage();
      const auto heading = Text(QStringLiteral("<p style=\"font-size:15pt; font-weight:bold; color:#1b3a5c;\">%1</p>")
                                    .arg(SectionHeading(doc_, i)));
      if (Remaining() < heading->size().height() + 0.22 * page_height_) NewPage();
      found_pages_.push_back(pages_);
      Draw(*heading);
      Rule();
      for (const Block& b : s.blocks) {
        if (b.kind == Block::Kind::kFigure) {
          FigureBlock(b.figure, ++figure);
        } else if (b.kind == Block::Kind::kTable) {
          TableBlock(b.table);
        } else {
          Flow(*Text(BlockHtml(b)), b.kind == Block::Kind::kSubheading);
        }
        y_ += Mm(kBlockGapMm);
      }
      y_ += Mm(3);
    }
    Footer();
  }

  int pages() const { return pages_; }
  const std::vector<int>& found_pages() const { return found_pages_; }

 private:
  double Remaining() const { return page_height_ - y_; }

  std::unique_ptr<QTextDocument> Text(const QString& html, double text_width = 0) const {
    auto d = std::make_unique<QTextDocument>();
    d->documentLayout()->setPaintDevice(&writer_);
    QFont font(QStringLiteral("DejaVu Sans"));
    font.setPointSizeF(9);
    d->setDefaultFont(font);
    d->setDefaultStyleSheet(QString::fromLatin1(kTextStyle));
    d->setDocumentMargin(0);
    d->setTextWidth(text_width > 0 ? text_width : width_);
    d->setHtml(html);
    return d;
  }

  void Draw(QTextDocument& d, double x = 0) {
    if (p_) {
      p_->save();
      p_->translate(x, y_);
      d.drawContents(p_);
      p_->restore();
    }
    y_ += d.size().height();
  }

  // Text that may run over pages (clipped slices of it, page by page).
  void Flow(QTextDocument& d, bool keep_with_next) {
    const double h = d.size().height();
    const double need = keep_with_next ? h + 0.15 * page_height_ : h;
    if (need > Remaining() && (h <= page_height_ || Remaining() < 0.2 * page_height_)) NewPage();
    if (h <= Remaining()) {
      Draw(d);
      return;
    }
    double done = 0;
    while (done < h) {
      const double slice = std::min(h - done, Remaining());
      if (p_) {
        p_->save();
        p_->translate(0, y_ - done);
        d.drawContents(p_, QRectF(0, done, width_, slice));
        p_->restore();
      }
      done += slice;
      y_ += slice;
      if (done < h) NewPage();
    }
  }

  void TableBlock(const Table& t) {
    std::size_t begin = 0;
    if (t.rows.empty()) {
      Draw(*Text(TableHtml(t, 0, 0)));
      return;
    }
    while (begin < t.rows.size()) {
      // The most rows from `begin` that fit on what is left of the page.
      const auto fits = [&](std::size_t end) { return Text(TableHtml(t, begin, end))->size().height() <= Remaining(); };
      std::size_t lo = begin, hi = t.rows.size();
      if (fits(hi)) {
        lo = hi;
      } else {
        while (hi - lo > 1) {
          const std::size_t mid = (lo + hi) / 2;
          (fits(mid) ? lo : hi) = mid;
        }
      }
      // At least three rows with the header, unless the page is fresh.
      if (lo - begin < std::min<std::size_t>(3, t.rows.size() - begin) && y_ > 0) {
        NewPage();
        continue;
      }
      const std::size_t end = std::max(lo, begin + 1);
      Draw(*Text(TableHtml(t, begin, end)));
      begin = end;
      if (begin < t.rows.size()) NewPage();
    }
  }

  void FigureBlock(const FigureRef& ref, int number) {
    const Figure& f = figure_(ref);
    const auto caption =
        Text(QStringLiteral("<p style=\"font-size:8.5pt; color:#333333;\">%1</p>").arg(FigureCaption(number, ref)));
    const double ch = caption->size().height() + Mm(1.5);
    double w = width_, h = width_ * f.Height() / kFigureWidth;
    if (h + ch > page_height_) {  // shrink to a page
      h = page_height_ - ch;
      w = h * kFigureWidth / f.Height();
    }
    if (h + ch > Remaining()) NewPage();
    if (p_) {
      const QRectF target((width_ - w) / 2, y_, w, h);
      PaintFigure(f, *p_, target);
      p_->save();
      p_->setPen(QPen(QColor(0xd0, 0xd0, 0xd0), Mm(0.2)));
      p_->setBrush(Qt::NoBrush);
      p_->drawRect(target);
      p_->restore();
    }
    y_ += h + Mm(1.5);
    Draw(*caption);
  }

  void Title() {
    Draw(*Text(QStringLiteral("<p style=\"font-size:21pt; font-weight:bold; color:#1b3a5c;\">%1</p>"
                              "<p style=\"font-size:13pt; margin-top:4px;\">%2</p>"
                              "<p style=\"font-size:8pt; color:#666666; margin-top:4px;\">%3</p>")
                   .arg(HtmlEscape(doc_.title), HtmlEscape(doc_.subtitle), HtmlEscape(doc_.generated))));
    y_ += Mm(2);
    Rule();
    // Contents with page numbers (from the first pass).
    QString toc = QStringLiteral("<table cellspacing=\"0\" cellpadding=\"1\" width=\"60%\">");
    for (std::size_t i = 0; i < doc_.sections.size(); ++i) {
      const QString page = i < section_pages_.size() ? QString::number(section_pages_[i]) : QString();
      toc += QStringLiteral("<tr><td>%1</td><td align=\"right\">%2</td></tr>").arg(SectionHeading(doc_, i), page);
    }
    toc += QStringLiteral("</table>");
    Draw(*Text(QStringLiteral("<p style=\"font-weight:bold;\">Contents</p>") + toc));
    y_ += Mm(6);
  }

  void Rule() {
    y_ += Mm(0.8);
    if (p_) {
      p_->save();
      p_->setPen(QPen(QColor(0x1b, 0x3a, 0x5c), Mm(0.35)));
      p_->drawLine(QPointF(0, y_), QPointF(width_, y_));
      p_->restore();
    }
    y_ += Mm(2.2);
  }

  void Footer() {
    if (!p_) return;
    p_->save();
    QFont font(QStringLiteral("DejaVu Sans"));
    font.setPointSizeF(7.5);
    p_->setFont(font);
    p_->setPen(QColor(0x70, 0x70, 0x70));
    const double top = page_height_ + Mm(3);
    p_->drawLine(QPointF(0, top), QPointF(width_, top));
    const QRectF box(0, top + Mm(0.8), width_, Mm(kFooterMm - 4));
    p_->drawText(box, Qt::AlignLeft | Qt::AlignVCenter,
                 QStringLiteral("HullInspect · %1 · %2")
                     .arg(QString::fromStdString(doc_.title), QString::fromStdString(doc_.subtitle)));
    p_->drawText(box, Qt::AlignRight | Qt::AlignVCenter,
                 total_pages_ > 0 ? QStringLiteral("page %1 of %2").arg(pages_).arg(total_pages_)
                                  : QStringLiteral("page %1").arg(pages_));
    p_->restore();
  }

  void NewPage() {
    Footer();
    if (p_) writer_.newPage();
    ++pages_;
    y_ = 0;
  }

  const ReportDocument& doc_;
  const std::function<const Figure&(const FigureRef&)>& figure_;
  QPdfWriter& writer_;
  QPainter* p_;
  double width_ = 0, page_height_ = 0, y_ = 0;
  int pages_ = 1, total_pages_ = 0;
  std::vector<int> section_pages_, found_pages_;
};

}  // namespace

int WriteReportPdf(const ReportDocument& doc, const std::function<const Figure&(const FigureRef&)>& figure,
                   const QString& path) {
  QPdfWriter writer(path);
  writer.setResolution(kDpi);
  writer.setPageLayout(QPageLayout(QPageSize(QPageSize::A4), QPageLayout::Portrait,
                                   QMarginsF(kMarginMm, kMarginMm, kMarginMm, kMarginMm - 4), QPageLayout::Millimeter));
  writer.setTitle(QString::fromStdString(doc.title + ": " + doc.subtitle));
  writer.setCreator(QStringLiteral("HullInspect"));
  // First pass: where each section lands and how many pages there are.
  PdfLayout dry(doc, figure, writer, nullptr);
  dry.Run({}, 0);
  QPainter painter;
  if (!painter.begin(&writer)) throw std::runtime_error("cannot write " + path.toStdString());
  PdfLayout layout(doc, figure, writer, &painter);
  layout.Run(dry.found_pages(), dry.pages());
  painter.end();
  if (!QFile::exists(path) || QFile(path).size() == 0) throw std::runtime_error("cannot write " + path.toStdString());
  return layout.pages();
}

}  // namespace hull::report
