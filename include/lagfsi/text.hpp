#pragma once
/// @file text.hpp
/// Text that comes from outside (case files, --set values, file names, table rows): UTF-8 validation and
/// the form in which such text is echoed in a one-line message (invalid bytes and control characters
/// escaped, at most ~80 characters).
#include <cstddef>
#include <string>
#include <string_view>

namespace lagfsi {

/// True when `s` is well-formed UTF-8 (no overlong forms, no surrogates, nothing beyond U+10FFFF). On
/// false, `bad_at` (if given) receives the offset of the first byte that is not.
bool valid_utf8(std::string_view s, std::size_t* bad_at = nullptr);

/// `s` as it may appear inside a one-line message: bytes that are not valid UTF-8 and control characters
/// (tab, line breaks, ...) written as \xNN, and the whole cut to `max_chars` characters with "..." and the
/// original size when longer ("aaaaaaa... (100000 bytes)").
std::string echo(std::string_view s, std::size_t max_chars = 80);

/// Line number (1-based) of byte `offset` in `text`.
std::size_t line_of(std::string_view text, std::size_t offset);

}  // namespace lagfsi
