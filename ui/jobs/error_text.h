// Turns an exception caught at a thread or file boundary into text a person
// can act on: for bad input the file, line, column and field at fault, then
// what was wrong.
#pragma once

#include <QString>
#include <exception>

namespace hull::ui {

// A readable description of the exception: "FILE, line L, column C (field
// F): what was expected" for hull::InputError, "option F: why" for
// hull::OptionError, what() for other std::exceptions.
QString DescribeException(const std::exception_ptr& error);

}  // namespace hull::ui
