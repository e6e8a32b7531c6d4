#pragma once
// Whether text is well-formed UTF-8, checked before an XML parser reads it: TinyXML 1 (urdfdom's
// parser, and telear's COLLADA check) skips a multi-byte character by its lead byte's length, so
// a sequence cut by the end of the text makes it read past the buffer (issue 25: found by the
// URDF and mesh doors' fuzzers). XML is UTF-8.

#include <cstddef>
#include <optional>
#include <string>

namespace telear::core {

// The offset of the first byte that does not begin or continue a well-formed UTF-8 sequence
// (RFC 3629: no overlong forms, no surrogates, nothing past U+10FFFF), or nothing.
std::optional<std::size_t> first_invalid_utf8(const std::string& text);

}  // namespace telear::core
