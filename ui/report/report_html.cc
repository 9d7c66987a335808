#include "ui/report/report_html.h"

#include <QStringList>
#include <algorithm>
#include <vector>

namespace hull::report {

QString HtmlEscape(const std::string& text) { return QString::fromStdString(text).toHtmlEscaped(); }

namespace {

// Columns that must not wrap: numbers, and text no longer than a short name.
std::vector<bool> NoWrapColumns(const Table& t) {
  std::vector<bool> nowrap(t.header.size(), false);
  for (std::size_t c = 0; c < t.header.size(); ++c) {
    int longest = 0;
    for (const auto& row : t.rows) {
      if (c < row.size()) longest = std::max(longest, QString::fromStdString(row[c]).size());
    }
    nowrap[c] = (c < t.numeric.size() && t.numeric[c]) || longest <= 16;
  }
  return nowrap;
}

}  // namespace

QString TableHtml(const Table& t, std::size_t begin, std::size_t end) {
  const std::vector<bool> nowrap = NoWrapColumns(t);
  QString h = QStringLiteral(
      "<table class=\"data\" width=\"100%\" cellspacing=\"0\" cellpadding=\"3\" border=\"1\" "
      "style=\"border-collapse:collapse; border-color:#b8b8b8;\">\n<thead><tr>");
  for (std::size_t c = 0; c < t.header.size(); ++c) {
    const bool num = c < t.numeric.size() && t.numeric[c];
    // Headers never break inside a word: the unit goes on a line of its own,
    // and the words of a long name on lines of their own.
    QString name = QString::fromStdString(t.header[c]), unit;
    const int paren = name.indexOf(QStringLiteral(" ("));
    if (paren >= 0) {
      unit = name.mid(paren + 1);
      name.truncate(paren);
    }
    QString text = name.toHtmlEscaped();
    if (name.size() > 14) text.replace(QLatin1Char(' '), QStringLiteral("<br>"));
    if (!unit.isEmpty()) text += QStringLiteral("<br>") + unit.toHtmlEscaped();
    h += QStringLiteral("<th bgcolor=\"#e8edf3\" align=\"%1\" style=\"white-space:nowrap;\">%2</th>")
             .arg(num ? QStringLiteral("right") : QStringLiteral("left"), text);
  }
  h += QStringLiteral("</tr></thead>\n<tbody>\n");
  for (std::size_t r = begin; r < end && r < t.rows.size(); ++r) {
    h += QStringLiteral("<tr>");
    for (std::size_t c = 0; c < t.rows[r].size(); ++c) {
      const bool num = c < t.numeric.size() && t.numeric[c];
      QString attrs = num ? QStringLiteral(" align=\"right\"") : QString();
      if (c < nowrap.size() && nowrap[c]) attrs += QStringLiteral(" style=\"white-space:nowrap;\"");
      if (static_cast<int>(c) == t.tone_column && r < t.tone.size() && !t.tone[r].empty()) {
        attrs += QStringLiteral(" bgcolor=\"%1\"").arg(QString::fromStdString(t.tone[r]));
      }
      h += QStringLiteral("<td%1>%2</td>").arg(attrs, HtmlEscape(t.rows[r][c]));
    }
    h += QStringLiteral("</tr>\n");
  }
  h += QStringLiteral("</tbody></table>\n");
  return h;
}

QString BlockHtml(const Block& b) {
  switch (b.kind) {
    case Block::Kind::kParagraph:
      return QStringLiteral("<p>%1</p>\n").arg(HtmlEscape(b.text));
    case Block::Kind::kNote:
      return QStringLiteral(
                 "<table class=\"note\" width=\"100%\" cellpadding=\"6\" cellspacing=\"0\" border=\"0\">"
                 "<tr><td bgcolor=\"#fff6dc\"><b>Note.</b> %1</td></tr></table>\n")
          .arg(HtmlEscape(b.text));
    case Block::Kind::kSubheading:
      return QStringLiteral("<h3>%1</h3>\n").arg(HtmlEscape(b.text));
    case Block::Kind::kFacts: {
      QString h =
          QStringLiteral("<table class=\"facts\" width=\"100%\" cellspacing=\"0\" cellpadding=\"2\" border=\"0\">\n");
      for (const auto& [label, value] : b.facts) {
        h += QStringLiteral("<tr><td width=\"28%\"><b>%1</b></td><td>%2</td></tr>\n")
                 .arg(HtmlEscape(label), HtmlEscape(value));
      }
      return h + QStringLiteral("</table>\n");
    }
    case Block::Kind::kTable:
      return TableHtml(b.table, 0, b.table.rows.size());
    case Block::Kind::kList: {
      // Items indented with four spaces are a list inside the item before them.
      QString h = QStringLiteral("<ul>\n");
      bool nested = false;
      for (std::size_t i = 0; i < b.items.size(); ++i) {
        const bool child = b.items[i].rfind("    ", 0) == 0;
        if (child && !nested) h += QStringLiteral("\n<ul>\n");
        if (!child && nested) h += QStringLiteral("</ul>\n</li>\n");
        if (!child && i > 0 && !nested) h += QStringLiteral("</li>\n");
        nested = child;
        h += QStringLiteral("<li>%1").arg(HtmlEscape(b.items[i]).trimmed());
        if (child) h += QStringLiteral("</li>\n");
      }
      if (nested) h += QStringLiteral("</ul>\n");
      if (!b.items.empty()) h += QStringLiteral("</li>\n");
      return h + QStringLiteral("</ul>\n");
    }
    case Block::Kind::kFigure:
      return {};
  }
  return {};
}

QString SectionHeading(const ReportDocument& doc, std::size_t section) {
  return QStringLiteral("%1. %2").arg(section + 1).arg(HtmlEscape(doc.sections[section].title));
}

QString FigureCaption(int number, const FigureRef& f) {
  return QStringLiteral("<b>Figure %1.</b> <b>%2.</b> %3").arg(number).arg(HtmlEscape(f.title), HtmlEscape(f.caption));
}

namespace {

const char* const kStyle = R"(
body { font-family: "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; font-size: 14px; color: #1d1d1d;
       max-width: 980px; margin: 24px auto; padding: 0 16px; line-height: 1.45; }
h1 { font-size: 28px; margin-bottom: 4px; color: #1b3a5c; }
h2 { font-size: 21px; margin-top: 36px; border-bottom: 2px solid #1b3a5c; padding-bottom: 3px; color: #1b3a5c; }
h3 { font-size: 16px; margin-top: 22px; }
p.subtitle { font-size: 17px; margin: 0; }
p.generated { color: #666; font-size: 12px; margin-top: 4px; }
nav ol { columns: 2; font-size: 13px; }
table.data { border-collapse: collapse; margin: 10px 0 16px; font-size: 12.5px; width: 100%; }
table.data th, table.data td { border: 1px solid #c4c4c4; padding: 3px 6px; }
table.data th { background: #e8edf3; }
table.data tbody tr:nth-child(even) td:not([bgcolor]) { background: #f7f8fa; }
table.facts td { padding: 2px 8px 2px 0; vertical-align: top; }
table.note { margin: 12px 0; }
figure { margin: 18px 0 26px; }
figure img { width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 12.5px; color: #333; margin-top: 6px; }
)";

}  // namespace

QString ReportHtml(const ReportDocument& doc, const std::function<QByteArray(const FigureRef&)>& png) {
  QString h = QStringLiteral("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
  h += QStringLiteral("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
  h += QStringLiteral("<title>%1: %2</title>\n").arg(HtmlEscape(doc.title), HtmlEscape(doc.subtitle));
  h += QStringLiteral("<style>%1</style>\n</head>\n<body>\n").arg(QString::fromLatin1(kStyle));
  h += QStringLiteral("<header>\n<h1>%1</h1>\n<p class=\"subtitle\">%2</p>\n<p class=\"generated\">%3</p>\n</header>\n")
           .arg(HtmlEscape(doc.title), HtmlEscape(doc.subtitle), HtmlEscape(doc.generated));
  h += QStringLiteral("<nav>\n<ol>\n");
  for (const Section& s : doc.sections) {
    h += QStringLiteral("<li><a href=\"#%1\">%2</a></li>\n").arg(QString::fromStdString(s.id), HtmlEscape(s.title));
  }
  h += QStringLiteral("</ol>\n</nav>\n");
  int figure = 0;
  for (std::size_t i = 0; i < doc.sections.size(); ++i) {
    const Section& s = doc.sections[i];
    h += QStringLiteral("<section id=\"%1\">\n<h2>%2</h2>\n").arg(QString::fromStdString(s.id), SectionHeading(doc, i));
    for (const Block& b : s.blocks) {
      if (b.kind != Block::Kind::kFigure) {
        h += BlockHtml(b);
        continue;
      }
      ++figure;
      const QByteArray bytes = png(b.figure);
      h += QStringLiteral("<figure id=\"fig-%1\">\n<img src=\"data:image/png;base64,%2\" alt=\"%3\">\n")
               .arg(QString::fromStdString(b.figure.id), QString::fromLatin1(bytes.toBase64()),
                    HtmlEscape(b.figure.title));
      h += QStringLiteral("<figcaption>%1</figcaption>\n</figure>\n").arg(FigureCaption(figure, b.figure));
    }
    h += QStringLiteral("</section>\n");
  }
  h += QStringLiteral("</body>\n</html>\n");
  return h;
}

}  // namespace hull::report
