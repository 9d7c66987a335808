// Text from an input file made safe to print (issue 14): control bytes
// (other than tab and newline) and bytes that are not valid UTF-8 become
// \xNN, and text past max_bytes is cut at a character boundary with
// "... (N more bytes)". InputError, OptionError and Problem pass their
// parts through this, so a malformed 100 kB header or a binary file echoes a
// bounded, printable line; the CLI does the same for any other message.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace hull {

std::string PrintableText(std::string_view text, std::size_t max_bytes = 400);
// Limits of a printed error: the file name, the field and the message.
constexpr std::size_t kMaxPrintedPath = 400, kMaxPrintedField = 120, kMaxPrintedMessage = 1000;

}  // namespace hull
