#include "base/error.h"

#include <algorithm>
#include <utility>

#include "base/printable.h"

namespace hull {
namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0.
std::size_t Utf8Length(std::string_view s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  unsigned min = 0;
  if (c >= 0xc2 && c <= 0xdf) {
    n = 2, min = 0x80;
  } else if (c >= 0xe0 && c <= 0xef) {
    n = 3, min = 0x800;
  } else if (c >= 0xf0 && c <= 0xf4) {
    n = 4, min = 0x10000;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  unsigned cp = c & (0x7fu >> n);
  for (std::size_t k = 1; k < n; ++k) {
    const auto d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (d & 0x3f);
  }
  if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  return n;
}

}  // namespace

std::string PrintableText(std::string_view text, std::size_t max_bytes) {
  static const char* kHex = "0123456789abcdef";
  std::string out;
  out.reserve(std::min(text.size(), max_bytes) + 16);
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t take = 1;
    std::string piece;
    if (c >= 0x80) {
      take = Utf8Length(text, i);
      if (take) piece.assign(text.substr(i, take));
    } else if (c >= 0x20 && c != 0x7f) {
      piece.assign(1, static_cast<char>(c));
    } else if (c == '\n' || c == '\t') {
      piece.assign(1, static_cast<char>(c));
    }
    if (piece.empty()) {  // a control byte or a byte that is not UTF-8
      take = 1;
      piece = std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
    }
    if (out.size() + piece.size() > max_bytes) break;
    out += piece;
    i += take;
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size() - i) + " more bytes)";
  return out;
}

std::string SourceLocation::ToString() const {
  std::string s = file.empty() ? std::string("<input>") : PrintableText(file, kMaxPrintedPath);
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  if (!field.empty()) s += " (" + PrintableText(field, kMaxPrintedField) + ")";
  return s;
}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(where.ToString() + ": " + PrintableText(message, kMaxPrintedMessage)),
      where_(std::move(where)),
      detail_(PrintableText(message, kMaxPrintedMessage)) {}

OptionError::OptionError(const std::string& field, const std::string& why)
    : std::invalid_argument("option " + PrintableText(field, kMaxPrintedField) + ": " +
                            PrintableText(why, kMaxPrintedMessage)),
      field_(field) {}

InsufficientData::InsufficientData(std::string stage, const std::string& what, std::string where)
    : std::runtime_error("insufficient data (" + PrintableText(stage, kMaxPrintedField) +
                         "): " + PrintableText(what, kMaxPrintedMessage) +
                         (where.empty() ? std::string() : " [" + PrintableText(where, kMaxPrintedPath) + "]")),
      stage_(std::move(stage)),
      where_(std::move(where)),
      detail_(PrintableText(what, kMaxPrintedMessage)) {}

std::string Problem::ToString() const {
  return where.ToString() + (severity == Severity::kWarning ? ": warning: " : ": ") +
         PrintableText(message, kMaxPrintedMessage);
}

}  // namespace hull
